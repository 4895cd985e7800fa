// batch_error.h — the standard error of a Monte Carlo mean from independent blocks of samples (the
// method of batch means), beside the textbook per-sample estimate, and the effective sample count
// that compares the two.
//
// Why blocks: the per-sample estimate s²/n is unbiased for the variance of the mean, but under a heavy
// tail (rare paths carrying most of the light: a forward-peaked phase function seen along the sun, a
// dim absorbing field that only a few long paths reach) s² is dominated by the few largest samples;
// a run that happened to miss them reports both a low mean and a too-small error, so its error bar
// is least honest exactly where it is most needed. Block means of many samples are much closer to
// normal (central limit theorem), so the spread of B of them estimates the variance of the mean
// with B - 1 degrees of freedom whatever the tail, and a correlation between samples (shared random
// numbers, a bug) shows up in it too. The blocks are contiguous ranges of the sample index, so they
// are independent exactly when the samples are.
//
// Estimator (blocks of n_b samples with means m_b, N = Σ n_b, weights w_b = n_b / N, m = Σ w_b m_b):
//   Var(m) ≈ B/(B-1) Σ_b w_b² (m_b - m)²,
// for equal blocks the usual Σ (m_b - m)² / (B (B-1)). Effective samples: the number of independent
// samples of the per-sample variance s² whose mean would have that variance, n_eff = s² / Var(m)
// (= N when the per-sample estimate is honest, < N when it is too small).
#pragma once
#include <cstddef>
#include <vector>

namespace seasim {

struct BatchEstimate {
  double mean = 0.0;
  double std_error = 0.0;         // from the spread of the block means (0 with fewer than 2 blocks)
  double sample_std_error = 0.0;  // sqrt(s² / N) from the per-sample variance
  double effective_samples = 0.0; // s² / std_error²; N when std_error is 0
  long long samples = 0;          // N
  int blocks = 0;                 // B
};

// Block means and per-sample statistics of `values` quantities at once (pixels x channels), one block
// at a time. Memory: five doubles per value.
class BatchMeans {
 public:
  explicit BatchMeans(size_t values);
  // One block of n >= 1 samples: per value its mean and its M2 (sum of squared deviations from that
  // mean; 0 for n = 1). Merged in double (Chan, Golub, LeVeque 1979).
  void addBlock(const float* block_mean, const float* block_m2, size_t stride, long long n);
  void addBlock(const double* block_mean, const double* block_m2, long long n);
  size_t values() const { return sum_.size(); }
  int blocks() const { return blocks_; }
  long long samples() const { return samples_; }
  BatchEstimate estimate(size_t i) const;

 private:
  void add(size_t i, double m, double m2, double n, double N_before);
  std::vector<double> sum_;     // Σ n_b m_b
  std::vector<double> m2_;      // Σ over samples of (x - mean)², merged
  std::vector<double> shift_;   // the first block's mean: the block sums below are about it, so
                                // Σ n_b² (m_b - m)² does not cancel when the spread is tiny
  std::vector<double> wsq_;     // Σ n_b² (m_b - shift)
  std::vector<double> wsq2_;    // Σ n_b² (m_b - shift)²
  double n2_ = 0.0;             // Σ n_b²
  long long samples_ = 0;
  int blocks_ = 0;
};

// The estimate from the samples themselves, cut into `blocks` contiguous blocks of nearly equal size
// (tests, and small CPU Monte Carlo loops). blocks is clamped to [1, samples.size()].
BatchEstimate batchEstimate(const std::vector<double>& samples, int blocks);

}  // namespace seasim
