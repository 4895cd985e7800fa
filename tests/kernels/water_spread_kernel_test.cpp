// water_spread_kernel_test.cpp — kernels/water_spread.cl on PoCL in float against its passes in double on
// the CPU (water_spread_cpu.h): random moments over a frame whose size is no multiple of the cell, with
// cells of 1 and 3 pixels, 3 and 5 channels, near and far depths; and what the blur keeps: a point of
// light in the middle of an even frame keeps its light, spreads it as the layers' Gaussians, and a near
// pixel receives from a far one only the share S'/D (spread_reach).
#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "passes/water_spread_pass.h"
#include "test_device.h"
#include "water_spread_cpu.h"

namespace {

// A blur of sigma_1 sigma_cells cells, on cells of factor pixels (makeWaterSpread's layout, chosen here).
seasim::WaterSpread spreadOf(int width, int height, int factor, double sigma_cells) {
  seasim::WaterSpread s = seasim::waterSpreadGrid(width, height, factor);
  for (int k = 0; k < UWS_LAYERS; ++k) seasim::addLayerTaps(s, k, sigma_cells * std::sqrt(double(1 << k)));
  return s;
}

struct Inputs {
  std::vector<double> s, depth, forward, frame;
};

// Runs the pass on the device: frame += the blurred forward light; returns the frame.
std::vector<double> runOnDevice(const seasim::WaterSpread& spread, int channels, const Inputs& in) {
  seasim::Device& device = seasim::test::testDevice();
  const size_t pixels = size_t(spread.params.width) * spread.params.height;
  std::vector<cl_float4> geom(pixels);
  for (size_t i = 0; i < pixels; ++i) geom[i] = {{float(in.s[i]), 0.0f, 1.0f, 0.0f}};
  std::vector<float> depth(in.depth.begin(), in.depth.end()), forward(in.forward.begin(), in.forward.end()),
      frame(in.frame.begin(), in.frame.end());
  const cl_mem_flags flags = CL_MEM_READ_WRITE | CL_MEM_COPY_HOST_PTR;
  cl::Buffer geom_b(device.context(), flags, sizeof(cl_float4) * pixels, geom.data());
  cl::Buffer depth_b(device.context(), flags, sizeof(float) * depth.size(), depth.data());
  cl::Buffer forward_b(device.context(), flags, sizeof(float) * forward.size(), forward.data());
  cl::Buffer frame_b(device.context(), flags, sizeof(float) * frame.size(), frame.data());
  const seasim::PassPlan plan{"water_spread", "water_spread.cl", {}, {}, {}, "", true, ""};
  if (channels == 3) {
    seasim::WaterSpreadPass pass(device, plan, spread, 0);
    pass.run(geom_b, depth_b, forward_b, frame_b);
  } else {
    // The spectral blur's path: bands as channels, the RGB blur run on a scratch frame.
    seasim::WaterSpreadPass pass(device, plan, spread, channels);
    std::vector<float> rgb(3 * pixels, 0.0f), rgb_forward(6 * pixels, 0.0f);
    cl::Buffer rgb_b(device.context(), flags, sizeof(float) * rgb.size(), rgb.data());
    cl::Buffer rgb_forward_b(device.context(), flags, sizeof(float) * rgb_forward.size(), rgb_forward.data());
    pass.run(geom_b, depth_b, rgb_forward_b, rgb_b, &forward_b, &frame_b);
  }
  device.queue().enqueueReadBuffer(frame_b, CL_TRUE, 0, sizeof(float) * frame.size(), frame.data());
  return {frame.begin(), frame.end()};
}

Inputs randomInputs(int width, int height, int channels, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  const size_t pixels = size_t(width) * height;
  Inputs in{std::vector<double>(pixels), std::vector<double>(2 * pixels), std::vector<double>(2 * pixels * channels),
            std::vector<double>(pixels * channels)};
  for (size_t i = 0; i < pixels; ++i) {
    // A near block (an object 3 m away) in front of far water (40 m) and sand (12 m), and a miss (1e30).
    const int x = int(i % width), y = int(i / width);
    in.s[i] = (x > width / 3 && x < width / 2 && y > height / 4) ? 3.0 : y > height / 2 ? 12.0 : x == 0 ? 1e30 : 40.0;
    double light = 0;
    for (int c = 0; c < channels; ++c) {
      const double f = u(rng) * (in.s[i] < 5 ? 2.0 : 1.0);
      in.forward[i * 2 * channels + c] = f;
      in.forward[i * 2 * channels + channels + c] = f * (1.0 + 9.0 * u(rng));  // mean counts 1 to 10
      in.frame[i * channels + c] = u(rng);
      light += f;
    }
    in.depth[2 * i] = light * std::min(in.s[i], 1e4) * (0.3 + 0.7 * u(rng));
    in.depth[2 * i + 1] = light;
  }
  return in;
}

void expectMatches(const seasim::WaterSpread& spread, int channels, const Inputs& in) {
  std::vector<double> ref = in.frame;
  seasim::test::waterSpreadCpu(spread, channels, in.s, in.depth, in.forward, ref);
  const std::vector<double> got = runOnDevice(spread, channels, in);
  ASSERT_EQ(got.size(), ref.size());
  double worst = 0;
  for (size_t i = 0; i < ref.size(); ++i) {
    ASSERT_TRUE(std::isfinite(got[i]));
    worst = std::max(worst, std::fabs(got[i] - ref[i]) / (std::fabs(ref[i]) + 1e-6));
  }
  EXPECT_LT(worst, 2e-5) << "factor " << spread.params.factor << ", " << channels << " channels";
}

TEST(WaterSpreadKernel, MatchesDoubleCpuEvaluation) {
  expectMatches(spreadOf(37, 23, 1, 1.3), 3, randomInputs(37, 23, 3, 1));
  expectMatches(spreadOf(37, 23, 3, 1.1), 3, randomInputs(37, 23, 3, 2));
  expectMatches(spreadOf(37, 23, 1, 0.8), 5, randomInputs(37, 23, 5, 3));
  expectMatches(spreadOf(37, 23, 3, 2.0), 5, randomInputs(37, 23, 5, 4));
  expectMatches(spreadOf(8, 5, 4, 2.5), 3, randomInputs(8, 5, 3, 5));  // cells wider than a quarter of the frame
}

// One pixel of light in the middle of a frame at one depth, mean count 1 (layer 0 only): the blur keeps
// its light and spreads it as the layer's Gaussian (per axis, the taps); with cells of 3 pixels the light
// is kept too, spread a little wider by the cells' sums and the bilinear expansion.
TEST(WaterSpreadKernel, APointKeepsItsLightAndSpreadsAsTheGaussian) {
  for (int factor : {1, 3}) {
    const int w = 63, h = 45;
    const seasim::WaterSpread spread = spreadOf(w, h, factor, 1.5);
    Inputs in{std::vector<double>(size_t(w) * h, 10.0), std::vector<double>(2 * size_t(w) * h, 0.0),
              std::vector<double>(6 * size_t(w) * h, 0.0), std::vector<double>(3 * size_t(w) * h, 0.0)};
    const size_t centre = size_t(h / 2) * w + w / 2;
    for (int c = 0; c < 3; ++c) {
      in.forward[6 * centre + c] = 1.0;
      in.forward[6 * centre + 3 + c] = 1.0;
    }
    in.depth[2 * centre] = 30.0;  // its light comes from 10 m, as far as every pixel ends: all reachable
    in.depth[2 * centre + 1] = 3.0;
    const std::vector<double> got = runOnDevice(spread, 3, in);
    double sum = 0, var_x = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const double v = got[3 * (size_t(y) * w + x)];
        sum += v;
        var_x += v * (x - w / 2) * (x - w / 2);
      }
    EXPECT_NEAR(sum, 1.0, 1e-5) << factor;
    const double sigma_px = 1.5 * factor;  // the layer's sigma in pixels
    if (factor == 1) {
      EXPECT_NEAR(got[3 * centre], double(spread.taps[0]) * spread.taps[0], 1e-6);
      EXPECT_NEAR(std::sqrt(var_x), sigma_px, 0.01);
    } else {
      // The cells' sums (factor^2 - 1)/12 and the bilinear expansion factor^2/6 add to the variance.
      EXPECT_NEAR(var_x, sigma_px * sigma_px + (factor * factor - 1) / 12.0 + factor * factor / 6.0, 0.15 * var_x);
    }
  }
}

// A near pixel (S' = 2 m) beside far light (D = 20 m) receives a tenth of what a far neighbour receives.
TEST(WaterSpreadKernel, NearPixelsReceiveTheReachableShare) {
  const int w = 21, h = 1;
  const seasim::WaterSpread spread = spreadOf(w, h, 1, 1.0);
  Inputs in{std::vector<double>(w, 20.0), std::vector<double>(2 * w, 0.0), std::vector<double>(6 * w, 0.0),
            std::vector<double>(3 * w, 0.0)};
  in.s[11] = 2.0;  // the near pixel, right of the source; its mirror image 9 is far
  in.forward[6 * 10] = 1.0;
  in.forward[6 * 10 + 3] = 1.0;
  in.depth[2 * 10] = 20.0;
  in.depth[2 * 10 + 1] = 1.0;
  const std::vector<double> got = runOnDevice(spread, 3, in);
  EXPECT_GT(got[3 * 9], 0.1);
  EXPECT_NEAR(got[3 * 11], 0.1 * got[3 * 9], 1e-6);
  // The light the source spreads over its own (far) neighbours keeps the Gaussian's weights (one row: the
  // column pass's taps all read it).
  EXPECT_NEAR(got[3 * 9], double(spread.taps[1]), 1e-6);
}

}  // namespace
