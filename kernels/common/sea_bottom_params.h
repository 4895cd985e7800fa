/* sea_bottom_params.h — the height-field sea floor of 000 §5.4 as a kernel argument, shared by
 * kernels/sea_single.cl, kernels/sea_second.cl, host/passes/sea_heightfield.cpp (which static_asserts
 * the layout) and kernels/common/sea_bottom.h. Plain C on both sides, included before
 * host/math/kernel_math.h's namespaces (it holds no math).
 *
 * The depths themselves are a float buffer depth[j * nx + i] (m, positive down) beside this block;
 * node (i, j) lies at x = -extent/2 + i extent/(nx - 1), z = -extent/2 + j extent/(ny - 1).
 */
#ifndef SEASIM_SEA_BOTTOM_PARAMS_H /* also included by host/math/kernel_math.h */
#define SEASIM_SEA_BOTTOM_PARAMS_H

typedef struct {
  int nx;            /* nodes along x (image columns), >= 2 */
  int ny;            /* nodes along z (image rows), >= 2 */
  float extent;      /* m, side of the square the nodes span, centred at x = z = 0 */
  float min_depth;   /* m, shallowest node: nothing above it can be hit */
  float max_depth;   /* m, deepest node: every ray reaching it has hit the floor */
  int max_cells;     /* cap on the cells one ray walks (a near-horizontal ray stops there) */
  float pad0;
  float pad1;
} SeaHeightField;

#endif
