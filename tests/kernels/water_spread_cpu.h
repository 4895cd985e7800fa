// water_spread_cpu.h — kernels/water_spread.cl's four passes evaluated in double on the CPU, for the
// kernel tests: the cells' sums and the layers' split, the two blurs with what the spread can reach, and
// the bilinear expansion, written as loops over the same definitions (common/water_spread_params.h).
#pragma once
#include <algorithm>
#include <cmath>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/water_spread_setup.h"

namespace seasim::test {

// frame [pixel][channels] += the blurred forward light. s: the G-buffer's S per pixel; depth [pixel][2];
// forward [pixel][2][channels].
inline void waterSpreadCpu(const WaterSpread& spread, int channels, const std::vector<double>& s,
                           const std::vector<double>& depth, const std::vector<double>& forward,
                           std::vector<double>& frame) {
  const UwsParams& p = spread.params;
  const int lw = p.low_width, lh = p.low_height, f = p.factor, L = UWS_LAYERS;
  const size_t cells = size_t(lw) * lh;
  std::vector<double> layers(cells * L * channels), cell_s(cells), cell_d(cells);
  for (int cy = 0; cy < lh; ++cy)
    for (int cx = 0; cx < lw; ++cx) {
      const size_t cell = size_t(cy) * lw + cx;
      double s_sum = 0, num = 0, den = 0;
      int n = 0;
      std::vector<double> fs(channels, 0.0), fe(channels, 0.0);
      for (int y = cy * f; y < std::min((cy + 1) * f, p.height); ++y)
        for (int x = cx * f; x < std::min((cx + 1) * f, p.width); ++x) {
          const size_t px = size_t(y) * p.width + x;
          s_sum += std::min(s[px], 1e4);
          num += depth[2 * px];
          den += depth[2 * px + 1];
          ++n;
          for (int c = 0; c < channels; ++c) {
            fs[c] += forward[px * 2 * channels + c];
            fe[c] += forward[px * 2 * channels + channels + c];
          }
        }
      cell_s[cell] = s_sum / n;
      cell_d[cell] = den > 0 ? num / den : cell_s[cell];
      for (int c = 0; c < channels; ++c)
        for (int k = 0; k < L; ++k)
          layers[(cell * L + k) * channels + c] = fs[c] * kmath_d::uws_layer_share(fs[c] > 0 ? fe[c] / fs[c] : 1.0, k);
    }
  auto reach = [](double s_dest, double d_src) { return d_src > s_dest ? s_dest / d_src : 1.0; };
  auto tap = [&](int k, int j) { return double(spread.taps[p.tap_offset[k] + std::abs(j)]); };
  std::vector<double> rows(cells * L * channels, 0.0), blurred(cells * channels, 0.0);
  for (int cy = 0; cy < lh; ++cy)
    for (int cx = 0; cx < lw; ++cx)
      for (int k = 0; k < L; ++k)
        for (int j = -p.radius[k]; j <= p.radius[k]; ++j) {
          const size_t dst = size_t(cy) * lw + cx, src = size_t(cy) * lw + std::clamp(cx + j, 0, lw - 1);
          const double w = tap(k, j) * reach(cell_s[dst], cell_d[src]);
          for (int c = 0; c < channels; ++c) rows[(dst * L + k) * channels + c] += w * layers[(src * L + k) * channels + c];
        }
  for (int cy = 0; cy < lh; ++cy)
    for (int cx = 0; cx < lw; ++cx)
      for (int k = 0; k < L; ++k)
        for (int j = -p.radius[k]; j <= p.radius[k]; ++j) {
          const size_t dst = size_t(cy) * lw + cx, src = size_t(std::clamp(cy + j, 0, lh - 1)) * lw + cx;
          const double w = tap(k, j) * reach(cell_s[dst], cell_d[src]);
          for (int c = 0; c < channels; ++c) blurred[dst * channels + c] += w * rows[(src * L + k) * channels + c];
        }
  auto pixels_of = [&](int cx, int cy) { return double(std::min(f, p.width - cx * f) * std::min(f, p.height - cy * f)); };
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const double u = (x + 0.5) / f - 0.5, v = (y + 0.5) / f - 0.5;
      const int ux = int(std::floor(u)), vy = int(std::floor(v));
      const double fx = u - ux, fy = v - vy;
      for (int dy = 0; dy <= 1; ++dy)
        for (int dx = 0; dx <= 1; ++dx) {
          const int cx = std::clamp(ux + dx, 0, lw - 1), cy = std::clamp(vy + dy, 0, lh - 1);
          const double w = (dx ? fx : 1 - fx) * (dy ? fy : 1 - fy) / pixels_of(cx, cy);
          for (int c = 0; c < channels; ++c)
            frame[(size_t(y) * p.width + x) * channels + c] += w * blurred[(size_t(cy) * lw + cx) * channels + c];
        }
    }
}

}  // namespace seasim::test
