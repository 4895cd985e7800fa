// expected_error.h — the error a render may carry against all orders of scattering, looked up in the
// measured study tables (data/expected_error/<view>_<model>.csv, made by
// tests/perf/expected_error_table.py from results/; docs/error_vs_time.md "Expected error").
//
// A scene's regime is its water (a and b at 550 nm, g), its bottom (depth, or none) and its sun's zenith.
// The nearest measured case of the model the scene runs, by the distance
//   d² = (ln(a/a_c)/ln 2)² + (ln(b/b_c)/ln 2)² + ((g - g_c)/0.1)² + ((f - f_c)/0.25)² + ((θ - θ_c)/15°)²,
//   f = 1 - e^{-(a + b) depth} (1 with no bottom: how much of the column the view sees),
// is one step per doubling of a or b, per 0.1 of g, per quarter of the column, per 15° of sun. Its
// worst region error |ratio - 1| is the expected error; where several cases are equally near, the
// largest. d > 1, or a feature no measured case has (waves, a non-uniform sky, a height-field
// bottom, spotlights seen from above, caustics), flags the scene "unmeasured here": the figure is then
// the nearest case's, for orientation only.
//
// Lamps under water have their own entry (view "lamps", the model quality.lamps_model names), looked up
// per lamp among the lamps' cases (one lamp, no daylight) with two more terms,
//   + (ln(ψ/ψ_c)/ln 2)² + ((f_l - f_lc)/0.25)²,   f_l = 1 - e^{-(a + b) l},
// ψ the cone's half angle and l the distance along the lamp's axis to the bottom (f_l = 1 when the axis
// meets no bottom): one step per doubling of the cone and per quarter of the beam's light that the water
// takes before the bottom. The scene's entry is its worst lamp's. A scene with objects is looked up among
// the cases with objects (rov_lights' own measurement) where there are any, as a sky among its own.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "scene/scene.h"

namespace seasim {

struct MeasuredCase {
  double a = 0, b = 0, g = 0;  // 1/m at 550 nm
  double bottom_m = -1;        // -1: no bottom
  double sun_zenith_deg = 0;
  int sky = 0;                 // the sky it was measured under: SEASIM_SKY_* (0 uniform, 1 CIE, 2 image, 3 Preetham)
  int floor = 0;               // its bottom: 0 flat or none, 1 a height field (bottom_m its mean depth)
  int surface = 0;             // the water's surface: 0 flat, 1 FFT waves
  int objects = 0;             // a lamp's case: 1 with objects in the lamps' light (a shipped scene's own case)
  double cone_deg = 0;         // a lamp's case: its cone's half angle (0: a daylight case)
  double lamp_bottom_m = -1;   // a lamp's case: the distance along its axis to the bottom (-1: none)
  double max_abs_error = 0;    // worst judged region, |model / all orders - 1|
  double worst_ratio = 1;
  double reference_rel_se = 0;  // the path tracer's relative noise in that region
  int source = 0;               // index into the table list of its file (data/expected_error/README.md)
};

struct ExpectedError {
  std::string view;   // "sea" (seen from above), "underwater" or "lamps" (spotlights under water)
  std::string model;  // "paper", "multiple", "thesis", "discrete_ordinates"; lamps "single", "delta_m", "orders"
  std::string subject;  // lamps: which of the scene's lamps the entry is ("spotlights[1]"); else empty
  bool measured = false;
  double max_abs_error = 0, worst_ratio = 1, distance = 0;
  MeasuredCase nearest;
  std::string table;               // the results/ table the nearest case came from
  std::vector<std::string> unmeasured_features;  // what no measured case has
};

constexpr double kExpectedErrorMaxDistance = 1.0;

// The distance above between the scene's regime and a case.
double regimeDistance(const MeasuredCase& scene_regime, const MeasuredCase& c);

// Reads data/expected_error/<view>_<model>.csv (RuntimeError naming the file when it is missing or bad).
std::vector<MeasuredCase> loadMeasuredCases(const std::string& view, const std::string& model);
// The results/ table of a case's `source` index for that view and model.
std::string measuredTable(const std::string& view, const std::string& model, int source);

// The expected error of the model the scene runs (none for a scene no table covers: shallow water,
// shafts in air), and with the camera and lamps under water the lamps' model's (its worst lamp's).
std::vector<ExpectedError> expectedErrors(const Scene& scene);
ExpectedError lookupExpectedError(const MeasuredCase& regime, const std::string& view, const std::string& model,
                                  const std::vector<MeasuredCase>& cases, std::vector<std::string> features);

nlohmann::json expectedErrorJson(const std::vector<ExpectedError>& errors);
std::string expectedErrorText(const std::vector<ExpectedError>& errors);

}  // namespace seasim
