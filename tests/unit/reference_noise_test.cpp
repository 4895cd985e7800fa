// reference_noise_test.cpp — reference/compare.h's referenceNoise8bit: the rmse that the reference's
// noise alone gives. A reference drawn as truth + Gaussian noise of a known standard error, compared
// with the truth, scores that rmse; the function predicts it from the standard-error image.
#include <gtest/gtest.h>

#include <random>

#include "reference/compare.h"

namespace seasim {
namespace {

TEST(ReferenceNoise, PredictsTheRmseOfAnExactImageAgainstANoisyReference) {
  const int w = 200, h = 100;
  Image truth = Image::rgb(w, h), noisy = Image::rgb(w, h), se = Image::rgb(w, h);
  std::mt19937 rng(7);
  std::normal_distribution<float> normal(0.0f, 1.0f);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const float base[3] = {0.05f + 0.4f * x / w, 0.1f + 0.3f * y / h, 0.2f};  // dark to mid: the tone map bends
      for (int c = 0; c < 3; ++c) {
        const float sigma = 0.01f * base[c];  // 1 % noise
        truth.at(x, y, c) = base[c];
        noisy.at(x, y, c) = base[c] + sigma * normal(rng);
        se.at(x, y, c) = sigma;
      }
    }
  for (double ev : {0.0, 1.5}) {
    const double measured = compareImages(truth, noisy, ev).rmse_8bit;
    const double predicted = referenceNoise8bit(noisy, se, ev);
    EXPECT_GT(measured, 0.1) << "the test needs noise visible in 8-bit levels";
    EXPECT_NEAR(predicted / measured, 1.0, 0.05) << "ev " << ev << ": predicted " << predicted << ", measured " << measured;
  }
  // No noise: zero; a standard error of another size: refused.
  EXPECT_EQ(referenceNoise8bit(truth, Image::rgb(w, h)), 0.0);
  EXPECT_THROW(referenceNoise8bit(truth, Image::rgb(w, h + 1)), std::runtime_error);
}

}  // namespace
}  // namespace seasim
