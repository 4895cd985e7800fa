/* water_spread.cl — the water's point-spread (common/water_spread.h derives it): the light
 * kd_multiple.cl kept apart as scattered by small angles, blurred by the phase's small angles and added
 * back into the frame (sensor RGB, or spectral.exr's bands: params->channels per pixel).
 *
 * Four passes on a grid of cells of factor x factor pixels (UwsParams, common/water_spread_params.h):
 *  - spread_reduce: each cell sums its pixels' moments (F, F E per channel; light-weighted F D and F) and
 *    splits each channel's light F between the layers by its mean count E = (F E)/F (uws_layer_share);
 *    it keeps the cell's mean S (the G-buffer's, what the cell's pixels end on) and its light's mean
 *    distance D;
 *  - spread_rows, spread_columns: each layer blurred by its Gaussian along x, then along y, the layers
 *    summed; each tap weighed by what the spread can reach, spread_reach(S of the cell it lands on, D of
 *    the cell it comes from) (the column pass takes the row pass's cell's own D for the light it
 *    gathered, an approximation where depths differ along a row). The grid's edges are clamped: a cell
 *    beyond it is taken as the edge's (the light from outside the frame is not known);
 *  - spread_expand: each pixel adds the blurred light of the cells around it, bilinearly, per pixel of
 *    the cell (a cell holds a sum).
 * With factor 1 a cell is a pixel. Work-items are cells (pixels for spread_expand); each loops over
 * layers, taps and channels. */
#include "common/compat.h"
#include "common/band_lanes.h"
#include "common/water_spread_params.h"
#include "common/water_spread.h"

/* The share of a tap's light that reaches a cell ending at s_dest from light that came from d_src. */
float spread_reach(float s_dest, float d_src) { return d_src > s_dest ? s_dest / d_src : 1.0f; }

/* forward: [pixel][2][channels]; depth: [pixel][2]; geom: the G-buffer (S in .x). Writes layers
 * [cell][UWS_LAYERS][channels], cell_s and cell_d [cell]. */
__kernel void spread_reduce(__constant UwsParams* p, __global const float4* geom, __global const float* depth,
                            __global const float* forward, __global float* layers, __global float* cell_s,
                            __global float* cell_d) {
  const int cx = get_global_id(0);
  const int cy = get_global_id(1);
  if (cx >= p->low_width || cy >= p->low_height) return;
  const int c_n = p->channels;
  const size_t cell = (size_t)cy * (size_t)p->low_width + cx;
  __global float* out = layers + cell * UWS_LAYERS * (size_t)c_n;
  const int x0 = cx * p->factor, y0 = cy * p->factor;
  const int x1 = min(x0 + p->factor, p->width), y1 = min(y0 + p->factor, p->height);
  float s_sum = 0.0f, d_num = 0.0f, d_den = 0.0f;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      const size_t pixel = (size_t)y * (size_t)p->width + x;
      s_sum += fmin(geom[pixel].x, 1e4f);
      d_num += depth[2 * pixel];
      d_den += depth[2 * pixel + 1];
    }
  const float s_mean = s_sum / (float)((x1 - x0) * (y1 - y0));
  cell_s[cell] = s_mean;
  cell_d[cell] = d_den > 0.0f ? d_num / d_den : s_mean;
  for (int c = 0; c < c_n; ++c) {
    float f = 0.0f, fe = 0.0f;
    for (int y = y0; y < y1; ++y)
      for (int x = x0; x < x1; ++x) {
        __global const float* in = forward + ((size_t)y * (size_t)p->width + x) * 2 * (size_t)c_n;
        f += in[c];
        fe += in[c_n + c];
      }
    const float mean_n = f > 0.0f ? fe / f : 1.0f;
    for (int k = 0; k < UWS_LAYERS; ++k) out[k * c_n + c] = f * uws_layer_share(mean_n, k);
  }
}

/* Adds layer k's taps along one axis of the grid into out[channels]: the cells base + clamp(pos + j, 0,
 * len - 1) * step of `in` ([cell][UWS_LAYERS][channels]), each weighed by what it can reach of s_dest. */
void spread_axis(__constant UwsParams* p, __global const float* taps, int k, float s_dest, __global const float* cell_d,
                 __global const float* in, size_t base, int pos, int len, size_t step, __global float* out) {
  const int c_n = p->channels;
  __global const float* t = taps + p->tap_offset[k];
  for (int j = -p->radius[k]; j <= p->radius[k]; ++j) {
    const size_t src = base + (size_t)clamp(pos + j, 0, len - 1) * step;
    const float w = t[abs(j)] * spread_reach(s_dest, cell_d[src]);
    __global const float* x = in + (src * UWS_LAYERS + k) * (size_t)c_n;
    for (int c = 0; c < c_n; ++c) out[c] += w * x[c];
  }
}

/* Writes rows [cell][UWS_LAYERS][channels]: each layer blurred along x. */
__kernel void spread_rows(__constant UwsParams* p, __global const float* taps, __global const float* cell_s,
                          __global const float* cell_d, __global const float* layers, __global float* rows) {
  const int cx = get_global_id(0);
  const int cy = get_global_id(1);
  if (cx >= p->low_width || cy >= p->low_height) return;
  const int c_n = p->channels;
  const size_t row = (size_t)cy * (size_t)p->low_width;
  for (int k = 0; k < UWS_LAYERS; ++k) {
    __global float* out = rows + ((row + cx) * UWS_LAYERS + k) * (size_t)c_n;
    for (int c = 0; c < c_n; ++c) out[c] = 0.0f;
    spread_axis(p, taps, k, cell_s[row + cx], cell_d, layers, row, cx, p->low_width, 1, out);
  }
}

/* Writes blurred [cell][channels]: each layer of rows blurred along y, the layers summed. */
__kernel void spread_columns(__constant UwsParams* p, __global const float* taps, __global const float* cell_s,
                             __global const float* cell_d, __global const float* rows, __global float* blurred) {
  const int cx = get_global_id(0);
  const int cy = get_global_id(1);
  if (cx >= p->low_width || cy >= p->low_height) return;
  const int c_n = p->channels;
  const size_t cell = (size_t)cy * (size_t)p->low_width + cx;
  __global float* out = blurred + cell * (size_t)c_n;
  for (int c = 0; c < c_n; ++c) out[c] = 0.0f;
  for (int k = 0; k < UWS_LAYERS; ++k)
    spread_axis(p, taps, k, cell_s[cell], cell_d, rows, cx, cy, p->low_height, (size_t)p->low_width, out);
}

/* The cell's light per pixel (the cells at the frame's right and bottom edges may hold fewer). */
float spread_cell_pixels(__constant UwsParams* p, int cx, int cy) {
  return (float)((min(p->factor, p->width - cx * p->factor)) * (min(p->factor, p->height - cy * p->factor)));
}

/* Adds into frame [pixel][channels] the blurred cells, bilinear between the four nearest cell centres. */
__kernel void spread_expand(__constant UwsParams* p, __global const float* blurred, __global float* frame) {
  const int x = get_global_id(0);
  const int y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int c_n = p->channels;
  const float u = ((float)x + 0.5f) / (float)p->factor - 0.5f;
  const float v = ((float)y + 0.5f) / (float)p->factor - 0.5f;
  const int ux = (int)floor(u), vy = (int)floor(v);
  const float fx = u - (float)ux, fy = v - (float)vy;
  const int x0 = clamp(ux, 0, p->low_width - 1), x1 = clamp(ux + 1, 0, p->low_width - 1);
  const int y0 = clamp(vy, 0, p->low_height - 1), y1 = clamp(vy + 1, 0, p->low_height - 1);
  const float w00 = (1.0f - fx) * (1.0f - fy) / spread_cell_pixels(p, x0, y0);
  const float w10 = fx * (1.0f - fy) / spread_cell_pixels(p, x1, y0);
  const float w01 = (1.0f - fx) * fy / spread_cell_pixels(p, x0, y1);
  const float w11 = fx * fy / spread_cell_pixels(p, x1, y1);
  __global const float* b00 = blurred + ((size_t)y0 * (size_t)p->low_width + x0) * (size_t)c_n;
  __global const float* b10 = blurred + ((size_t)y0 * (size_t)p->low_width + x1) * (size_t)c_n;
  __global const float* b01 = blurred + ((size_t)y1 * (size_t)p->low_width + x0) * (size_t)c_n;
  __global const float* b11 = blurred + ((size_t)y1 * (size_t)p->low_width + x1) * (size_t)c_n;
  __global float* out = frame + ((size_t)y * (size_t)p->width + x) * (size_t)c_n;
  for (int c = 0; c < c_n; ++c) out[c] += w00 * b00[c] + w10 * b10[c] + w01 * b01[c] + w11 * b11[c];
}
