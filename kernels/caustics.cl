/* caustics.cl — caustics on a plane under the FFT ocean by flux conservation (004 §5.2.1): sunlight
 * crosses each facet of the displaced surface, refracts (Snell, 004 eq. 38–42 via optics.h), loses
 * the Fresnel reflectance (eq. 43–44) and is attenuated along its refracted path (Beer–Lambert),
 * and lands on the plane y = -d; the flux of each ray bundle is splatted there, so the irradiance
 * at depth is the flux per area the bundles arrive on (focussing raises it, spreading lowers it).
 *
 * Inputs: CausticsParams; the ocean pass's four FFT'd field slots (ocean.cl header: h, ∂h/∂x,
 * ∂h/∂z, Dx, Dz, ∂Dx/∂x, ∂Dz/∂z, ∂Dx/∂z on the N x N grid, D without λ).
 * Output: map[M x M], float bits in int words (for the atomic add), texel (i, j) centred at
 * ((i + ½) L/M, -d, (j + ½) L/M): irradiance on the plane divided by the sun's irradiance on a
 * horizontal surface above the water (so a flat surface gives T(θ) e^{-c d/cos θt} everywhere).
 *
 * Each of the (N s)² rays stands for an equal patch of the undisplaced grid, dA = (L/(N s))²; the
 * linear fields are bilinearly interpolated (periodic), and the flux through the displaced facet is
 * E_sun max(0, ŝ·(∂P/∂z × ∂P/∂x)) dA — the sun sees the facet's projected area, so the flux through
 * the whole patch is ŝ_y L² whatever the waves (the gradients integrate to 0 and J to 1 over a
 * period). Facets turned away from the sun receive nothing; shadowing by other waves is ignored.
 * The map wraps around (the patch is periodic), so no flux leaves it: Σ map·area·ŝ_y equals the
 * transmitted, attenuated flux (tests/kernels/caustics_test.cpp checks this to 1 %).
 *
 * Stiff cases: refracted rays that do not go down (possible on folded facets) and facets facing
 * away from the sun carry no flux; a surface point below the plane gets path length 0; a sun at or
 * below the horizon is handled by the host (empty map).
 */
#include "common/compat.h"
#include "common/optics.h"
#include "common/ocean_params.h"
#include "common/sea_surface.h"
#include "common/sea_second.h"
#include "common/sea_bottom_params.h"
/* sea_hf_intersect (sea_bottom.h needs sea_surface.h and sea_second.h before it) */
#include "common/sea_bottom.h"

/* float atomic add through compare-and-swap on the bit pattern (OpenCL 1.2 has no float atomics). */
static inline void atomic_add_float(volatile __global int* addr, float value) {
  int old_bits = *addr;
  while (true) {
    const int new_bits = as_int(as_float(old_bits) + value);
    const int seen = atomic_cmpxchg(addr, old_bits, new_bits);
    if (seen == old_bits) break;
    old_bits = seen;
  }
}

/* The eight linear fields at texel (i, j) (wrapped): f[0..7] = h, hx, hz, Dx, Dz, Dxx, Dzz, Dxz. */
static inline void fetch_fields(__global const float2* fields, int n, int i, int j, float* f) {
  i &= n - 1;
  j &= n - 1;
  const size_t nn = (size_t)n * (size_t)n;
  const size_t at = (size_t)j * n + i;
  const float2 a = fields[at], b = fields[nn + at], c = fields[2 * nn + at], d = fields[3 * nn + at];
  f[0] = a.x; f[1] = a.y; f[2] = b.x; f[3] = b.y;
  f[4] = c.x; f[5] = c.y; f[6] = d.x; f[7] = d.y;
}

/* The refracted sun ray from the surface sample at grid coordinates (u, v) (texel units: texel i
 * sits at x = i L/N; the fields wrap, so the patch tiles): its start *P on the displaced surface, its
 * unit direction *t into the water, and the return value projected · T, the flux it carries per unit
 * undisplaced area over the sun's normal irradiance (004 eq. 38–44). 0 for a facet turned from the
 * sun or a refracted ray that does not go down (possible on folded facets). */
static inline float surface_ray(__constant CausticsParams* p, __global const float2* fields, float u, float v,
                                float3* P, float3* t) {
  const int n = p->n;
  const float fu = floor(u), fv = floor(v);
  const int i0 = (int)fu, j0 = (int)fv;
  const float wx = u - fu, wz = v - fv;
  float f00[8], f10[8], f01[8], f11[8], f[8];
  fetch_fields(fields, n, i0, j0, f00);
  fetch_fields(fields, n, i0 + 1, j0, f10);
  fetch_fields(fields, n, i0, j0 + 1, f01);
  fetch_fields(fields, n, i0 + 1, j0 + 1, f11);
  for (int c = 0; c < 8; ++c)
    f[c] = (1.0f - wz) * ((1.0f - wx) * f00[c] + wx * f10[c]) + wz * ((1.0f - wx) * f01[c] + wx * f11[c]);

  const float lambda = p->choppiness;
  const float cell = p->patch_size / (float)n;
  *P = (float3)(u * cell + lambda * f[3], f[0], v * cell + lambda * f[4]);
  const float3 tx = (float3)(1.0f + lambda * f[5], f[1], lambda * f[7]);
  const float3 tz = (float3)(lambda * f[7], f[2], 1.0f + lambda * f[6]);
  const float3 n_area = cross(tz, tx); /* per unit undisplaced area */
  const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  const float projected = dot(sun, n_area);
  const float len = length(n_area);
  if (!(projected > 0.0f) || !(len > 0.0f)) return 0.0f;
  const float3 nrm = n_area / len;
  const float T = 1.0f - fresnel_reflectance(projected / len, 1.0f, p->ior);
  refract_dir(-sun, nrm, 1.0f / p->ior, t); /* air -> water: no TIR */
  if (!((*t).y < 0.0f)) return 0.0f;
  return projected * T;
}

__kernel void caustics_splat(__constant CausticsParams* p, __global const float2* fields,
                             volatile __global int* map) {
  const int I = get_global_id(0), J = get_global_id(1);
  const int n = p->n, s = p->supersample;
  if (I >= n * s || J >= n * s) return;

  float3 P, t;
  const float weight = surface_ray(p, fields, ((float)I + 0.5f) / (float)s, ((float)J + 0.5f) / (float)s, &P, &t);
  if (!(weight > 0.0f)) return;
  const float L = p->patch_size, cell = L / (float)n;
  const float path = fmax(P.y + p->plane_depth, 0.0f) / (-t.y);
  const float3 Q = P + path * t;
  const float dA = (cell / (float)s) * (cell / (float)s);
  const float flux = weight * dA * beer_lambert(p->attenuation, path);
  const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);

  /* Bilinear splat, periodic; the map stores flux / (texel area · ŝ_y). */
  const int m = p->map_size;
  const float texel = L / (float)m;
  const float scale = flux / (texel * texel * sun.y);
  const float qx = Q.x / texel - 0.5f, qz = Q.z / texel - 0.5f;
  const float gx = floor(qx), gz = floor(qz);
  const float ax = qx - gx, az = qz - gz;
  const int mx = (int)(gx - floor(gx / (float)m) * (float)m); /* gx mod m, gx may be negative */
  const int mz = (int)(gz - floor(gz / (float)m) * (float)m);
  const int x0 = mx % m, z0 = mz % m;
  const int x1 = (x0 + 1) % m, z1 = (z0 + 1) % m;
  atomic_add_float(&map[z0 * m + x0], scale * (1.0f - ax) * (1.0f - az));
  atomic_add_float(&map[z0 * m + x1], scale * ax * (1.0f - az));
  atomic_add_float(&map[z1 * m + x0], scale * (1.0f - ax) * az);
  atomic_add_float(&map[z1 * m + x1], scale * ax * az);
}

/* The same splat onto a height-field floor (000 §5.4, [bottom] type = "heightfield"), which is not
 * periodic: the ocean patch is tiled `tiles` × `tiles` times from (origin_x, origin_z) so the surface
 * covers the floor's square plus a margin the refracted rays can drift across, each ray walks to the
 * floor (common/sea_bottom.h sea_hf_intersect), and its flux lands in the M × M map over the floor's
 * square [-E/2, E/2]²: texel (i, j) centred at (-E/2 + (i + ½) E/M, -E/2 + (j + ½) E/M). Flux landing
 * outside the square is dropped. Values: the irradiance on the floor itself (flux per unit floor area:
 * per horizontal area times the floor normal's y) over the sun's irradiance on a horizontal surface
 * above the water, so a flat sea gives T(θ) e^{-c l} (-t·n̂)/cos θt, l the refracted path length, t
 * its direction and n̂ the floor's normal (the Lambert cosine of the slope). Rays that miss the floor
 * within the walk (a near-horizontal ray) carry no flux. */
__kernel void caustics_splat_floor(__constant CausticsParams* p, __global const float2* fields,
                                   __constant SeaHeightField* hf, __global const float* depth, int tiles,
                                   float origin_x, float origin_z, volatile __global int* map) {
  const int I = get_global_id(0), J = get_global_id(1);
  const int n = p->n, s = p->supersample;
  if (I >= n * s * tiles || J >= n * s * tiles) return;

  /* Surface-grid texel units from the world origin (texel i at x = i L/N, as in the plane splat). */
  const float cell = p->patch_size / (float)n;
  float3 P, t;
  const float weight = surface_ray(p, fields, origin_x / cell + ((float)I + 0.5f) / (float)s,
                                   origin_z / cell + ((float)J + 0.5f) / (float)s, &P, &t);
  if (!(weight > 0.0f)) return;
  /* Long enough to pass the deepest node from the highest crest. */
  const float t_max = (hf->max_depth + fmax(P.y, 0.0f) + 1.0f) / (-t.y);
  float t_hit;
  float3 floor_normal;
  if (!sea_hf_intersect(hf, depth, P, t, t_max, &t_hit, &floor_normal)) return;
  const float path = fmax(t_hit - fmax(P.y, 0.0f) / (-t.y), 0.0f); /* the part in the water */
  const float3 Q = P + t_hit * t;
  const float dA = (cell / (float)s) * (cell / (float)s);
  const float flux = weight * dA * beer_lambert(p->attenuation, path);

  const float3 sun = (float3)(p->sun_dir[0], p->sun_dir[1], p->sun_dir[2]);
  const int m = p->map_size;
  const float E = hf->extent, texel = E / (float)m;
  const float scale = flux * floor_normal.y / (texel * texel * sun.y);
  const float qx = (Q.x + 0.5f * E) / texel - 0.5f, qz = (Q.z + 0.5f * E) / texel - 0.5f;
  const float gx = floor(qx), gz = floor(qz);
  if (!(gx >= -1.0f && gz >= -1.0f && gx < (float)m && gz < (float)m)) return; /* off the floor's square */
  const int x0 = (int)gx, z0 = (int)gz;
  const float ax = qx - gx, az = qz - gz;
  const float w[4] = {(1.0f - ax) * (1.0f - az), ax * (1.0f - az), (1.0f - ax) * az, ax * az};
  const int xs[4] = {x0, x0 + 1, x0, x0 + 1}, zs[4] = {z0, z0, z0 + 1, z0 + 1};
  for (int c = 0; c < 4; ++c)
    if (xs[c] >= 0 && xs[c] < m && zs[c] >= 0 && zs[c] < m) atomic_add_float(&map[zs[c] * m + xs[c]], scale * w[c]);
}
