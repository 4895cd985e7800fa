// output_layers_test.cpp — the ground-truth layers' scene key, CLI merge and plan (scene/output_layers.h,
// host/passes/nodes/*layers*, effective_coefficients_node.cpp): unknown names fail at file:line:key,
// the planner adds a layer's pass and kernel features only when it is asked for and shows its memory,
// and the formation model's effective coefficients (kernels/common/output_layers.h) in float and
// double at their stiff points: range -> 0, range -> inf, black objects, clear water, behind the camera.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "jobs/layer_image.h"
#include "math/kernel_math.h"
#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "scene/output_layers.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "small_underwater_scene.h"

namespace seasim {
namespace {

const char* kUnderwater = kSmallUnderwaterScene;

std::string errorOf(const std::string& text) { return parseErrorOf(text, "layers.toml"); }

bool hasDefine(const Plan& plan, const std::string& pass, const std::string& define) {
  const PassPlan* p = plan.find(pass);
  return p && std::find(p->defines.begin(), p->defines.end(), define) != p->defines.end();
}

bool anyLayerDefine(const Plan& plan) {
  for (const PassPlan& p : plan.passes)
    for (const auto& d : p.defines)
      if (d.find("SEASIM_LAYER_") != std::string::npos) return true;
  return false;
}

TEST(OutputLayersKey, ParsesNamesInCatalogueOrderWithoutDuplicates) {
  const Scene s = parseScene(std::string(kUnderwater) + "[outputs]\nlayers = [\"object_id\", \"range\", \"range\"]\n",
                             "layers.toml");
  EXPECT_EQ(s.outputs.layers, (std::vector<std::string>{"range", "object_id"}));
  EXPECT_TRUE(parseScene(kUnderwater, "layers.toml").outputs.layers.empty());
}

TEST(OutputLayersKey, UnknownNamesFailAtTheirFileLineAndKey) {
  const std::string e = errorOf(std::string(kUnderwater) + "[outputs]\nlayers = [\"range\",\n  \"rnage\"]\n");
  EXPECT_NE(e.find("layers.toml:11"), std::string::npos) << e;
  EXPECT_NE(e.find("outputs.layers[1]"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'range'"), std::string::npos) << e;
  EXPECT_NE(errorOf("[outputs]\nlayers = \"range\"\n").find("must be an array of layer names"), std::string::npos);
  EXPECT_NE(errorOf("[outputs]\nlayers = [3]\n").find("must be a layer name"), std::string::npos);
  EXPECT_NE(errorOf("[outputs]\nlayer = [\"range\"]\n").find("layer"), std::string::npos);  // unknown key
}

TEST(OutputLayersKey, TheCliAddsToTheScenesLayersAndRefusesUnknownOnes) {
  OutputsDesc o;
  o.layers = {"direct"};
  addOutputLayers(o, {"range", "direct"}, "--output");
  EXPECT_EQ(o.layers, (std::vector<std::string>{"range", "direct"}));
  try {
    addOutputLayers(o, {"depht"}, "--output");
    FAIL();
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("--output: unknown layer 'depht'"), std::string::npos);
  }
}

TEST(OutputLayersPlan, NoLayerAskedMeansNoLayerPassAndNoLayerDefine) {
  const Plan plan = makePlan(parseScene(kUnderwater, "layers.toml"));
  EXPECT_FALSE(plan.hasPass("geometry_layers"));
  EXPECT_FALSE(plan.hasPass("effective_coefficients"));
  EXPECT_FALSE(anyLayerDefine(plan));
  EXPECT_FALSE(plan.produces("formation_layers"));
  EXPECT_EQ(plan.toText().find("layers"), std::string::npos);
}

TEST(OutputLayersPlan, EachLayerAddsOnlyItsOwnWork) {
  auto planWith = [](const std::string& layers) {
    return makePlan(parseScene(std::string(kUnderwater) + "[outputs]\nlayers = " + layers + "\n", "layers.toml"));
  };
  const Plan range = planWith("[\"range\"]");
  ASSERT_TRUE(range.hasPass("geometry_layers"));
  EXPECT_TRUE(hasDefine(range, "geometry_layers", "SEASIM_LAYER_RANGE=0"));
  EXPECT_TRUE(hasDefine(range, "geometry_layers", "SEASIM_LAYER_CHANNELS=1"));
  EXPECT_TRUE(hasDefine(range, "geometry_layers", "SEASIM_LAYER_ALBEDO=-1"));
  EXPECT_FALSE(hasDefine(range, "kd_multiple", "SEASIM_LAYER_FORMATION=1"));
  EXPECT_FALSE(range.hasPass("effective_coefficients"));
  EXPECT_NE(range.find("geometry_layers")->why.find("4 B/pixel"), std::string::npos) << range.toText();

  const Plan direct = planWith("[\"direct\"]");
  EXPECT_FALSE(direct.hasPass("geometry_layers"));
  EXPECT_TRUE(hasDefine(direct, "kd_multiple", "SEASIM_LAYER_FORMATION=1"));
  EXPECT_FALSE(hasDefine(direct, "kd_multiple", "SEASIM_LAYER_VEILING=1"));
  EXPECT_FALSE(direct.hasPass("effective_coefficients"));
  EXPECT_NE(direct.find("kd_multiple")->why.find("outputs.layers: direct"), std::string::npos);

  const Plan beta_b = planWith("[\"beta_b\"]");
  EXPECT_TRUE(hasDefine(beta_b, "kd_multiple", "SEASIM_LAYER_VEILING=1"));
  ASSERT_TRUE(beta_b.hasPass("effective_coefficients"));
  EXPECT_TRUE(hasDefine(beta_b, "effective_coefficients", "SEASIM_LAYER_BETA_B=0"));
  EXPECT_TRUE(hasDefine(beta_b, "effective_coefficients", "SEASIM_LAYER_BETA_D=-1"));

  // The layers' kernels keep +inf and their finiteness tests: never relaxed maths.
  for (const PassPlan& p : planWith("[\"range\", \"beta_d\"]").passes)
    if (p.name == "geometry_layers" || p.name == "effective_coefficients")
      EXPECT_TRUE(std::find(p.defines.begin(), p.defines.end(), "SEASIM_FAST_MATH=1") == p.defines.end()) << p.name;
}

TEST(OutputLayersPlan, TheLampsLayerRunsThroughTheLampsPassOnlyWhenAsked) {
  const std::string lamps = std::string(kUnderwater) +
                            "[[spotlights]]\nposition = [0, -4, 0]\ndirection = [0, -0.2, -1]\n";
  const Plan without = makePlan(parseScene(lamps, "layers.toml"));
  ASSERT_TRUE(without.hasPass("underwater_lamps"));
  EXPECT_FALSE(anyLayerDefine(without));
  const Plan with = makePlan(parseScene(lamps + "[outputs]\nlayers = [\"lamps\"]\n", "layers.toml"));
  EXPECT_TRUE(hasDefine(with, "underwater_lamps", "SEASIM_LAYER_LAMPS=1"));
  EXPECT_FALSE(hasDefine(with, "underwater_lamps", "SEASIM_LAYER_LAMPS_SPLIT=1"));
}

TEST(OutputLayersPlan, TheLampsSplitIsItsOwnLayerOfTheAskedPartsOnly) {
  const std::string lamps = std::string(kUnderwater) +
                            "[[spotlights]]\nposition = [0, -4, 0]\ndirection = [0, -0.2, -1]\n";
  const Plan single = makePlan(parseScene(lamps + "[outputs]\nlayers = [\"lamps_single\"]\n", "layers.toml"));
  EXPECT_TRUE(hasDefine(single, "underwater_lamps", "SEASIM_LAYER_LAMPS_SPLIT=1"));
  // Neither the image's formation split nor the lamps' own total layer is computed for it.
  EXPECT_FALSE(hasDefine(single, "underwater_lamps", "SEASIM_LAYER_LAMPS=1"));
  EXPECT_FALSE(hasDefine(single, "kd_multiple", "SEASIM_LAYER_FORMATION=1"));
  EXPECT_NE(single.find("kd_multiple")->why.find("outputs.layers: lamps_single (12 B/pixel"), std::string::npos)
      << single.toText();
  const Plan both =
      makePlan(parseScene(lamps + "[outputs]\nlayers = [\"lamps_multiple\", \"lamps_single\"]\n", "layers.toml"));
  EXPECT_NE(both.find("kd_multiple")->why.find("lamps_single, lamps_multiple (24 B/pixel"), std::string::npos)
      << both.toText();
  // Without lamps the layers are still written (zero): kd_multiple owns them.
  const Plan dark = makePlan(parseScene(std::string(kUnderwater) + "[outputs]\nlayers = [\"lamps_single\"]\n", "layers.toml"));
  EXPECT_FALSE(dark.hasPass("underwater_lamps"));
  const auto& writes = dark.find("kd_multiple")->writes;
  EXPECT_NE(std::find(writes.begin(), writes.end(), "lamps_split_layer"), writes.end());
}

TEST(OutputLayersPlan, TheLayersMemoryIsInTheBudgetOnlyWhenAsked) {
  const Scene plain = parseScene(kUnderwater, "layers.toml");
  const Scene layered =
      parseScene(std::string(kUnderwater) + "[outputs]\nlayers = [\"range\", \"direct\"]\n", "layers.toml");
  double plain_bytes = 0, layered_bytes = 0;
  for (const BufferEstimate& b : estimateBuffers(plain, makePlan(plain))) plain_bytes += b.bytes;
  for (const BufferEstimate& b : estimateBuffers(layered, makePlan(layered))) layered_bytes += b.bytes;
  // range: 1 float; the split: 18 floats; each on the device and read back.
  EXPECT_DOUBLE_EQ(layered_bytes - plain_bytes, 2.0 * 4 * 19 * 640 * 360);
}

TEST(OutputLayersPlan, LayersOutsideTheUnderwaterViewArePlannedAsUnavailable) {
  const Plan plan = makePlan(parseScene(
      "[camera]\nposition = [0, 10, 0]\n[water]\njerlov = \"IB\"\n[outputs]\nlayers = [\"range\", \"direct\"]\n",
      "layers.toml"));
  int unavailable = 0;
  for (const PassPlan& p : plan.passes)
    if (!p.implemented) {
      ++unavailable;
      EXPECT_NE(p.missing.find("camera below the surface"), std::string::npos);
    }
  EXPECT_EQ(unavailable, 2);  // the geometry layers and the split
  EXPECT_NE(plan.toText().find("not implemented yet"), std::string::npos);
}

// The effective coefficients in float and double: finite everywhere, 0 with the mask off where undefined.
template <class Real>
struct Beta {
  static Real d(Real direct, Real clear, Real z, int* ok);
  static Real b(Real bs, Real veil, Real z, int* ok);
};
template <>
float Beta<float>::d(float direct, float clear, float z, int* ok) {
  return kmath_f::layer_beta_d(direct, clear, z, ok);
}
template <>
double Beta<double>::d(double direct, double clear, double z, int* ok) {
  return kmath_d::layer_beta_d(direct, clear, z, ok);
}
template <>
float Beta<float>::b(float bs, float veil, float z, int* ok) { return kmath_f::layer_beta_b(bs, veil, z, ok); }
template <>
double Beta<double>::b(double bs, double veil, double z, int* ok) { return kmath_d::layer_beta_b(bs, veil, z, ok); }

template <class Real>
void checkStiffCases() {
  using B = Beta<Real>;
  const Real c = Real(0.3);
  int ok = -1;
  // Regular: direct = clear e^{-c z}, backscatter = B∞ (1 - e^{-c z}): both give c back.
  for (Real z : {Real(0.5), Real(3), Real(40)}) {
    EXPECT_NEAR(B::d(Real(2) * std::exp(-c * z), Real(2), z, &ok), c, 1e-4 * c);
    EXPECT_EQ(ok, 1);
    // Near saturation the rest 1 - backscatter/B∞ = e^{-c z} carries the value, known only to the
    // inputs' rounding (eps B∞): β_B's error is eps e^{c z} / z, the inputs' and not the formula's.
    const double input_rounding = std::numeric_limits<Real>::epsilon() * std::exp(double(c * z)) / double(z);
    EXPECT_NEAR(B::b(Real(0.1) * -std::expm1(-c * z), Real(0.1), z, &ok), c, 1e-4 * c + input_rounding);
    EXPECT_EQ(ok, 1);
  }
  // range -> 0: the ratio tends to 1; log1p keeps c down to the ratio's resolution, never NaN.
  for (Real z : {Real(1e-3), Real(1e-6), Real(1e-12), Real(1e-30), Real(1e-38)}) {
    const Real bd = B::d(std::exp(-c * z), Real(1), z, &ok);
    EXPECT_TRUE(std::isfinite(bd));
    EXPECT_GE(bd, Real(0));
    EXPECT_LE(bd, Real(2) * c + Real(1e-30));
    const Real bb = B::b(-std::expm1(-c * z) * Real(0.1), Real(0.1), z, &ok);
    EXPECT_TRUE(std::isfinite(bb));
    if (z >= Real(1e-6)) EXPECT_NEAR(bb, c, 1e-3 * c);
  }
  // Exactly 0 range (an object behind the camera or at its near plane), negative, infinite (open water):
  // undefined.
  for (Real z : {Real(0), Real(-1), Real(1e30), std::numeric_limits<Real>::infinity()}) {
    EXPECT_EQ(B::d(Real(0.5), Real(1), z, &ok), Real(0));
    EXPECT_EQ(ok, 0);
    EXPECT_EQ(B::b(Real(0.05), Real(0.1), z, &ok), Real(0));
    EXPECT_EQ(ok, 0);
  }
  // range -> ∞ in finite numbers: the direct light underflows to 0 (undefined) or keeps c.
  EXPECT_EQ(B::d(Real(0), Real(1), Real(1e4), &ok), Real(0));
  EXPECT_EQ(ok, 0);
  EXPECT_NEAR(B::d(std::exp(Real(-80)), Real(1), Real(80) / c, &ok), c, 1e-4);
  // The backscatter saturates at B∞ (β_B infinite): undefined, not Inf.
  EXPECT_EQ(B::b(Real(0.1), Real(0.1), Real(5), &ok), Real(0));
  EXPECT_EQ(ok, 0);
  // Black objects: clear = direct = 0.
  EXPECT_EQ(B::d(Real(0), Real(0), Real(2), &ok), Real(0));
  EXPECT_EQ(ok, 0);
  // Clear water, β -> 0: direct = clear and no backscatter give 0, defined; no veiling light: undefined.
  EXPECT_EQ(B::d(Real(1), Real(1), Real(2), &ok), Real(0));
  EXPECT_EQ(ok, 1);
  EXPECT_EQ(B::b(Real(0), Real(0.1), Real(2), &ok), Real(0));
  EXPECT_EQ(ok, 1);
  EXPECT_EQ(B::b(Real(0), Real(0), Real(2), &ok), Real(0));
  EXPECT_EQ(ok, 0);
  // Denormal light: finite.
  EXPECT_TRUE(std::isfinite(B::d(std::numeric_limits<Real>::denorm_min(), Real(1), Real(1e-30), &ok)));
  const Real nearly_saturated = Real(0.1) * (Real(1) - std::numeric_limits<Real>::epsilon());
  EXPECT_TRUE(std::isfinite(B::b(nearly_saturated, Real(0.1), Real(1e-30), &ok)));
}

TEST(EffectiveCoefficients, StiffCasesAreFiniteInFloat) { checkStiffCases<float>(); }
TEST(EffectiveCoefficients, StiffCasesAreFiniteInDouble) { checkStiffCases<double>(); }

TEST(GeometryLayerMaths, ObjectIdsAndDepth) {
  EXPECT_EQ(kmath_f::layer_object_id(-1), 0);  // UW_MAT_NONE: open water
  EXPECT_EQ(kmath_f::layer_object_id(-2), 0);  // UW_MAT_SURFACE
  EXPECT_EQ(kmath_f::layer_object_id(-3), 1);  // UW_MAT_BOTTOM
  EXPECT_EQ(kmath_f::layer_object_id(0), 2);
  EXPECT_EQ(kmath_d::layer_object_id(7), 9);
  const kmath_d::real3 d{0.6, 0.0, -0.8}, fwd{0.0, 0.0, -1.0};
  EXPECT_DOUBLE_EQ(kmath_d::layer_depth(5.0, d, fwd), 4.0);
  EXPECT_FALSE(kmath_f::layer_hit(1e30f));
  EXPECT_TRUE(kmath_f::layer_hit(1e4f));
  EXPECT_DOUBLE_EQ(kmath_d::layer_weighted_mean(1.0, 0.0), 0.0);
  EXPECT_DOUBLE_EQ(kmath_d::layer_weighted_mean(1.0, 4.0), 0.25);
}

// image.exr's channels: R, G, B, then the asked layers in the catalogue's order whatever order the
// passes wrote them in; a layer the passes wrote but nobody asked for is left out; +inf range kept,
// any other non-finite value refused.
TEST(LayerImage, OrdersTheAskedLayersAndRefusesNaN) {
  FrameResult frame;
  frame.rgb = Image::rgb(2, 1);
  frame.layers.resize(2, 1, 3);
  frame.layers.channel_names = {"object_id", "clear.R", "range"};
  frame.layers.pixels = {2.0f, 0.5f, 3.0f, 0.0f, 0.25f, std::numeric_limits<float>::infinity()};
  OutputsDesc outputs;
  outputs.layers = {"range", "object_id"};
  const Image image = imageWithLayers(frame, outputs);
  EXPECT_EQ(image.channel_names, (std::vector<std::string>{"R", "G", "B", "range", "object_id"}));
  EXPECT_EQ(image.at(0, 0, 3), 3.0f);
  EXPECT_EQ(image.at(0, 0, 4), 2.0f);
  EXPECT_TRUE(std::isinf(image.at(1, 0, 3)));
  EXPECT_EQ(imageWithLayers(frame, OutputsDesc{}).channels, 3);
  frame.layers.pixels[1] = std::numeric_limits<float>::quiet_NaN();
  outputs.layers = {"clear"};
  frame.layers.channel_names = {"object_id", "clear.R", "range"};
  EXPECT_THROW(imageWithLayers(frame, outputs), RuntimeError);  // clear.G and .B missing: a plan's bug
  frame.layers.resize(2, 1, 4);
  frame.layers.channel_names = {"clear.R", "clear.G", "clear.B", "range"};
  frame.layers.pixels[0] = std::numeric_limits<float>::quiet_NaN();
  try {
    imageWithLayers(frame, outputs);
    FAIL();
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find("NaN/Inf values (first in 'clear.R')"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace seasim
