// water_spread_setup.h — the water's point-spread for underwater.model = "discrete_ordinates"
// (kernels/common/water_spread.h derives it): the spread of one small-angle scattering from the phase,
// in the image's pixels, and the Gaussian taps of kernels/water_spread.cl's layers.
#pragma once
#include <vector>

#include "common/water_spread_params.h"

namespace seasim {

// The median polar angle (radians) of delta-M's forward peak for an HG phase of asymmetry g truncated to
// `order` Legendre moments (f = g^order): the peak is (p_HG - sum_{l < order} (2l + 1)(g^l - f) P_l) / f,
// integrated over the sphere by the trapezoid rule on 20,000 steps in theta. 0 for g <= 0 or f < 1e-6
// (no peak). Measured: 4.1 deg at g = 0.95, 7.1 at 0.9, 11 at 0.8 for order 3.
double deltaMPeakMedianAngle(double g, int order);

// The median of one scattering's displacement seen from the camera, theta v (radians): theta from the
// peak above, v = 1 - x/S uniform on [0, 1] (kernels/common/water_spread.h (2)). About 0.7 of the peak's
// median angle (0.73 for a 2-D Gaussian theta).
double deltaMPeakDisplacementMedian(double g, int order);

// sigma_1 of water_spread.h, radians per image axis: the 2-D Gaussian with the displacement's median
// radius, median / sqrt(2 ln 2). The median, not the variance: the displacement is peaked at 0 (a
// scattering near the hit hardly moves the light) and heavy-tailed, and a Gaussian of its variance
// (sigma_theta / sqrt(3)) would spread the light's bulk too wide.
double singleScatterSpread(double g, int order);

// Gaussian taps of sigma pixels, j = 0..radius (radius = ceil(3 sigma), capped at max_radius), normalised
// so that the taps over -radius..radius sum to 1. sigma <= 0: one tap of 1.
std::vector<float> gaussianTaps(double sigma, int max_radius);

struct WaterSpread {
  UwsParams params{};        // channels: 3 (sensor RGB); the spectral blur copies it with band_count
  std::vector<float> taps;   // the layers' taps in cells, layer k at params.tap_offset[k]
  double sigma1_px = 0;      // sigma_1 in pixels (layer k: sigma_1 sqrt(2^k))
};

// The grid of cells of factor x factor pixels over a width x height frame (channels 3, no layers yet).
WaterSpread waterSpreadGrid(int width, int height, int factor);

// Appends layer k's taps for a Gaussian of sigma_cells cells (radius capped at the grid's larger side) and
// sets its radius and offset in s.params. Layers are added in order, k = 0 first.
void addLayerTaps(WaterSpread& s, int k, double sigma_cells);

// The blur for an image of width x height with vertical half-angle atan(tan_half_fov_y): sigma_1 in
// pixels at the image's centre (2 tan_half_fov_y / height radians per pixel). The grid's cell is
// factor = max(1, floor(sigma_1 / 2)) pixels on a side, so that the narrowest layer is about 2 cells wide
// and the blur's cost follows the spread's angle, not the image's resolution (cells of 1 pixel up to
// about 4 pixels of sigma_1). Each layer's Gaussian in cells leaves out the spread that the cells' sums
// and the bilinear expansion add, (factor^2 - 1)/12 + factor^2/6 pixels^2.
WaterSpread makeWaterSpread(double g, int order, double tan_half_fov_y, int width, int height);

}  // namespace seasim
