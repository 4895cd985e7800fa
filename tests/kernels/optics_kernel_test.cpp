// optics_kernel_test.cpp — kernels/common/optics.h as the device compiles it (float, OpenCL C,
// through kernels/optics_check.cl and the Device API) against the host's double evaluation of the
// same header (seasim::kmath_d) at the same float inputs, over grids that include the stiff points:
// θ = 0, the critical angle ± 1e-6 rad, grazing, |g| -> 1 at cos θ -> ±1, x -> 0 in (e^x - 1)/x.
//
// Error bounds (ε = FLT_EPSILON ≈ 1.19e-7; OpenCL 1.2 allows sqrt/cos/exp/expm1 3–4 ulp and
// division 2.5 ulp in float, so a few tens of ε is the honest budget):
//   Fresnel R      |Δ| ≤ 16ε (1 + 1/max(cos θt, √ε)): the slope dR/dcos θi grows like 1/cos θt
//                  at the critical angle, so float rounding of 1 - η² sin²θi is amplified there.
//   refraction     |Δt| ≤ 16ε (1 + 1/max(cos θt, √ε)) per component, same reason; TIR flag equal
//                  wherever |η sin θi - 1| > 1e-5 (closer is below float resolution of the input).
//   reflection     |Δr| ≤ 8ε per component.
//   HG             |Δp| ≤ 32ε p (stable form: no cancellation, den·√den ≈ 6 roundings).
//   shafts (cos)   |ΔF| ≤ 16ε F (three squarings); shafts (angle) |ΔF| ≤ 96ε F: cos(α/2) is good
//                  to 4 ulp and F raises it to the 16th power.
//   Beer–Lambert   |ΔT| ≤ 8ε T (1 + σd) + FLT_MIN: rounding σd is an ε σd error in the exponent;
//                  FLT_MIN absorbs flush-to-zero of subnormal results.
//   expm1_over_x   |Δ| ≤ 1e-6 relative (≈ 8ε).
// And nothing the device writes is NaN or Inf.
#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <algorithm>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include "device/device.h"
#include "test_device.h"
#include "math/kernel_math.h"

namespace {

namespace kd = seasim::kmath_d;

constexpr double kEps = FLT_EPSILON;
constexpr double kPi = 3.14159265358979323846;
constexpr double kAir = 1.0;
constexpr double kWater = 1.333;

// The device under test: tests/kernels/test_device.h.
class OpticsKernelTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    program_ = device().program("optics_check.cl", {}).program;
  }
  static void TearDownTestSuite() {
    program_ = cl::Program();
  }

  template <class T>
  static cl::Buffer input(const std::vector<T>& v) {
    return cl::Buffer(device().context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR,
                      v.size() * sizeof(T), const_cast<T*>(v.data()));
  }
  template <class T>
  static cl::Buffer output(size_t n) {
    return cl::Buffer(device().context(), CL_MEM_WRITE_ONLY, n * sizeof(T));
  }
  template <class T>
  static std::vector<T> read(const cl::Buffer& b, size_t n) {
    std::vector<T> v(n);
    device().queue().enqueueReadBuffer(b, CL_TRUE, 0, n * sizeof(T), v.data());
    return v;
  }
  // Sets the arguments in order and runs one work-item per element.
  template <class... Args>
  static void run(const char* name, size_t n, const Args&... args) {
    cl::Kernel k(program_, name);
    cl_uint i = 0;
    (k.setArg(i++, args), ...);
    device().queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(n), cl::NullRange);
    device().queue().finish();
  }

  static seasim::Device& device() { return seasim::test::testDevice(); }
  static cl::Program program_;
};
cl::Program OpticsKernelTest::program_;

// cos θt for the float inputs, in double (the conditioning factor of the bounds above).
double cosT(double cos_i, double eta) {
  double ct2 = kd::snell_cos_t2(cos_i, eta);
  return ct2 > 0 ? std::sqrt(ct2) : 0.0;
}
double nearCriticalFactor(double cos_t) { return 1 + 1 / std::max(cos_t, std::sqrt(kEps)); }

void expectFinite(const std::vector<float>& v, const char* what) {
  for (size_t i = 0; i < v.size(); ++i) ASSERT_TRUE(std::isfinite(v[i])) << what << "[" << i << "]";
}

TEST_F(OpticsKernelTest, FresnelMatchesDouble) {
  std::vector<float> c, n1, n2;
  auto add = [&](double cos_i, double a, double b) {
    c.push_back(float(cos_i));
    n1.push_back(float(a));
    n2.push_back(float(b));
  };
  for (auto [a, b] : {std::pair{kAir, kWater}, std::pair{kWater, kAir}, std::pair{1.0, 1.5}}) {
    for (int i = 0; i <= 2000; ++i) add(std::cos(i * (kPi / 2) / 2000), a, b);
    // Stiff points: θ = 0 from both sides of the normal, grazing and just off it.
    for (double s : {1.0, -1.0, 0.0, 1e-6, 1e-3, -1e-3}) add(s, a, b);
    if (a > b) {  // the critical angle and ±1e-6, ±1e-5, ±1e-4 rad around it
      double crit = std::asin(b / a);
      for (double d : {0.0, 1e-6, -1e-6, 1e-5, -1e-5, 1e-4, -1e-4}) add(std::cos(crit + d), a, b);
    }
  }
  add(0.7, 1.333, 1.333);  // no interface
  const size_t n = c.size();
  cl::Buffer bc = input(c), b1 = input(n1), b2 = input(n2), bo = output<float>(n);
  run("check_fresnel", n, bc, b1, b2, bo);
  std::vector<float> got = read<float>(bo, n);
  expectFinite(got, "fresnel");

  double max_regular = 0, max_critical = 0;
  for (size_t i = 0; i < n; ++i) {
    double expect = kd::fresnel_reflectance(c[i], n1[i], n2[i]);
    double cos_t = cosT(c[i], double(n1[i]) / n2[i]);
    double err = std::fabs(got[i] - expect);
    EXPECT_LE(err, 16 * kEps * nearCriticalFactor(cos_t))
        << "cos_i=" << c[i] << " n1=" << n1[i] << " n2=" << n2[i] << " cos_t=" << cos_t;
    EXPECT_GE(got[i], 0.0f);
    EXPECT_LE(got[i], 1.0f);
    double& max_err = (cos_t > 0.1 || cos_t == 0) ? max_regular : max_critical;
    max_err = std::max(max_err, err);
  }
  std::printf("[ measured ] fresnel: max |dR| %.3g (cos t > 0.1 or TIR), %.3g (near critical), %zu points\n",
              max_regular, max_critical, n);
}

TEST_F(OpticsKernelTest, RefractReflectMatchDouble) {
  std::vector<float> dir, nrm, eta;
  auto add = [&](double dx, double dy, double dz, double nx, double ny, double nz, double e) {
    double l = std::sqrt(dx * dx + dy * dy + dz * dz), m = std::sqrt(nx * nx + ny * ny + nz * nz);
    for (double v : {dx / l, dy / l, dz / l}) dir.push_back(float(v));
    for (double v : {nx / m, ny / m, nz / m}) nrm.push_back(float(v));
    eta.push_back(float(e));
  };
  std::mt19937 rng(7);
  std::normal_distribution<double> gauss;
  for (double e : {kAir / kWater, kWater / kAir, 1.0, 1.5}) {
    for (int k = 0; k < 1000; ++k) {
      add(gauss(rng), gauss(rng), gauss(rng), gauss(rng), gauss(rng), gauss(rng), e);
    }
  }
  // Stiff: normal incidence, grazing, and the critical angle ± 1e-4 from below the surface.
  add(0, -1, 0, 0, 1, 0, kAir / kWater);
  add(0, 1, 0, 0, 1, 0, kWater / kAir);
  add(1, -1e-6, 0, 0, 1, 0, kAir / kWater);
  double crit = std::asin(kAir / kWater);
  for (double d : {-1e-4, 1e-4}) {
    add(std::sin(crit + d), std::cos(crit + d), 0, 0, 1, 0, kWater / kAir);
  }
  const size_t n = eta.size();
  cl::Buffer bd = input(dir), bn = input(nrm), be = input(eta);
  cl::Buffer bt = output<float>(3 * n), bok = output<cl_int>(n), br = output<float>(3 * n);
  run("check_refract_reflect", n, bd, bn, be, bt, bok, br);
  std::vector<float> t = read<float>(bt, 3 * n), r = read<float>(br, 3 * n);
  std::vector<cl_int> ok = read<cl_int>(bok, n);
  expectFinite(t, "refracted");
  expectFinite(r, "reflected");

  double max_t = 0, max_r = 0;
  int compared = 0;
  for (size_t i = 0; i < n; ++i) {
    kd::real3 d{dir[3 * i], dir[3 * i + 1], dir[3 * i + 2]};
    kd::real3 nn{nrm[3 * i], nrm[3 * i + 1], nrm[3 * i + 2]};
    kd::real3 te{};
    int ok_d = kd::refract_dir(d, nn, eta[i], &te);
    kd::real3 re = kd::reflect_dir(d, nn);
    double cos_i = std::fabs(kd::dot(d, nn));
    double s = eta[i] * std::sqrt(std::max(0.0, 1 - cos_i * cos_i));
    if (std::fabs(s - 1) > 1e-5) {
      EXPECT_EQ(ok[i], ok_d) << "TIR flag, eta sin θi = " << s;
      if (ok[i] != ok_d) continue;
      double tol = 16 * kEps * nearCriticalFactor(cosT(cos_i, eta[i]));
      double e = std::max({std::fabs(t[3 * i] - te.x), std::fabs(t[3 * i + 1] - te.y),
                           std::fabs(t[3 * i + 2] - te.z)});
      EXPECT_LE(e, tol) << "refracted, i=" << i << " eta sin θi = " << s;
      max_t = std::max(max_t, e);
      ++compared;
    }
    double er = std::max({std::fabs(r[3 * i] - re.x), std::fabs(r[3 * i + 1] - re.y),
                          std::fabs(r[3 * i + 2] - re.z)});
    EXPECT_LE(er, 8 * kEps) << "reflected, i=" << i;
    max_r = std::max(max_r, er);
  }
  EXPECT_GT(compared, 3900);
  std::printf("[ measured ] refract: max |dt| %.3g over %d; reflect: max |dr| %.3g\n", max_t,
              compared, max_r);
}

TEST_F(OpticsKernelTest, HenyeyGreensteinMatchesDouble) {
  std::vector<float> c, g;
  for (double gd : {-0.9999, -0.999, -0.99, -0.5, 0.0, 0.3, 0.9, 0.99, 0.999, 0.9999}) {
    for (int i = 0; i <= 200; ++i) {
      c.push_back(float(-1 + 2.0 * i / 200));
      g.push_back(float(gd));
    }
    // The spikes: cos θ within a few float steps of ±1.
    for (double cd : {1.0, 1 - 6e-8, 1 - 1e-6, 1 - 1e-4, -1.0, -1 + 6e-8, -1 + 1e-6, -1 + 1e-4}) {
      c.push_back(float(cd));
      g.push_back(float(gd));
    }
  }
  const size_t n = c.size();
  cl::Buffer bc = input(c), bg = input(g), bo = output<float>(n);
  run("check_hg", n, bc, bg, bo);
  std::vector<float> got = read<float>(bo, n);
  expectFinite(got, "hg");
  double max_rel = 0;
  for (size_t i = 0; i < n; ++i) {
    double expect = kd::hg_phase(c[i], g[i]);
    double rel = std::fabs(got[i] - expect) / expect;
    EXPECT_LE(rel, 32 * kEps) << "cos=" << c[i] << " g=" << g[i];
    max_rel = std::max(max_rel, rel);
  }
  std::printf("[ measured ] hg: max rel %.3g over %zu points\n", max_rel, n);
}

TEST_F(OpticsKernelTest, ShaftsPhaseMatchesDouble) {
  std::vector<float> a, c;
  for (int i = 0; i <= 720; ++i) {
    a.push_back(float(kPi * i / 720));
    c.push_back(float(-1 + 2.0 * i / 720));
  }
  const size_t n = a.size();
  cl::Buffer ba = input(a), bc = input(c), boa = output<float>(n), boc = output<float>(n);
  run("check_shafts", n, ba, bc, boa, boc);
  std::vector<float> fa = read<float>(boa, n), fc = read<float>(boc, n);
  expectFinite(fa, "shafts(angle)");
  expectFinite(fc, "shafts(cos)");
  double max_a = 0, max_c = 0;
  for (size_t i = 0; i < n; ++i) {
    double ea = kd::shafts_phase(a[i]), ec = kd::shafts_phase_cos(c[i]);
    double ra = std::fabs(fa[i] - ea) / ea, rc = std::fabs(fc[i] - ec) / ec;
    EXPECT_LE(ra, 96 * kEps) << "alpha=" << a[i];
    EXPECT_LE(rc, 16 * kEps) << "cos alpha=" << c[i];
    max_a = std::max(max_a, ra);
    max_c = std::max(max_c, rc);
  }
  std::printf("[ measured ] shafts: max rel %.3g (angle form), %.3g (cos form)\n", max_a, max_c);
}

TEST_F(OpticsKernelTest, BeerLambertMatchesDouble) {
  std::vector<float> s, d;
  for (double sd : {0.0, 0.01, 0.1, 1.0, 10.0, 100.0}) {
    for (double dd : {0.0, 1e-3, 0.1, 1.0, 10.0, 100.0, 1e4}) {
      s.push_back(float(sd));
      d.push_back(float(dd));
    }
  }
  const size_t n = s.size();
  cl::Buffer bs = input(s), bd = input(d), bo = output<float>(n);
  run("check_beer_lambert", n, bs, bd, bo);
  std::vector<float> got = read<float>(bo, n);
  expectFinite(got, "beer_lambert");
  for (size_t i = 0; i < n; ++i) {
    double expect = kd::beer_lambert(s[i], d[i]);
    double tol = 8 * kEps * expect * (1 + double(s[i]) * d[i]) + FLT_MIN;
    EXPECT_NEAR(got[i], expect, tol) << "sigma=" << s[i] << " d=" << d[i];
    EXPECT_GE(got[i], 0.0f);
    if (s[i] == 0 || d[i] == 0) {
      EXPECT_EQ(got[i], 1.0f);
    }
  }
}

TEST_F(OpticsKernelTest, Expm1OverXMatchesDouble) {
  std::vector<float> x;
  // 0, ±tiny (FLT_MIN, 1e-30), both sides of the series/exp switch at |x| = 0.5, ±large (88 is
  // just below float's exp overflow; -1e4 and -1e30 give -1/x), plus a sweep over [-90, 88].
  for (double v : {0.0, 1e-30, double(FLT_MIN), 1e-8, 1e-6, 1e-4, 9.99e-4, 1e-3, 1.001e-3, 0.01, 0.25, 0.4999,
                   0.5, 0.5001, 1.0, 10.0, 50.0, 88.0}) {
    x.push_back(float(v));
    x.push_back(float(-v));
  }
  x.push_back(std::nextafter(0.5f, 0.0f));
  x.push_back(-std::nextafter(0.5f, 0.0f));
  x.push_back(-1e4f);
  x.push_back(-1e30f);
  for (int i = -900; i <= 880; ++i) x.push_back(float(i) * 0.1f);
  const size_t n = x.size();
  cl::Buffer bx = input(x), bo = output<float>(n);
  run("check_expm1_over_x", n, bx, bo);
  std::vector<float> got = read<float>(bo, n);
  expectFinite(got, "expm1_over_x");
  double max_rel = 0;
  for (size_t i = 0; i < n; ++i) {
    double expect = kd::expm1_over_x(x[i]);
    double rel = std::fabs(got[i] / expect - 1);
    EXPECT_LE(rel, 1e-6) << "x=" << x[i];
    max_rel = std::max(max_rel, rel);
  }
  std::printf("[ measured ] expm1_over_x: max rel %.3g over %zu points\n", max_rel, n);
}

}  // namespace
