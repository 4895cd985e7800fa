#include "underwater/underwater_cpu.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <array>
#include <cmath>
#include <type_traits>

#include "math/kernel_math.h"

namespace seasim {

namespace {

// One pixel, in the precision of the kmath namespace M (kmath_f or kmath_d), as raycast.cl + kd_multiple.cl.
template <class Real>
void shadePixel(const UnderwaterSetup& s, const UnderwaterCpuOptions& opt, int x, int y, float* out) {
  using namespace std;
  const UwParams& p = s.params;
  auto v3 = [](const float a[4]) { return std::array<Real, 3>{Real(a[0]), Real(a[1]), Real(a[2])}; };
  const auto pos = v3(p.cam_pos), sw = v3(p.sun_dir_water);
  const Real sx = (Real(x) + Real(0.5)) / Real(p.width), sy = (Real(y) + Real(0.5)) / Real(p.height);
  const bool sun = s.bands.empty() ? false : s.params.sun_dir_water[1] > 0 && s.bands[0].e_beam0 >= 0;
  Real rgb[3] = {0, 0, 0};
  auto run = [&](auto ns) {
    using M = decltype(ns);
    using real3 = typename M::real3;
    const real3 d = M::dir(&p, sx, sy);
    const real3 o{pos[0], pos[1], pos[2]};
    const real3 s_w{sw[0], sw[1], sw[2]};
    real3 n{};
    int mat = 0;
    const Real S = M::hit(s.objects.data(), p.object_count, Real(p.bottom_depth), o, d, Real(0), &n, &mat);
    Real vis = 0;
    if (sun && (mat >= 0 || mat == UW_MAT_BOTTOM)) {
      vis = 1;
      if (p.object_count > 0) {
        real3 sn{};
        int smat = 0;
        const real3 hit = o + S * d;
        M::hit(s.objects.data(), p.object_count, Real(0), hit + Real(1e-3) * n, s_w, Real(0), &sn, &smat);
        if (smat >= 0) vis = 0;
      }
    }
    for (int i = 0; i < p.band_count; ++i) {
      const UwBand& band = s.bands[i];
      const Real alb = mat >= 0 ? Real(s.albedo[mat * p.band_count + i]) : Real(band.bottom_albedo);
      const Real L = M::shade(&band, mat, S, n, d, -Real(p.cam_pos[1]), s_w, alb, vis, Real(p.ior),
                              Real(p.bottom_depth), opt.single_split ? 1 : 0, opt.multiple ? 1 : 0);
      rgb[0] += L * Real(band.w_r);
      rgb[1] += L * Real(band.w_g);
      rgb[2] += L * Real(band.w_b);
    }
  };
  if constexpr (std::is_same_v<Real, double>) {
    struct M {
      using real3 = kmath_d::real3;
      static real3 dir(const UwParams* p, double sx, double sy) { return kmath_d::uw_screen_dir(p, sx, sy); }
      static double hit(const UwObject* ob, int n, double bd, real3 o, real3 d, double t, real3* nn, int* m) {
        return kmath_d::uw_scene_hit(ob, n, bd, o, d, t, nn, m);
      }
      static double shade(const UwBand* b, int mat, double S, real3 n, real3 d, double od, real3 sw, double alb,
                          double vis, double ior, double bd, int ss, int ms) {
        return kmath_d::uw_band_radiance(b, mat, S, n, d, od, sw, alb, vis, ior, bd, ss, ms);
      }
    };
    run(M{});
  } else {
    struct M {
      using real3 = kmath_f::real3;
      static real3 dir(const UwParams* p, float sx, float sy) { return kmath_f::uw_screen_dir(p, sx, sy); }
      static float hit(const UwObject* ob, int n, float bd, real3 o, real3 d, float t, real3* nn, int* m) {
        return kmath_f::uw_scene_hit(ob, n, bd, o, d, t, nn, m);
      }
      static float shade(const UwBand* b, int mat, float S, real3 n, real3 d, float od, real3 sw, float alb,
                         float vis, float ior, float bd, int ss, int ms) {
        return kmath_f::uw_band_radiance(b, mat, S, n, d, od, sw, alb, vis, ior, bd, ss, ms);
      }
    };
    run(M{});
  }
  for (int k = 0; k < 3; ++k) out[k] = static_cast<float>(rgb[k]);
}

}  // namespace

void forRowBlocks(int height, bool parallel, const std::function<void(int, int)>& rows) {
  if (parallel)
    tbb::parallel_for(tbb::blocked_range<int>(0, height),
                      [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
  else
    rows(0, height);
}

Image renderUnderwaterCpu(const UnderwaterSetup& setup, const UnderwaterCpuOptions& options) {
  const int w = setup.params.width, h = setup.params.height;
  Image img = Image::rgb(w, h);
  auto rows = [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < w; ++x) {
        float* out = &img.pixels[(static_cast<size_t>(y) * w + x) * 3];
        if (options.use_double)
          shadePixel<double>(setup, options, x, y, out);
        else
          shadePixel<float>(setup, options, x, y, out);
      }
  };
  forRowBlocks(h, options.parallel, rows);
  return img;
}

}  // namespace seasim
