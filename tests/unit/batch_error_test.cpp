// batch_error_test.cpp — the batch-means standard error (host/reference/batch_error.h) on synthetic
// samples whose variance of the mean is known: a heavy-tailed log-normal and a Pareto (mean-square
// calibration over many replicates), samples correlated in runs (the blocks see the correlation, the
// per-sample estimate does not), and the exact identities (one sample per block is the per-sample
// estimate; float and double blocks agree). Fixed seeds.
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "reference/batch_error.h"

namespace {

using seasim::BatchEstimate;
using seasim::BatchMeans;
using seasim::batchEstimate;

// Mean over `replicates` runs of N samples: the RMS reported standard errors (blocks and per-sample)
// over the true one, sqrt(variance / N).
struct Calibration {
  double blocks = 0, per_sample = 0, effective = 0;
};

template <typename Draw>
Calibration calibrate(Draw draw, double variance, int n, int blocks, int replicates, unsigned seed) {
  std::mt19937_64 rng(seed);
  double se2 = 0, sse2 = 0, neff = 0;
  std::vector<double> x(static_cast<size_t>(n));
  for (int r = 0; r < replicates; ++r) {
    for (double& v : x) v = draw(rng);
    const BatchEstimate e = batchEstimate(x, blocks);
    se2 += e.std_error * e.std_error / replicates;
    sse2 += e.sample_std_error * e.sample_std_error / replicates;
    neff += e.effective_samples / replicates;
  }
  const double truth = std::sqrt(variance / n);
  return {std::sqrt(se2) / truth, std::sqrt(sse2) / truth, neff};
}

TEST(BatchError, LogNormalHeavyTailIsCalibrated) {
  // X = e^{σ Z}, σ = 1.2: Var = (e^{σ²} - 1) e^{σ²}, kurtosis about 1900: most of the variance sits in
  // samples beyond the 99th percentile.
  const double s = 1.2, var = std::expm1(s * s) * std::exp(s * s);
  std::normal_distribution<double> z(0.0, 1.0);
  const Calibration c =
      calibrate([&](std::mt19937_64& g) { return std::exp(s * z(g)); }, var, 4096, 32, 2000, 7);
  std::printf("log-normal: blocks %.3f, per-sample %.3f, effective samples %.0f of 4096\n", c.blocks, c.per_sample,
              c.effective);
  EXPECT_NEAR(c.blocks, 1.0, 0.05);
  EXPECT_NEAR(c.per_sample, 1.0, 0.05);
}

TEST(BatchError, ParetoTailIsCalibrated) {
  // Pareto with x_m = 1, α = 5: Var = α / ((α - 1)² (α - 2)) (finite fourth moment, heavy fifth).
  const double a = 5.0, var = a / ((a - 1) * (a - 1) * (a - 2));
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const Calibration c =
      calibrate([&](std::mt19937_64& g) { return std::pow(1.0 - u(g), -1.0 / a); }, var, 2048, 16, 3000, 11);
  std::printf("Pareto: blocks %.3f, per-sample %.3f\n", c.blocks, c.per_sample);
  EXPECT_NEAR(c.blocks, 1.0, 0.05);
  EXPECT_NEAR(c.per_sample, 1.0, 0.05);
}

TEST(BatchError, BlocksSeeSamplesCorrelatedInRuns) {
  // Every draw repeated 8 times in a row: Var(mean) = 8 σ² / N, the per-sample estimate says σ² / N
  // (a factor sqrt(8) too small), the blocks (256 samples each) see the runs; effective samples N/8.
  const int n = 8192, run = 8;
  std::mt19937_64 rng(3);
  std::normal_distribution<double> z(0.0, 1.0);
  double se2 = 0, sse2 = 0, neff = 0;
  const int replicates = 1000;
  std::vector<double> x(n);
  for (int r = 0; r < replicates; ++r) {
    for (int i = 0; i < n; i += run) {
      const double v = z(rng);
      for (int k = 0; k < run; ++k) x[static_cast<size_t>(i + k)] = v;
    }
    const BatchEstimate e = batchEstimate(x, 32);
    se2 += e.std_error * e.std_error / replicates;
    sse2 += e.sample_std_error * e.sample_std_error / replicates;
    neff += e.effective_samples / replicates;
  }
  const double truth = std::sqrt(double(run) / n);
  EXPECT_NEAR(std::sqrt(se2) / truth, 1.0, 0.05);
  EXPECT_NEAR(std::sqrt(sse2) / truth, 1.0 / std::sqrt(double(run)), 0.02);
  EXPECT_NEAR(neff, double(n) / run, 0.1 * n / run);
}

TEST(BatchError, OneSamplePerBlockIsThePerSampleEstimate) {
  const std::vector<double> x = {1.0, 4.0, 2.5, 0.5, 9.0, 3.0, 2.0};
  const BatchEstimate e = batchEstimate(x, 100);  // clamped to 7 blocks of one
  EXPECT_EQ(e.blocks, 7);
  EXPECT_EQ(e.samples, 7);
  EXPECT_NEAR(e.std_error, e.sample_std_error, 1e-12);
  EXPECT_NEAR(e.effective_samples, 7.0, 1e-9);
  double m = 0, s2 = 0;
  for (double v : x) m += v / 7;
  for (double v : x) s2 += (v - m) * (v - m) / 6;
  EXPECT_NEAR(e.mean, m, 1e-12);
  EXPECT_NEAR(e.sample_std_error, std::sqrt(s2 / 7), 1e-12);
}

TEST(BatchError, UnequalBlocksAndTheTextbookFormula) {
  // Equal blocks: Σ (m_b - m)² / (B (B - 1)); blocks of 3, 3, 3 and one of 3 from 12 samples.
  const std::vector<double> x = {1, 2, 3, 10, 11, 12, 4, 4, 4, 7, 8, 9};
  const BatchEstimate e = batchEstimate(x, 4);
  const double mb[4] = {2, 11, 4, 8}, m = 6.25;
  double ss = 0;
  for (double v : mb) ss += (v - m) * (v - m);
  EXPECT_NEAR(e.mean, m, 1e-12);
  EXPECT_NEAR(e.std_error, std::sqrt(ss / (4 * 3)), 1e-12);
  // One block: no spread, the error is 0 and the per-sample one stands.
  const BatchEstimate one = batchEstimate(x, 1);
  EXPECT_EQ(one.std_error, 0.0);
  EXPECT_GT(one.sample_std_error, 0.0);
  // A tiny spread about a large mean does not cancel (the sums are about the first block's mean).
  std::vector<double> y(64);
  for (size_t i = 0; i < y.size(); ++i) y[i] = 1e9 + (i % 2 ? 1e-3 : -1e-3);
  const BatchEstimate tiny = batchEstimate(y, 64);
  EXPECT_NEAR(tiny.std_error / tiny.sample_std_error, 1.0, 1e-3);
  EXPECT_NEAR(tiny.sample_std_error, 1e-3 / std::sqrt(63.0), 1e-6);
}

TEST(BatchError, FloatAndDoubleBlocksAgree) {
  // The device's layout: float4 per pixel (RGB used), and plain doubles.
  const float mean4[8] = {1.0f, 2.0f, 3.0f, 99.0f, 4.0f, 5.0f, 6.0f, 99.0f};
  const float m24[8] = {0.5f, 0.25f, 0.0f, 0.0f, 1.0f, 2.0f, 3.0f, 0.0f};
  const float mean4b[8] = {1.5f, 2.5f, 2.0f, 99.0f, 4.5f, 4.0f, 7.0f, 99.0f};
  BatchMeans f(6), d(6);
  f.addBlock(mean4, m24, 4, 5);
  f.addBlock(mean4b, m24, 4, 3);
  const double md[6] = {1, 2, 3, 4, 5, 6}, m2d[6] = {0.5, 0.25, 0, 1, 2, 3}, mdb[6] = {1.5, 2.5, 2, 4.5, 4, 7};
  d.addBlock(md, m2d, 5);
  d.addBlock(mdb, m2d, 3);
  for (size_t i = 0; i < 6; ++i) {
    EXPECT_NEAR(f.estimate(i).mean, d.estimate(i).mean, 1e-6);
    EXPECT_NEAR(f.estimate(i).std_error, d.estimate(i).std_error, 1e-6);
    EXPECT_NEAR(f.estimate(i).sample_std_error, d.estimate(i).sample_std_error, 1e-6);
  }
  EXPECT_NEAR(d.estimate(0).mean, (5 * 1.0 + 3 * 1.5) / 8, 1e-12);
}

}  // namespace
