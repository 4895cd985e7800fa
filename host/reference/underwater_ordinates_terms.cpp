#include "reference/underwater_ordinates_terms.h"

#include <algorithm>
#include <cmath>

#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

namespace kd = kmath_d;

namespace {

// uwi_multiple's sum before its clamp, term by term (common/underwater_ordinates.h).
struct InScatter {
  double modes = 0, beam = 0, tms = 0, froxel_ss = 0;
};

// v_sand, v_diffuse: the shares of the sunlit and of the diffusely lit sand's parts of the source kept
// (uwi_sand_shares); v_above: the share of the source from above that the objects leave (uwi_above_share;
// both as uwi_multiple_sand takes them).
InScatter inScatterTerms(const UwiBand& ib, const UwBand& band, double g, double bottom_depth, double S, double d_y,
                         double o_d, double cos_s, double mu_w, double v_sand, double v_diffuse, double v_above) {
  InScatter t;
  const int node = kd::uwi_source_node(d_y);
  const double cos_dphi = kd::uwi_cos_azimuth(cos_s, d_y, mu_w);
  double w[3];
  kd::uwi_shaded_weights(&ib, node, cos_dphi, v_sand, v_diffuse, v_above, w);
  const double w1 = w[0], w2 = w[1], wp = w[2];
  const double p_hg = kd::hg_phase(cos_s, g);
  const double phase = double(band.b) * p_hg * band.e_beam0;
  const double tms_phase = double(band.b) * kd::uwi_tms_phase(p_hg, ib.p_clip) * band.e_beam0;
  const double i1 = kd::kd_exp_integral(ib.k, ib.c_dm, d_y, o_d, S);
  const double i2 = bottom_depth > 0 ? kd::kd_exp_integral(ib.k, ib.c_dm, -d_y, std::max(bottom_depth - o_d, 0.0), S) : 0.0;
  const double ip = kd::kd_exp_integral(ib.m, ib.c_dm, d_y, o_d, S);
  t.modes = w1 * i1 + w2 * i2;
  t.beam = wp * ip;
  t.tms = tms_phase * ip;
  t.froxel_ss = phase * kd::kd_exp_integral(band.c / std::max(mu_w, 1e-4), band.c, d_y, o_d, S);
  return t;
}

}  // namespace

std::vector<UwiPixelTerms> ordinatesModelTerms(const UnderwaterSetup& s, bool multiple_scattering) {
  const UwParams& p = s.params;
  if (s.ordinates.size() != s.bands.size() || s.bands.empty())
    throw RuntimeError("discrete-ordinates model terms: the setup has no discrete-ordinates model (underwater.model = \"discrete_ordinates\")");
  std::vector<UwiPixelTerms> out(size_t(p.width) * p.height);
  const kd::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  const kd::real3 s_w{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  const double o_d = -o.y, mu_w = s_w.y, H = p.bottom_depth;
  const int froxels = s.single_scattering ? 1 : 0;
  const int multiple = multiple_scattering ? 1 : 0;
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      const kd::real3 d = kd::uw_screen_dir(&p, (x + 0.5) / p.width, (y + 0.5) / p.height);
      kd::real3 n{};
      int mat = 0;
      const double S = kd::uw_scene_hit(s.objects.data(), p.object_count, H, o, d, 0.0, &n, &mat);
      double vis = 0;  // the sun's shadow ray from a Lambertian hit (raycast.cl)
      if (mat >= 0 || mat == UW_MAT_BOTTOM) vis = kd::uw_sun_visibility(s.objects.data(), p.object_count, o + S * d, n, s_w);
      // The share of the sand an object's face sees that is sunlit (kd_multiple.cl's).
      const double vis_b = mat >= 0 ? kd::uwi_bottom_visibility(s.objects.data(), p.object_count, H, o + S * d, n, s_w) : 1.0;
      UwiPixelTerms& t = out[size_t(y) * p.width + x];
      int mat_m = UW_MAT_NONE;  // the object in the surface's mirror, as kd_multiple.cl traces it
      kd::UwiMirrorHit mirror = mat == UW_MAT_SURFACE
                                    ? kd::uwi_mirror_hit(s.objects.data(), p.object_count, o, d, S, s_w, &mat_m)
                                    : kd::uwi_no_mirror_object();
      const bool object_in_mirror = mat_m >= 0 && !(H > 0 && mirror.s >= H / std::max(d.y, 1e-6));
      t.reflected_object = object_in_mirror ? 1.0 : 0.0;
      // kd_multiple.cl's shares of the sunlit and of the diffusely lit sand's light the ray gathers unhidden
      // and unshaded.
      double v_diffuse = 1.0;
      const double v_sand =
          multiple ? kd::uwi_sand_shares(s.objects.data(), p.object_count, H, o, d, S, s.ordinates[0].c_dm,
                                         s.ordinates[0].k, s_w, s.albedo.data(), p.band_count,
                                         s.bands[0].bottom_albedo, &v_diffuse)
                   : 1.0;
      // and the share of the source from above that the objects leave it.
      const double v_above = multiple ? kd::uwi_above_share(s.objects.data(), p.object_count, H, o, d, S,
                                                            s.ordinates[0].c_dm, s.ordinates[0].k)
                                      : 1.0;
      for (int i = 0; i < p.band_count; ++i) {
        const UwBand& b = s.bands[i];
        const UwiBand& ib = s.ordinates[i];
        const double w = double(b.w_r) + b.w_g + b.w_b;
        const double albedo =
            mat >= 0 ? s.albedo[size_t(mat) * p.band_count + i] : mat == UW_MAT_BOTTOM ? b.bottom_albedo : 0.0;
        if (multiple) {
          const InScatter v = inScatterTerms(ib, b, p.g, H, S, d.y, o_d, kd::dot(d, s_w), mu_w, v_sand, v_diffuse, v_above);
          t.inscatter_modes += w * v.modes;
          t.inscatter_beam += w * v.beam;
          t.inscatter_tms += w * v.tms;
          const double y1 = mat == UW_MAT_SURFACE ? 0.0 : std::max(o_d - S * d.y, 0.0);
          t.aureole += w * kd::uwi_aureole(&ib, &b, kd::hg_phase(kd::dot(d, s_w), p.g), kd::dot(d, s_w), d.y, o_d, y1, mu_w);
          if (froxels) t.froxel_ss += w * v.froxel_ss;
        }
        const double T = std::exp(-double(ib.c_dm) * S);
        // The share of T(S) that was scattered by small angles (delta-M's peak): 1 - e^{-(c - c') S}, as
        // kd_multiple.cl takes it (common/water_spread.h).
        const double small_angle =
            kd::uws_hit_share_b(kd::uws_expm1_neg_b((double(b.c) - double(ib.c_dm)) * std::min(S, 1e4)));
        if (mat_m >= 0) mirror.albedo = s.albedo[size_t(mat_m) * p.band_count + i];
        if (mat == UW_MAT_SURFACE) {
          // uwi_surface, its two parts apart (the reflected ray ends on the object in the mirror, if any).
          const double dy = std::max(d.y, 1e-6);
          const double s_r = object_in_mirror ? mirror.s : H > 0 ? H / dy : 1e30;  // UW_INFINITE
          const double cos_r = kd::dot(d, s_w) - 2.0 * d.y * s_w.y;
          const double f = kd::fresnel_reflectance(d.y, p.ior, 1.0);
          const double l_ms = kd::uwi_multiple(&ib, &b, p.g, H, s_r, -dy, 0.0, cos_r, mu_w, 0, multiple);
          const double l_bottom =
              object_in_mirror
                  ? std::exp(-double(ib.c_dm) * s_r) *
                        kd::uwi_lambert(&ib, &b, H, s_r * dy, mirror.n, s_w, mirror.albedo, mirror.vis, 1.0)
              : H > 0 ? std::exp(-double(ib.c_dm) * std::min(s_r, 1e4)) *
                            kd::uwi_lambert(&ib, &b, H, H, kd::real3{0, 1, 0}, s_w, b.bottom_albedo, 1.0, 1.0)
                      : 0.0;
          t.window += w * T * p.ior * p.ior * (1 - f) * b.sky_radiance;
          t.reflected_inscatter += w * T * f * l_ms;
          t.reflected_bottom += w * T * f * l_bottom;
          t.forward += w * small_angle * T * (p.ior * p.ior * (1 - f) * b.sky_radiance + f * (l_ms + l_bottom));
          if (froxels && multiple)
            t.reflected_froxel_ss +=
                w * T * f * inScatterTerms(ib, b, p.g, H, s_r, -dy, 0.0, cos_r, mu_w, 1.0, 1.0, 1.0).froxel_ss;
        } else if (mat != UW_MAT_NONE) {
          const double lambert = T * kd::uwi_lambert(&ib, &b, H, std::max(o_d - S * d.y, 0.0), n, s_w, albedo, vis, vis_b);
          t.lambert += w * lambert;
          t.forward += w * small_angle * lambert;
        }
        t.total += w * (kd::uwi_band_radiance_sand(&ib, &b, p.g, mat, S, n, d, o_d, s_w, albedo, vis, vis_b,
                                                   b.sky_radiance, p.ior, H, froxels, multiple, mirror, v_sand, v_diffuse,
                                                   v_above) +
                        (froxels && multiple ? inScatterTerms(ib, b, p.g, H, S, d.y, o_d, kd::dot(d, s_w), mu_w, 1.0, 1.0, 1.0).froxel_ss
                                             : 0.0));
      }
    }
  return out;
}

}  // namespace seasim
