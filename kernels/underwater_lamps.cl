/* underwater_lamps.cl — spotlights in the water (divers' torches, ROV lamps): paper 001's sampling
 * planes in the water's spectral medium, added into the underwater frame that kd_multiple.cl wrote
 * (sun K_d multiple scattering, froxels, caustics). The math and its derivation: common/underwater_lamps.h.
 *
 * Per pixel, per lamp: the part of the view ray inside the cone up to the G-buffer's hit (S), n planes
 * with m sub-samples each (H P by exact shadow rays against the objects), the far field beyond K r by 8
 * Gauss–Legendre samples in the lamp's angle; the bands in vector lanes over blocks of planes and samples
 * (lamp_beam_block), each with its own σ_s,
 * σ_t (002: Jerlov/IOP data) and the lamp's I(λ). A hit object or bottom adds the lamp's direct light.
 * Bands go to RGB through the sensor weights (002 eq. 4.8), added to rgb (and to spectral with
 * SEASIM_SPECTRAL_OUTPUT).
 *
 * Inputs: UwParams (camera, g, bottom), UwBand[band_count] (b, c, bottom albedo, sensor weights),
 * albedo[object * band_count + band], UwObject[], the G-buffer of raycast.cl (geom, material),
 * UwLampParams, UwLamp[lamp_count], lamp_spectra[lamp * band_count + band] (W sr⁻¹ nm⁻¹ on the axis).
 * Output: rgb[3 * pixels] (+=), spectral[band_count * pixels] (+=, SEASIM_SPECTRAL_OUTPUT), and with
 * SEASIM_LAYER_LAMPS (outputs.layers) the same light into lamps_layer[3 * pixels] (+=; kd_multiple.cl
 * zeroed it) so that lamp and sun light can be told apart; with SEASIM_LAYER_BANDS as well per band into
 * layer_bands[pixel][5][band_count]'s slot 3 (kd_multiple.cl's layout; spectral.exr's lamps layer).
 * SEASIM_LAYER_LAMPS_SPLIT (outputs.layers lamps_single, lamps_multiple; kd_multiple zeroed the buffer):
 * lamps_split[split_stride * pixel + split_single_at + channel] += the light scattered at most once in the
 * water (the lit surface seen unscattered, e^{-c S}, and the beam's planes and tail: 001's single
 * scattering with the water's own σ_s, σ_t and g), and at split_multiple_at the rest of the model's light
 * (an offset < 0: not asked). The "single" model's rest is 0; the "orders" model's is its orders of
 * multiple scattering and the surfaces' light scattered on its way to the eye (T_view - e^{-c S}). The
 * "delta_m" model has no single-scattering term of its own (its whole light comes from the scaled
 * medium): with single_apart = 1 the single part's band factors are evaluated once more in plain_bands
 * with plain_g, the water as it is (on the same shadow rays), and the rest is delta-M's light minus it (it can be negative where delta-M's scaled phase
 * puts less light than the unscaled one, at small scattering angles).
 * Defines: SEASIM_HAS_OBJECTS (shadow rays), SEASIM_SPECTRAL_OUTPUT, SEASIM_LAMPS_ORDERS (the "orders"
 * model, common/underwater_lamps_ms.h: the lamps' light scattered more than once, from ms_table's
 * blurred profiles, ms_orders orders, ms_steps quadrature steps per view ray, the orders' weights per
 * band from ms_weights (host/underwater/lamps_ms_weights.h; the stretch exponent κ is in it); the
 * surfaces' light then reaches the eye through T_view instead of e^{-σ_t S}, the bottom's direct light
 * blurred in its terms k >= 1 (uw_ms_blurred_bottom); and the lit
 * bottom's glow from ms_glow, 4 + band_count floats per lamp, host/underwater/lamps_bottom_glow.h; the
 * bottom's halo, the orders' light on the bottom sent back up, from the weight table's halo rows).
 * SEASIM_LAMPS_MS_LATTICE (ms_step > 1 pixels in a quality.lamps_ms_cell_deg cell): the part of the
 * orders model that varies smoothly across the image (lamp_orders_smooth: the orders and the glow along
 * the view ray, the orders' light on the surfaces, the bottom's blur) is evaluated first by
 * underwater_lamps_lattice on every ms_step-th pixel in x and y, per band into ms_lattice (ms_map_w x
 * ms_map_h entries), and read by underwater_lamps bilinearly from the lattice pixels on the same surface
 * (lamp_lattice_read); a pixel at a silhouette, at the lit patch's edge or near a lamp in view evaluates
 * it itself. The direct light and 001's planes stay per pixel.
 * Stiff cases: common/underwater_lamps.h; never NaN/Inf (every division is by a clamped distance).
 */
#include "common/compat.h"
#include "common/gauss_legendre.h"
#include "common/band_lanes.h"
#include "common/optics.h"
#include "common/band_lanes_math.h"
#include "common/shafts.h"
#include "common/underwater_params.h"
#include "common/underwater.h"
#include "common/underwater_hit_lanes.h"
#include "common/underwater_lamps_params.h"
#include "common/underwater_lamps.h"
#if SEASIM_LAMPS_ORDERS
#include "common/path_tracer.h"
#include "common/polynomial_trig.h"
#include "common/underwater_lamps_ms.h"
#endif

#define v3(a) ((float3)((a)[0], (a)[1], (a)[2]))

/* H: 1 when nothing lies between the point p and the lamp (objects only: the bottom and the surface
 * cannot come between two points under water above the bottom); only the candidates are tested
 * (uw_objects_block: UW_ALL_OBJECTS, or those near the fan of shadow rays, uw_objects_near_triangle). */
static inline float lamp_visible(__global const UwObject* objects, int count, unsigned int candidates, float3 p,
                                 float3 lamp) {
#if SEASIM_HAS_OBJECTS
  const float3 w = lamp - p;
  const float s = length(w);
  if (!(s > 0.0f)) return 1.0f;
  return uw_objects_block(objects, count, candidates, p, w / s, 0.0f, s) ? 0.0f : 1.0f;
#else
  return 1.0f;
#endif
}

/* lamp_visible per lane, as a mask: whether a candidate object lies between the point o + t d (t per lane) and
 * the lamp. */
static inline maskb lamp_blocked_b(__global const UwObject* objects, int count, unsigned int candidates, float3 o,
                                   float3 d, realb t, float3 lamp) {
#if SEASIM_HAS_OBJECTS
  const real3b p = uw_along3b(uw_splat3b(o), t, uw_splat3b(d));
  const real3b w = uw_r3b(lamp.x - p.x, lamp.y - p.y, lamp.z - p.z);
  const realb s = sqrt(uw_dot3b(w, w));
  const maskb apart = s > 0.0f;
  const realb inv = 1.0f / SELECTB(apart, s, SPLATB(1.0f));
  return apart & uw_objects_block_b(objects, count, candidates, p, uw_r3b(w.x * inv, w.y * inv, w.z * inv),
                                    SPLATB(0.0f), s);
#else
  return SPLATB(1.0f) < 0.0f; /* no objects: nothing in the way */
#endif
}

#if SEASIM_LAMPS_ORDERS
/* 1 when the lamp's light leaves it: the lamp is inside no sphere or box (a sealed lamp has no multiple
 * scattering either; its single scattering and direct light are 0 by the shadow rays). */
static inline float lamp_escapes(__global const UwObject* objects, int count, float3 lamp) {
#if SEASIM_HAS_OBJECTS
  for (int k = 0; k < count; ++k) {
    __global const UwObject* ob = &objects[k];
    const float3 a = (float3)(ob->a[0], ob->a[1], ob->a[2]);
    const float3 b = (float3)(ob->b[0], ob->b[1], ob->b[2]);
    if (ob->type == UW_SPHERE && dot(lamp - a, lamp - a) < ob->a[3] * ob->a[3]) return 0.0f;
    if (ob->type == UW_BOX && all(lamp > a) && all(lamp < b)) return 0.0f;
  }
#endif
  return 1.0f;
}
#endif

/* The pixel's lamp light so far, in sensor RGB (002 eq. 4.8), and where its per-band values go. */
typedef struct {
  float r, g, b;
  float single_r, single_g, single_b; /* SEASIM_LAYER_LAMPS_SPLIT: the part scattered at most once */
  int to_single;                       /* whether lamp_add's terms are single scattering too */
  int pixel, nb;
  __global float* spectral;    /* SEASIM_SPECTRAL_OUTPUT */
  __global float* layer_bands; /* SEASIM_LAYER_BANDS: slot 3 (lamps) of kd_multiple.cl's layout */
  __global float* band_sums;   /* SEASIM_LAMPS_MS_LATTICE, the lattice's kernel: per band instead (see there) */
} LampSums;

/* Band i's light L into the image's sums and per-band images (to_image) and into the single-scattering
 * sums (to_single). */
static inline void lamp_add_to(LampSums* o, __global const UwBand* bands, int i, float L, int to_image, int to_single) {
#if SEASIM_LAMPS_MS_LATTICE
  if (o->band_sums) {
    if (to_image) o->band_sums[i] += L;
#if SEASIM_LAYER_LAMPS_SPLIT
    if (to_single) o->band_sums[o->nb + i] += L;
#endif
    return;
  }
#endif
  if (to_image) {
    o->r += L * bands[i].w_r;
    o->g += L * bands[i].w_g;
    o->b += L * bands[i].w_b;
#if SEASIM_SPECTRAL_OUTPUT
    o->spectral[(size_t)o->pixel * o->nb + i] += L;
#endif
#if SEASIM_LAYER_BANDS
    o->layer_bands[((size_t)o->pixel * 5 + 3) * o->nb + i] += L;
#endif
  }
#if SEASIM_LAYER_LAMPS_SPLIT
  if (to_single) {
    o->single_r += L * bands[i].w_r;
    o->single_g += L * bands[i].w_g;
    o->single_b += L * bands[i].w_b;
  }
#endif
}

static inline void lamp_add(LampSums* o, __global const UwBand* bands, int i, float L) {
  lamp_add_to(o, bands, i, L, 1, o->to_single);
}

/* Bands b0 .. b0 + count - 1 of L in lanes, added band by band (lamp_add_to). */
static inline void lamp_add_lanes(LampSums* o, __global const UwBand* bands, int b0, int count, realb L, int to_image,
                                  int to_single) {
  float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  *(realb*)lanes = L;
  for (int q = 0; q < count; ++q) lamp_add_to(o, bands, b0 + q, lanes[q], to_image, to_single);
}

/* The water's a and b, the bottom's albedo and a lamp's I for bands b0 .. b0 + count - 1 in lanes (0 in
 * the lanes past count). */
typedef struct {
  realb a, b, rho, I;
} LampBandLanes;

static inline LampBandLanes lamp_band_lanes(__global const UwBand* bands, __global const float* I, int b0, int count) {
  float a[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  float b[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  float rho[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
  for (int q = 0; q < SEASIM_BAND_LANES; ++q) {
    a[q] = q < count ? bands[b0 + q].a : 0.0f;
    b[q] = q < count ? bands[b0 + q].b : 0.0f;
    rho[q] = q < count ? bands[b0 + q].bottom_albedo : 0.0f;
  }
  LampBandLanes l = {.a = *(realb*)a, .b = *(realb*)b, .rho = *(realb*)rho, .I = load_lanes(I + b0, count)};
  return l;
}

/* The media the lamps' light crosses: the image's (the water, delta-M scaled in that model) and, with
 * single_apart (SEASIM_LAYER_LAMPS_SPLIT, the delta-M model), the water as it is, whose single scattering
 * goes into lamps_single alone. The shadow rays are the same for both: only the band factors differ. */
typedef struct {
  __global const UwBand* bands;
  float g;
  __global const UwBand* plain;
  float plain_g;
  int single_apart;
} LampMedia;

/* The view ray and its first surface, as every lamp sees them. */
typedef struct {
  float3 o, d, n;
  float S, t_end;
  int lit_surface;
  int bottom; /* the surface is the flat bottom (its lamp light is blurred on the way to the eye) */
  __global const float* alb; /* the surface's albedo per band, every alb_stride floats */
  int alb_stride;
} LampRay;

#if SEASIM_LAMPS_ORDERS
/* The bottom's glow under one lamp (common/underwater_lamps_ms.h): the lit patch as a Lambertian source
 * at glow[0..2] of radius glow[3], strengths glow[4 + i] (the lamp's direct light on the bottom; its
 * orders' light there is lamp_halo_ray's), on the surface the pixel sees (through T_view), orders
 * 0..ms_orders. Order 0 is light scattered once in the water (lamps_single); the rest is multiple. */
static inline void lamp_glow_surface(__constant UwParams* p, __global const UwBand* bands, __global const float* glow,
                                     __global const float* ms_rows, __global const float* ms_weights, int ms_orders,
                                     __global const float* I, const LampRay* v, LampSums* o) {
  const int nb = p->band_count;
  const float radius = glow[3];
  if (!(radius > 0.0f) || !v->lit_surface) return;
  const float3 c = (float3)(glow[0], glow[1], glow[2]), up = (float3)(0.0f, 1.0f, 0.0f);
  __global const float* J = glow + 4;
  __global const float* glow_rows = uw_ms_glow_weight_rows(ms_weights, nb, ms_orders);
  const float3 P = v->o + v->S * v->d;
  int wj;
  float wf;
  uw_ms_weight_index(ms_weights, length(P - c), &wj, &wf);
  for (int i = 0; i < nb; ++i) {
    float first, wn[UW_MS_MAX_ORDERS + 1];
    uw_ms_weights_at(glow_rows, nb, i, ms_orders + 1, wj, wf, wn);
    const float E = uw_ms_glow_surface_weighted(P, v->n, c, up, radius, ms_rows, ms_orders, wn, &first);
    if (!(E > 0.0f)) continue;
    const float alb = I[i] * v->alb[i * v->alb_stride];
    lamp_add_to(o, bands, i, alb * J[i] * E * uw_ms_view_transmission(bands[i].a, bands[i].b, p->g, v->S, ms_orders), 1, 0);
    lamp_add_to(o, bands, i, alb * J[i] * first * exp(-bands[i].c * v->S), 0, 1);
  }
}

/* The same glow along the view ray: the steps' geometry once (distance, weight, the table's entry, each
 * order's phase), then the bands in lanes, each run of lanes summed over the steps before it is added. */
static inline void lamp_glow_ray(__constant UwParams* p, __global const UwBand* bands, __global const float* glow,
                                 __global const float* ms_weights, int ms_orders, int ms_steps, float c_min,
                                 __global const float* I, const LampRay* v, LampSums* o) {
  const int nb = p->band_count;
  const float radius = glow[3];
  if (!(radius > 0.0f)) return;
  const float3 c = (float3)(glow[0], glow[1], glow[2]), up = (float3)(0.0f, 1.0f, 0.0f);
  __global const float* J = glow + 4;
  __global const float* glow_rows = uw_ms_glow_weight_rows(ms_weights, nb, ms_orders);
  UwMsRay q;
  const int steps = uw_ms_glow_steps(ms_steps);
  uw_ms_ray(v->o, v->d, c, radius, v->t_end, uw_ms_ray_cap(c_min), steps, &q);
  if (!(q.dv > 0.0f)) return;
  float st_t[UW_MS_MAX_STEPS], st_w[UW_MS_MAX_STEPS], st_f[UW_MS_MAX_STEPS];
  int st_j[UW_MS_MAX_STEPS];
  float st_geo[UW_MS_MAX_STEPS * (UW_MS_MAX_ORDERS + 1)];
  int used = 0;
  for (int j = 0; j < steps; ++j) {
    const float t = uw_ms_ray_t(&q, j);
    float s, ca;
    uw_lamp_at(v->o, v->d, c, t, &s, &ca);
    const float cos_psi = s > 0.0f ? dot(v->o + t * v->d - c, up) / s : 0.0f;
    if (!(cos_psi > 0.0f)) continue;
    st_t[used] = t;
    st_w[used] = cos_psi * uw_ms_glow_ray_weight(&q, t, s, radius);
    uw_ms_weight_index(ms_weights, s, &st_j[used], &st_f[used]);
    float* geo = st_geo + used * (UW_MS_MAX_ORDERS + 1);
    float gk = p->g;
    geo[0] = uw_ms_glow_phase(ca, gk);
    for (int k = 1; k <= ms_orders; ++k) {
      gk *= p->g;
      geo[k] = uw_ms_glow_phase(ca, gk);
    }
    ++used;
  }
  for (int b0 = 0; b0 < nb && used > 0; b0 += SEASIM_BAND_LANES) {
    const int in_run = min(SEASIM_BAND_LANES, nb - b0);
    const LampBandLanes band = lamp_band_lanes(bands, I, b0, in_run);
    const realb c_t = band.a + band.b;
    realb all = SPLATB(0.0f), first = SPLATB(0.0f);
    for (int u = 0; u < used; ++u) {
      realb wn[UW_MS_MAX_ORDERS + 1];
      uw_ms_weights_at_b(glow_rows, nb, b0, ms_orders + 1, st_j[u], st_f[u], wn);
      const float* geo = st_geo + u * (UW_MS_MAX_ORDERS + 1);
      const realb f = exp(-(c_t * st_t[u])) * st_w[u];
      const realb order0 = wn[0] * geo[0];
      realb sum = order0;
      for (int k = 1; k <= ms_orders; ++k) sum += wn[k] * geo[k];
      all += f * sum;
      first += f * order0;
    }
    const maskb scatters = band.b > 0.0f;
    const realb scale = band.I * band.b * load_lanes(J + b0, in_run);
    lamp_add_lanes(o, bands, b0, in_run, SELECTB(scatters, scale * all, SPLATB(0.0f)), 1, 0);
    lamp_add_lanes(o, bands, b0, in_run, SELECTB(scatters, scale * first, SPLATB(0.0f)), 0, 1);
  }
}

/* The bottom's halo along the view ray (common/underwater_lamps_ms.h, uw_ms_halo_inscatter): the orders'
 * light on the bottom right below each step, sent back up as from a uniform Lambertian plane and
 * scattered towards the eye as the glow's light is (F from the weight table's halo rows). The steps'
 * geometry once (the foot's, uw_ms_surface_geometry, and the table's entries), then the bands in lanes
 * with their weights at the foot, as in lamp_glow_ray. */
static inline void lamp_halo_ray(__constant UwParams* p, __global const UwBand* bands, __constant UwLampParams* lp,
                                 __global const UwLamp* L, __global const float* I, __global const float* ms_rows,
                                 __global const float* ms_weights, int ms_orders, int ms_steps, float c_min,
                                 const LampRay* v, LampSums* o) {
  const float depth = p->bottom_depth;
  if (!(depth > 0.0f)) return;
  const int nb = lp->band_count;
  const float3 lamp = v3(L->position), axis = v3(L->direction), up = (float3)(0.0f, 1.0f, 0.0f);
  const int steps = uw_ms_glow_steps(ms_steps);
  UwMsRay q;
  uw_ms_ray(v->o, v->d, (float3)(lamp.x, -depth, lamp.z), lp->s_min, v->t_end, uw_ms_ray_cap(c_min), steps, &q);
  if (!(q.dv > 0.0f)) return;
  __global const float* halo_rows = uw_ms_halo_rows(ms_weights, nb, ms_orders);
  int hm;
  float hf;
  uw_ms_halo_dir_index(-v->d.y, &hm, &hf);
  float st_t[UW_MS_MAX_STEPS], st_dt[UW_MS_MAX_STEPS], st_f[UW_MS_MAX_STEPS], st_zf[UW_MS_MAX_STEPS];
  int st_j[UW_MS_MAX_STEPS], st_zj[UW_MS_MAX_STEPS];
  float st_geo[UW_MS_MAX_STEPS * UW_MS_MAX_ORDERS];
  int used = 0;
  for (int j = 0; j < steps; ++j) {
    const float t = uw_ms_ray_t(&q, j);
    const float3 x = v->o + t * v->d;
    const float z = x.y + depth;
    if (!(z >= 0.0f)) continue;
    const float s = uw_ms_surface_geometry((float3)(x.x, -depth, x.z), up, lamp, axis, lp->s_min, ms_rows, ms_orders,
                                           st_geo + used * UW_MS_MAX_ORDERS);
    if (!(s > 0.0f)) continue;
    st_t[used] = t;
    st_dt[used] = uw_ms_ray_dt(&q, t);
    uw_ms_weight_index(ms_weights, s, &st_j[used], &st_f[used]);
    uw_ms_halo_z_index(ms_weights, z, &st_zj[used], &st_zf[used]);
    ++used;
  }
  for (int b0 = 0; b0 < nb && used > 0; b0 += SEASIM_BAND_LANES) {
    const int in_run = min(SEASIM_BAND_LANES, nb - b0);
    const LampBandLanes band = lamp_band_lanes(bands, I, b0, in_run);
    const realb c_t = band.a + band.b;
    realb acc = SPLATB(0.0f);
    for (int u = 0; u < used; ++u) {
      const realb E = uw_ms_orders_sum_b(ms_weights + UW_MS_WEIGHT_HEADER, nb, b0, ms_orders, st_j[u], st_f[u],
                                         st_geo + u * UW_MS_MAX_ORDERS);
      const realb F = uw_ms_halo_at_b(halo_rows, nb, b0, hm, hf, st_zj[u], st_zf[u]);
      acc += exp(-(c_t * st_t[u])) * (st_dt[u] * E * F);
    }
    const maskb lit = (band.b > 0.0f) & (band.rho > 0.0f);
    lamp_add_lanes(o, bands, b0, in_run, SELECTB(lit, band.I * band.rho * acc, SPLATB(0.0f)), 1, 0);
  }
}

/* The "orders" model's direct light of one lamp on the surface the pixel sees (common/underwater_lamps_ms.h):
 * exact and shadowed, seen through T_view (its first term, e^{-c S}, is the part scattered at most
 * once). On the flat bottom only that first term: the rest there is lamp_orders_smooth's, which blurs it.
 * That split is exact: the bottom's light is I ρ [(E_direct + E_ms) T_view + Σ_{k>=1} view_k (B_k − E_direct)]
 * with its blurred terms B_k, and T_view − Σ_{k>=1} view_k = view_0 = e^{-c S} (a lamp sealed in an
 * object has E_direct = 0 and no escaping light, so its terms vanish either way). */
static inline void lamp_orders_surface(__constant UwParams* p, __global const UwBand* bands,
                                       __global const UwObject* objects, int count, __constant UwLampParams* lp,
                                       __global const UwLamp* L, __global const float* I, int ms_orders,
                                       const LampRay* v, LampSums* o) {
  if (!v->lit_surface) return;
  const int nb = lp->band_count;
  const float3 lamp = v3(L->position), axis = v3(L->direction);
  const float3 P = v->o + v->S * v->d;
  const float vis = lamp_visible(objects, count, UW_ALL_OBJECTS, P + 1e-3f * v->n, lamp);
  if (!(vis > 0.0f)) return;
  float s;
  const float geometry = uw_lamp_surface_geometry(P, v->n, lamp, axis, L->cos_cone, L->cos_inner, lp->s_min, vis, &s);
  if (!(geometry > 0.0f)) return;
  /* The bands in lanes: the lamp's light at the surface (uw_lamp_surface, S = 0) and through the view. */
  for (int b0 = 0; b0 < nb; b0 += SEASIM_BAND_LANES) {
    const int in_run = min(SEASIM_BAND_LANES, nb - b0);
    const LampBandLanes band = lamp_band_lanes(bands, I, b0, in_run);
    float alb[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    float c[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    for (int q = 0; q < SEASIM_BAND_LANES; ++q) {
      alb[q] = q < in_run ? v->alb[(b0 + q) * v->alb_stride] : 0.0f;
      c[q] = q < in_run ? bands[b0 + q].c : 0.0f;
    }
    const realb E = band.I * *(realb*)alb * geometry * exp(-*(realb*)c * s);
    if (v->bottom) {
      lamp_add_lanes(o, bands, b0, in_run, E * exp(-*(realb*)c * v->S), 1, 1);
      continue;
    }
    realb view[UW_MS_MAX_ORDERS + 1];
    lamp_add_lanes(o, bands, b0, in_run, E * uw_ms_view_terms_b(band.a, band.b, p->g, v->S, ms_orders, view), 1, 0);
    lamp_add_lanes(o, bands, b0, in_run, E * view[0], 0, 1);
  }
}

/* The rest of the "orders" model's light of one lamp, which varies smoothly from pixel to pixel along a
 * surface (the quantities SEASIM_LAMPS_MS_LATTICE evaluates on a lattice): on the flat bottom, the
 * orders' irradiance seen through T_view, the direct light blurred on its way to the eye (T_view's
 * terms k >= 1 see the spread, uw_ms_blurred_bottom) and the glow; along the view ray, the glow's and
 * the orders' in-scatter, the geometry per step once (distance, the blurred profiles times HG(g^{n+1})
 * at the scattering angle), then the bands with their weights. Light scattered around an object reaches
 * behind it: nothing here is shadowed, but nothing leaves a sealed lamp. parts: LAMP_SMOOTH_SURFACE (the
 * light on the surface the pixel sees, which follows its normal and the lit patch's edge) and
 * LAMP_SMOOTH_RAY (the in-scatter along the view ray up to it, which follows only the ray and its end),
 * so that a lattice read can leave to the pixel just the part that varies too fast to interpolate. */
#define LAMP_SMOOTH_SURFACE 1
#define LAMP_SMOOTH_RAY 2
#define LAMP_SMOOTH_ALL 3
static inline void lamp_orders_smooth(__constant UwParams* p, __global const UwBand* bands,
                                      __global const UwObject* objects, int count, __constant UwLampParams* lp,
                                      __global const UwLamp* L, __global const float* I, __global const float* ms_rows,
                                      __global const float* glow, __global const float* ms_weights, int ms_orders,
                                      int ms_steps, int parts, const LampRay* v, LampSums* o) {
  const int nb = lp->band_count;
  const float3 lamp = v3(L->position), axis = v3(L->direction);
  if (!(lamp_escapes(objects, count, lamp) > 0.0f)) return;
  if ((parts & LAMP_SMOOTH_SURFACE) && v->lit_surface) {
    const float3 P = v->o + v->S * v->d;
    UwMsBlur blur[UW_MS_MAX_ORDERS];
    float geo[UW_MS_MAX_ORDERS];
    const float s_P = uw_ms_surface_geometry(P, v->n, lamp, axis, lp->s_min, ms_rows, ms_orders, geo);
    int wj;
    float wf;
    uw_ms_weight_index(ms_weights, s_P, &wj, &wf);
    if (v->bottom)
      for (int k = 1; k <= ms_orders; ++k)
        blur[k - 1] = uw_ms_blurred_bottom(v->o, v->d, p->bottom_depth, lamp, axis, L->cos_cone, L->cos_inner, lp->s_min,
                                           uw_ms_spread(p->g, k, UW_MS_VIEW_BETA));
    /* The bands in lanes: the orders' irradiance (uw_ms_orders_sum_b, as uw_ms_surface_sum) seen through
     * T_view, and on the bottom its direct light blurred on the way to the eye (T_view's terms k >= 1 see the
     * spread). */
    for (int b0 = 0; b0 < nb; b0 += SEASIM_BAND_LANES) {
      const int in_run = min(SEASIM_BAND_LANES, nb - b0);
      const LampBandLanes band = lamp_band_lanes(bands, I, b0, in_run);
      float alb[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      float c[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      for (int q = 0; q < SEASIM_BAND_LANES; ++q) {
        alb[q] = q < in_run ? v->alb[(b0 + q) * v->alb_stride] : 0.0f;
        c[q] = q < in_run ? bands[b0 + q].c : 0.0f;
      }
      const realb ms = s_P > 0.0f ? SELECTB(band.b > 0.0f,
                                             uw_ms_orders_sum_b(ms_weights + UW_MS_WEIGHT_HEADER, nb, b0, ms_orders, wj,
                                                                wf, geo),
                                             SPLATB(0.0f))
                                  : SPLATB(0.0f);
      realb view[UW_MS_MAX_ORDERS + 1];
      const realb T = uw_ms_view_terms_b(band.a, band.b, p->g, v->S, ms_orders, view);
      realb blurred = SPLATB(0.0f);
      if (v->bottom)
        for (int k = 1; k <= ms_orders; ++k)
          blurred += view[k] * blur[k - 1].geometry * exp(-*(realb*)c * blur[k - 1].s_mean);
      lamp_add_lanes(o, bands, b0, in_run, band.I * *(realb*)alb * (ms * T + blurred), 1, 0);
    }
    lamp_glow_surface(p, bands, glow, ms_rows, ms_weights, ms_orders, I, v, o);
  }
  if (!(parts & LAMP_SMOOTH_RAY)) return;
  float c_min = bands[0].c;
  for (int i = 1; i < nb; ++i) c_min = fmin(c_min, bands[i].c);
  lamp_glow_ray(p, bands, glow, ms_weights, ms_orders, ms_steps, c_min, I, v, o);
  lamp_halo_ray(p, bands, lp, L, I, ms_rows, ms_weights, ms_orders, ms_steps, c_min, v, o);
  /* The orders' in-scatter along the view ray: the steps' geometry once (distance, weight, the tables'
   * entries, each order's blurred profile times its phase towards the eye), then the bands in lanes. */
  UwMsRay q;
  uw_ms_ray(v->o, v->d, lamp, lp->s_min, v->t_end, uw_ms_ray_cap(c_min), ms_steps, &q);
  if (!(q.dv > 0.0f)) return;
  float st_t[UW_MS_MAX_STEPS], st_w[UW_MS_MAX_STEPS], st_f[UW_MS_MAX_STEPS];
  int st_j[UW_MS_MAX_STEPS];
  float st_geo[UW_MS_MAX_STEPS * UW_MS_MAX_ORDERS];
  for (int j = 0; j < ms_steps; ++j) {
    const float t = uw_ms_ray_t(&q, j);
    float s, c;
    uw_lamp_at(v->o, v->d, lamp, t, &s, &c);
    const float cos_psi = s > 0.0f ? dot(v->o + t * v->d - lamp, axis) / s : 1.0f;
    st_t[j] = t;
    st_w[j] = uw_ms_ray_weight(&q, t, s, lp->s_min);
    int ti;
    float tf;
    uw_ms_table_index(cos_psi, &ti, &tf);
    uw_ms_weight_index(ms_weights, s, &st_j[j], &st_f[j]);
    float* geo = st_geo + j * UW_MS_MAX_ORDERS;
    float gk = p->g;
    for (int k = 1; k <= ms_orders; ++k) {
      gk *= p->g;
      const float phase =
          k == 1 ? uw_ms_order1_phase(v->o + t * v->d, lamp, axis, L->cos_cone, p->g, c_min, -v->d) : hg_phase(c, gk);
      geo[k - 1] = uw_ms_table_lerp(ms_rows + (k - 1) * UW_MS_ROW, ti, tf) * phase;
    }
  }
  for (int b0 = 0; b0 < nb; b0 += SEASIM_BAND_LANES) {
    const int in_run = min(SEASIM_BAND_LANES, nb - b0);
    const LampBandLanes band = lamp_band_lanes(bands, I, b0, in_run);
    const realb c_t = band.a + band.b;
    realb acc = SPLATB(0.0f);
    for (int u = 0; u < ms_steps; ++u) {
      const realb sum = uw_ms_orders_sum_b(ms_weights + UW_MS_WEIGHT_HEADER, nb, b0, ms_orders, st_j[u], st_f[u],
                                           st_geo + u * UW_MS_MAX_ORDERS);
      acc += exp(-(c_t * st_t[u])) * (sum * st_w[u]);
    }
    lamp_add_lanes(o, bands, b0, in_run, SELECTB(band.b > 0.0f, band.I * band.b * acc, SPLATB(0.0f)), 1, 0);
  }
}
#else
/* The lamp's direct light on the surface the pixel sees (001 eq. 1, first term). */
static inline void lamp_surface(const LampMedia* md, __global const UwObject* objects, int count,
                                __constant UwLampParams* lp, __global const UwLamp* L, __global const float* I,
                                const LampRay* v, LampSums* o) {
  if (!v->lit_surface) return;
  const float3 lamp = v3(L->position), axis = v3(L->direction);
  const float3 P = v->o + v->S * v->d;
  const float vis = lamp_visible(objects, count, UW_ALL_OBJECTS, P + 1e-3f * v->n, lamp);
  if (!(vis > 0.0f)) return;
  float s;
  const float geometry = uw_lamp_surface_geometry(P, v->n, lamp, axis, L->cos_cone, L->cos_inner, lp->s_min, vis, &s);
  if (!(geometry > 0.0f)) return;
  for (int i = 0; i < lp->band_count; ++i) { /* uw_lamp_surface: the geometry once, e^{-σ_t (s + S)} per band */
    const float E = I[i] * v->alb[i * v->alb_stride] * geometry;
    lamp_add(o, md->bands, i, E * exp(-(md->bands[i].c * (s + v->S))));
#if SEASIM_LAYER_LAMPS_SPLIT
    if (md->single_apart) lamp_add_to(o, md->bands, i, E * exp(-(md->plain[i].c * (s + v->S))), 0, 1);
#endif
  }
}
#endif

/* The lamp's profile (uw_lamp_profile, shafts_cone_profile) at SEASIM_BAND_LANES points of the view ray, each
 * u past the closest approach (see lamp_beam), from the sine of the angle off the axis rather than its
 * cosine: q = u d + h⃗ the lamp-to-point vector, |q|² = h² + u², its part off the axis q × axis = u D + E
 * (D = d × axis, E = h⃗ × axis), sin² = |u D + E|² / |q|². With cos − cos_cone = (sin²_cone − sin²) / (cos +
 * cos_cone), the smoothstep's argument (cos − cos_cone) / (cos_inner − cos_cone) is
 *   (sin²_cone − sin²) / (sin²_cone − sin²_inner) · (cos_inner + cos_cone) / (cos + cos_cone),
 * well conditioned for a narrow cone, where the cosines all round to within a few ulp of 1 (a 0.1° cone
 * with a 0.05° falloff is 1.1e-6 wide in cosine). 0 behind the lamp (q·axis <= 0) and outside the cone, 1
 * inside the inner cone; a hard edge (sin²_inner >= sin²_cone) a step. */
static inline realb lamp_profile_lanes(realb u, float h2, float3 D, float3 E, float d_axis, float offset_axis,
                                       __global const UwLamp* L) {
  const realb px = u * D.x + E.x, py = u * D.y + E.y, pz = u * D.z + E.z;
  const realb sin2 = (px * px + py * py + pz * pz) / fmax(h2 + u * u, 1e-30f);
  const maskb front = u * d_axis + offset_axis > SPLATB(0.0f);
  const float width = L->sin2_cone - L->sin2_inner;
  if (!(width > 0.0f)) return SELECTB(front & (sin2 < SPLATB(L->sin2_cone)), SPLATB(1.0f), SPLATB(0.0f));
  const realb cos_axis = sqrt(fmax(1.0f - sin2, 0.0f));
  const realb f = clamp((L->sin2_cone - sin2) / width * ((L->cos_inner + L->cos_cone) / (cos_axis + L->cos_cone)), 0.0f, 1.0f);
  return SELECTB(front, f * f * (3.0f - 2.0f * f), SPLATB(0.0f));
}

/* Planes per block of the beam: each plane's band-free factor (its H P sum, the HG phase, 1/s² and the spacing:
 * 001's h(s, t) without σ_s e^{-σ_t (s + t)}) and path length s + t in private arrays, then each run of
 * SEASIM_BAND_LANES bands sums the block's planes in its lanes, one vector exp per plane, and adds the sum to
 * each band once per block (not once per plane). */
#define LAMP_PLANE_BLOCK 32

/* Adds to every band i, through lamp_add_to with the image's sensor weights (bands), the block's
 * I(λ) σ_s(λ) sum_u w[u] e^{-σ_t(λ) x[u]} with σ_s, σ_t from coef (the image's medium or the plain water). */
static inline void lamp_beam_block(LampSums* o, __global const UwBand* bands, __global const UwBand* coef,
                                   __global const float* I, int nb, const float* w, const float* x, int used,
                                   int to_image, int to_single) {
  for (int b0 = 0; b0 < nb; b0 += SEASIM_BAND_LANES) {
    const int count = min(SEASIM_BAND_LANES, nb - b0);
    float lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    for (int q = 0; q < SEASIM_BAND_LANES; ++q) lanes[q] = q < count ? coef[b0 + q].c : 0.0f;
    const realb sigma_t = LOADB(lanes, 0);
    realb sum = SPLATB(0.0f);
    for (int u = 0; u < used; ++u) sum += w[u] * exp(-(sigma_t * x[u])); /* shafts_h_scaled over σ_s, in lanes */
    *(realb*)lanes = sum;
    for (int q = 0; q < count; ++q)
      lamp_add_to(o, bands, b0 + q, I[b0 + q] * coef[b0 + q].b * lanes[q], to_image, to_single);
  }
}

/* The light one lamp scatters towards the eye (001 eq. 2, 5, 7–9): the planes' geometry (profile at the
 * sub-samples, distance, phase) SEASIM_BAND_LANES planes at a time in vector lanes, the shadow rays lane by
 * lane, then blocks of planes whose bands run in vector lanes (lamp_beam_block); then the far field's
 * Gauss–Legendre samples beyond the last plane (uw_lamp_tail_weight). The host's double evaluation
 * (uw_lamp_inscatter) takes the same planes one at a time. */
static inline void lamp_beam(const LampMedia* md, __global const UwObject* objects, int count,
                             __constant UwLampParams* lp, __global const UwLamp* L, __global const float* I,
                             const LampRay* v, LampSums* o) {
  const int nb = lp->band_count, n_planes = lp->planes, m = lp->subplanes;
  __global const UwBand* bands = md->bands;
  const float3 lamp = v3(L->position), axis = v3(L->direction);
  UwLampSpan sp;
  if (!uw_lamp_span(v->o, v->d, lamp, axis, L->cos_cone, lp->s_min, v->t_end, n_planes, &sp)) return;
  /* The planes' shadow rays fan out from the lamp to the ray's span [ta, tp]: only objects near that
   * triangle can be in their way. */
  const unsigned int fan_objects =
      count > 0 ? uw_objects_near_triangle(objects, count, lamp, v->o + sp.ta * v->d, v->o + sp.tp * v->d) : 0u;
  const int shadowed = fan_objects != 0u || count > 32; /* else every plane's shadow ray is clear */
  /* The planes' geometry in lanes, SEASIM_BAND_LANES planes at a time: along the ray, with u = t - a the
   * distance past the closest approach, s = sqrt(h² + u²) and cos α = -u / s; the profile from the sine off
   * the lamp's axis (lamp_profile_lanes), with h⃗ = o - lamp + a d the closest approach's offset. Where both
   * ends of an interval lie in the inner cone (convex), so does every sub-sample between them, and its
   * profile is 1. Lanes past the last plane are computed and dropped. */
  const float3 offset = v->o - lamp + sp.a * v->d;
  const float h2 = sp.h * sp.h, d_axis = dot(v->d, axis), offset_axis = dot(offset, axis);
  const float3 D = cross(v->d, axis), E = cross(offset, axis);
  const float sub = sp.dt / m;
  for (int k0 = 0; k0 < n_planes && sp.dt > 0.0f; k0 += LAMP_PLANE_BLOCK) {
    float w[LAMP_PLANE_BLOCK], x[LAMP_PLANE_BLOCK];
#if SEASIM_LAYER_LAMPS_SPLIT
    float w_plain[LAMP_PLANE_BLOCK];
#endif
    int used = 0;
    for (int l0 = k0; l0 < min(k0 + LAMP_PLANE_BLOCK, n_planes); l0 += SEASIM_BAND_LANES) {
      const realb k = lane_offsets() + (float)l0;
      const realb t0 = sp.ta + k * sp.dt;
      const maskb inner = (lamp_profile_lanes(t0 - sp.a, h2, D, E, d_axis, offset_axis, L) >= 1.0f) &
                          (lamp_profile_lanes(t0 + sp.dt - sp.a, h2, D, E, d_axis, offset_axis, L) >= 1.0f);
      float J_lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      realb J = SPLATB(0.0f);
      for (int j = 0; j < m; ++j) {
        const realb t = t0 + (j + 0.5f) * sub;
        const realb prof = SELECTB(inner, SPLATB(1.0f),
                                   lamp_profile_lanes(t - sp.a, h2, D, E, d_axis, offset_axis, L));
        /* Shadow rays in the lanes: exact tests against the fan's objects, where the profile is lit. */
        if (shadowed && ANYB(prof > 0.0f)) {
          J += SELECTB(lamp_blocked_b(objects, count, fan_objects, v->o, v->d, t, lamp), SPLATB(0.0f), prof);
          continue;
        }
        J += prof;
      }
      const realb u = t0 + 0.5f * sp.dt - sp.a;
      const realb s = sqrt(h2 + u * u);
      const realb cos_alpha = -u / fmax(s, 1e-30f);
      const realb sc = fmax(s, lp->s_min);
      const realb geometry = J * sub / (sc * sc);
      float w_lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      float x_lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      *(realb*)w_lanes = geometry * hg_phase_b(cos_alpha, md->g);
      *(realb*)x_lanes = s + u + sp.a;
      *(realb*)J_lanes = J;
#if SEASIM_LAYER_LAMPS_SPLIT
      float w_plain_lanes[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
      *(realb*)w_plain_lanes = geometry * hg_phase_b(cos_alpha, md->plain_g);
#endif
      for (int q = 0; q < min(SEASIM_BAND_LANES, n_planes - l0); ++q) {
        if (!(J_lanes[q] > 0.0f)) continue;
        w[used] = w_lanes[q];
#if SEASIM_LAYER_LAMPS_SPLIT
        w_plain[used] = w_plain_lanes[q];
#endif
        x[used++] = x_lanes[q];
      }
    }
    if (used == 0) continue;
    lamp_beam_block(o, bands, bands, I, nb, w, x, used, 1, o->to_single);
#if SEASIM_LAYER_LAMPS_SPLIT
    if (md->single_apart) lamp_beam_block(o, bands, md->plain, I, nb, w_plain, x, used, 0, 1);
#endif
  }
  if (!sp.tail) return;
  /* The far field's samples (uw_lamp_tail_weight) as one more block, SEASIM_BAND_LANES samples at a time in the
   * lanes: the rule's angles, the samples' geometry and profile (lamp_profile_lanes, as the planes'), and their
   * shadow rays, which may leave the fan. */
  float w[UW_LAMP_TAIL_SAMPLES], x[UW_LAMP_TAIL_SAMPLES];
#if SEASIM_LAYER_LAMPS_SPLIT
  float w_plain[UW_LAMP_TAIL_SAMPLES];
#endif
  int used = 0;
  const float half_range = 0.5f * (sp.phi_b - sp.phi_p);
  for (int j0 = 0; j0 < UW_LAMP_TAIL_SAMPLES; j0 += SEASIM_BAND_LANES) {
    float node_l[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    float weight_l[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    for (int q = 0; q < SEASIM_BAND_LANES; ++q) {
      float gw;
      node_l[q] = gauss_legendre8_node(min(j0 + q, UW_LAMP_TAIL_SAMPLES - 1), &gw);
      weight_l[q] = gw;
    }
    const realb tan_phi = tan(sp.phi_p + half_range * (1.0f + *(realb*)node_l));
    const realb t = sp.a + sp.r * tan_phi;
    const realb u = t - sp.a;
    /* uw_lamp_at in the lanes: the lamp's distance s and the scattering angle's cosine. */
    const real3b q3 = uw_r3b(offset.x + u * v->d.x, offset.y + u * v->d.y, offset.z + u * v->d.z);
    const realb s = sqrt(uw_dot3b(q3, q3));
    const maskb apart = s > 0.0f;
    const realb cos_alpha =
        SELECTB(apart, -(q3.x * v->d.x + q3.y * v->d.y + q3.z * v->d.z) / SELECTB(apart, s, SPLATB(1.0f)), SPLATB(1.0f));
    const realb jacobian = sp.r * (1.0f + tan_phi * tan_phi) * half_range * *(realb*)weight_l / fmax(s * s, 1e-30f);
    realb H = lamp_profile_lanes(u, h2, D, E, d_axis, offset_axis, L);
    if (count > 0 && ANYB(H > 0.0f))
      H = SELECTB(lamp_blocked_b(objects, count, UW_ALL_OBJECTS, v->o, v->d, t, lamp), SPLATB(0.0f), H);
    float H_l[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    float w_l[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    float x_l[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    *(realb*)H_l = H;
    *(realb*)w_l = H * jacobian * hg_phase_b(cos_alpha, md->g);
    *(realb*)x_l = s + t;
#if SEASIM_LAYER_LAMPS_SPLIT
    float w_plain_l[SEASIM_BAND_LANES] __attribute__((aligned(4 * SEASIM_BAND_LANES)));
    *(realb*)w_plain_l = H * jacobian * hg_phase_b(cos_alpha, md->plain_g);
#endif
    for (int q = 0; q < min(SEASIM_BAND_LANES, UW_LAMP_TAIL_SAMPLES - j0); ++q) {
      if (!(H_l[q] > 0.0f)) continue;
      w[used] = w_l[q];
#if SEASIM_LAYER_LAMPS_SPLIT
      w_plain[used] = w_plain_l[q];
#endif
      x[used++] = x_l[q];
    }
  }
  if (used == 0) return;
  lamp_beam_block(o, bands, bands, I, nb, w, x, used, 1, o->to_single);
#if SEASIM_LAYER_LAMPS_SPLIT
  if (md->single_apart) lamp_beam_block(o, bands, md->plain, I, nb, w_plain, x, used, 0, 1);
#endif
}

/* The objects the shadow rays test: none without SEASIM_HAS_OBJECTS. */
static inline int lamp_object_count(__constant UwParams* p) {
#if SEASIM_HAS_OBJECTS
  return p->object_count;
#else
  return 0;
#endif
}

/* The view ray of pixel (x, y) and the surface the G-buffer (raycast.cl) found on it. */
static inline LampRay lamp_ray(__constant UwParams* p, __global const UwBand* bands, __global const float* albedo,
                               __global const float4* geom, __global const int* material, int x, int y) {
  const int pixel = y * p->width + x;
  const float4 gb = geom[pixel];
  const int mat = material[pixel];
  LampRay v = {.o = v3(p->cam_pos), .d = uw_screen_dir(p, (x + 0.5f) / p->width, (y + 0.5f) / p->height),
               .n = (float3)(gb.y, gb.z, gb.w), .S = gb.x, .lit_surface = mat >= 0 || mat == UW_MAT_BOTTOM,
               .bottom = mat == UW_MAT_BOTTOM};
  v.t_end = v.S >= UW_INFINITE ? SHAFTS_T_INF : v.S;
  v.alb = mat >= 0 ? albedo + mat * p->band_count : &bands[0].bottom_albedo;
  v.alb_stride = mat >= 0 ? 1 : (int)(sizeof(UwBand) / sizeof(float));
  return v;
}

#if SEASIM_LAMPS_MS_LATTICE
/* The lattice of lamp_orders_smooth (step > 1: lampsMsLatticeStep, host/passes/underwater_lamps_pass.h):
 * the pixel (i step, j step), clamped to the image's last row and column, at lattice[(j map_w + i)
 * stride ...], per band the light of every lamp into the image, then (SEASIM_LAYER_LAMPS_SPLIT) its part
 * scattered at most once. */
#ifndef LAMP_LATTICE_NEAR
#define LAMP_LATTICE_NEAR 8.0f
#endif
#if SEASIM_LAYER_LAMPS_SPLIT
#define LAMP_LATTICE_STRIDE(nb) (2 * (nb))
#else
#define LAMP_LATTICE_STRIDE(nb) (nb)
#endif
/* A lattice pixel's entry: the surface's part (LAMP_SMOOTH_SURFACE), then the view ray's (LAMP_SMOOTH_RAY),
 * LAMP_LATTICE_STRIDE floats each (host: lampsMsLatticeFloats). */
#define LAMP_LATTICE_ENTRY(nb) (2 * LAMP_LATTICE_STRIDE(nb))

/* Whether a lamp lies within the angle whose cosine is cos_near of the view ray o + t d (in front of the
 * eye): near a lamp its light along the ray peaks like 1/h, h the ray's distance from it, faster than
 * a lattice's bilinear weights can follow. */
static inline int lamp_near_view(__constant UwLampParams* lp, __global const UwLamp* lamps, float3 o, float3 d,
                                 float cos_near) {
  for (int l = 0; l < lp->lamp_count; ++l) {
    const float3 w = v3(lamps[l].position) - o;
    const float s = length(w);
    if (!(s > 0.0f) || dot(w, d) >= cos_near * s) return 1;
  }
  return 0;
}

/* Whether every lamp's cone profile (uw_lamp_profile) at P is within 5 % of its peak of the bilinear read
 * (weights wq) of the profiles at the n bottom points q[k]: the bottom's direct light blurred on its way
 * to the eye (uw_ms_blurred_bottom) is nearly as sharp as the lit patch's edge in forward-scattering
 * water, so where the profile bends within the cell (a hard edge, the ends of a soft edge's ramp) a
 * bilinear read of the light would not follow it either. Along a soft edge's ramp it does: asking only
 * that the neighbours' profiles be alike (within 10 %) sent the whole ramp to per-pixel evaluation,
 * 9.5 % of rov_lights' pixels, for 0.01 % of rel. L2. */
static inline int lamp_profiles_alike(__constant UwLampParams* lp, __global const UwLamp* lamps, float3 P,
                                      const float3* q, const float* wq, int n) {
  float wsum = 0.0f;
  for (int k = 0; k < n; ++k) wsum += wq[k];
  for (int l = 0; l < lp->lamp_count; ++l) {
    __global const UwLamp* L = &lamps[l];
    const float3 lamp = v3(L->position), axis = v3(L->direction);
    const float at_P = uw_lamp_profile(P, lamp, axis, L->cos_cone, L->cos_inner);
    float interp = 0.0f;
    for (int k = 0; k < n; ++k) interp += wq[k] * uw_lamp_profile(q[k], lamp, axis, L->cos_cone, L->cos_inner);
    if (fabs(at_P - interp / wsum) > 0.05f) return 0;
  }
  return 1;
}

/* lamp_orders_smooth of the pixel from the (up to) four lattice pixels around it that see the same
 * surface (the flat bottom, the water's surface from below, open water, or the same object), weighted
 * bilinearly by position, added into o, part by part: returns the parts it added (LAMP_SMOOTH_SURFACE,
 * LAMP_SMOOTH_RAY); the caller evaluates the others itself. Neither where no neighbour sees the same
 * surface (a silhouette, where the light jumps) or where an object's lattice neighbour lies more than
 * 5 % further or nearer (the view ray's end jumps with it). The ray's part alone where the surface's
 * light varies within the cell faster than a bilinear read follows: an object's neighbour turning its
 * normal by more than 5.7° (its light follows the normal), and the bottom across the edge of a lamp's
 * lit patch (lamp_profiles_alike); the in-scatter along the ray sees neither. The bottom, the surface and
 * open water are one plane each, or nothing, so elsewhere their light varies smoothly across the image
 * however fast S does towards the horizon. A lattice pixel reads its own value. */
static inline int lamp_lattice_read(__constant UwParams* p, __global const UwBand* bands, __global const float4* geom,
                                    __global const int* material, __constant UwLampParams* lp,
                                    __global const UwLamp* lamps, __global const float* lattice, int step, int map_w,
                                    int map_h, int x, int y, const LampRay* v, LampSums* o) {
  const int i0 = x / step, j0 = y / step, nb = p->band_count;
  const float fx = (float)(x - i0 * step) / step, fy = (float)(y - j0 * step) / step;
  const int mat = material[y * p->width + x];
  float w[4];
  int at[4];
  float3 bottom_points[4]; /* the bottom neighbours' hits, for the lit patch's edge */
  float bottom_w[4];
  int bottoms = 0, parts = LAMP_SMOOTH_ALL;
  float wsum = 0.0f;
  for (int c = 0; c < 4; ++c) {
    const int di = c & 1, dj = c >> 1;
    const int i = min(i0 + di, map_w - 1), j = min(j0 + dj, map_h - 1);
    const int xq = min(i * step, p->width - 1), yq = min(j * step, p->height - 1);
    const float w_c = (di ? fx : 1.0f - fx) * (dj ? fy : 1.0f - fy);
    const int q = yq * p->width + xq;
    const float4 gq = geom[q];
    const int same = material[q] == mat;
    /* The same object behind itself (the pixel evaluates both parts) or turning away (its light follows
     * the normal: the surface's part), as at the lit patch's edge below. */
    if (same && mat >= 0 && w_c > 0.0f) {
      if (!(fabs(gq.x - v->S) <= 0.05f * v->S)) return 0;
      if (!(dot((float3)(gq.y, gq.z, gq.w), v->n) >= 0.995f)) parts &= ~LAMP_SMOOTH_SURFACE;
    }
    if (same && v->bottom && w_c > 0.0f) {
      bottom_w[bottoms] = w_c;
      bottom_points[bottoms++] = v->o + gq.x * uw_screen_dir(p, (xq + 0.5f) / p->width, (yq + 0.5f) / p->height);
    }
    w[c] = same ? w_c : 0.0f;
    at[c] = (j * map_w + i) * LAMP_LATTICE_ENTRY(nb);
    wsum += w[c];
  }
  if (!(wsum > 0.0f)) return 0;
  /* The lit patch's edge in the cell: the pixel evaluates the surface's part itself (its neighbours on one
   * side of the edge alone would carry that side's light across it). */
  if ((parts & LAMP_SMOOTH_SURFACE) && bottoms > 0 &&
      !lamp_profiles_alike(lp, lamps, v->o + v->S * v->d, bottom_points, bottom_w, bottoms))
    parts &= ~LAMP_SMOOTH_SURFACE;
  for (int c = 0; c < 4; ++c) w[c] /= wsum;
  for (int part = 0; part < 2; ++part) {
    if (!(parts & (part == 0 ? LAMP_SMOOTH_SURFACE : LAMP_SMOOTH_RAY))) continue;
    const int from = part * LAMP_LATTICE_STRIDE(nb);
    for (int i = 0; i < nb; ++i) {
      float L = 0.0f;
      for (int c = 0; c < 4; ++c) L += w[c] * lattice[at[c] + from + i];
      lamp_add_to(o, bands, i, L, 1, 0);
#if SEASIM_LAYER_LAMPS_SPLIT
      float Ls = 0.0f;
      for (int c = 0; c < 4; ++c) Ls += w[c] * lattice[at[c] + from + nb + i];
      lamp_add_to(o, bands, i, Ls, 0, 1);
#endif
    }
  }
  return parts;
}

/* One lattice pixel per work-item (map_w x map_h): every lamp's lamp_orders_smooth, per band. */
__kernel void underwater_lamps_lattice(__constant UwParams* p, __global const UwBand* bands,
                                       __global const float* albedo, __global const UwObject* objects,
                                       __global const float4* geom, __global const int* material,
                                       __constant UwLampParams* lp, __global const UwLamp* lamps,
                                       __global const float* lamp_spectra, __global const float* ms_table,
                                       __global const float* ms_glow, __global const float* ms_weights, int ms_orders,
                                       int ms_steps, int step, int map_w, int map_h, __global float* lattice) {
  const int i = get_global_id(0), j = get_global_id(1);
  if (i >= map_w || j >= map_h) return;
  const int nb = lp->band_count;
  const int count = lamp_object_count(p);
  const LampRay v = lamp_ray(p, bands, albedo, geom, material, min(i * step, p->width - 1), min(j * step, p->height - 1));
  __global float* sums = lattice + (size_t)(j * map_w + i) * LAMP_LATTICE_ENTRY(nb);
  for (int k = 0; k < LAMP_LATTICE_ENTRY(nb); ++k) sums[k] = 0.0f;
  LampSums o = {.r = 0.0f, .g = 0.0f, .b = 0.0f, .single_r = 0.0f, .single_g = 0.0f, .single_b = 0.0f,
                .to_single = 0, .pixel = 0, .nb = nb, .band_sums = sums};
  for (int part = 0; part < 2; ++part) {
    o.band_sums = sums + part * LAMP_LATTICE_STRIDE(nb);
    for (int l = 0; l < lp->lamp_count; ++l)
      lamp_orders_smooth(p, bands, objects, count, lp, &lamps[l], lamp_spectra + l * nb,
                         ms_table + l * ms_orders * UW_MS_ROW, ms_glow + l * (4 + nb), ms_weights, ms_orders,
                         ms_steps, part == 0 ? LAMP_SMOOTH_SURFACE : LAMP_SMOOTH_RAY, &v, &o);
  }
}
#endif

__kernel void underwater_lamps(__constant UwParams* p, __global const UwBand* bands, __global const float* albedo,
                               __global const UwObject* objects, __global const float4* geom,
                               __global const int* material, __constant UwLampParams* lp,
                               __global const UwLamp* lamps, __global const float* lamp_spectra,
#if SEASIM_LAMPS_ORDERS
                               __global const float* ms_table, __global const float* ms_glow,
                               __global const float* ms_weights, int ms_orders, int ms_steps,
#endif
#if SEASIM_LAMPS_MS_LATTICE
                               __global const float* ms_lattice, int ms_step, int ms_map_w, int ms_map_h,
#endif
                               __global float* rgb
#if SEASIM_SPECTRAL_OUTPUT
                               , __global float* spectral
#endif
#if SEASIM_LAYER_LAMPS
                               , __global float* lamps_layer
#endif
#if SEASIM_LAYER_BANDS
                               , __global float* layer_bands
#endif
#if SEASIM_LAYER_LAMPS_SPLIT
                               , __global float* lamps_split, int split_stride, int split_single_at,
                               int split_multiple_at, __global const UwBand* plain_bands, float plain_g, int single_apart
#endif
) {
  const int x = get_global_id(0), y = get_global_id(1);
  if (x >= p->width || y >= p->height) return;
  const int pixel = y * p->width + x;
  const int nb = lp->band_count;
  const int count = lamp_object_count(p);
  const LampRay v = lamp_ray(p, bands, albedo, geom, material, x, y);
  LampSums o = {.r = 0.0f, .g = 0.0f, .b = 0.0f, .single_r = 0.0f, .single_g = 0.0f, .single_b = 0.0f,
                .to_single = 1, .pixel = pixel, .nb = nb, .band_sums = 0};
  LampMedia md = {.bands = bands, .g = p->g, .plain = bands, .plain_g = p->g, .single_apart = 0};
#if SEASIM_LAYER_LAMPS_SPLIT
  md.plain = plain_bands;
  md.plain_g = plain_g;
  md.single_apart = single_apart;
  o.to_single = !single_apart;
#endif
#if SEASIM_SPECTRAL_OUTPUT
  o.spectral = spectral;
#endif
#if SEASIM_LAYER_BANDS
  o.layer_bands = layer_bands;
#endif
#if SEASIM_LAMPS_MS_LATTICE
  /* Within LAMP_LATTICE_NEAR lattice cells of a lamp in view every pixel evaluates itself. */
  const float cell = LAMP_LATTICE_NEAR * ms_step * length(uw_screen_dir(p, (x + 1.5f) / p->width, (y + 0.5f) / p->height) - v.d);
  const int smooth_left =
      lamp_near_view(lp, lamps, v.o, v.d, cos(fmin(cell, 1.5f)))
          ? LAMP_SMOOTH_ALL
          : LAMP_SMOOTH_ALL & ~lamp_lattice_read(p, bands, geom, material, lp, lamps, ms_lattice, ms_step, ms_map_w,
                                                 ms_map_h, x, y, &v, &o);
#elif SEASIM_LAMPS_ORDERS
  const int smooth_left = LAMP_SMOOTH_ALL;
#endif
  for (int l = 0; l < lp->lamp_count; ++l) {
    __global const UwLamp* L = &lamps[l];
    __global const float* I = lamp_spectra + l * nb;
#if SEASIM_LAMPS_ORDERS
    __global const float* ms_rows = ms_table + l * ms_orders * UW_MS_ROW;
    __global const float* glow = ms_glow + l * (4 + nb);
    lamp_orders_surface(p, bands, objects, count, lp, L, I, ms_orders, &v, &o);
    if (smooth_left)
      lamp_orders_smooth(p, bands, objects, count, lp, L, I, ms_rows, glow, ms_weights, ms_orders, ms_steps,
                         smooth_left, &v, &o);
#else
    lamp_surface(&md, objects, count, lp, L, I, &v, &o);
#endif
    lamp_beam(&md, objects, count, lp, L, I, &v, &o);
  }
  rgb[3 * pixel + 0] += o.r;
  rgb[3 * pixel + 1] += o.g;
  rgb[3 * pixel + 2] += o.b;
#if SEASIM_LAYER_LAMPS
  lamps_layer[3 * pixel + 0] += o.r;
  lamps_layer[3 * pixel + 1] += o.g;
  lamps_layer[3 * pixel + 2] += o.b;
#endif
#if SEASIM_LAYER_LAMPS_SPLIT
  __global float* split = lamps_split + (size_t)split_stride * pixel;
  if (split_single_at >= 0) {
    split[split_single_at + 0] += o.single_r;
    split[split_single_at + 1] += o.single_g;
    split[split_single_at + 2] += o.single_b;
  }
  if (split_multiple_at >= 0) {
    split[split_multiple_at + 0] += o.r - o.single_r;
    split[split_multiple_at + 1] += o.g - o.single_g;
    split[split_multiple_at + 2] += o.b - o.single_b;
  }
#endif
}
