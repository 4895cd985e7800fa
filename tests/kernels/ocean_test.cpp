// ocean_test.cpp — kernels/ocean.cl + VkFFT (OceanPass) against the CPU double reference (OceanCpu)
// and against the physics of 004 §3: FFT accuracy, real (Hermitian) height, spectrum statistics over
// seeds, RMS scaling with V²/g and A, dispersion in a (k, ω) power spectrum, exact looping, folding
// (J, J-, J+), and the stiff cases (wind 0, λ large, depth -> 0, N = 2048 float vs double).
#include <fftw3.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdlib>
#include <numbers>
#include <vector>

#include "device/device.h"
#include "test_device.h"
#include "math/kernel_math.h"
#include "ocean/ocean_cpu.h"
#include "passes/ocean_pass.h"

namespace {

using seasim::OceanConfig;
using seasim::OceanCpu;
using seasim::OceanPass;

seasim::Device& device() { return seasim::test::testDevice(); }

OceanConfig smallOcean() {
  OceanConfig c;
  c.grid = 64;
  c.patch_size = 50.0;
  c.wind_speed = 8.0;
  c.wind_direction = 0.3;
  c.choppiness = 0.8;
  c.seed = 7;
  return c;
}

// max |a - b| / max |b|, over entries with stride/offset (a component of a vector map).
double maxRel(const std::vector<float>& a, const std::vector<double>& b, size_t stride = 1, size_t offset = 0) {
  double num = 0, den = 0;
  for (size_t i = offset; i < b.size(); i += stride) {
    num = std::max(num, std::abs(static_cast<double>(a[i]) - b[i]));
    den = std::max(den, std::abs(b[i]));
  }
  return den > 0 ? num / den : num;
}

bool allFinite(const std::vector<float>& v) {
  return std::all_of(v.begin(), v.end(), [](float x) { return std::isfinite(x); });
}

// Forward 2-D DFT (FFTW, e^{-ik·x}), divided by N²: the h̃(k) of a real field.
std::vector<std::complex<double>> forwardSpectrum(const std::vector<float>& field, int n) {
  std::vector<std::complex<double>> data(field.begin(), field.end());
  auto* p = reinterpret_cast<fftw_complex*>(data.data());
  fftw_plan plan = fftw_plan_dft_2d(n, n, p, p, FFTW_FORWARD, FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  for (auto& z : data) z /= static_cast<double>(n) * n;
  return data;
}

// Ph(k) Δk² on the lattice for texel (i, j), double.
double latticePower(const OceanConfig& c, int i, int j) {
  if (i == c.grid / 2 || j == c.grid / 2) return 0.0;
  const double dk = 2 * std::numbers::pi / c.patch_size;
  const double kx = dk * seasim::kmath_d::ocean_wave_index(i, c.grid);
  const double kz = dk * seasim::kmath_d::ocean_wave_index(j, c.grid);
  return seasim::kmath_d::ocean_phillips(kx, kz, std::cos(c.wind_direction), std::sin(c.wind_direction), c.wind_speed,
                                         c.gravity, c.phillips_a, c.directional_exponent, c.small_wave) * dk * dk;
}

TEST(Ocean, FftMapsMatchCpuDoubleReference) {
  const OceanConfig c = smallOcean();
  OceanPass pass(device(), c);
  OceanCpu cpu(c, OceanCpu::Precision::Double, OceanCpu::Transform::DirectDft);
  for (double t : {0.0, 1.7}) {
    pass.run(t);
    cpu.run(t);
    // 004 eq. 19, 20, 29, 30: every map within 1e-5 of the largest reference value.
    EXPECT_LT(maxRel(pass.readHeight(), cpu.height()), 1e-5) << "t=" << t;
    const auto slope = pass.readSlope();
    const auto slope_ref = cpu.slope();
    EXPECT_LT(maxRel(slope, slope_ref, 2, 0), 1e-5);
    EXPECT_LT(maxRel(slope, slope_ref, 2, 1), 1e-5);
    const auto disp = pass.readDisplacement();
    const auto disp_ref = cpu.displacement();
    for (size_t comp = 0; comp < 3; ++comp) EXPECT_LT(maxRel(disp, disp_ref, 4, comp), 1e-5) << "component " << comp;
    EXPECT_LT(maxRel(pass.readJacobian(), cpu.jacobian()), 1e-5);
    const auto nrm = pass.readNormal();
    const auto nrm_ref = cpu.normal();
    for (size_t comp = 0; comp < 3; ++comp) EXPECT_LT(maxRel(nrm, nrm_ref, 4, comp), 2e-5) << "normal " << comp;
    const auto fold = pass.readFolding();
    const auto fold_ref = cpu.folding();
    EXPECT_LT(maxRel(fold, fold_ref, 4, 0), 1e-5);
    EXPECT_LT(maxRel(fold, fold_ref, 4, 1), 1e-5);
    // The eigenvector is only defined where J- and J+ are apart.
    double worst = 0;
    for (size_t i = 0; i < fold_ref.size(); i += 4)
      if (fold_ref[i + 1] - fold_ref[i] > 1e-2)
        worst = std::max({worst, std::abs(fold[i + 2] - fold_ref[i + 2]), std::abs(fold[i + 3] - fold_ref[i + 3])});
    EXPECT_LT(worst, 1e-4);
  }
  // FFTW double agrees with the direct DFT (the reference used for large N).
  OceanCpu fftw(c, OceanCpu::Precision::Double, OceanCpu::Transform::Fftw);
  fftw.run(1.7);
  const auto a = fftw.height(), b = cpu.height();
  double d = 0;
  for (size_t i = 0; i < a.size(); ++i) d = std::max(d, std::abs(a[i] - b[i]));
  EXPECT_LT(d, 1e-12);
}

TEST(Ocean, HeightIsRealAndSpectrumHermitian) {
  const OceanConfig c = smallOcean();
  OceanPass pass(device(), c);
  const int n = c.grid;
  const auto spec = pass.heightSpectrum(2.3);
  double max_amp = 0, max_asym = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const auto a = spec[j * n + i];
      const auto b = spec[((n - j) & (n - 1)) * n + ((n - i) & (n - 1))];
      max_amp = std::max(max_amp, static_cast<double>(std::abs(a)));
      max_asym = std::max(max_asym, static_cast<double>(std::abs(a - std::conj(b))));
    }
  EXPECT_GT(max_amp, 0.0);
  EXPECT_LE(max_asym, 1e-6 * max_amp) << "h~(k,t) = h~*(-k,t) (004 eq. 26)";
  const auto h = pass.heightComplex(2.3);
  double sum2 = 0, max_imag = 0;
  for (const auto& z : h) {
    sum2 += static_cast<double>(z.real()) * z.real();
    max_imag = std::max(max_imag, static_cast<double>(std::abs(z.imag())));
  }
  const double rms = std::sqrt(sum2 / h.size());
  EXPECT_GT(rms, 0.0);
  EXPECT_LT(max_imag, 1e-6 * rms) << "imaginary part of h(x,t)";
}

TEST(Ocean, SameSeedSameOceanAndDrawsIndependentOfGrid) {
  OceanConfig c = smallOcean();
  OceanPass a(device(), c);
  const auto h0 = a.readH0();
  OceanCpu cpu(c, OceanCpu::Precision::Double);
  const auto h0_ref = cpu.h0();
  double worst = 0, peak = 0;
  for (size_t i = 0; i < h0.size(); ++i) {
    worst = std::max(worst, std::abs(std::complex<double>(h0[i]) - h0_ref[i]));
    peak = std::max(peak, std::abs(h0_ref[i]));
  }
  EXPECT_LT(worst, 2e-6 * peak) << "device h~0 = host double h~0 (same counter-based draws)";
  // Same wavenumber, other N: the same amplitude (the counter is the wavenumber, not the index).
  OceanConfig c2 = c;
  c2.grid = 32;
  c2.patch_size = c.patch_size;  // same Δk
  OceanPass b(device(), c2);
  const auto h0b = b.readH0();
  for (int q = -15; q < 16; q += 3)
    for (int m = -15; m < 16; m += 2) {
      const auto x = h0[((q + 64) % 64) * 64 + (m + 64) % 64];
      const auto y = h0b[((q + 32) % 32) * 32 + (m + 32) % 32];
      EXPECT_EQ(x, y) << "m=" << m << " q=" << q;
    }
  // Another seed: another ocean.
  c.seed = 8;
  OceanPass d(device(), c);
  const auto h0d = d.readH0();
  double diff = 0;
  for (size_t i = 0; i < h0.size(); ++i) diff += std::abs(h0[i] - h0d[i]);
  EXPECT_GT(diff, 0.1 * peak * h0.size() / 100);
}

// Over many seeds, <|h~(k,0)|²> from the generated height field is Ph(k)Δk² + Ph(-k)Δk² (eq. 22,
// 25, 26), within sampling error, in each radial band of |k|.
TEST(Ocean, SpectrumStatisticsOverSeeds) {
  OceanConfig c;
  c.grid = 32;
  c.patch_size = 120.0;
  c.wind_speed = 9.0;
  c.wind_direction = 0.7;
  const int n = c.grid, seeds = 96;
  std::vector<double> mean(n * n, 0.0);
  double mean_var = 0.0;
  for (int s = 0; s < seeds; ++s) {
    c.seed = 1000 + s;
    OceanPass pass(device(), c);
    pass.run(0.0);
    const auto h = pass.readHeight();
    const auto spec = forwardSpectrum(h, n);
    for (int i = 0; i < n * n; ++i) mean[i] += std::norm(spec[i]) / seeds;
    double v = 0;
    for (float x : h) v += static_cast<double>(x) * x;
    mean_var += v / h.size() / seeds;
  }
  const double dk = 2 * std::numbers::pi / c.patch_size;
  const double k_max = dk * n / 2;
  const int bands = 5;
  std::vector<double> got(bands, 0), want(bands, 0), var(bands, 0);
  double total_want = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int ij = ((n - j) & (n - 1)) * n + ((n - i) & (n - 1));
      const double expect = latticePower(c, i, j) + latticePower(c, (n - i) & (n - 1), (n - j) & (n - 1));
      total_want += expect;
      const double kx = dk * seasim::kmath_d::ocean_wave_index(i, n), kz = dk * seasim::kmath_d::ocean_wave_index(j, n);
      const int b = std::min(bands - 1, static_cast<int>(std::sqrt(kx * kx + kz * kz) / k_max * bands));
      got[b] += mean[j * n + i];
      want[b] += expect;
      // |h~|² is exponential (std = mean); k and -k carry the same draw, hence the factor 2.
      var[b] += (j * n + i == ij ? 1.0 : 2.0) * expect * expect / seeds / 2;
    }
  for (int b = 0; b < bands; ++b) {
    if (want[b] < 1e-6 * total_want) continue;
    const double sigma = std::sqrt(var[b]);
    EXPECT_NEAR(got[b], want[b], 4 * sigma + 1e-4 * want[b]) << "band " << b << " ratio " << got[b] / want[b];
  }
  // Parseval: <h²> = Σ_k <|h~|²>.
  EXPECT_NEAR(mean_var / total_want, 1.0, 0.15);
}

// Height scales as V²/g (with L ∝ V²/g the spectrum is self-similar: same draws, heights x 4 for
// V x 2) and as √A.
TEST(Ocean, RmsHeightScalesWithWindSquaredAndSqrtA) {
  OceanConfig c = smallOcean();
  c.choppiness = 0.0;
  OceanPass base(device(), c);
  base.run(0.0);
  const auto h = base.readHeight();
  OceanConfig c2 = c;
  c2.wind_speed = 2 * c.wind_speed;
  c2.patch_size = 4 * c.patch_size;
  OceanPass windy(device(), c2);
  windy.run(0.0);
  const auto h2 = windy.readHeight();
  OceanConfig c3 = c;
  c3.phillips_a = 4 * c.phillips_a;
  OceanPass strong(device(), c3);
  strong.run(0.0);
  const auto h3 = strong.readHeight();
  double peak = 0, e2 = 0, e3 = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    peak = std::max(peak, std::abs(static_cast<double>(h[i])));
    e2 = std::max(e2, std::abs(h2[i] - 4.0 * h[i]));
    e3 = std::max(e3, std::abs(h3[i] - 2.0 * h[i]));
  }
  EXPECT_LT(e2, 4 * 2e-6 * peak) << "V -> 2V (L -> 4L): h -> 4h";
  EXPECT_LT(e3, 2 * 2e-6 * peak) << "A -> 4A: h -> 2h";
}

// The experiment of 004 §3.6 on our own output: a (k, ω) power spectrum of an animated field
// puts >= 95 % of its energy on ω = ±ω(k).
// check_depth: the depth of the dispersion relation the energy is checked against.
double dispersionFraction(const OceanConfig& c, int frames, double dt, bool hann, double tolerance_bins,
                          double check_depth) {
  OceanPass pass(device(), c);
  const int n = c.grid;
  std::vector<std::vector<std::complex<double>>> spec(frames);
  for (int f = 0; f < frames; ++f) {
    pass.run(f * dt);
    spec[f] = forwardSpectrum(pass.readHeight(), n);
  }
  const double dk = 2 * std::numbers::pi / c.patch_size;
  const double d_omega = 2 * std::numbers::pi / (frames * dt);
  double on = 0, total = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double kx = dk * seasim::kmath_d::ocean_wave_index(i, n), kz = dk * seasim::kmath_d::ocean_wave_index(j, n);
      const double k = std::sqrt(kx * kx + kz * kz);
      if (k == 0) continue;
      const double w = seasim::kmath_d::ocean_omega(k, c.gravity, check_depth);
      for (int q = 0; q < frames; ++q) {
        const int signed_q = q < frames / 2 ? q : q - frames;
        std::complex<double> acc = 0;
        for (int f = 0; f < frames; ++f) {
          const double win = hann ? 0.5 - 0.5 * std::cos(2 * std::numbers::pi * f / frames) : 1.0;
          acc += win * spec[f][j * n + i] * std::polar(1.0, -2 * std::numbers::pi * q * f / frames);
        }
        const double p = std::norm(acc);
        total += p;
        if (std::abs(std::abs(signed_q * d_omega) - w) <= tolerance_bins * d_omega) on += p;
      }
    }
  return on / total;
}

TEST(Ocean, DispersionEnergyOnBranches) {
  OceanConfig c;
  c.grid = 32;
  c.patch_size = 40.0;
  c.wind_speed = 5.0;
  // Deep water, no loop: windowed, energy within 2 frequency bins of ±√(gk).
  const double deep = dispersionFraction(c, 64, 0.2, true, 2.0, 0.0);
  EXPECT_GE(deep, 0.95) << "deep water";
  // Finite depth (eq. 15) with a loop (eq. 18): frequencies on the bins, within 1 bin of ±ω(k).
  c.depth = 0.5;
  c.loop_period = 64 * 0.2;
  const double shallow = dispersionFraction(c, 64, 0.2, false, 1.0, c.depth);
  EXPECT_GE(shallow, 0.95) << "finite depth";
  // The deep-water branches do not hold the shallow field's energy: the test can fail.
  const double mismatch = dispersionFraction(c, 64, 0.2, false, 1.0, 0.0);
  EXPECT_LT(mismatch, 0.5);
}

TEST(Ocean, LoopPeriodRepeatsExactly) {
  OceanConfig c = smallOcean();
  c.loop_period = 7.3;
  OceanPass pass(device(), c);
  pass.run(1.1);
  const auto a = pass.readDisplacement();
  pass.run(1.1 + 7.3);
  const auto b = pass.readDisplacement();
  pass.run(1.1 + 3 * 7.3);
  const auto d = pass.readDisplacement();
  double peak = 0, diff = 0, diff3 = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    peak = std::max(peak, std::abs(static_cast<double>(a[i])));
    diff = std::max(diff, std::abs(static_cast<double>(a[i]) - b[i]));
    diff3 = std::max(diff3, std::abs(static_cast<double>(a[i]) - d[i]));
  }
  EXPECT_LE(diff, 1e-6 * peak);
  EXPECT_LE(diff3, 1e-6 * peak);
  pass.run(1.1 + 7.3 / 2);
  const auto half = pass.readDisplacement();
  double moved = 0;
  for (size_t i = 0; i < a.size(); ++i) moved = std::max(moved, std::abs(static_cast<double>(a[i]) - half[i]));
  EXPECT_GT(moved, 0.1 * peak) << "the surface does move within the period";
}

TEST(Ocean, NoChoppinessMeansUnitJacobian) {
  OceanConfig c = smallOcean();
  c.choppiness = 0.0;
  OceanPass pass(device(), c);
  pass.run(0.9);
  const auto J = pass.readJacobian();
  const auto fold = pass.readFolding();
  const auto slope = pass.readSlope();
  const auto nrm = pass.readNormal();
  for (size_t i = 0; i < J.size(); ++i) {
    ASSERT_EQ(J[i], 1.0f);
    ASSERT_EQ(fold[4 * i], 1.0f);
    ASSERT_EQ(fold[4 * i + 1], 1.0f);
    // Normal of the height field: (-hx, 1, -hz) / |.|.
    const double hx = slope[2 * i], hz = slope[2 * i + 1], len = std::sqrt(1 + hx * hx + hz * hz);
    ASSERT_NEAR(nrm[4 * i], -hx / len, 1e-6);
    ASSERT_NEAR(nrm[4 * i + 1], 1 / len, 1e-6);
    ASSERT_NEAR(nrm[4 * i + 2], -hz / len, 1e-6);
  }
}

// J < 0 exactly where the displaced surface overlaps itself: the signed area of each displaced grid
// cell has the sign of J there; J- <= J+, J = J- J+, e- is J-'s unit eigenvector (eq. 30–34).
TEST(Ocean, FoldingWhereDisplacedSurfaceOverlaps) {
  OceanConfig c;
  c.grid = 64;
  c.patch_size = 200.0;
  c.wind_speed = 10.0;
  c.small_wave = 2.0;  // keep waves several cells long so a cell's area measures J
  c.choppiness = 7.0;
  c.seed = 3;
  OceanPass pass(device(), c);
  pass.run(0.0);
  const int n = c.grid;
  const double cell = c.patch_size / n;
  const auto disp = pass.readDisplacement();
  const auto J = pass.readJacobian();
  const auto fold = pass.readFolding();
  int negative = 0, compared = 0, agree = 0;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const size_t at = static_cast<size_t>(j) * n + i;
      negative += J[at] < 0;
      // Eigen-decomposition.
      const double jm = fold[4 * at], jp = fold[4 * at + 1], ex = fold[4 * at + 2], ez = fold[4 * at + 3];
      ASSERT_LE(jm, jp);
      ASSERT_NEAR(jm * jp, J[at], 1e-5 * std::max(1.0, std::abs(jm * jp)));
      ASSERT_NEAR(ex * ex + ez * ez, 1.0, 1e-5);
      // Displaced cell (i, j)-(i+1, j+1), periodic.
      auto corner = [&](int di, int dj, double* x, double* z) {
        const int ii = (i + di) % n, jj = (j + dj) % n;
        const size_t a = static_cast<size_t>(jj) * n + ii;
        *x = (i + di) * cell + disp[4 * a];
        *z = (j + dj) * cell + disp[4 * a + 2];
      };
      double x[4], z[4];
      corner(0, 0, &x[0], &z[0]);
      corner(1, 0, &x[1], &z[1]);
      corner(1, 1, &x[2], &z[2]);
      corner(0, 1, &x[3], &z[3]);
      double area = 0;  // shoelace in the (x, z) plane; +cell² for the identity map
      for (int q = 0; q < 4; ++q) area += x[q] * z[(q + 1) % 4] - x[(q + 1) % 4] * z[q];
      area *= 0.5;
      double jbar = 0;
      for (int q = 0; q < 4; ++q) {
        const int ii = (i + (q == 1 || q == 2)) % n, jj = (j + (q >= 2)) % n;
        jbar += 0.25 * J[static_cast<size_t>(jj) * n + ii];
      }
      if (std::abs(jbar) < 0.15) continue;  // the fold line itself: sign decided by discretisation
      ++compared;
      agree += (area < 0) == (jbar < 0);
    }
  EXPECT_GT(negative, n * n / 100) << "this sea should fold somewhere";
  std::printf("folded texels %d of %d; cells compared %d, sign agreement %d\n", negative, n * n, compared, agree);
  EXPECT_GT(compared, n * n / 2);
  EXPECT_GE(agree, compared - compared / 200) << agree << " of " << compared;
}

TEST(Ocean, StiffWindZeroIsFlat) {
  OceanConfig c = smallOcean();
  c.wind_speed = 0.0;
  c.choppiness = 1.0;
  OceanPass pass(device(), c);
  pass.run(3.0);
  const auto h = pass.readHeight();
  const auto nrm = pass.readNormal();
  const auto J = pass.readJacobian();
  for (size_t i = 0; i < h.size(); ++i) {
    ASSERT_EQ(h[i], 0.0f);
    ASSERT_EQ(nrm[4 * i + 1], 1.0f);
    ASSERT_EQ(J[i], 1.0f);
  }
}

TEST(Ocean, StiffLargeChoppinessFoldsEverywhereWithoutNaN) {
  OceanConfig c = smallOcean();
  c.choppiness = 40.0;
  OceanPass pass(device(), c);
  pass.run(0.5);
  for (const auto& v : {pass.readHeight(), pass.readSlope(), pass.readDisplacement(), pass.readNormal(),
                        pass.readJacobian(), pass.readFolding()})
    ASSERT_TRUE(allFinite(v));
  const auto J = pass.readJacobian();
  const auto fold = pass.readFolding();
  size_t negative = 0;
  for (size_t i = 0; i < J.size(); ++i) {
    negative += J[i] < 0;
    ASSERT_LE(fold[4 * i], fold[4 * i + 1]);
    ASSERT_EQ(J[i] < 0, fold[4 * i] < 0 && fold[4 * i + 1] > 0) << "J < 0 means J- < 0 < J+";
  }
  EXPECT_GT(negative, J.size() / 5);
}

TEST(Ocean, StiffShallowDepthDispersion) {
  OceanConfig c = smallOcean();
  c.depth = 1e-4;
  OceanPass pass(device(), c);
  OceanCpu cpu(c);
  pass.run(20.0);
  cpu.run(20.0);
  ASSERT_TRUE(allFinite(pass.readHeight()));
  EXPECT_LT(maxRel(pass.readHeight(), cpu.height()), 1e-5);
}

// N = 2048 (the paper's upper limit, "numerical accuracy ... can become noticeable"): float on the
// device against double FFTW.
TEST(Ocean, StiffN2048FloatAgainstDouble) {
  OceanConfig c;
  c.grid = 2048;
  c.patch_size = 1000.0;
  c.wind_speed = 31.0;  // the paper's Figure 6 sea (gale, ℓ = 1 m)
  c.small_wave = 1.0;
  c.choppiness = 1.0;
  OceanPass pass(device(), c);
  pass.run(2.0);
  const auto h = pass.readHeight();
  const auto J = pass.readJacobian();
  OceanCpu cpu(c, OceanCpu::Precision::Double, OceanCpu::Transform::Fftw);
  cpu.run(2.0);
  const auto h_ref = cpu.height();
  const auto J_ref = cpu.jacobian();
  double num = 0, den = 0;
  for (size_t i = 0; i < h.size(); ++i) {
    num += (h[i] - h_ref[i]) * (h[i] - h_ref[i]);
    den += h_ref[i] * h_ref[i];
  }
  const double rel_l2 = std::sqrt(num / den);
  const double rel_max = maxRel(h, h_ref);
  std::printf("N=2048 height: relative L2 %.3g, max relative %.3g; Jacobian max relative %.3g\n", rel_l2, rel_max,
              maxRel(J, J_ref));
  EXPECT_LT(rel_l2, 1e-5);
  EXPECT_LT(rel_max, 1e-4);
  EXPECT_LT(maxRel(J, J_ref), 1e-4);
}

}  // namespace
