#include "reference/batch_error.h"

#include <algorithm>
#include <cmath>

#include "util/error.h"

namespace seasim {

BatchMeans::BatchMeans(size_t values) : sum_(values, 0.0), m2_(values, 0.0), shift_(values, 0.0), wsq_(values, 0.0), wsq2_(values, 0.0) {}

void BatchMeans::add(size_t i, double m, double m2, double n, double N_before) {
  // Chan's merge of the per-sample M2: the new block's M2 plus the shift of its mean from the running one.
  if (N_before > 0) {
    const double delta = m - sum_[i] / N_before;
    m2_[i] += m2 + delta * delta * N_before * n / (N_before + n);
  } else {
    m2_[i] = m2;
    shift_[i] = m;
  }
  sum_[i] += n * m;
  const double d = m - shift_[i];
  wsq_[i] += n * n * d;
  wsq2_[i] += n * n * d * d;
}

void BatchMeans::addBlock(const float* block_mean, const float* block_m2, size_t stride, long long n) {
  if (n < 1) throw RuntimeError("batch means: a block needs at least one sample");
  const double N_before = static_cast<double>(samples_), dn = static_cast<double>(n);
  for (size_t i = 0; i < sum_.size(); ++i) {
    const size_t pixel = i / 3, ch = i % 3;  // float4 per pixel, RGB used (the kernels' layout)
    add(i, block_mean[pixel * stride + ch], std::max(0.0, double(block_m2[pixel * stride + ch])), dn, N_before);
  }
  samples_ += n;
  n2_ += dn * dn;
  ++blocks_;
}

void BatchMeans::addBlock(const double* block_mean, const double* block_m2, long long n) {
  if (n < 1) throw RuntimeError("batch means: a block needs at least one sample");
  const double N_before = static_cast<double>(samples_), dn = static_cast<double>(n);
  for (size_t i = 0; i < sum_.size(); ++i) add(i, block_mean[i], block_m2 ? std::max(0.0, block_m2[i]) : 0.0, dn, N_before);
  samples_ += n;
  n2_ += dn * dn;
  ++blocks_;
}

BatchEstimate BatchMeans::estimate(size_t i) const {
  BatchEstimate e;
  e.samples = samples_;
  e.blocks = blocks_;
  if (samples_ < 1) return e;
  const double N = static_cast<double>(samples_);
  e.mean = sum_[i] / N;
  const double s2 = samples_ > 1 ? m2_[i] / (N - 1) : 0.0;
  e.sample_std_error = std::sqrt(s2 / N);
  if (blocks_ >= 2) {
    // Σ n_b² (m_b - m)² = Σ n_b² d_b² - 2 d Σ n_b² d_b + d² Σ n_b² with d_b = m_b - shift, d = m - shift;
    // divided by N² for the weights.
    const double d = e.mean - shift_[i];
    const double ss = std::max(0.0, wsq2_[i] - 2.0 * d * wsq_[i] + d * d * n2_);
    const double B = blocks_;
    e.std_error = std::sqrt(B / (B - 1.0) * ss) / N;
  }
  e.effective_samples = e.std_error > 0 ? s2 / (e.std_error * e.std_error) : N;
  return e;
}

BatchEstimate batchEstimate(const std::vector<double>& samples, int blocks) {
  const long long n = static_cast<long long>(samples.size());
  if (n < 1) return BatchEstimate{};
  const long long B = std::clamp<long long>(blocks, 1, n);
  BatchMeans acc(1);
  long long start = 0;
  for (long long b = 0; b < B; ++b) {
    const long long end = n * (b + 1) / B;
    double mean = 0.0, m2 = 0.0;
    for (long long j = start; j < end; ++j) {  // Welford
      const double delta = samples[static_cast<size_t>(j)] - mean;
      mean += delta / double(j - start + 1);
      m2 += delta * (samples[static_cast<size_t>(j)] - mean);
    }
    acc.addBlock(&mean, &m2, end - start);
    start = end;
  }
  return acc.estimate(0);
}

}  // namespace seasim
