// underwater_model_option_test.cpp — underwater.model: the parser's choice with file:line:key
// errors, the planner's SEASIM_UNDERWATER_MODEL define on kd_multiple, and the set-up's per-band block
// that only "discrete_ordinates" fills.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_ordinates_setup.h"
#include "underwater/underwater_setup.h"
#include "util/error.h"

#include "underwater_ordinates_fixtures.h"

namespace {

using namespace seasim;

const char* kScene = R"([scene]
name = "uw"
[camera]
position = [0, -3, 0]
look_at = [0, -3, -5]
width = 8
height = 6
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 5
[underwater]
caustics = "none"
)";

std::string withModel(const std::string& value) {
  std::string s = kScene;
  return s + "model = " + value + "\n";
}

bool hasDefine(const Plan& plan, const std::string& define) {
  const PassPlan* p = plan.find("kd_multiple");
  return p && std::find(p->defines.begin(), p->defines.end(), define) != p->defines.end();
}

TEST(UnderwaterModelOption, DefaultIsTheDiscreteOrdinatesModelTheThesisByNameAndThePlanSaysSo) {
  const Scene scene = parseScene(kScene, "uw.toml");
  EXPECT_EQ(scene.underwater.model, UnderwaterDesc::Model::DiscreteOrdinates);
  const Plan plan = makePlan(scene);
  EXPECT_TRUE(hasDefine(plan, "SEASIM_UNDERWATER_MODEL=1"));
  EXPECT_FALSE(hasDefine(plan, "SEASIM_UNDERWATER_MODEL=0"));
  const Plan thesis = makePlan(parseScene(withModel("\"thesis\""), "uw.toml"));
  EXPECT_TRUE(hasDefine(thesis, "SEASIM_UNDERWATER_MODEL=0"));
  EXPECT_FALSE(hasDefine(thesis, "SEASIM_UNDERWATER_MODEL=1"));
}

// "improved", the discrete-ordinates model's earlier name, still reads as that model, with the same
// plan; any other name is refused naming the key and the names allowed.
TEST(UnderwaterModelOption, TheEarlierNameImprovedIsTheDiscreteOrdinatesModel) {
  const Scene alias = parseScene(withModel("\"improved\""), "uw.toml");
  EXPECT_EQ(alias.underwater.model, UnderwaterDesc::Model::DiscreteOrdinates);
  EXPECT_EQ(makePlan(alias).toText(), makePlan(parseScene(withModel("\"discrete_ordinates\""), "uw.toml")).toText());
  try {
    (void)parseScene(withModel("\"better\""), "uw.toml");
    FAIL() << "an unknown model was accepted";
  } catch (const std::exception& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("model"), std::string::npos) << what;
    EXPECT_NE(what.find("discrete_ordinates"), std::string::npos) << what;
    EXPECT_EQ(what.find("'improved'"), std::string::npos) << what;  // the earlier name is not offered
  }
}

TEST(UnderwaterModelOption, OrdinatesModelSetsTheDefineAndFillsThePerBandBlock) {
  const Scene scene = parseScene(withModel("\"discrete_ordinates\""), "uw.toml");
  EXPECT_EQ(scene.underwater.model, UnderwaterDesc::Model::DiscreteOrdinates);
  const Plan plan = makePlan(scene);
  EXPECT_TRUE(hasDefine(plan, "SEASIM_UNDERWATER_MODEL=1"));
  EXPECT_NE(plan.find("kd_multiple")->why.find("discrete_ordinates"), std::string::npos);
  const WavelengthGrid grid = makeGrid(4, 400, 700);
  const UnderwaterSetup ordinates = makeUnderwaterSetup(scene, grid, makeSensor("cie1931", grid, true, ""));
  ASSERT_EQ(ordinates.ordinates.size(), 4u);
  for (const UwiBand& b : ordinates.ordinates) {
    EXPECT_GT(b.c_dm, 0.0f);
    EXPECT_LT(b.c_dm, ordinates.bands[0].c + 10.0f);
    EXPECT_GT(b.k, 0.0f);
  }
  const UnderwaterSetup thesis =
      makeUnderwaterSetup(parseScene(withModel("\"thesis\""), "uw.toml"), grid, makeSensor("cie1931", grid, true, ""));
  EXPECT_TRUE(thesis.ordinates.empty());
}

TEST(UnderwaterModelOption, BadValuesNameFileLineAndKey) {
  for (const char* bad : {"\"improv\"", "\"Thesis\"", "1", "true"}) {
    try {
      parseScene(withModel(bad), "uw.toml");
      ADD_FAILURE() << "accepted " << bad;
    } catch (const InputError& e) {
      const std::string m = e.what();
      EXPECT_NE(m.find("uw.toml:15"), std::string::npos) << m;
      EXPECT_NE(m.find("underwater.model"), std::string::npos) << m;
    }
  }
  try {
    parseScene(kScene, "uw.toml", {{"underwater.model", "\"discrete_ordinate\"", {"command line", 0}}});
    ADD_FAILURE() << "accepted --set underwater.model=\"discrete_ordinate\"";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("did you mean 'discrete_ordinates'"), std::string::npos) << e.what();
  }
}

TEST(UnderwaterModelOption, MeanCosineKeysOverrideTheFittedTableOrAreRejectedWithFileLineAndKey) {
  const WavelengthGrid grid = makeGrid(2, 400, 700);
  const Sensor sensor = makeSensor("cie1931", grid, true, "");
  // With the two-stream's diffuse field, default: the fitted table at the water's g (jerlov IB's default
  // g); the scalar irradiance of each exponential is its plane irradiances over the streams' mean cosines.
  const std::string two = "\"discrete_ordinates\"\ndiffuse = \"two_stream\"";
  const Scene plain = parseScene(withModel(two), "uw.toml");
  const DiffuseMeanCosines table = diffuseMeanCosines(plain.water.g);
  const UnderwaterSetup a = makeUnderwaterSetup(plain, grid, sensor);
  auto scalar = [](const UwiBand& ib, double down, double up, double beam_down, double beam_up) {
    EXPECT_FLOAT_EQ(ib.o1, float(ib.d1 / down + ib.u1 / up));
    EXPECT_FLOAT_EQ(ib.o2, float(ib.d2 / down + ib.u2 / up));
    EXPECT_FLOAT_EQ(ib.op, float(ib.dp / beam_down + ib.up / beam_up));
  };
  scalar(a.ordinates[0], table.down, table.up, table.beam_down, table.beam_up);
  // Set: each key replaces its stream's value only.
  const Scene set = parseScene(withModel(two + "\nmean_cosine_down = 0.8"), "uw.toml");
  const UnderwaterSetup b = makeUnderwaterSetup(set, grid, sensor);
  scalar(b.ordinates[1], 0.8, table.up, table.beam_down, table.beam_up);
  // The beam's offspring's keys replace its pair only.
  const Scene beam = parseScene(withModel(two + "\nbeam_mean_cosine_down = 0.9\n"
                                                "beam_mean_cosine_up = 0.45"), "uw.toml");
  const UnderwaterSetup c = makeUnderwaterSetup(beam, grid, sensor);
  scalar(c.ordinates[1], table.down, table.up, 0.9, 0.45);
  // The closure key: "asymptotic" lowers k below the default (quadrature) one's; "quadrature" is it.
  const Scene asym = parseScene(withModel(two + "\ntwo_stream_closure = \"asymptotic\""), "uw.toml");
  const Scene quad = parseScene(withModel(two + "\ntwo_stream_closure = \"quadrature\""), "uw.toml");
  EXPECT_LT(makeUnderwaterSetup(asym, grid, sensor).ordinates[1].k, 0.95f * a.ordinates[1].k);
  EXPECT_EQ(makeUnderwaterSetup(quad, grid, sensor).ordinates[1].k, a.ordinates[1].k);
  for (const std::string bad : {"mean_cosine_up = 0.05", "mean_cosine_down = 1.5",
                                "beam_mean_cosine_down = 1.5", "beam_mean_cosine_up = -0.2",
                                "two_stream_closure = \"cubic\"", "diffuse = \"four_stream\""})
    seasim::testing::expectOrdinatesSceneRejects(bad, "underwater." + bad.substr(0, bad.find(' ')));
}

}  // namespace
