// underwater_cpu_simd.cpp — renderUnderwaterCpuSimd (underwater_cpu.h): the K_d frame in float, laid
// out for auto-vectorisation. CMakeLists.txt compiles this file alone with -O3 -ffast-math: glibc then
// declares SIMD variants of expf (libmvec) and GCC vectorises the band loops below across pixels,
// reassociating the float sums. Results differ from renderUnderwaterCpu's float image only by that
// reassociation and libmvec's rounding (a few ulp).
//
// Shape: per row (oneTBB over rows), the scalar ray cast fills structure-of-arrays G-buffer rows; the
// pixels are split by material class (deep water, the surface from below, a Lambertian hit), so each
// class's band loop calls one branch-free function of common/underwater.h (uw_band_multiple,
// uw_band_surface, uw_band_lambert) over contiguous arrays: the loop the vectoriser wants.

#include <vector>

#include "math/kernel_math.h"
#include "underwater/underwater_cpu.h"

namespace seasim {

namespace {

namespace K = kmath_f;

// One material class of a row: its pixels' G-buffer values, contiguous, and their RGB sums.
struct ClassRows {
  std::vector<int> x, albedo_index;  // pixel column; object index, or object_count for the bottom
  std::vector<float> S, dy, nx, ny, nz, vis, r, g, b;
  void clear() {
    for (auto* v : {&x, &albedo_index}) v->clear();
    for (auto* v : {&S, &dy, &nx, &ny, &nz, &vis, &r, &g, &b}) v->clear();
  }
  void add(int px, int albedo_at, float s, K::real3 d, K::real3 n, float v) {
    x.push_back(px);
    albedo_index.push_back(albedo_at);
    S.push_back(s);
    dy.push_back(d.y);
    nx.push_back(n.x);
    ny.push_back(n.y);
    nz.push_back(n.z);
    vis.push_back(v);
    r.push_back(0.0f);
    g.push_back(0.0f);
    b.push_back(0.0f);
  }
};

// On x86-64 with GCC, cloned for AVX2+FMA (8 floats per libmvec call) with a plain x86-64 fallback,
// picked at load time; elsewhere (an ARM GPU host, clang) the compiler's default target only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SEASIM_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v3", "default")))
#else
#define SEASIM_SIMD_CLONES
#endif
SEASIM_SIMD_CLONES
void shadeRow(const UnderwaterSetup& s, const UnderwaterCpuOptions& opt, int y, ClassRows cls[3],
              std::vector<float>& band_albedo, float* out) {
  const UwParams& p = s.params;
  const K::real3 o{p.cam_pos[0], p.cam_pos[1], p.cam_pos[2]};
  const K::real3 s_w{p.sun_dir_water[0], p.sun_dir_water[1], p.sun_dir_water[2]};
  const bool sun = !s.bands.empty() && p.sun_dir_water[1] > 0 && s.bands[0].e_beam0 >= 0;
  const float o_d = -p.cam_pos[1];
  const int single = opt.single_split ? 1 : 0, multiple = opt.multiple ? 1 : 0;
  for (int c = 0; c < 3; ++c) cls[c].clear();

  // G-buffer (scalar, as raycast.cl and renderUnderwaterCpu): hit, normal, material, sun visibility.
  for (int x = 0; x < p.width; ++x) {
    const K::real3 d = K::uw_screen_dir(&p, (x + 0.5f) / p.width, (y + 0.5f) / p.height);
    K::real3 n{};
    int mat = 0;
    const float S = K::uw_scene_hit(s.objects.data(), p.object_count, p.bottom_depth, o, d, 0.0f, &n, &mat);
    float vis = 0.0f;
    if (sun && (mat >= 0 || mat == UW_MAT_BOTTOM)) {
      vis = p.object_count > 0 ? K::uw_sun_visibility(s.objects.data(), p.object_count, o + S * d, n, s_w) : 1.0f;
    }
    const int c = mat == UW_MAT_NONE ? 0 : mat == UW_MAT_SURFACE ? 1 : 2;
    cls[c].add(x, mat >= 0 ? mat : p.object_count, S, d, n, vis);
  }

  // Per band, one straight loop per class (the vectorised part).
  for (int i = 0; i < p.band_count; ++i) {
    const UwBand* band = &s.bands[i];
    const float wr = band->w_r, wg = band->w_g, wb = band->w_b, c_t = band->c;
    for (int k = 0; k < p.object_count; ++k) band_albedo[k] = s.albedo[size_t(k) * p.band_count + i];
    band_albedo[p.object_count] = band->bottom_albedo;
    {
      ClassRows& q = cls[0];
      const int m = static_cast<int>(q.x.size());
      for (int j = 0; j < m; ++j) {
        const float L = K::uw_band_multiple(band, q.S[j], q.dy[j], o_d, s_w.y, single, multiple);
        q.r[j] += L * wr;
        q.g[j] += L * wg;
        q.b[j] += L * wb;
      }
    }
    {
      ClassRows& q = cls[1];
      const int m = static_cast<int>(q.x.size());
      for (int j = 0; j < m; ++j) {
        const float L =
            K::exp(-c_t * q.S[j]) * K::uw_band_surface(band, q.dy[j], s_w.y, p.ior, p.bottom_depth, single, multiple) +
            K::uw_band_multiple(band, q.S[j], q.dy[j], o_d, s_w.y, single, multiple);
        q.r[j] += L * wr;
        q.g[j] += L * wg;
        q.b[j] += L * wb;
      }
    }
    {
      ClassRows& q = cls[2];
      const int m = static_cast<int>(q.x.size());
      const float* alb = band_albedo.data();
      for (int j = 0; j < m; ++j) {
        const K::real3 n{q.nx[j], q.ny[j], q.nz[j]};
        const float L = K::exp(-c_t * q.S[j]) * K::uw_band_lambert(band, q.S[j], n, q.dy[j], o_d, s_w,
                                                                   alb[q.albedo_index[j]], q.vis[j], single) +
                        K::uw_band_multiple(band, q.S[j], q.dy[j], o_d, s_w.y, single, multiple);
        q.r[j] += L * wr;
        q.g[j] += L * wg;
        q.b[j] += L * wb;
      }
    }
  }
  for (int c = 0; c < 3; ++c)
    for (size_t j = 0; j < cls[c].x.size(); ++j) {
      float* px = out + 3 * size_t(cls[c].x[j]);
      px[0] = cls[c].r[j];
      px[1] = cls[c].g[j];
      px[2] = cls[c].b[j];
    }
}

}  // namespace

Image renderUnderwaterCpuSimd(const UnderwaterSetup& setup, const UnderwaterCpuOptions& options) {
  const int w = setup.params.width, h = setup.params.height;
  Image img = Image::rgb(w, h);
  auto rows = [&](int y0, int y1) {
    ClassRows cls[3];
    std::vector<float> band_albedo(size_t(setup.params.object_count) + 1);
    for (int y = y0; y < y1; ++y) shadeRow(setup, options, y, cls, band_albedo, &img.pixels[size_t(y) * w * 3]);
  };
  forRowBlocks(h, options.parallel, rows);
  return img;
}

}  // namespace seasim
