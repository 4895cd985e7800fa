// fourflow_test.cpp — kernels/fourflow.cl (paper 003) on the device (PoCL here) against the host's
// double evaluation of the same header (kernels/common/fourflow.h, seasim::kmath_d) at the same float
// inputs: the exact spectral path (eq. 20 per band and pixel), the (l, h) tables (eq. 22–23) and the
// per-pixel blend, over pixels that include the stiff points (h = 0, l = 0, deep water ε h ≈ 200 and
// beyond, a resonant band λ0 = λ, a band without absorption); nothing the device writes is NaN/Inf.
//
// Error bound: |Δ| <= 2e-6 |want| + 2e-7 · I_rgb, I_rgb the pixel colour scale (Σ_b w_b (E_sun + E_sky)).
// The float closed form is good to ~1e-6 relative on O(I) quantities and to a few ε I absolutely on
// small ones (tests/unit/fourflow_math_test.cpp measures that); the band sums and the device's exp
// (4 ulp allowed) add a few ulp per band.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <vector>

#include "device/device.h"
#include "math/kernel_math.h"
#include "test_device.h"
#include "passes/fourflow_pass.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/fourflow_setup.h"

namespace {

namespace kd = seasim::kmath_d;

// 16 bands, 400–700 nm: clear-ish water (absorption rising to the red, λ^-4-like scattering), a sandy
// and a dark bottom material, sun and sky, and a Gaussian RGB trio. Band 3 is made resonant (k and S
// with λ0 = λ) and band 9 lossless (k = 0) to put the stiff cases inside a real band sum.
std::vector<FfBand> makeBands() {
  std::vector<FfBand> bands;
  for (int i = 0; i < 16; ++i) {
    const double nm = 400 + 20 * i;
    seasim::FourFlowBandInput in;
    in.absorption = 0.01 + 0.5 * std::pow((nm - 400) / 300, 3);
    in.scattering = 0.05 * std::pow(500 / nm, 4);
    in.mean_cosine = 0.85;
    in.e_sun = 1.2 + 0.3 * std::sin(nm / 50);
    in.e_sky = 0.4 * std::pow(450 / nm, 2);
    in.rho_a = 0.2 + 0.3 * (nm - 400) / 300;
    in.rho_b = 0.05;
    in.rho_mean = 0.5 * (in.rho_a + in.rho_b);
    auto g = [&](double mu, double sd) { return 20 * std::exp(-0.5 * std::pow((nm - mu) / sd, 2)) / 100; };
    in.rgb = {g(600, 40), g(545, 40), g(450, 30)};
    FfBand b = seasim::makeFourFlowBand(in, std::cos(35 * M_PI / 180), 1.333);
    if (i == 3) {  // resonant: k = 0.5, S = (1 - k²)/(2k) = 0.75, λ0 = 1 = λ
      b.k = 0.5f, b.S = 0.75f, b.S1 = 0.5f * 0.5f * 1.85f, b.S2 = 0.5f * 0.5f * 0.15f;
    }
    if (i == 9) {  // lossless
      b.k = 0.0f, b.S = 0.6f, b.S1 = 0.5f * 1.85f, b.S2 = 0.5f * 0.15f;
    }
    bands.push_back(b);
  }
  return bands;
}

double colourScale(const std::vector<FfBand>& bands, int c) {
  double s = 0;
  for (const FfBand& b : bands) s += b.rgb[c] * (b.e_sun + b.e_sky);
  return s;
}

class FourFlowKernelTest : public ::testing::Test {
 protected:
  static seasim::Device& device() { return seasim::test::testDevice(); }
  static cl::Program program() {
    static cl::Program p = device().program("fourflow.cl", {}).program;
    return p;
  }
  template <class T>
  static cl::Buffer input(const std::vector<T>& v) {
    return cl::Buffer(device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, v.size() * sizeof(T),
                      const_cast<T*>(v.data()));
  }
  static std::vector<float> read(const cl::Buffer& b, size_t n) {
    std::vector<float> v(n);
    device().queue().enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(float), v.data());
    return v;
  }
};

struct Pixels {
  std::vector<float> l, h, tex;
};

Pixels makePixels() {
  Pixels p;
  for (float l : {0.0f, 1e-4f, 0.5f, 3.0f, 20.0f, 200.0f, 1e4f}) {
    for (float h : {0.0f, 1e-5f, 0.05f, 1.0f, 5.0f, 15.0f, 100.0f, 400.0f, 1e4f}) {
      for (float t : {0.0f, 0.37f, 1.0f}) {
        p.l.push_back(l);
        p.h.push_back(h);
        p.tex.push_back(t);
      }
    }
  }
  return p;
}

TEST_F(FourFlowKernelTest, ExactPathMatchesDouble) {
  const std::vector<FfBand> bands = makeBands();
  const Pixels px = makePixels();
  const int n = int(px.l.size());
  cl::Buffer bb = input(bands), bl = input(px.l), bh = input(px.h), bt = input(px.tex);
  cl::Buffer out(device().context(), CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
  cl::Kernel k(program(), "ff_exact");
  k.setArg(0, bb), k.setArg(1, int(bands.size())), k.setArg(2, bl), k.setArg(3, bh), k.setArg(4, bt);
  k.setArg(5, out), k.setArg(6, n);
  device().queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n), cl::NullRange);
  const std::vector<float> got = read(out, 3 * n);
  double worst = 0;
  for (int i = 0; i < n; ++i) {
    double want[3];
    kd::ff_exact_rgb(bands.data(), int(bands.size()), px.l[i], px.h[i], px.tex[i], want);
    for (int c = 0; c < 3; ++c) {
      const double g = got[3 * i + c];
      ASSERT_TRUE(std::isfinite(g)) << i;
      const double bound = 2e-6 * std::fabs(want[c]) + 2e-7 * colourScale(bands, c);
      worst = std::max(worst, std::fabs(g - want[c]) / bound);
      EXPECT_LE(std::fabs(g - want[c]), bound) << "l=" << px.l[i] << " h=" << px.h[i] << " tex=" << px.tex[i] << " c=" << c;
      EXPECT_GE(g, 0.0);
    }
  }
  std::printf("[ measured ] fourflow exact path: %d pixels x 16 bands, worst |error| / bound %.3f\n", n, worst);
}

TEST_F(FourFlowKernelTest, TablesAndBlendMatchDouble) {
  const std::vector<FfBand> bands = makeBands();
  FfParams p{};
  p.n_bands = int(bands.size());
  p.n_l = 17, p.n_h = 13;
  p.l_max = 60.0f, p.h_max = 15.0f;
  p.gamma = 1.5f;
  for (int c = 0; c < 3; ++c) p.rgb_a[c] = 0.3f + 0.1f * c, p.rgb_b[c] = 0.05f;
  const size_t cells = size_t(p.n_l) * p.n_h;
  cl::Buffer bb = input(bands);
  cl::Buffer bp(device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(FfParams), &p);
  cl::Buffer table(device().context(), CL_MEM_READ_WRITE, cells * FF_TABLE_STRIDE * sizeof(float));
  cl::Kernel build(program(), "ff_build_tables");
  build.setArg(0, bb), build.setArg(1, bp), build.setArg(2, table);
  device().queue().enqueueNDRangeKernel(build, cl::NullRange, cl::NDRange(p.n_l, p.n_h), cl::NullRange);
  const std::vector<float> t = read(table, cells * FF_TABLE_STRIDE);
  for (int j = 0; j < p.n_h; ++j) {
    for (int i = 0; i < p.n_l; ++i) {
      double want[FF_TABLE_STRIDE];
      kd::ff_table_cell(bands.data(), p.n_bands, p.gamma, kd::ff_table_l(p, i), kd::ff_table_h(p, j), want);
      for (int q = 0; q < FF_TABLE_STRIDE; ++q) {
        const double g = t[(size_t(j) * p.n_l + i) * FF_TABLE_STRIDE + q];
        ASSERT_TRUE(std::isfinite(g));
        const double scale = (q == 3 || q % 4 == 3 || (q >= 8 && q <= 10)) ? 1.0 : colourScale(bands, q % 4);
        EXPECT_LE(std::fabs(g - want[q]), 2e-6 * std::fabs(want[q]) + 2e-7 * scale) << i << " " << j << " " << q;
      }
      // eq. 23: a in [0, 1], 1 at l = 0 (the bottom alone), falling with l.
      const double a = t[(size_t(j) * p.n_l + i) * FF_TABLE_STRIDE + 3];
      EXPECT_GE(a, 0.0);
      EXPECT_LE(a, 1.0);
      if (i == 0) EXPECT_NEAR(a, 1.0, 1e-6);
      if (i > 0) EXPECT_LE(a, t[(size_t(j) * p.n_l + i - 1) * FF_TABLE_STRIDE + 3] + 1e-7);
    }
  }
  // The blend per pixel, with the device's table on both sides (so only the lookup and eq. 22 are
  // compared here).
  const Pixels px = makePixels();
  const int n = int(px.l.size());
  cl::Buffer bl = input(px.l), bh = input(px.h), bt = input(px.tex);
  cl::Buffer out(device().context(), CL_MEM_WRITE_ONLY, 3 * n * sizeof(float));
  cl::Kernel blend(program(), "ff_table_blend");
  blend.setArg(0, bp), blend.setArg(1, table), blend.setArg(2, bl), blend.setArg(3, bh), blend.setArg(4, bt);
  blend.setArg(5, out), blend.setArg(6, n), blend.setArg(7, 0);
  device().queue().enqueueNDRangeKernel(blend, cl::NullRange, cl::NDRange(n), cl::NullRange);
  const std::vector<float> got = read(out, 3 * n);
  for (int i = 0; i < n; ++i) {
    double want[3];
    kd::ff_table_rgb(p, t.data(), px.l[i], px.h[i], px.tex[i], 0, want);
    for (int c = 0; c < 3; ++c) {
      ASSERT_TRUE(std::isfinite(got[3 * i + c]));
      EXPECT_LE(std::fabs(got[3 * i + c] - want[c]), 2e-6 * std::fabs(want[c]) + 2e-7 * colourScale(bands, c))
          << "l=" << px.l[i] << " h=" << px.h[i] << " tex=" << px.tex[i];
    }
  }
}

TEST_F(FourFlowKernelTest, TablePathIsExactAtTableNodesForTheMeanBottomAndAtZeroPath) {
  // Physics of eq. 22 (host, double): at l = 0, a = 1 and T_refr = T0 T_bottom, which is the exact
  // path when the band sums commute with the product, i.e. for a spectrally flat bottom; with a
  // coloured bottom the two differ — the error the sweep measures. At the nodes and tex giving the
  // mean bottom with a = 0 (l large), T_refr = T1 = the exact path.
  std::vector<FfBand> bands = makeBands();
  for (FfBand& b : bands) b.rho_a = b.rho_b = b.rho_mean = 0.3f;  // flat grey bottom
  FfParams p{};
  p.n_bands = int(bands.size());
  p.n_l = 9, p.n_h = 9;
  p.l_max = 400.0f, p.h_max = 15.0f;
  p.gamma = 1.0f;
  for (int c = 0; c < 3; ++c) p.rgb_a[c] = p.rgb_b[c] = 0.3f;
  std::vector<float> table(size_t(p.n_l) * p.n_h * FF_TABLE_STRIDE);
  for (int j = 0; j < p.n_h; ++j)
    for (int i = 0; i < p.n_l; ++i) {
      double cell[FF_TABLE_STRIDE];
      kd::ff_table_cell(bands.data(), p.n_bands, p.gamma, kd::ff_table_l(p, i), kd::ff_table_h(p, j), cell);
      for (int q = 0; q < FF_TABLE_STRIDE; ++q) table[(size_t(j) * p.n_l + i) * FF_TABLE_STRIDE + q] = float(cell[q]);
    }
  for (int j = 0; j < p.n_h; ++j) {
    const double h = kd::ff_table_h(p, j);
    double exact[3], fast[3];
    kd::ff_exact_rgb(bands.data(), p.n_bands, 0.0, h, 0.5, exact);
    kd::ff_table_rgb(p, table.data(), 0.0, h, 0.5, 0, fast);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fast[c], exact[c], 1e-6 * colourScale(bands, c)) << h << " " << c;
    kd::ff_exact_rgb(bands.data(), p.n_bands, p.l_max, h, 0.5, exact);
    kd::ff_table_rgb(p, table.data(), p.l_max, h, 0.5, 0, fast);
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(fast[c], exact[c], 1e-6 * colourScale(bands, c)) << h << " " << c;
  }
}

// The frame kernel ff_render over a flat bottom, exact path and tables (eq. 22 and 24), against the
// same per-pixel steps (ff_camera_dir, ff_enter_water, ff_shade) in double on the host, with the
// device's own table on both sides for the table modes. Camera 3 m up looking down over the horizon,
// so sky, grazing water and steep water are all in the frame.
TEST_F(FourFlowKernelTest, FrameKernelMatchesDouble) {
  const seasim::Scene scene = seasim::parseScene(R"(
[camera]
position = [0, 3, 0]
look_at = [0, 0.5, -10]
fov_deg = 70
width = 40
height = 24
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 4
albedo = 0.4
[shallow]
texture_scale_m = 0.7
[spectral]
count = 8
)", "frame.toml");
  const seasim::WavelengthGrid grid = seasim::makeGrid(8, 400.0, 700.0);
  const seasim::Sensor sensor = seasim::makeSensor("cie1931", grid, true);
  const seasim::FourFlowSetup s = seasim::makeFourFlowSetup(scene, grid, sensor, 16);
  const int w = s.view.width, hgt = s.view.height;
  for (int mode : {0, 1, 2}) {
    const auto& built = device().program("fourflow.cl", {"SEASIM_FF_TABLES=" + std::to_string(mode), "SEASIM_FF_HEIGHTFIELD=0"});
    cl::Buffer bv(device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(FfView), const_cast<FfView*>(&s.view));
    cl::Buffer bb = input(s.bands);
    cl::Buffer bp(device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(FfParams), const_cast<FfParams*>(&s.params));
    const size_t cells = size_t(s.params.n_l) * s.params.n_h;
    cl::Buffer table(device().context(), CL_MEM_READ_WRITE, cells * FF_TABLE_STRIDE * sizeof(float));
    cl::Kernel build(built.program, "ff_build_tables");
    build.setArg(0, bb), build.setArg(1, bp), build.setArg(2, table);
    device().queue().enqueueNDRangeKernel(build, cl::NullRange, cl::NDRange(s.params.n_l, s.params.n_h), cl::NullRange);
    const std::vector<float> t = read(table, cells * FF_TABLE_STRIDE);
    cl::Buffer out(device().context(), CL_MEM_WRITE_ONLY, 3 * size_t(w) * hgt * sizeof(float));
    cl::Kernel render(built.program, "ff_render");
    render.setArg(0, bv), render.setArg(1, bb), render.setArg(2, bp), render.setArg(3, table), render.setArg(4, out);
    device().queue().enqueueNDRangeKernel(render, cl::NullRange, cl::NDRange(w, hgt), cl::NullRange);
    const std::vector<float> got = read(out, 3 * size_t(w) * hgt);
    int water = 0;
    for (int y = 0; y < hgt; ++y) {
      for (int x = 0; x < w; ++x) {
        const kd::real3 o{s.view.cam_pos[0], s.view.cam_pos[1], s.view.cam_pos[2]};
        const kd::real3 d = kd::ff_camera_dir(s.view, x, y);
        double want[3] = {s.view.sky_rgb[0], s.view.sky_rgb[1], s.view.sky_rgb[2]};
        kd::real3 b{}, dw{};
        double F = 0;
        if (kd::ff_enter_water(s.view, o, d, &b, &F, &dw)) {
          ++water;
          const double h = s.view.bottom_depth, l = h / std::max(-dw.y, 1e-6);
          kd::ff_shade(s.view, s.bands.data(), s.params, t.data(), mode, F, l, h, b + l * dw, want);
        }
        for (int c = 0; c < 3; ++c) {
          const double g = got[3 * (size_t(y) * w + x) + c];
          ASSERT_TRUE(std::isfinite(g));
          // Float geometry: the refracted direction and the bottom point carry ~1e-6 relative errors that
          // the texture and e^{-ε l} pass on; 1e-4 of the value plus 1e-6 of the colour scale.
          EXPECT_LE(std::fabs(g - want[c]), 1e-4 * std::fabs(want[c]) + 1e-6 * colourScale(s.bands, c))
              << "mode " << mode << " pixel " << x << "," << y << " c " << c;
        }
      }
    }
    EXPECT_GT(water, w * hgt / 3) << mode;
    EXPECT_LT(water, w * hgt) << mode;  // the sky is in the frame too
  }
}

}  // namespace
