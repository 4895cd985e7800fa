/* water_spread_params.h — the block of kernels/water_spread.cl (the water's point-spread;
 * common/water_spread.h derives it), built on the host (host/underwater/water_spread_setup.*, which
 * static_asserts its layout). Plain C on both sides, no math.
 *
 * kd_multiple.cl keeps per pixel the moments of its forward light: [pixel][2][channel] (F, then F E;
 * channels: 3 for sensor RGB, band_count for spectral.exr) and [pixel][2] (the sums of light-weighted F D
 * and F). The blur runs on a grid of cells of factor x factor pixels (1 where the spread is a few pixels
 * wide; coarser where it is wider, so that its cost does not grow with the image's resolution): layer k is
 * blurred there by a Gaussian of taps[tap_offset[k] + j], |offset| j = 0..radius[k] cells, normalised over
 * -radius..radius (so the blur keeps the light; the grid's edges are clamped). */
#ifndef SEASIM_WATER_SPREAD_PARAMS_H
#define SEASIM_WATER_SPREAD_PARAMS_H

#define UWS_LAYERS 4 /* the ladder of scattering counts n_k = 1, 2, 4, 8 (common/water_spread.h) */

typedef struct {
  int width;      /* the frame, pixels */
  int height;
  int low_width;  /* the blur's grid, cells: ceil(width / factor) */
  int low_height;
  int factor;     /* a cell's side, pixels */
  int channels;
  int pad0;
  int pad1;
  int radius[UWS_LAYERS];     /* per layer, cells */
  int tap_offset[UWS_LAYERS]; /* per layer, into the taps buffer */
} UwsParams;

#endif
