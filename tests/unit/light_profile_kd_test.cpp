// light_profile_kd_test.cpp — the K_d the light profile gives for a Jerlov water (its a, b from Solonenko &
// Mobley 2015, Petzold's phase, sun at 30°, a little sky; E_d between 0 m and the shallower of 10 m and
// the 10 % depth) against the K_d tables. Neither table is the plane-parallel solution of those a, b:
// Jerlov's (1976) K_d is a classification fitted to measured profiles; Solonenko & Mobley's is their
// Eq. (3), a fit of K_d to a and b_b. So the test states how far apart they are (docs/radiometry.md) and
// fails when that changes: -43...+14 % from Jerlov's table, -23...+7 % from Eq. (3).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "radiometry/light_profile.h"
#include "spectral/csv_table.h"
#include "spectral/jerlov.h"
#include "util/paths.h"

namespace {

using namespace seasim;

TEST(LightProfileKd, JerlovWatersWithinTheTablesStatedSpread) {
  const CsvTable eq3 = loadCsv(dataDir() + "/jerlov_kd_solonenko2015.csv");
  const PhaseFunction petzold = PhaseFunction::petzold();
  double lo_j = 0, hi_j = 0, lo_s = 0, hi_s = 0;
  for (const char* type : {"I", "IA", "IB", "II", "III", "1C", "7C", "9C"}) {  // 3C, 5C: Eq. (3) has gaps
    const WaterSpectra js = jerlovWater(type);
    const Spectrum kd_eq3 = eq3.spectrum(type);
    for (double nm = 400; nm <= 700; nm += 50) {
      PlaneParallelWater w;
      w.a = js.a.at(nm);
      w.b = js.b.at(nm);
      w.ior = 1.34;
      w.sun_zenith = 30 * 3.14159265358979323846 / 180;
      w.sun_irradiance = 1;
      w.sky_irradiance = 0.2;
      const double z = std::min(10.0, 2.3 / js.kd.at(nm));
      const LightProfile p = solveLightProfile(w, petzold, {0.0, z}, 16);
      const double kd = std::log(p.rows[0].e_d / p.rows[1].e_d) / z;
      const double dj = kd / js.kd.at(nm) - 1, ds = kd / kd_eq3.at(nm) - 1;
      lo_j = std::min(lo_j, dj), hi_j = std::max(hi_j, dj);
      lo_s = std::min(lo_s, ds), hi_s = std::max(hi_s, ds);
    }
  }
  std::printf("K_d from the profile: %+.0f...%+.0f %% from Jerlov's table, %+.0f...%+.0f %% from Eq. (3)\n",
              100 * lo_j, 100 * hi_j, 100 * lo_s, 100 * hi_s);
  EXPECT_GT(lo_j, -0.45);
  EXPECT_LT(hi_j, 0.16);
  EXPECT_GT(lo_s, -0.25);
  EXPECT_LT(hi_s, 0.09);
}

}  // namespace
