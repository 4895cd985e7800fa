// underwater_cpu_simd.cpp — renderUnderwaterCpuSimd (underwater_cpu.h): the K_d frame in float, laid
// out so that GCC vectorises the band loops across pixels. What it takes (CMakeLists.txt compiles this
// file alone with -O3 -ffast-math -fopenmp-simd):
//  - the flags single/multiple are template arguments, so uw_band_* fold their `if (!multiple)` and
//    `single ? ... : 0` away and each loop body is straight-line code;
//  - each class's loop is a function over `__restrict` pointers with `#pragma omp simd`: no aliasing
//    question between the G-buffer rows and the sums (through std::vector members GCC assumed they
//    could alias and gave up);
//  - a vector exp: with -ffast-math, glibc's <bits/math-vector.h> declares SIMD variants of expf
//    (libmvec: _ZGVbN4v_expf for SSE2, _ZGVdN8v_expf for AVX2, _ZGVeN16v_expf for AVX-512), which GCC
//    calls for 4/8/16 pixels at a time (GCC's counterpart of clang's -fveclib=libmvec);
//  - target_clones: an AVX2+FMA and an AVX-512 copy of each row, picked at load time, beside the
//    plain x86-64 one.
// results/underwater/peer_vectorisation.txt has the compiler's report and the instruction mix. The
// image differs from renderUnderwaterCpu's float one by fast-math's reassociation and libmvec's
// rounding only (tests/kernels/underwater_kd_test.cpp).
//
// Shape: per row (oneTBB over rows), the scalar ray cast fills structure-of-arrays G-buffer rows; the
// pixels are split by material class (deep water, the surface from below, a Lambertian hit), and per
// band each class runs one branch-free function of common/underwater.h (uw_band_multiple,
// uw_band_surface, uw_band_lambert) over its contiguous arrays.

#include <vector>

#include "math/kernel_math.h"
#include "underwater/underwater_cpu.h"

namespace seasim {

namespace {

namespace K = kmath_f;
using K::real;  // for the shared headers' macros (UW_INFINITE)

// One material class of a row: its pixels' G-buffer values, contiguous, and their RGB sums.
struct ClassRows {
  std::vector<int> x, albedo_index;  // pixel column; object index, or object_count for the bottom
  std::vector<float> S, dy, nx, ny, nz, vis, r, g, b;
  std::vector<float> l_r;  // scratch: the surface's reflected L_MS for one band
  void clear() {
    for (auto* v : {&x, &albedo_index}) v->clear();
    for (auto* v : {&S, &dy, &nx, &ny, &nz, &vis, &r, &g, &b, &l_r}) v->clear();
  }
  int count = 0;  // the class's pixels; the arrays are longer when padded
  // Repeats the last pixel up to a multiple of `lanes`: the band loops then run whole vectors only,
  // with no scalar remainder (scalar libm expf per pixel and band); the copies' sums are not written out.
  void pad(std::size_t lanes) {
    count = static_cast<int>(x.size());
    if (count == 0) return;
    while (x.size() % lanes != 0) add(x.back(), albedo_index.back(), S.back(), K::real3{0, dy.back(), 0},
                                      K::real3{nx.back(), ny.back(), nz.back()}, vis.back());
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
    l_r.push_back(0.0f);
  }
};

// The widest vector the clones use (AVX-512: 16 floats); the class arrays are padded to a multiple.
constexpr std::size_t kPadLanes = 16;

// What every band loop of a row reads besides the class's arrays.
struct RowConstants {
  float o_d, ior, bottom_depth;
  float s_w_x, s_w_y, s_w_z;  // the refracted sun direction; s_w_y = μ_w
};

// The three band loops. Always inlined into shadeRow, so each target clone of shadeRow vectorises them
// for its own instruction set.
#define SEASIM_BAND_LOOP [[gnu::always_inline]] inline

// L_MS along each ray (002 eq. 4.7), added to the sums: all of deep water's L, and the second term of
// the surface's.
template <int Single, int Multiple>
SEASIM_BAND_LOOP void bandMultiple(const UwBand* __restrict band, const RowConstants& c, int m,
                                   const float* __restrict S, const float* __restrict dy, float* __restrict r,
                                   float* __restrict g, float* __restrict b) {
  const float wr = band->w_r, wg = band->w_g, wb = band->w_b;
#pragma omp simd
  for (int j = 0; j < m; ++j) {
    const float L = K::uw_band_multiple(band, S[j], dy[j], c.o_d, c.s_w_y, Single, Multiple);
    r[j] += L * wr;
    g[j] += L * wg;
    b[j] += L * wb;
  }
}

// The surface seen from below, T(S) L_s: uw_band_surface (common/underwater.h) in two loops, first the
// reflected ray's L_MS into l_r, then Snell's window. Fused into one loop (or with the view ray's L_MS),
// GCC 12 leaves it scalar ("control flow in loop": Fresnel's total-internal-reflection test with
// kd_exp_integral's selects is more than its if-conversion takes).
template <int Single, int Multiple>
SEASIM_BAND_LOOP void bandSurface(const UwBand* __restrict band, const RowConstants& c, int m, const float* __restrict S,
                                  const float* __restrict dy, float* __restrict l_r, float* __restrict r,
                                  float* __restrict g, float* __restrict b) {
  const float wr = band->w_r, wg = band->w_g, wb = band->w_b, c_t = band->c, sky = band->sky_radiance;
  if (c.bottom_depth > 0.0f) {  // the reflected ray runs to the bottom
#pragma omp simd
    for (int j = 0; j < m; ++j)
      l_r[j] = K::uw_band_multiple(band, c.bottom_depth / K::fmax(dy[j], 1e-6f), -dy[j], 0.0f, c.s_w_y, Single, Multiple);
  } else {  // into deep water
#pragma omp simd
    for (int j = 0; j < m; ++j) l_r[j] = K::uw_band_multiple(band, UW_INFINITE, -dy[j], 0.0f, c.s_w_y, Single, Multiple);
  }
#pragma omp simd
  for (int j = 0; j < m; ++j) {
    const float L = K::exp(-c_t * S[j]) * K::uw_window_radiance(dy[j], c.ior, sky, l_r[j]);
    r[j] += L * wr;
    g[j] += L * wg;
    b[j] += L * wb;
  }
}

// A Lambertian hit's L = T(S) L_s + L_MS for one pixel, from scalars only: under `omp simd` GCC turns
// every aggregate declared in the loop body (a real3 built there, or copied as an argument) into a
// per-lane array it then fails to vectorise; built here, after inlining, they are plain registers.
template <int Single, int Multiple>
SEASIM_BAND_LOOP float lambertPixel(const UwBand* band, const RowConstants& c, float S, float dy, float nx, float ny,
                                    float nz, float albedo, float vis) {
  const K::real3 s_w{c.s_w_x, c.s_w_y, c.s_w_z};
  return K::exp(-band->c * S) * K::uw_band_lambert(band, S, K::real3{nx, ny, nz}, dy, c.o_d, s_w, albedo, vis, Single) +
         K::uw_band_multiple(band, S, dy, c.o_d, c.s_w_y, Single, Multiple);
}

// A Lambertian hit (an object or the bottom); alb[k] is this band's albedo of object k
// (k = object_count: the bottom), gathered per pixel.
template <int Single, int Multiple>
SEASIM_BAND_LOOP void bandLambert(const UwBand* __restrict band, const RowConstants& c, int m, const float* __restrict S,
                                  const float* __restrict dy, const float* __restrict nx, const float* __restrict ny,
                                  const float* __restrict nz, const float* __restrict vis,
                                  const int* __restrict albedo_index, const float* __restrict alb, float* __restrict r,
                                  float* __restrict g, float* __restrict b) {
  const float wr = band->w_r, wg = band->w_g, wb = band->w_b;
#pragma omp simd
  for (int j = 0; j < m; ++j) {
    const float L =
        lambertPixel<Single, Multiple>(band, c, S[j], dy[j], nx[j], ny[j], nz[j], alb[albedo_index[j]], vis[j]);
    r[j] += L * wr;
    g[j] += L * wg;
    b[j] += L * wb;
  }
}

template <int Single, int Multiple>
SEASIM_BAND_LOOP void shadeBands(const UnderwaterSetup& s, const RowConstants& c, ClassRows cls[3],
                                 std::vector<float>& band_albedo) {
  const UwParams& p = s.params;
  for (int i = 0; i < p.band_count; ++i) {
    // A copy on the stack: the loops' stores cannot reach it, so GCC keeps its fields in registers
    // (loading them from s.bands, PRE re-reads one in each loop's latch, which stops if-conversion).
    const UwBand band_copy = s.bands[i];
    const UwBand* band = &band_copy;
    for (int k = 0; k < p.object_count; ++k) band_albedo[k] = s.albedo[size_t(k) * p.band_count + i];
    band_albedo[p.object_count] = band->bottom_albedo;
    ClassRows& w = cls[0];
    bandMultiple<Single, Multiple>(band, c, static_cast<int>(w.x.size()), w.S.data(), w.dy.data(), w.r.data(),
                                   w.g.data(), w.b.data());
    ClassRows& u = cls[1];
    bandSurface<Single, Multiple>(band, c, static_cast<int>(u.x.size()), u.S.data(), u.dy.data(), u.l_r.data(),
                                  u.r.data(), u.g.data(), u.b.data());
    bandMultiple<Single, Multiple>(band, c, static_cast<int>(u.x.size()), u.S.data(), u.dy.data(), u.r.data(),
                                   u.g.data(), u.b.data());
    ClassRows& l = cls[2];
    bandLambert<Single, Multiple>(band, c, static_cast<int>(l.x.size()), l.S.data(), l.dy.data(), l.nx.data(),
                                  l.ny.data(), l.nz.data(), l.vis.data(), l.albedo_index.data(), band_albedo.data(),
                                  l.r.data(), l.g.data(), l.b.data());
  }
}

// On x86-64 with GCC, cloned for AVX-512 (16 floats per libmvec call), AVX2+FMA (8) and plain x86-64
// (SSE2, 4), picked at load time; elsewhere (an ARM GPU host, clang) the compiler's default target only.
#if defined(__x86_64__) && defined(__GNUC__) && !defined(__clang__)
#define SEASIM_SIMD_CLONES __attribute__((target_clones("arch=x86-64-v4", "arch=x86-64-v3", "default"), flatten))
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
  for (int c = 0; c < 3; ++c) cls[c].pad(kPadLanes);

  // Per band, one vectorised loop per class.
  const RowConstants c{-p.cam_pos[1], p.ior, p.bottom_depth, s_w.x, s_w.y, s_w.z};
  if (opt.single_split) {
    if (opt.multiple) shadeBands<1, 1>(s, c, cls, band_albedo);
    else shadeBands<1, 0>(s, c, cls, band_albedo);
  } else {
    if (opt.multiple) shadeBands<0, 1>(s, c, cls, band_albedo);
    else shadeBands<0, 0>(s, c, cls, band_albedo);
  }
  for (int k = 0; k < 3; ++k)
    for (int j = 0; j < cls[k].count; ++j) {
      float* px = out + 3 * size_t(cls[k].x[j]);
      px[0] = cls[k].r[j];
      px[1] = cls[k].g[j];
      px[2] = cls[k].b[j];
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
