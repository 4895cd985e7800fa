// caustic_map_test.cpp — kernels/common/caustic_map.h in float and double: the bilinear read hits the
// texel values at texel centres and wraps around the periodic patch (also far from the origin and at
// negative coordinates), depth interpolation runs from 1 at the surface through the layers to the
// deepest one, and degenerate inputs (no layers, zero extent, depth 0) read as "no focusing" (1).
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "math/kernel_math.h"

namespace {

template <typename T>
class CausticMapTest : public ::testing::Test {};
struct F { using real = float; };
struct D { using real = double; };
using Precisions = ::testing::Types<F, D>;
TYPED_TEST_SUITE(CausticMapTest, Precisions);

template <typename real>
real sample(const std::vector<float>& maps, int m, int layers, real extent, real depth_max, real x, real depth, real z) {
  if constexpr (std::is_same_v<real, float>)
    return seasim::kmath_f::caustic_map_sample(maps.data(), m, layers, extent, depth_max, x, depth, z);
  else
    return seasim::kmath_d::caustic_map_sample(maps.data(), m, layers, extent, depth_max, x, depth, z);
}

// Two 4×4 layers with distinct texel values: layer k texel (i, j) = 1 + k + 0.1 i + 0.01 j.
std::vector<float> twoLayers() {
  std::vector<float> maps(2 * 16);
  for (int k = 0; k < 2; ++k)
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i) maps[k * 16 + j * 4 + i] = 1.0f + k + 0.1f * i + 0.01f * j;
  return maps;
}

TYPED_TEST(CausticMapTest, TexelCentresAndWrapAround) {
  using real = typename TypeParam::real;
  const std::vector<float> maps = twoLayers();
  const real L = 8, tol = (std::is_same_v<real, float> ? real(2e-5) : real(1e-12));
  // depth_max = 10, 2 layers: layer 0 at 5 m, layer 1 at 10 m.
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      const real x = (i + real(0.5)) * 2, z = (j + real(0.5)) * 2;
      EXPECT_NEAR(sample<real>(maps, 4, 2, L, 10, x, 5, z), maps[j * 4 + i], tol);
      EXPECT_NEAR(sample<real>(maps, 4, 2, L, 10, x, 10, z), maps[16 + j * 4 + i], tol);
      // The patch tiles: one and a thousand patches away, on both sides.
      for (real shift : {L, -L, 1000 * L, -1000 * L})
        EXPECT_NEAR(sample<real>(maps, 4, 2, L, 10, x + shift, 5, z - shift), maps[j * 4 + i],
                    (std::is_same_v<real, float> ? real(2e-3) : tol));
    }
  // Between the last and the first texel (x = 0 is half way between texel 3 and texel 0 of the next tile).
  EXPECT_NEAR(sample<real>(maps, 4, 2, L, 10, 0, 5, 1), 0.5 * (maps[0] + maps[3]), tol);
}

TYPED_TEST(CausticMapTest, DepthInterpolation) {
  using real = typename TypeParam::real;
  const std::vector<float> maps = twoLayers();
  const real x = 1, z = 1, tol = (std::is_same_v<real, float> ? real(2e-5) : real(1e-12));
  const double l0 = maps[0], l1 = maps[16];
  EXPECT_NEAR(sample<real>(maps, 4, 2, 8, 10, x, 0, z), 1.0, tol);            // surface: no focusing yet
  EXPECT_NEAR(sample<real>(maps, 4, 2, 8, 10, x, 2.5, z), 0.5 * (1 + l0), tol);  // half way to layer 0
  EXPECT_NEAR(sample<real>(maps, 4, 2, 8, 10, x, 7.5, z), 0.5 * (l0 + l1), tol); // between the layers
  EXPECT_NEAR(sample<real>(maps, 4, 2, 8, 10, x, 10, z), l1, tol);
  EXPECT_NEAR(sample<real>(maps, 4, 2, 8, 10, x, 1000, z), l1, tol);           // below: the deepest layer
  // Continuous across a layer.
  EXPECT_NEAR(sample<real>(maps, 4, 2, 8, 10, x, real(5) - real(1e-4), z), sample<real>(maps, 4, 2, 8, 10, x, 5, z),
              real(1e-3));
}

TYPED_TEST(CausticMapTest, ReadPeriodicOrClampedOverASquare) {
  using real = typename TypeParam::real;
  const std::vector<float> maps = twoLayers();  // layer 0: 4 × 4 over the square [-4, 4]² here
  const real tol = (std::is_same_v<real, float> ? real(2e-5) : real(1e-12));
  auto read = [&](int periodic, real x, real z) {
    if constexpr (std::is_same_v<real, float>)
      return seasim::kmath_f::caustic_map_read(maps.data(), 4, real(8), real(-4), periodic, x, z);
    else
      return seasim::kmath_d::caustic_map_read(maps.data(), 4, real(8), real(-4), periodic, x, z);
  };
  for (int periodic : {0, 1})
    for (int j = 0; j < 4; ++j)
      for (int i = 0; i < 4; ++i)  // texel centres at -4 + (i + ½) 2
        EXPECT_NEAR(read(periodic, real(-3 + 2 * i), real(-3 + 2 * j)), maps[j * 4 + i], tol);
  // Periodic: one square away reads the same; clamped: beyond the edge reads the edge texel.
  EXPECT_NEAR(read(1, real(-3 + 8), real(-1 - 8)), maps[1 * 4 + 0], tol);
  EXPECT_NEAR(read(0, real(-100), real(-100)), maps[0], tol);
  EXPECT_NEAR(read(0, real(100), real(-1)), maps[1 * 4 + 3], tol);
  EXPECT_NEAR(read(0, real(3.5), real(3.5)), maps[15], tol);
  EXPECT_TRUE(std::isfinite(read(0, real(NAN), real(1e30))));
}

TYPED_TEST(CausticMapTest, DegenerateInputsReadAsNoFocusing) {
  using real = typename TypeParam::real;
  const std::vector<float> maps = twoLayers();
  EXPECT_EQ(sample<real>(maps, 4, 0, 8, 10, 1, 5, 1), real(1));   // no layers
  EXPECT_EQ(sample<real>(maps, 4, 2, 0, 10, 1, 5, 1), real(1));   // zero extent
  EXPECT_EQ(sample<real>(maps, 4, 2, 8, 0, 1, 5, 1), real(1));    // zero depth range
  EXPECT_EQ(sample<real>(maps, 4, 2, 8, 10, 1, 0, 1), real(1));   // at the surface
  EXPECT_EQ(sample<real>(maps, 4, 2, 8, 10, 1, -3, 1), real(1));  // above the surface
  EXPECT_EQ(sample<real>(maps, 4, 2, 8, 10, 1, real(NAN), 1), real(1));
  EXPECT_TRUE(std::isfinite(sample<real>(maps, 4, 2, 8, 10, real(1e30), 5, real(-1e30))));
}

}  // namespace
