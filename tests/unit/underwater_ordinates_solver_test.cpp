// underwater_ordinates_solver_test.cpp — the discrete-ordinates underwater model's diffuse field from discrete
// ordinates (underwater.diffuse = "discrete_ordinates", the default; host/underwater/
// underwater_ordinates_solver.*): the band's exponentials hold the solver's field (E_d,
// E_u, E_0, F_h) over the depths the frame sees, as the kernel evaluates them in float and double; k
// keeps away from the beam's m; no horizontal flux where the field has none; degenerate bands stay
// finite; the source's azimuth factor.
#include <gtest/gtest.h>

#include <cmath>
#include <algorithm>
#include <cstdio>
#include <vector>

#include "math/kernel_math.h"
#include "underwater/discrete_ordinates.h"
#include "underwater/underwater_ordinates_solver.h"

#include "underwater_ordinates_fixtures.h"

namespace {

namespace kd = seasim::kmath_d;
namespace kf = seasim::kmath_f;
using seasim::DiscreteOrdinates;
using seasim::DiscreteOrdinatesLayer;
using seasim::FieldPart;
using seasim::makeUwiBandFromOrdinates;
using seasim::OrdinatesFitError;
using seasim::testing::uwTestBand;

constexpr double kMuW = seasim::testing::kUwTestMuW;

DiscreteOrdinatesLayer layerOf(const UwBand& b, double g, double H) { return seasim::testing::uwTestLayer(b, g, H); }

// E_d (with the kernel's delta-M beam) and E_u from the band as the kernel evaluates them
// (uwi_irradiance), against the solver's at its full delta-M order (the band is fitted to its order
// kOrdinatesSourceMoments), over the bottom's whole depth: within 4 %. The fit's own largest errors,
// printed: 0.01–0.2 % in clear water, up to 3.6 % (E_0) at 8 optical depths, where three exponentials no
// longer hold the field near both ends; the source table's 0.6–8.6 %.
TEST(UnderwaterOrdinatesSolver, BandHoldsTheSolversIrradiance) {
  struct Case {
    double a, b, g, H;
  };
  for (const Case c : {Case{0.1, 0.3, 0.9, 5}, Case{0.1, 0.3, 0.0, 20}, Case{0.03, 0.05, 0.95, 2},
                       Case{0.4, 1.2, 0.5, 5}}) {
    const UwBand band = uwTestBand(c.a, c.b, 0.146, 0.85, kMuW, 0.35);
    OrdinatesFitError fit;
    const UwiBand ib = makeUwiBandFromOrdinates(band, c.g, kMuW, c.H, 1.34, c.H - 1.2, 16, &fit);
    std::printf("a %.2f b %.2f g %.2f H %2.0f: k %.4f m %.4f, fit errors E_d %.4f E_u %.4f E_0 %.4f F_h %.4f "
                "source %.4f\n", c.a, c.b, c.g, c.H, ib.k, ib.m, fit.down, fit.up, fit.scalar, fit.horizontal, fit.source);
    EXPECT_LT(fit.down, 0.04);
    EXPECT_LT(fit.up, 0.04);
    EXPECT_LT(fit.scalar, 0.05);
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
TEST(UnderwaterOrdinatesSolver, ScalarIrradianceAndHorizontalFlux) {
  const UwBand band = uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.35);
  const UwiBand ib = makeUwiBandFromOrdinates(band, 0.9, kMuW, 5, 1.34, 3.8);
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
  const UwiBand iso = makeUwiBandFromOrdinates(band, 0.0, kMuW, 5, 1.34, 3.8);
  const UwiBand zenith = makeUwiBandFromOrdinates(band, 0.9, 1.0, 5, 1.34, 3.8);
  for (const UwiBand& b : {iso, zenith}) {
    EXPECT_EQ(b.h1, 0.0f);
    EXPECT_EQ(b.h2, 0.0f);
    EXPECT_EQ(b.hp, 0.0f);
  }
  const UwiBand deep = makeUwiBandFromOrdinates(band, 0.9, kMuW, 0, 1.34, 3.8);
  EXPECT_EQ(deep.d2, 0.0f);
  EXPECT_EQ(deep.u2, 0.0f);
  EXPECT_EQ(deep.o2, 0.0f);
  EXPECT_GT(deep.d1 + deep.dp, 0.0f);
  EXPECT_FLOAT_EQ(ib.c_dm, float(0.1 + 0.3 * (1 - 0.729)));  // the solver's delta-M, f = g³
}

// No medium, no light, no absorption, no scattering, a black bottom 1 mm down: every coefficient and the
// source's table finite, and no light gives no field and no source.
TEST(UnderwaterOrdinatesSolver, DegenerateBandsStayFinite) {
  auto finite = [](const UwiBand& b) {
    for (float v : {b.c_dm, b.k, b.m, b.d1, b.u1, b.d2, b.u2, b.dp, b.up, b.o1, b.o2, b.op, b.h1, b.h2, b.hp})
      if (!std::isfinite(v)) return false;
    for (float v : b.src)
      if (!std::isfinite(v)) return false;
    return true;
  };
  const UwBand dark = uwTestBand(0.1, 0.3, 0.0, 0.0, kMuW, 0.35);
  const UwiBand none = makeUwiBandFromOrdinates(dark, 0.9, kMuW, 5, 1.34, 3.8);
  EXPECT_TRUE(finite(none));
  EXPECT_EQ(none.d1, 0.0f);
  EXPECT_EQ(none.o1, 0.0f);
  for (float v : none.src) ASSERT_EQ(v, 0.0f);
  for (const UwBand& b : {uwTestBand(0.0, 0.0, 0.146, 0.85, kMuW, 0.35), uwTestBand(0.0, 0.3, 0.146, 0.85, kMuW, 0.35),
                          uwTestBand(0.1, 0.0, 0.146, 0.85, kMuW, 0.35), uwTestBand(0.1, 0.3, 0.146, 0.85, kMuW, 0.0)})
    for (double H : {0.0, 1e-3, 5.0})
      for (double g : {0.0, 0.5, 0.95}) EXPECT_TRUE(finite(makeUwiBandFromOrdinates(b, g, kMuW, H, 1.34, 3.8)))
          << b.a << " " << b.b << " " << H << " " << g;
  // The sun below the horizon: mu_w is any value, there is no beam.
  EXPECT_TRUE(finite(makeUwiBandFromOrdinates(uwTestBand(0.1, 0.3, 0.146, 0.0, 0.85, 0.35), 0.9, 0.85, 5, 1.34, 3.8)));
}

// cos Δφ from the cosines: ±1 in the sun's vertical plane, along and against the beam's azimuth, 0 across
// it, any azimuth in between; 0 with the sun at the zenith or a vertical photon, and within [-1, 1] where
// rounding would take it past; float as double.
TEST(UnderwaterOrdinatesSolver, CosAzimuth) {
  const double mu_w = 0.8, s_w = std::sqrt(1 - mu_w * mu_w);
  for (double nu : {-0.6, 0.0, 0.3, 0.999}) {
    const double sn = std::sqrt(1 - nu * nu);
    for (double phi : {0.0, 0.7, M_PI / 2, 2.0, M_PI}) {
      const double cos_s = nu * mu_w + sn * s_w * std::cos(phi);
      EXPECT_NEAR(kd::uwi_cos_azimuth(cos_s, nu, mu_w), std::cos(phi), 1e-9) << nu << " " << phi;
      EXPECT_NEAR(kf::uwi_cos_azimuth(float(cos_s), float(nu), float(mu_w)), std::cos(phi), 2e-3) << nu << " " << phi;
    }
  }
  EXPECT_EQ(kd::uwi_cos_azimuth(0.3, 0.3, 1.0), 0.0);
  EXPECT_EQ(kf::uwi_cos_azimuth(0.3f, 0.3f, 1.0f), 0.0f);
  EXPECT_EQ(kd::uwi_cos_azimuth(0.8, 1.0, 0.8), 0.0);
  EXPECT_EQ(kd::uwi_cos_azimuth(-0.8, -1.0, 0.8), 0.0);
  EXPECT_EQ(kd::uwi_cos_azimuth(1.0, 0.8, 0.8), 1.0);  // the beam's own direction
  EXPECT_LE(std::fabs(kf::uwi_cos_azimuth(0.9999f, 0.8f, 0.8f)), 1.0f);
}

}  // namespace

namespace {

// The kernel's radiance from a discrete-ordinates band with the order-3 source (uwi_band_radiance, double:
// the source's table integrated along the view with c', the surface and the bottom at the ray's end)
// against the solver's own radiance at its cosines, for the same delta-M order, 2 m down, looking down into deep
// water or onto a 5 m bottom and up at the surface. Lit by the sky alone at g = 0.9 (no beam: the
// source is the solver's in-scatter and nothing else), and by the sun and the sky at g = 0 (the TMS term's
// exact phase is then the solver's). Measures what the table's exponential fit and its linear
// interpolation in ν lose: within 5 % (the worst printed: 4.0 %, 4.7 % before the split quadrature; the
// dimmest views down into deep water lit by the sky alone at g = 0.9). Would fail with the table's cosines reversed,
// the source integrated with another extinction than the solver's, or a mode of the table left out.
TEST(UnderwaterOrdinatesSolver, SourceTableGivesTheSolversRadiance) {
  struct Light {
    double g, e_sky0, e_sun0;
  };
  const double sky_l = 0.05, sky_e = 0.146135, y = 2.0;  // the sky's radiance in air and its irradiance in water
  double worst = 0;
  for (const Light& light : {Light{0.9, sky_e, 0.0}, Light{0.0, sky_e, 0.85}})
    for (double H : {0.0, 5.0}) {
      const UwBand band = uwTestBand(0.1, 0.3, light.e_sky0, light.e_sun0, kMuW, 0.35);
      // The order-3 field's own in-scatter (source_streams 0): ordinates_high_order_test.cpp holds the
      // default table to the high-order field's radiance.
      const UwiBand ib = makeUwiBandFromOrdinates(band, light.g, kMuW, H, 1.34, y, 16, nullptr, 0);
      const DiscreteOrdinates field(layerOf(band, light.g, H), 16, 0, seasim::kOrdinatesSourceMoments);
      std::vector<double> down, up;
      field.radiances(y, down, up);
      const std::vector<double>& mu = field.cosines();
      const kd::real3 s_w{std::sqrt(1 - kMuW * kMuW), kMuW, 0.0};
      for (size_t i = 0; i < mu.size(); ++i)
        for (double sign : {-1.0, 1.0}) {
          // Camera ray d (d_y = sign μ): the photon travels along -d, downward cosine d_y.
          const double d_y = sign * mu[i];
          const kd::real3 d{0.0, d_y, std::sqrt(1 - d_y * d_y)};
          int mat = UW_MAT_NONE;
          double S = 1e30;
          if (d_y > 0) mat = UW_MAT_SURFACE, S = y / d_y;
          if (d_y < 0 && H > 0) mat = UW_MAT_BOTTOM, S = (H - y) / -d_y;
          const double L = kd::uwi_band_radiance(&ib, &band, light.g, mat, S, kd::real3{0, 1, 0}, d, y, s_w,
                                                 band.bottom_albedo, 1.0, 1.0, sky_l, 1.34, H, 0, 1,
                                                 kd::uwi_no_mirror_object());
          const double ref = d_y > 0 ? down[i] : up[i];
          worst = std::max(worst, std::fabs(L / ref - 1));
          EXPECT_NEAR(L, ref, 0.05 * ref) << "g " << light.g << " H " << H << " d_y " << d_y;
        }
    }
  std::printf("kernel radiance from the source table vs the solver's (16 cosines each way, 4 layers): worst %.2f %%\n",
              100 * worst);
}

}  // namespace

namespace {

// The source table's part that the bottom brings per unit of the irradiance it reflects first
// (UwiBand.src_sand: what the kernel takes off, times sand_beam or sand_diffuse, where objects hide or shade the
// sand) against the solver's own in-scatter of that part (FieldPart::sand_unit) at every node's cosine and
// 0-5 m, over a 5 m bottom in clear and turbid water: within 15 % of its largest value (measured 2.9, 6.1 and
// 12 %, each worst on the sand itself for level photons, where the sand's light changes fastest with depth:
// the three exponentials' limit, the same fit as the whole source's); and the two irradiances the solver's. Would fail with the table left at 0, fitted from the
// whole field, or the irradiances swapped.
TEST(UnderwaterOrdinatesSolver, SourceTablesSandPartIsTheSolversBottomLight) {
  const double H = 5.0;
  for (const auto& [a, b] : {std::pair{0.1, 0.3}, std::pair{0.05, 0.15}, std::pair{0.2, 0.5}}) {
    const UwBand band = uwTestBand(a, b, 0.146135, 0.85, kMuW, 0.8);
    const UwiBand ib = makeUwiBandFromOrdinates(band, 0.9, kMuW, H, 1.34, 2.0, 16, nullptr, 0);
    const DiscreteOrdinates field(layerOf(band, 0.9, H), 16, 0, seasim::kOrdinatesSourceMoments);
    EXPECT_FLOAT_EQ(ib.sand_beam, float(field.sandBeam()));
    EXPECT_FLOAT_EQ(ib.sand_diffuse, float(field.sandDiffuse()));
    EXPECT_GT(ib.sand_diffuse, 0.0f);
    EXPECT_GT(ib.sand_beam, ib.sand_diffuse);  // the sun high, the sky 0.05: the beam lights most of the sand
    std::vector<double> nus(UWI_SOURCE_NODES);
    for (int j = 0; j < UWI_SOURCE_NODES; ++j) nus[j] = kd::uwi_source_node_cosine(j);
    const int samples = 6;
    const std::vector<double> solver = field.inscatterProfile(nus, H, samples, FieldPart::sand_unit);
    const double peak = *std::max_element(solver.begin(), solver.end());
    ASSERT_GT(peak, 0.0);
    double worst = 0, worst_y = 0, worst_nu = 0;
    for (int s = 0; s < samples; ++s) {
      const double y = H * s / (samples - 1);
      for (int j = 0; j < UWI_SOURCE_NODES; ++j) {
        const float* t = ib.src_sand + 3 * j;
        const double fitted = t[0] * std::exp(-ib.k * y) + t[1] * std::exp(-ib.k * (H - y)) + t[2] * std::exp(-ib.m * y);
        const double e = std::fabs(fitted - solver[size_t(s) * nus.size() + j]) / peak;
        if (e > worst) worst = e, worst_y = y, worst_nu = nus[j];
      }
    }
    std::printf("a %.2f b %.2f, the sand's part of the source: table vs solver %.4f of its peak (y %.1f m, nu %.2f)\n",
                a, b, worst, worst_y, worst_nu);
    EXPECT_LT(worst, 0.15) << a << " " << b;
  }
}

}  // namespace
