// spectral_test.cpp — host/spectral: CSV reading, wavelength grids, CIE data, Jerlov water types
// (data/jerlov_*.csv, Solonenko & Mobley 2015 eq. (3)) and sensors (002 eq. 4.8).
#include <gtest/gtest.h>

#include <utility>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <numeric>
#include <string>

#include "spectral/csv_table.h"
#include "spectral/jerlov.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {
namespace {

std::string messageOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const RuntimeError& e) {
    return e.what();
  }
  return "(no RuntimeError)";
}

double csvCell(const std::string& file, const std::string& column, double lambda_nm) {
  const CsvTable t = loadCsv(dataDir() + "/" + file);
  const auto& wl = t.columns[0];
  for (std::size_t r = 0; r < t.rows(); ++r)
    if (wl[r] == lambda_nm) return t.column(column)[r];
  ADD_FAILURE() << file << " has no row at " << lambda_nm << " nm";
  return NAN;
}

double maxAbsDiff(const std::array<double, 3>& v, double target) {
  return std::max({std::abs(v[0] - target), std::abs(v[1] - target), std::abs(v[2] - target)});
}

// D65 × 1 per band through a sensor.
std::array<double, 3> d65Through(const std::string& sensor, int n, bool wb, double lo = 400, double hi = 700) {
  const WavelengthGrid g = makeGrid(n, lo, hi);
  const std::vector<double> e = sunIrradianceBands(g, 1.0);
  return makeSensor(sensor, g, wb).apply(e.data());
}

// ---------------------------------------------------------------- CSV

TEST(CsvTable, ReadsColumnsAndTracksEmptyCells) {
  const CsvTable t = parseCsv("nm, a ,b\r\n400,1.5,\r\n\r\n410,+2,3e-1\r\n", "mem.csv");
  ASSERT_EQ(t.names, (std::vector<std::string>{"nm", "a", "b"}));
  ASSERT_EQ(t.rows(), 2u);
  EXPECT_EQ(t.column("a")[1], 2.0);
  EXPECT_EQ(t.column("b")[1], 0.3);
  EXPECT_TRUE(std::isnan(t.column("b")[0]));
  ASSERT_EQ(t.empty_cells.size(), 1u);
  EXPECT_EQ(t.empty_cells[0].row, 0u);
  EXPECT_EQ(t.empty_cells[0].column, 2u);
  EXPECT_EQ(t.empty_cells[0].line, 2);
  EXPECT_EQ(t.lines, (std::vector<int>{2, 4}));
  const Spectrum s = t.spectrum("a");
  EXPECT_EQ(s.values, (std::vector<double>{1.5, 2.0}));
  EXPECT_NE(messageOf([&] { t.spectrum("b"); }).find("mem.csv:2:"), std::string::npos);
  EXPECT_NE(messageOf([&] { t.column("zz"); }).find("no column 'zz'"), std::string::npos);
}

TEST(CsvTable, MalformedRowsNameFileAndLine) {
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n400,1\n410\n", "f.csv"); }).find("f.csv:3: expected 2 cells"),
            std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n400,1\n410,1,2\n", "f.csv"); }).find("f.csv:3:"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n400,abc\n", "f.csv"); }).find("f.csv:2: column 'a': 'abc'"),
            std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n400,1.0x\n", "f.csv"); }).find("f.csv:2:"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n400,nan\n", "f.csv"); }).find("f.csv:2:"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n400,inf\n", "f.csv"); }).find("f.csv:2:"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,nm\n400,1\n", "f.csv"); }).find("f.csv:1:"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n", "f.csv"); }).find("no data rows"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("", "f.csv"); }).find("empty file"), std::string::npos);
  EXPECT_NE(messageOf([] { parseCsv("nm,a\n500,1\n400,2\n", "f.csv").spectrum("a"); })
                .find("f.csv:3: wavelengths must increase"),
            std::string::npos);
  EXPECT_NE(messageOf([] { loadCsv("/nonexistent/x.csv"); }).find("/nonexistent/x.csv: cannot open"),
            std::string::npos);
}

// ---------------------------------------------------------------- grid

TEST(WavelengthGrid, CentresAndWidths) {
  const WavelengthGrid g1 = makeGrid(1, 400, 700);
  ASSERT_EQ(g1.size(), 1u);
  EXPECT_DOUBLE_EQ(g1.centers_nm[0], 550.0);
  EXPECT_DOUBLE_EQ(g1.widths_nm[0], 300.0);

  const WavelengthGrid g3 = makeGrid(3, 400, 700);
  ASSERT_EQ(g3.size(), 3u);
  EXPECT_DOUBLE_EQ(g3.centers_nm[0], 450.0);
  EXPECT_DOUBLE_EQ(g3.centers_nm[1], 550.0);
  EXPECT_DOUBLE_EQ(g3.centers_nm[2], 650.0);
  for (double w : g3.widths_nm) EXPECT_DOUBLE_EQ(w, 100.0);

  const WavelengthGrid g = makeGrid(1000, 380, 780);
  ASSERT_EQ(g.size(), 1000u);
  EXPECT_NEAR(std::accumulate(g.widths_nm.begin(), g.widths_nm.end(), 0.0), 400.0, 1e-9);
  EXPECT_NEAR(g.centers_nm.front(), 380.2, 1e-12);
  EXPECT_NEAR(g.centers_nm.back(), 779.8, 1e-9);
  EXPECT_NEAR(g.minNm(), 380.0, 1e-9);
  EXPECT_NEAR(g.maxNm(), 780.0, 1e-9);
  for (std::size_t i = 1; i < g.size(); ++i) EXPECT_NEAR(g.centers_nm[i] - g.centers_nm[i - 1], 0.4, 1e-9);

  EXPECT_THROW(makeGrid(0, 400, 700), RuntimeError);
  EXPECT_THROW(makeGrid(1001, 400, 700), RuntimeError);
  EXPECT_THROW(makeGrid(3, 700, 400), RuntimeError);
  EXPECT_THROW(makeGrid(3, 0, 400), RuntimeError);
  EXPECT_THROW(makeGrid(3, 400, INFINITY), RuntimeError);
}

// ---------------------------------------------------------------- CIE

TEST(Cie, YBarPeaksAtOneAt555) {
  const Spectrum& y = cie1931Cmf().y_bar;
  const auto peak = std::max_element(y.values.begin(), y.values.end());
  EXPECT_EQ(y.wavelengths_nm[static_cast<std::size_t>(peak - y.values.begin())], 555.0);
  EXPECT_NEAR(*peak, 1.0, 1e-6);
  EXPECT_EQ(y.wavelengths_nm.front(), 360.0);
  EXPECT_EQ(y.wavelengths_nm.back(), 830.0);
  EXPECT_EQ(responseAt(y, 359.0), 0.0);  // 0 outside the table, not the end value
  EXPECT_EQ(responseAt(y, 831.0), 0.0);
  EXPECT_DOUBLE_EQ(d65().at(560.0), 1.0);
}

TEST(Cie, SrgbMatrixMatchesIec61966) {
  const double printed[9] = {3.2406, -1.5372, -0.4986, -0.9689, 1.8758, 0.0415, 0.0557, -0.2040, 1.0570};
  const auto& m = xyzToLinearSrgbMatrix();
  // The printed matrix was rounded from a rounded forward matrix: agreement to 4e-4, not 1e-4.
  for (int i = 0; i < 9; ++i) EXPECT_NEAR(m[static_cast<std::size_t>(i)], printed[i], 4e-4) << i;
  const auto white = xyzToLinearSrgb({0.3127 / 0.3290, 1.0, (1 - 0.3127 - 0.3290) / 0.3290});
  EXPECT_LT(maxAbsDiff(white, 1.0), 1e-12);
}

// ---------------------------------------------------------------- sensors

// 002 eq. 4.8 converges to the continuum normalisation: D65 -> (1, 1, 1) with white balance.
TEST(Sensor, CieD65IsWhiteAndConverges) {
  const double e30 = maxAbsDiff(d65Through("cie1931", 30, true), 1.0);
  const double e300 = maxAbsDiff(d65Through("cie1931", 300, true), 1.0);
  const double e1000 = maxAbsDiff(d65Through("cie1931", 1000, true), 1.0);
  std::printf("cie1931 D65 max|rgb-1|: n=3 %.3g  n=30 %.3g  n=300 %.3g  n=1000 %.3g\n",
              maxAbsDiff(d65Through("cie1931", 3, true), 1.0), e30, e300, e1000);
  EXPECT_LT(e30, 1e-2);
  EXPECT_LT(e300, e30);
  EXPECT_LT(e1000, 1e-3);
  // Without white balance the sRGB matrix alone makes D65 nearly white and Y = 1 exactly in the limit.
  const auto raw = d65Through("cie1931", 1000, false);
  const auto Y = 0.2126 * raw[0] + 0.7152 * raw[1] + 0.0722 * raw[2];
  EXPECT_NEAR(Y, 1.0, 1e-3);
  EXPECT_LT(maxAbsDiff(raw, 1.0), 2e-2);
  // Linear in the radiance scale.
  const WavelengthGrid g = makeGrid(40, 400, 700);
  const Sensor s = makeSensor("cie1931", g, true);
  const auto e1 = sunIrradianceBands(g, 1.0), e3 = sunIrradianceBands(g, 3.0);
  const auto c1 = s.apply(e1.data()), c3 = s.apply(e3.data());
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(c3[static_cast<std::size_t>(k)], 3 * c1[static_cast<std::size_t>(k)], 1e-12);
}

// White balance on narrow ranges: D65 over 10 nm is nearly a spectral colour outside the sRGB
// gamut; the sensor then balances X and Z (von Kries) and still maps D65 to (1, 1, 1). Only where a
// curve sees nothing (z̄ above ~650 nm) does that channel stay unbalanced, finite and with no error.
TEST(Sensor, CieWhiteBalanceWorksOnNarrowRanges) {
  for (const auto& [lo, hi] : {std::pair{500.0, 510.0}, std::pair{440.0, 450.0}, std::pair{580.0, 600.0},
                               std::pair{400.0, 700.0}}) {
    const auto rgb = d65Through("cie1931", 200, true, lo, hi);
    std::printf("cie1931 white-balanced D65 over [%g, %g] nm: (%.6f, %.6f, %.6f)\n", lo, hi, rgb[0], rgb[1], rgb[2]);
    EXPECT_LT(maxAbsDiff(rgb, 1.0), 1e-3) << lo << "-" << hi;
  }
  const auto red = d65Through("cie1931", 50, true, 690, 700);
  for (double v : red) EXPECT_TRUE(std::isfinite(v));
  EXPECT_NEAR(red[0], 1.0, 1e-3);  // r balanced; g and b cannot be (z̄ = 0 there)
}

// "identity": raw bands out, and a grey luminance preview in RGB: D65 -> (1, 1, 1) on any range.
TEST(Sensor, IdentityPreviewIsTheLuminance) {
  for (const auto& [lo, hi] : {std::pair{400.0, 700.0}, std::pair{500.0, 510.0}}) {
    const auto rgb = d65Through("identity", 300, true, lo, hi);
    EXPECT_LT(maxAbsDiff(rgb, 1.0), 1e-3) << lo;
    EXPECT_EQ(rgb[0], rgb[1]);
    EXPECT_EQ(rgb[1], rgb[2]);
  }
}

TEST(Sensor, CamerasLoadAndAreFiniteNonNegative) {
  const auto names = cameraNames();
  // Only the BSD-licensed curves ship (data/README.md §5).
  EXPECT_EQ(names.size(), 3u);
  for (const char* want : {"nikon_d5100_npl", "sigma_sdmerrill_npl", "canon_eos_5d_mark_ii_rawtoaces"})
    EXPECT_NE(std::find(names.begin(), names.end(), want), names.end()) << want;
  for (const auto& name : names) {
    const CameraCurves c = loadCamera(name);
    for (const Spectrum* s : {&c.r, &c.g, &c.b}) {
      ASSERT_GE(s->values.size(), 20u) << name;
      double peak = 0.0;
      for (double v : s->values) {
        EXPECT_TRUE(std::isfinite(v) && v >= 0.0) << name;
        peak = std::max(peak, v);
      }
      EXPECT_GT(peak, 0.0) << name;
    }
  }
  EXPECT_NE(messageOf([] { makeSensor("no_such_camera", makeGrid(3, 400, 700), true); }).find("unknown sensor"),
            std::string::npos);
}

TEST(Sensor, CamerasWhiteBalanceD65AndKeepLuminanceWithout) {
  for (const auto& name : cameraNames()) {
    const double e30 = maxAbsDiff(d65Through(name, 30, true), 1.0);
    const double e300 = maxAbsDiff(d65Through(name, 300, true), 1.0);
    EXPECT_LT(e30, 5e-3) << name;
    EXPECT_LT(e300, 1e-3) << name;
    const auto raw = d65Through(name, 300, false);
    EXPECT_NEAR(0.2126 * raw[0] + 0.7152 * raw[1] + 0.0722 * raw[2], 1.0, 1e-3) << name;
  }
}

// A narrow band (±5 nm) of light is blue at 450 nm, green at 550 nm, red at 650 nm, for every sensor,
// with and without white balance.
TEST(Sensor, NarrowBandsHaveTheExpectedHue) {
  std::vector<std::string> sensors = cameraNames();
  sensors.insert(sensors.begin(), "cie1931");
  const WavelengthGrid g = makeGrid(300, 400, 700);
  for (const auto& name : sensors) {
    for (bool wb : {true, false}) {
      const Sensor s = makeSensor(name, g, wb);
      for (int k = 0; k < 3; ++k) {
        const double centre = 450.0 + 100.0 * k;
        std::vector<double> L(g.size(), 0.0);
        for (std::size_t i = 0; i < g.size(); ++i)
          if (std::abs(g.centers_nm[i] - centre) <= 5.0) L[i] = 1.0;
        const auto rgb = s.apply(L.data());
        const int dominant = static_cast<int>(std::max_element(rgb.begin(), rgb.end()) - rgb.begin());
        EXPECT_EQ(dominant, 2 - k) << name << (wb ? " wb" : " raw") << " at " << centre << " nm: " << rgb[0]
                                   << " " << rgb[1] << " " << rgb[2];
      }
    }
  }
}

TEST(Sensor, SunIrradianceIsD65TimesScale) {
  const WavelengthGrid g = makeGrid(3, 510, 610);  // centres 526.67, 560, 593.33
  const auto e = sunIrradianceBands(g, 2.5);
  EXPECT_DOUBLE_EQ(e[1], 2.5);
  EXPECT_DOUBLE_EQ(e[0], 2.5 * d65().at(g.centers_nm[0]));
  EXPECT_THROW(sunIrradianceBands(g, -1.0), RuntimeError);
}

// ---------------------------------------------------------------- Jerlov

TEST(Jerlov, TabulatedCellsAreReturnedExactly) {
  EXPECT_EQ(jerlovTypes().size(), 10u);
  for (const char* type : {"I", "9C"}) {
    const WaterSpectra w = jerlovWater(type);
    EXPECT_EQ(w.a.at(500), csvCell("jerlov_a.csv", type, 500)) << type;
    EXPECT_EQ(w.b.at(500), csvCell("jerlov_b.csv", type, 500)) << type;
    EXPECT_EQ(w.kd.at(500), csvCell("jerlov_kd.csv", type, 500)) << type;
    // Through resolveWater on a one-band grid centred on 500 nm.
    WaterDesc d;
    d.present = true;
    d.jerlov = type;
    const BandOptics o = resolveWater(d, makeGrid(1, 450, 550));
    EXPECT_EQ(o.a[0], w.a.at(500));
    EXPECT_EQ(o.b[0], w.b.at(500));
    EXPECT_EQ(o.kd[0], w.kd.at(500));
    EXPECT_EQ(o.c[0], o.a[0] + o.b[0]);
  }
  // The cells themselves (data/jerlov_*.csv, row 500 nm).
  EXPECT_EQ(jerlovWater("I").a.at(500), 0.026);
  EXPECT_EQ(jerlovWater("I").b.at(500), 0.00249);
  EXPECT_EQ(jerlovWater("I").kd.at(500), 0.027);
  EXPECT_EQ(jerlovWater("9C").a.at(500), 0.543);
  EXPECT_EQ(jerlovWater("9C").b.at(500), 3.67);
  EXPECT_EQ(jerlovWater("9C").kd.at(500), 0.99);
  EXPECT_EQ(jerlovWater("ib").a.at(500), jerlovWater("IB").a.at(500));
  EXPECT_NE(messageOf([] { jerlovWater("4C"); }).find("unknown Jerlov water type '4C'"), std::string::npos);
}

TEST(Jerlov, KdIncreasesFromClearestToMostTurbidAt400) {
  double prev = 0.0;
  for (const auto& type : jerlovTypes()) {
    const double kd = jerlovWater(type).kd.at(400);
    EXPECT_GT(kd, prev) << type;
    prev = kd;
  }
}

TEST(Jerlov, EmptyCellsFilledByTheDocumentedRule) {
  auto A = [](const char* t, double l) { return csvCell("jerlov_a.csv", t, l); };
  auto B = [](const char* t, double l) { return csvCell("jerlov_b.csv", t, l); };
  ASSERT_TRUE(std::isnan(A("5C", 600)));
  ASSERT_TRUE(std::isnan(B("3C", 700)));
  const WaterSpectra w5 = jerlovWater("5C"), w3 = jerlovWater("3C");
  // The rule of jerlov.h, anchored at the last published wavelength, reference type 7C.
  for (double l : {600.0, 625.0, 650.0, 675.0, 700.0}) {
    const double a = A("I", l) + (A("5C", 575) - A("I", 575)) * (A("7C", l) - A("I", l)) / (A("7C", 575) - A("I", 575));
    EXPECT_NEAR(w5.a.at(l), a, 1e-12) << l;
    EXPECT_NEAR(w5.b.at(l), B("5C", 575) * B("7C", l) / B("7C", 575), 1e-12) << l;
  }
  for (double l : {675.0, 700.0}) {
    const double a = A("I", l) + (A("3C", 650) - A("I", 650)) * (A("7C", l) - A("I", l)) / (A("7C", 650) - A("I", 650));
    EXPECT_NEAR(w3.a.at(l), a, 1e-12) << l;
    EXPECT_NEAR(w3.b.at(l), B("3C", 650) * B("7C", l) / B("7C", 650), 1e-12) << l;
  }
  // Plausibility: within 5 % of the values Williamson & Hollins (2022) put in these cells (their
  // figshare spreadsheet, as quoted by github.com/tishibashi-cpu/jerlov), and ordered between the
  // neighbouring types wherever those are published.
  EXPECT_NEAR(w5.a.at(600), 0.259, 0.05 * 0.259);
  EXPECT_NEAR(w5.a.at(700), 0.598, 0.05 * 0.598);
  EXPECT_NEAR(w5.b.at(600), 1.147, 0.05 * 1.147);
  EXPECT_NEAR(w5.b.at(700), 0.883, 0.05 * 0.883);
  EXPECT_NEAR(w3.a.at(675), 0.477, 0.05 * 0.477);
  EXPECT_NEAR(w3.b.at(700), 0.690, 0.05 * 0.690);
  for (double l : {600.0, 625.0, 650.0}) {
    EXPECT_GT(w5.a.at(l), A("3C", l)) << l;
    EXPECT_LT(w5.a.at(l), A("7C", l)) << l;
    EXPECT_GT(w5.b.at(l), B("3C", l)) << l;
    EXPECT_LT(w5.b.at(l), B("7C", l)) << l;
  }
  for (double l : {675.0, 700.0}) {
    EXPECT_GT(w3.a.at(l), A("1C", l) - 0.01) << l;  // 1C and 3C are within 0.003 1/m at 575–650 nm
    EXPECT_LT(w3.a.at(l), w5.a.at(l)) << l;
    EXPECT_GT(w3.b.at(l), B("1C", l)) << l;
    EXPECT_LT(w3.b.at(l), w5.b.at(l)) << l;
  }
}

// Solonenko & Mobley (2015) eq. (3) reproduces their own modelled Kd column from their a and b.
TEST(Jerlov, KdModelReproducesSolonenkoMobleyColumn) {
  const CsvTable a = loadCsv(dataDir() + "/jerlov_a.csv");
  const CsvTable b = loadCsv(dataDir() + "/jerlov_b.csv");
  const CsvTable kd = loadCsv(dataDir() + "/jerlov_kd_solonenko2015.csv");
  double worst = 0.0;
  int cells = 0;
  for (std::size_t t = 0; t < jerlovTypes().size(); ++t) {
    const std::string& type = jerlovTypes()[t];
    const double mu = t < 5 ? 0.98 : 0.85;  // oceanic types: high sun; coastal: 45° sun
    for (std::size_t r = 0; r < a.rows(); ++r) {
      const double av = a.column(type)[r], bv = b.column(type)[r], kv = kd.column(type)[r];
      if (std::isnan(av) || std::isnan(kv)) continue;
      worst = std::max(worst, std::abs(kdFromIops(av, bv, a.columns[0][r], mu) / kv - 1.0));
      ++cells;
    }
  }
  std::printf("S&M eq. (3) vs their Kd column: worst relative error %.3f over %d cells\n", worst, cells);
  EXPECT_EQ(cells, 163);
  EXPECT_LT(worst, 0.07);
  // Stiff ends: no absorption -> Kd = 0; no scattering -> Kd = a / mu.
  EXPECT_EQ(kdFromIops(0.0, 1.0, 500, 0.85), 0.0);
  EXPECT_NEAR(kdFromIops(0.3, 0.0, 500, 0.85), 0.3 / 0.85, 1e-15);
}

TEST(Jerlov, ExplicitSpectraGiveCEqualsAPlusB) {
  WaterDesc d;
  d.present = true;
  d.a = Spectrum{{400, 700}, {0.05, 0.6}};
  d.b = Spectrum{{400, 700}, {0.3, 0.1}};
  const WavelengthGrid g = makeGrid(7, 400, 700);
  const BandOptics o = resolveWater(d, g);
  for (std::size_t i = 0; i < g.size(); ++i) {
    EXPECT_EQ(o.c[i], o.a[i] + o.b[i]);
    EXPECT_NEAR(o.a[i], d.a.at(g.centers_nm[i]), 1e-15);
    EXPECT_EQ(o.kd[i], kdFromIops(o.a[i], o.b[i], g.centers_nm[i], 0.85));  // no explicit kd: eq. (3)
    EXPECT_GE(o.kd[i], o.a[i]);  // Kd >= a/mu > a for any water that scatters
  }
  d.kd = Spectrum::constant(0.2);
  EXPECT_EQ(resolveWater(d, g).kd[3], 0.2);
  // A Jerlov type with an explicit override of one quantity.
  WaterDesc j;
  j.jerlov = "II";
  j.b = Spectrum::constant(0.5);
  const BandOptics oj = resolveWater(j, makeGrid(1, 450, 550));
  EXPECT_EQ(oj.a[0], 0.0288);
  EXPECT_EQ(oj.b[0], 0.5);
  EXPECT_EQ(oj.kd[0], 0.07);
  // Errors.
  WaterDesc none;
  EXPECT_THROW(resolveWater(none, g), RuntimeError);
  WaterDesc neg = d;
  neg.b = Spectrum::constant(-1.0);
  EXPECT_NE(messageOf([&] { resolveWater(neg, g); }).find("water: b at"), std::string::npos);
  EXPECT_THROW(resolveWater(d, g, 0.3), RuntimeError);
}

// ---------------------------------------------------------------- end to end

// Sun through 10 m of every Jerlov water (exp(-Kd z)) into CIE and a camera, at n = 1 and n = 1000.
TEST(Spectral, ExtremeBandCountsEndToEndWithoutNan) {
  for (int n : {1, 1000}) {
    const WavelengthGrid g = makeGrid(n, 380, 780);
    const std::vector<double> sun = sunIrradianceBands(g, 1.0);
    const Sensor sensors[] = {makeSensor("cie1931", g, true), makeSensor("cie1931", g, false),
                              makeSensor("nikon_d5100_npl", g, true), makeSensor("canon_eos_5d_mark_ii_rawtoaces", g, false)};
    for (const auto& type : jerlovTypes()) {
      WaterDesc d;
      d.jerlov = type;
      const BandOptics o = resolveWater(d, g);
      std::vector<double> L(g.size());
      for (std::size_t i = 0; i < g.size(); ++i) L[i] = sun[i] * std::exp(-o.kd[i] * 10.0);
      for (const Sensor& s : sensors) {
        ASSERT_EQ(s.size(), g.size());
        const auto rgb = s.apply(L.data());
        for (double v : rgb) EXPECT_TRUE(std::isfinite(v)) << type << " n=" << n << " " << s.name;
        for (std::size_t i = 0; i < g.size(); ++i)
          ASSERT_TRUE(std::isfinite(s.to_r[i]) && std::isfinite(s.to_g[i]) && std::isfinite(s.to_b[i]));
      }
    }
  }
}

}  // namespace
}  // namespace seasim
