// underwater_improved_ordinates_test.cpp — the improved underwater model's diffuse field from discrete
// ordinates (underwater.improved_diffuse = "discrete_ordinates", the default; host/underwater/
// underwater_improved_ordinates.*, issue 13 s9a): the band's exponentials hold the solver's field (E_d,
// E_u, E_0, F_h) over the depths the frame sees, as the kernel evaluates them in float and double; k
// keeps away from the beam's m; no horizontal flux where the field has none; degenerate bands stay
// finite; the source's azimuth factor.
#include <gtest/gtest.h>

#include <cmath>

#include "math/kernel_math.h"
#include "underwater/discrete_ordinates.h"
#include "underwater/underwater_improved_ordinates.h"

#include "underwater_improved_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
using seasim::DiscreteOrdinates;
using seasim::DiscreteOrdinatesLayer;
using seasim::makeUwiBandFromOrdinates;
using seasim::OrdinatesFitError;
using seasim::testing::uwTestBand;

constexpr double kMuW = 0.9273;  // the sun 30° from the zenith, refracted (n = 1.34)

DiscreteOrdinatesLayer layerOf(const UwBand& b, double g, double H) {
  DiscreteOrdinatesLayer l;
  l.a = b.a;
  l.b = b.b;
  l.g = g;
  l.bottom_depth = H;
  l.bottom_albedo = b.bottom_albedo;
  l.ior = 1.34;
  l.mu_sun = kMuW;
  l.e_sun0 = b.e_sun0;
  l.e_sky0 = b.e_sky0;
  return l;
}

// E_d (with the kernel's delta-M beam) and E_u from the band as the kernel evaluates them
// (uwi_irradiance), against the solver's, over the bottom's whole depth: within 4 % (the fit's measured
// largest errors, printed: 0.05–0.5 % in clear water, 1.3–3.6 % at 8 optical depths, where three
// exponentials no longer hold the field near both ends).
TEST(UnderwaterImprovedOrdinates, BandHoldsTheSolversIrradiance) {
  struct Case {
    double a, b, g, H;
  };
  for (const Case c : {Case{0.1, 0.3, 0.9, 5}, Case{0.1, 0.3, 0.0, 20}, Case{0.03, 0.05, 0.95, 2},
                       Case{0.4, 1.2, 0.5, 5}}) {
    const UwBand band = uwTestBand(c.a, c.b, 0.146, 0.85, kMuW, 0.35);
    OrdinatesFitError fit;
    const UwiBand ib = makeUwiBandFromOrdinates(band, c.g, kMuW, c.H, 1.34, c.H - 1.2, 1.2, 16, &fit);
    std::printf("a %.2f b %.2f g %.2f H %2.0f: k %.4f m %.4f, fit errors E_d %.4f E_u %.4f E_0 %.4f F_h %.4f\n", c.a,
                c.b, c.g, c.H, ib.k, ib.m, fit.down, fit.up, fit.scalar, fit.horizontal);
    EXPECT_LT(fit.down, 0.04);
    EXPECT_LT(fit.up, 0.04);
    EXPECT_LT(fit.scalar, 0.04);
    const DiscreteOrdinates field(layerOf(band, c.g, c.H), 16);
    for (int i = 0; i <= 20; ++i) {
      const double y = c.H * i / 20;
      double ed = 0, eu = 0;
      kd::uwi_irradiance(&ib, c.H, y, &ed, &eu);
      float edf = 0, euf = 0;
      kf::uwi_irradiance(&ib, float(c.H), float(y), &edf, &euf);
      const auto e = field.at(y);
      const double total = e.down + e.beam_down, beam = band.e_sun0 * std::exp(-double(ib.m) * y);
      EXPECT_NEAR(ed + beam, total, 0.04 * total) << c.g << " " << y;
      EXPECT_NEAR(eu, e.up, 0.04 * e.up) << c.g << " " << y;
      EXPECT_NEAR(edf, ed, 1e-5 * total) << y;  // float: the exponentials' cancellation stays small
      EXPECT_NEAR(euf, eu, 1e-5 * total) << y;
    }
    // k is not the beam's m (their exponentials would cancel each other's digits), and decays no
    // slower than the field's K∞ within the scan's range.
    EXPECT_GT(std::abs(ib.k - ib.m), 0.019 * ib.m);
    EXPECT_GE(ib.k, 0.79 * field.asymptoticK());
    EXPECT_LE(ib.k, 2.51 * field.asymptoticK());
  }
}

// The band's scalar irradiance and horizontal flux: E_0 within 2.5 % of the solver's less the beam's; F_h
// 0 at g = 0 and with the sun at the zenith; without a bottom the second exponential is unused.
TEST(UnderwaterImprovedOrdinates, ScalarIrradianceAndHorizontalFlux) {
  const UwBand band = uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.35);
  const UwiBand ib = makeUwiBandFromOrdinates(band, 0.9, kMuW, 5, 1.34, 3.8, 1.2);
  const DiscreteOrdinates field(layerOf(band, 0.9, 5), 16), field_h(layerOf(band, 0.9, 5), 16, 1);
  for (double y : {0.0, 1.0, 3.8, 5.0}) {
    const double ek = std::exp(-double(ib.k) * y), e2 = std::exp(-double(ib.k) * (5 - y)),
                 ep = std::exp(-double(ib.m) * y);
    const double o = ib.o1 * ek + ib.o2 * e2 + ib.op * ep, h = ib.h1 * ek + ib.h2 * e2 + ib.hp * ep;
    const auto e = field.at(y);
    const double beam_scalar = band.e_sun0 / kMuW * ep;
    EXPECT_NEAR(o + beam_scalar, e.scalar + e.beam_scalar, 0.025 * (e.scalar + e.beam_scalar)) << y;
    const auto eh = field_h.at(y);
    EXPECT_NEAR(h + beam_scalar * std::sqrt(1 - kMuW * kMuW), eh.horizontal + eh.beam_horizontal,
                0.025 * (e.scalar + e.beam_scalar))
        << y;
    EXPECT_GT(h, 0.0) << y;  // the diffuse light flows along the sun's azimuth
  }
  const UwiBand iso = makeUwiBandFromOrdinates(band, 0.0, kMuW, 5, 1.34, 3.8, 1.2);
  const UwiBand zenith = makeUwiBandFromOrdinates(band, 0.9, 1.0, 5, 1.34, 3.8, 1.2);
  for (const UwiBand& b : {iso, zenith}) {
    EXPECT_EQ(b.h1, 0.0f);
    EXPECT_EQ(b.h2, 0.0f);
    EXPECT_EQ(b.hp, 0.0f);
  }
  const UwiBand deep = makeUwiBandFromOrdinates(band, 0.9, kMuW, 0, 1.34, 3.8, 1.2);
  EXPECT_EQ(deep.d2, 0.0f);
  EXPECT_EQ(deep.u2, 0.0f);
  EXPECT_EQ(deep.o2, 0.0f);
  EXPECT_GT(deep.d1 + deep.dp, 0.0f);
  // g_flux = s g'.
  EXPECT_FLOAT_EQ(ib.g_flux, float(1.2 * 0.9 / 1.9));
  EXPECT_FLOAT_EQ(ib.c_dm, float(0.1 + 0.3 * (1 - 0.81)));
}

// No medium, no light, no absorption, no scattering, a black bottom 1 mm down: every coefficient finite,
// and no light gives no field.
TEST(UnderwaterImprovedOrdinates, DegenerateBandsStayFinite) {
  auto finite = [](const UwiBand& b) {
    for (float v : {b.k, b.m, b.d1, b.u1, b.d2, b.u2, b.dp, b.up, b.o1, b.o2, b.op, b.h1, b.h2, b.hp})
      if (!std::isfinite(v)) return false;
    return true;
  };
  const UwBand dark = uwTestBand(0.1, 0.3, 0.0, 0.0, kMuW, 0.35);
  const UwiBand none = makeUwiBandFromOrdinates(dark, 0.9, kMuW, 5, 1.34, 3.8, 1.2);
  EXPECT_TRUE(finite(none));
  EXPECT_EQ(none.d1, 0.0f);
  EXPECT_EQ(none.o1, 0.0f);
  for (const UwBand& b : {uwTestBand(0.0, 0.0, 0.146, 0.85, kMuW, 0.35), uwTestBand(0.0, 0.3, 0.146, 0.85, kMuW, 0.35),
                          uwTestBand(0.1, 0.0, 0.146, 0.85, kMuW, 0.35), uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.0)})
    for (double H : {0.0, 1e-3, 5.0})
      for (double g : {0.0, 0.5, 0.95}) EXPECT_TRUE(finite(makeUwiBandFromOrdinates(b, g, kMuW, H, 1.34, 3.8, 1.2)))
          << b.a << " " << b.b << " " << H << " " << g;
  // The sun below the horizon: mu_w is any value, there is no beam.
  EXPECT_TRUE(finite(makeUwiBandFromOrdinates(uwTestBand(0.1, 0.3, 0.146, 0.0, 0.85, 0.35), 0.9, 0.85, 5, 1.34, 3.8, 1.2)));
}

// √(1 - ν²) cos Δφ from the cosines: ±√(1 - ν²) in the sun's vertical plane, along and against the beam's
// azimuth; 0 with the sun at the zenith; float as double.
TEST(UnderwaterImprovedOrdinates, AzimuthFactor) {
  const double mu_w = 0.8, s_w = std::sqrt(1 - mu_w * mu_w);
  for (double nu : {-0.6, 0.0, 0.3}) {
    const double sn = std::sqrt(1 - nu * nu);
    // The photon (ν, horizontal along the beam) and (ν, against it).
    EXPECT_NEAR(kd::uwi_azimuth_factor(nu * mu_w + sn * s_w, nu, mu_w), sn, 1e-12);
    EXPECT_NEAR(kd::uwi_azimuth_factor(nu * mu_w - sn * s_w, nu, mu_w), -sn, 1e-12);
    EXPECT_NEAR(kd::uwi_azimuth_factor(nu * mu_w, nu, mu_w), 0.0, 1e-12);  // across it
    EXPECT_NEAR(kf::uwi_azimuth_factor(float(nu * mu_w + sn * s_w), float(nu), float(mu_w)), sn, 1e-6);
  }
  EXPECT_EQ(kd::uwi_azimuth_factor(0.3, 0.3, 1.0), 0.0);
  EXPECT_EQ(kf::uwi_azimuth_factor(0.3f, 0.3f, 1.0f), 0.0f);
}

}  // namespace
