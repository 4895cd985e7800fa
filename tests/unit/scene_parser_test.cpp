// scene_parser_test.cpp — scene files: a full scene read back with its unit conversions, the
// defaults, overrides (applied, and errors located at the override), the example scenes, and a
// table of bad inputs each with the exact "file:line: key 'KEY'" its message must contain.
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "plan/scene_facts.h"
#include "scene/model_keys.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/paths.h"
#include "util/error.h"

namespace fs = std::filesystem;
using namespace seasim;

namespace {

constexpr double kDeg = std::numbers::pi / 180.0;

// A fresh folder under the system temp dir holding the files a test needs (per process: ctest may
// run the tests of this file in parallel processes).
fs::path tempDir(const std::string& name) {
  fs::path dir = fs::temp_directory_path() /
                 ("seasim_scene_test_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

void writeFile(const fs::path& p, const std::string& text) {
  std::ofstream out(p, std::ios::binary);
  out << text;
}

// The message parseScene throws, or "" when it does not throw.
std::string errorOf(const std::string& text, const std::vector<Override>& overrides = {},
                    const std::string& path = "bad.toml") {
  try {
    parseScene(text, path, overrides);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

}  // namespace

TEST(SceneParser, FullSceneRoundTrip) {
  fs::path dir = tempDir("full");
  writeFile(dir / "sky.exr", "not decoded by the parser");
  writeFile(dir / "rock.png", "x");
  writeFile(dir / "lamp.png", "x");
  const std::string text = R"(
[scene]
name = "full"
[camera]
position = [1, 12.5, 3]
look_at = [1, 0, -50]
up = [0, 2, 0]
fov_deg = 45
width = 320
height = 200
exposure_ev = -1.5
[sun]
enabled = false
zenith_deg = 30
azimuth_deg = 90
irradiance = 2
angular_radius_deg = 0.5
[sky]
model = "image"
radiance = 0.1
image = "sky.exr"
[water]
wavelengths_nm = [400, 500, 600]
a = [0.1, 0.05, 0.3]
c = [0.3, 0.25, 0.4]
kd = [0.2, 0.1, 0.4]
g = 0.8
ior = 1.34
[air]
density = 2
extinction = 0.1
phase = "hg"
g = 0.3
[surface]
type = "fft"
wind_speed = 7
wind_direction_deg = 180
patch_size = 64
grid = 512
choppiness = 1.2
directional_exponent = 4
small_wave = 0.01
depth = 20
loop_period = 10
time = 2.5
seed = 42
[bottom]
type = "heightfield"
heightfield = "rock.png"
min_depth = 2
max_depth = 12
extent = 50
albedo = { wavelengths_nm = [400, 700], values = [0.1, 0.4] }
[[objects]]
type = "sphere"
center = [0, -3, -10]
radius = 1.5
albedo = 0.7
[[objects]]
type = "box"
min = [-1, -5, -20]
max = [1, -4, -18]
[[objects]]
type = "plane"
point = [0, -30, 0]
normal = [0, 3, 4]
[[objects]]
type = "heightfield"
heightfield = "rock.png"
point = [0, -10, 0]
extent = 20
height = 2
[[spotlights]]
position = [0, 5, -5]
direction = [0, -2, 0]
cone_deg = 25
falloff_deg = 3
intensity = 500
color = [1, 0.9, 0.8]
light_map = "lamp.png"
[spectral]
count = 16
range_nm = [420, 680]
sensor = "nikon_d5100_npl"
white_balance = false
spectral_exr = true
[sea]
single_scattering = false
second_order = true
reflection = false
[quality]
sea_nz = 24
froxel_x = "auto"
shafts_exact = true
fast_math = false
)";
  Scene s = parseScene(text, (dir / "full.toml").string());
  const double tol = 1e-12;
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.file, (dir / "full.toml").lexically_normal().string());
  EXPECT_DOUBLE_EQ(s.camera.position.y, 12.5);
  EXPECT_DOUBLE_EQ(s.camera.look_at.z, -50);
  EXPECT_NEAR(s.camera.up.y, 1.0, tol);  // normalised
  EXPECT_NEAR(s.camera.fov_y, 45 * kDeg, tol);
  EXPECT_EQ(s.camera.width, 320);
  EXPECT_EQ(s.camera.height, 200);
  EXPECT_DOUBLE_EQ(s.camera.exposure_ev, -1.5);

  EXPECT_FALSE(s.sun.enabled);
  EXPECT_NEAR(s.sun.zenith, std::numbers::pi / 6, tol);
  EXPECT_NEAR(s.sun.azimuth, std::numbers::pi / 2, tol);
  EXPECT_DOUBLE_EQ(s.sun.irradiance, 2);
  EXPECT_NEAR(s.sun.angular_radius, 0.5 * kDeg, tol);

  EXPECT_EQ(s.sky.model, SkyDesc::Model::Image);
  EXPECT_DOUBLE_EQ(s.sky.radiance, 0.1);
  EXPECT_EQ(s.sky.image, (dir / "sky.exr").string());

  ASSERT_TRUE(s.water.present);
  EXPECT_TRUE(s.water.jerlov.empty());
  EXPECT_NEAR(s.water.a.at(500), 0.05, tol);
  // c given instead of b: b = c - a.
  ASSERT_EQ(s.water.b.values.size(), 3u);
  EXPECT_NEAR(s.water.b.at(400), 0.2, tol);
  EXPECT_NEAR(s.water.b.at(500), 0.2, tol);
  EXPECT_NEAR(s.water.b.at(600), 0.1, tol);
  EXPECT_NEAR(s.water.b.at(450), 0.2, tol);  // linear in between
  EXPECT_NEAR(s.water.kd.at(600), 0.4, tol);
  EXPECT_DOUBLE_EQ(s.water.g, 0.8);
  EXPECT_DOUBLE_EQ(s.water.ior, 1.34);

  ASSERT_TRUE(s.air.present);
  EXPECT_DOUBLE_EQ(s.air.density, 2);
  EXPECT_DOUBLE_EQ(s.air.extinction, 0.1);
  EXPECT_EQ(s.air.phase, AirDesc::Phase::HenyeyGreenstein);
  EXPECT_DOUBLE_EQ(s.air.g, 0.3);

  EXPECT_EQ(s.surface.type, SurfaceDesc::Type::Fft);
  EXPECT_DOUBLE_EQ(s.surface.wind_speed, 7);
  EXPECT_NEAR(s.surface.wind_direction, std::numbers::pi, tol);
  EXPECT_DOUBLE_EQ(s.surface.patch_size, 64);
  EXPECT_EQ(s.surface.grid, 512);
  EXPECT_DOUBLE_EQ(s.surface.choppiness, 1.2);
  EXPECT_DOUBLE_EQ(s.surface.directional_exponent, 4);
  EXPECT_DOUBLE_EQ(s.surface.small_wave, 0.01);
  EXPECT_DOUBLE_EQ(s.surface.depth, 20);
  EXPECT_DOUBLE_EQ(s.surface.loop_period, 10);
  EXPECT_DOUBLE_EQ(s.surface.time, 2.5);
  EXPECT_EQ(s.surface.seed, 42u);

  EXPECT_EQ(s.bottom.type, BottomDesc::Type::HeightField);
  EXPECT_EQ(s.bottom.heightfield, (dir / "rock.png").string());
  EXPECT_DOUBLE_EQ(s.bottom.min_depth, 2);
  EXPECT_DOUBLE_EQ(s.bottom.max_depth, 12);
  EXPECT_DOUBLE_EQ(s.bottom.extent, 50);
  EXPECT_NEAR(s.bottom.albedo.at(550), 0.25, tol);

  ASSERT_EQ(s.objects.size(), 4u);
  EXPECT_EQ(s.objects[0].type, ObjectDesc::Type::Sphere);
  EXPECT_DOUBLE_EQ(s.objects[0].center.y, -3);
  EXPECT_DOUBLE_EQ(s.objects[0].radius, 1.5);
  EXPECT_DOUBLE_EQ(s.objects[0].albedo.at(600), 0.7);
  EXPECT_EQ(s.objects[0].loc.line, 54);  // the [[objects]] header
  EXPECT_EQ(s.objects[1].type, ObjectDesc::Type::Box);
  EXPECT_DOUBLE_EQ(s.objects[1].box_min.z, -20);
  EXPECT_DOUBLE_EQ(s.objects[1].box_max.y, -4);
  EXPECT_DOUBLE_EQ(s.objects[1].albedo.at(500), 0.5);  // default
  EXPECT_EQ(s.objects[2].type, ObjectDesc::Type::Plane);
  EXPECT_NEAR(s.objects[2].normal.y, 0.6, tol);
  EXPECT_NEAR(s.objects[2].normal.z, 0.8, tol);
  EXPECT_EQ(s.objects[3].type, ObjectDesc::Type::HeightField);
  EXPECT_EQ(s.objects[3].heightfield, (dir / "rock.png").string());
  EXPECT_DOUBLE_EQ(s.objects[3].extent, 20);
  EXPECT_DOUBLE_EQ(s.objects[3].height, 2);

  ASSERT_EQ(s.spotlights.size(), 1u);
  EXPECT_NEAR(s.spotlights[0].direction.y, -1, tol);
  EXPECT_NEAR(s.spotlights[0].cone, 25 * kDeg, tol);
  EXPECT_NEAR(s.spotlights[0].falloff, 3 * kDeg, tol);
  EXPECT_DOUBLE_EQ(s.spotlights[0].intensity, 500);
  EXPECT_DOUBLE_EQ(s.spotlights[0].color.z, 0.8);
  EXPECT_EQ(s.spotlights[0].light_map, (dir / "lamp.png").string());

  EXPECT_EQ(s.spectral.count, 16);
  EXPECT_DOUBLE_EQ(s.spectral.min_nm, 420);
  EXPECT_DOUBLE_EQ(s.spectral.max_nm, 680);
  EXPECT_EQ(s.spectral.sensor, "nikon_d5100_npl");
  EXPECT_FALSE(s.spectral.white_balance);
  EXPECT_TRUE(s.spectral.spectral_exr);

  EXPECT_FALSE(s.sea.single_scattering);
  EXPECT_TRUE(s.sea.second_order);
  EXPECT_FALSE(s.sea.reflection);

  EXPECT_DOUBLE_EQ(s.quality.at("sea_nz").value, 24);
  EXPECT_FALSE(s.quality.at("sea_nz").automatic);
  EXPECT_TRUE(s.quality.at("froxel_x").automatic);
  EXPECT_DOUBLE_EQ(s.quality.at("shafts_exact").value, 1);
  EXPECT_FALSE(s.quality.at("fast_math").automatic);
  EXPECT_DOUBLE_EQ(s.quality.at("fast_math").value, 0);
  EXPECT_DOUBLE_EQ(s.quality.at("sea_nd").value, 128);  // untouched knobs keep their default
  fs::remove_all(dir);
}

TEST(SceneParser, Defaults) {
  Scene s = parseScene("", "empty.toml");
  EXPECT_EQ(s.name, "empty");
  EXPECT_DOUBLE_EQ(s.camera.position.y, 10);
  EXPECT_NEAR(s.camera.fov_y, 60 * kDeg, 1e-12);
  EXPECT_EQ(s.camera.width, 640);
  EXPECT_EQ(s.camera.height, 360);
  EXPECT_TRUE(s.sun.enabled);
  EXPECT_NEAR(s.sun.zenith, 45 * kDeg, 1e-12);
  EXPECT_NEAR(s.sun.angular_radius, 0.2667 * kDeg, 1e-12);
  EXPECT_EQ(s.sky.model, SkyDesc::Model::Uniform);
  EXPECT_FALSE(s.water.present);
  EXPECT_FALSE(s.air.present);
  EXPECT_EQ(s.surface.type, SurfaceDesc::Type::Flat);
  EXPECT_EQ(s.bottom.type, BottomDesc::Type::None);
  EXPECT_TRUE(s.objects.empty());
  EXPECT_TRUE(s.spotlights.empty());
  EXPECT_EQ(s.spectral.count, 3);
  EXPECT_EQ(s.spectral.sensor, "cie1931");
  EXPECT_DOUBLE_EQ(s.spectral.min_nm, 400);
  EXPECT_DOUBLE_EQ(s.spectral.max_nm, 700);
  EXPECT_TRUE(s.sea.single_scattering);
  EXPECT_FALSE(s.sea.second_order);
  EXPECT_FALSE(s.shallow.present);  // no [shallow]: the four-flow model is not asked for
  // Every knob is present with its documented default.
  const std::pair<const char*, double> knobs[] = {
      {"sea_lut_size", 64},      {"sea_nz", 12},          {"sea_nd", 128},
      {"sea_map_size", 32},      {"shafts_planes", 30},   {"shafts_subplanes", 6},
      {"shafts_table_size", 256}, {"shadow_map_size", 512}, {"froxel_z", 32},
      {"froxel_columns", 80},    {"caustic_map_size", 256}, {"caustic_layers", 8},
      {"reference_spp", 64},     {"reference_steps", 200}, {"shafts_exact", 0},
      {"shafts_error_budget", 1}, {"sea_supersample", 1},  {"wave_filter", 1},
      {"fourflow_table_size", 32}, {"lamps_delta_m", 0}, {"shafts_panel_deg", 4}, {"shafts_panel_texels", 2},
      {"profile_streams", 16}, {"lamps_model", 2}, {"shafts_march_steps", 20}, {"sea_sky_table", 256}};
  EXPECT_EQ(s.quality.size(), std::size(knobs) + 4);
  EXPECT_TRUE(s.quality.at("fast_math").automatic);  // "auto": the planner decides (fastMathFor)
  EXPECT_TRUE(s.quality.at("froxel_x").automatic);   // "auto": from froxel_columns (froxel_setup.h)
  EXPECT_TRUE(s.quality.at("froxel_y").automatic);
  EXPECT_TRUE(s.quality.at("shafts_method").automatic);  // the planner decides (plan/shafts_method.h)
  for (const auto& [name, knob] : s.quality) EXPECT_FALSE(knob.given) << name;  // nothing written: all defaults
  for (const auto& [name, value] : knobs) {
    ASSERT_TRUE(s.quality.count(name)) << name;
    EXPECT_FALSE(s.quality.at(name).automatic) << name;
    EXPECT_DOUBLE_EQ(s.quality.at(name).value, value) << name;
  }
  // The passes' count knobs are read from their descriptors, with the descriptors' defaults.
  for (const seasim::KnobDefault& k : seasim::qualityCountKnobs()) {
    ASSERT_TRUE(s.quality.count(k.name)) << k.name;
    EXPECT_DOUBLE_EQ(s.quality.at(k.name).value, k.value) << k.name;
  }
  // The lamps' "orders" settings are the underwater_lamps descriptor's scene keys.
  const std::pair<const char*, double> lamp_keys[] = {{"quality.lamps_orders", 4}, {"quality.lamps_ms_steps", 12},
                                                      {"quality.lamps_ms_kappa", 0.6}, {"quality.lamps_ms_spread", 0.6},
                                                      {"quality.lamps_ms_cell_deg", 1.0}};
  for (const auto& [key, value] : lamp_keys) EXPECT_DOUBLE_EQ(seasim::modelKey(s, key), value) << key;

  // A [bottom] table without type is a flat bottom at the default depth; water defaults.
  Scene b = parseScene("[water]\njerlov = \"IB\"\n[bottom]\n", "b.toml");
  EXPECT_EQ(b.bottom.type, BottomDesc::Type::Flat);
  EXPECT_DOUBLE_EQ(b.bottom.depth, 10);
  EXPECT_DOUBLE_EQ(b.bottom.albedo.at(500), 0.3);
  EXPECT_DOUBLE_EQ(b.water.g, 0.9);
  EXPECT_DOUBLE_EQ(b.water.ior, 1.333);
}

// "auto" written for the shafts' method asks for a measurement (host/quality/shafts_method_auto.h);
// absent, the planner's rule. Both are automatic; only the written one is given. A count knob written
// as a number or as "auto" is given, so the method's search keeps a number fixed.
TEST(SceneParser, WrittenKnobsAreGiven) {
  const Scene absent = parseScene("", "a.toml");
  EXPECT_TRUE(absent.quality.at("shafts_method").automatic);
  EXPECT_FALSE(absent.quality.at("shafts_method").given);
  const Scene written = parseScene("[quality]\nshafts_method = \"auto\"\nshafts_march_steps = 40\n"
                                   "shafts_planes = \"auto\"\n", "w.toml");
  EXPECT_TRUE(written.quality.at("shafts_method").automatic);
  EXPECT_TRUE(written.quality.at("shafts_method").given);
  EXPECT_TRUE(written.quality.at("shafts_march_steps").given);
  EXPECT_FALSE(written.quality.at("shafts_march_steps").automatic);
  EXPECT_DOUBLE_EQ(written.quality.at("shafts_march_steps").value, 40);
  EXPECT_TRUE(written.quality.at("shafts_planes").given);
  EXPECT_TRUE(written.quality.at("shafts_planes").automatic);
  EXPECT_FALSE(written.quality.at("shafts_subplanes").given);
  const Scene fixed = parseScene("[quality]\nshafts_method = \"march\"\n", "f.toml");
  EXPECT_FALSE(fixed.quality.at("shafts_method").automatic);
  EXPECT_TRUE(fixed.quality.at("shafts_method").given);
}

TEST(SceneParser, JerlovSpectraFromData) {
  // Values from data/jerlov_a.csv, jerlov_b.csv (Solonenko & Mobley 2015) and jerlov_kd.csv
  // (Jerlov 1976); the type name is case-insensitive.
  Scene s = parseScene("[water]\njerlov = \"ib\"\n", "j.toml");
  EXPECT_EQ(s.water.jerlov, "IB");
  EXPECT_DOUBLE_EQ(s.water.a.at(400), 0.0331);
  EXPECT_DOUBLE_EQ(s.water.b.at(500), 0.0597);
  EXPECT_DOUBLE_EQ(s.water.kd.at(400), 0.051);
  EXPECT_EQ(s.water.a.wavelengths_nm.front(), 300);
  EXPECT_EQ(s.water.a.wavelengths_nm.back(), 700);
  // 5C has no published a, b past 575 nm; spectral/jerlov.h fills the gap, so the spectra reach 700.
  Scene c = parseScene("[water]\njerlov = \"5C\"\n", "j.toml");
  EXPECT_EQ(c.water.b.wavelengths_nm.back(), 700);
  EXPECT_EQ(c.water.a.wavelengths_nm.size(), c.water.a.values.size());
}

TEST(SceneParser, ExplicitSpectraWithConsistentC) {
  Scene s = parseScene("[water]\nwavelengths_nm = [400, 500]\na = [0.1, 0.2]\nb = [0.3, 0.4]\n"
                       "c = [0.4, 0.6]\n", "c.toml");
  EXPECT_NEAR(s.water.b.at(500), 0.4, 1e-12);
  EXPECT_TRUE(s.water.kd.empty());  // optional when explicit
}

TEST(SceneParser, ExampleScenesValidate) {
  Scene flat = loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/flat_sea.toml");
  EXPECT_EQ(flat.water.jerlov, "IB");
  EXPECT_EQ(flat.bottom.type, BottomDesc::Type::Flat);
  EXPECT_DOUBLE_EQ(flat.bottom.depth, 8);
  EXPECT_DOUBLE_EQ(flat.bottom.albedo.at(550), 0.3);
  EXPECT_EQ(flat.camera.width, 480);
  EXPECT_EQ(flat.camera.height, 270);
  EXPECT_NEAR(flat.sun.zenith, 40 * kDeg, 1e-12);
  EXPECT_GT(flat.camera.position.y, flat.camera.look_at.y);  // looking down

  Scene deep = loadScene(std::string(SEASIM_SOURCE_DIR) + "/scenes/deep_ocean.toml");
  EXPECT_EQ(deep.water.jerlov, "II");
  EXPECT_EQ(deep.bottom.type, BottomDesc::Type::None);
  EXPECT_EQ(deep.spectral.count, 16);
  EXPECT_TRUE(deep.sea.second_order);
}

TEST(SceneParser, OverridesAreApplied) {
  const std::string text = "[water]\njerlov = \"IB\"\n[sun]\nzenith_deg = 30\n[[objects]]\n"
                           "type = \"sphere\"\nradius = 1\n";
  SourceLoc at{"job.toml", 7};
  Scene s = parseScene(text, "o.toml",
                       {{"sun.zenith_deg", "40", at},
                        {"water.jerlov", "\"II\"", at},
                        {"air.density", "3.5", at},            // creates [air]
                        {"objects[0].radius", "2.5", at},      // indexes [[objects]]
                        {"spectral.range_nm", "[450, 650]", at},
                        {"quality.sea_nd", "\"auto\"", at}});
  EXPECT_NEAR(s.sun.zenith, 40 * kDeg, 1e-12);
  EXPECT_EQ(s.water.jerlov, "II");
  EXPECT_TRUE(s.air.present);
  EXPECT_DOUBLE_EQ(s.air.density, 3.5);
  EXPECT_DOUBLE_EQ(s.objects[0].radius, 2.5);
  EXPECT_DOUBLE_EQ(s.spectral.min_nm, 450);
  EXPECT_TRUE(s.quality.at("sea_nd").automatic);
  // Later overrides win over earlier ones; a number becomes a spectrum table by override.
  Scene t = parseScene(text + "[bottom]\nalbedo = 0.2\n", "o.toml",
                       {{"sun.zenith_deg", "40", at},
                        {"sun.zenith_deg", "50", at},
                        {"bottom.albedo.wavelengths_nm", "[400, 700]", at},
                        {"bottom.albedo.values", "[0.1, 0.7]", at}});
  EXPECT_NEAR(t.sun.zenith, 50 * kDeg, 1e-12);
  EXPECT_NEAR(t.bottom.albedo.at(550), 0.4, 1e-12);
}

TEST(SceneParser, OverrideErrorsNameTheOverride) {
  const std::string text = "[water]\njerlov = \"IB\"\ng = 0.5\n[sun]\nzenith_deg = 30\n";
  struct Case {
    Override o;
    std::string expected;
  };
  const Case cases[] = {
      {{"water.g", "1.2", {"job.toml", 7}}, "job.toml:7: key 'water.g': must satisfy |g| < 1"},
      {{"sun.zenith", "40", {"cli", 1}}, "cli:1: key 'sun.zenith': unknown key; did you mean 'zenith_deg'?"},
      {{"sunn.zenith_deg", "40", {"job.toml", 3}}, "job.toml:3: key 'sunn': unknown table; did you mean 'sun'?"},
      {{"sun.zenith_deg", "\"high\"", {"job.toml", 4}}, "job.toml:4: key 'sun.zenith_deg': expected a number, got a string"},
      {{"sun.zenith_deg", "4 0", {"job.toml", 5}}, "job.toml:5: key 'sun.zenith_deg': cannot read override value '4 0'"},
      {{"objects[2].radius", "1", {"job.toml", 6}}, "job.toml:6: key 'objects[2].radius': the scene has no objects[2]"},
      {{"sun..zenith_deg", "1", {"job.toml", 8}}, "job.toml:8: key 'sun..zenith_deg': cannot use this override key"},
      {{"camera.position", "[0, 0, -100]", {"job.toml", 9}}, "job.toml:9: key 'camera.position': camera.position and camera.look_at are the same point"},
  };
  for (const Case& c : cases) EXPECT_NE(errorOf(text, {c.o}).find(c.expected), std::string::npos)
      << "override " << c.o.key << " = " << c.o.value_toml << "\n  got: " << errorOf(text, {c.o});
  // A value the override did not touch still reports the scene file.
  EXPECT_NE(errorOf("[water]\njerlov = \"IB\"\ng = 1.5\n", {{"sun.zenith_deg", "40", {"job.toml", 2}}})
                .find("bad.toml:3: key 'water.g'"),
            std::string::npos);
}

TEST(SceneParser, TexturesResolveAgainstTheSceneFile) {
  fs::path dir = tempDir("tex");
  fs::create_directories(dir / "sub" / "tex");
  writeFile(dir / "sub" / "tex" / "hf.png", "x");
  const std::string text = "[water]\njerlov = \"IB\"\n[bottom]\ntype = \"heightfield\"\nheightfield = \"tex/hf.png\"\n";
  Scene s = parseScene(text, (dir / "sub" / "s.toml").string());
  EXPECT_EQ(s.bottom.heightfield, (dir / "sub" / "tex" / "hf.png").string());
  // The same scene anchored one folder up does not find its texture.
  std::string msg = errorOf(text, {}, (dir / "s.toml").string());
  EXPECT_NE(msg.find("s.toml:5: key 'bottom.heightfield': file not found: " + (dir / "tex" / "hf.png").string()),
            std::string::npos) << msg;
  fs::remove_all(dir);
}

// Camera curves that do not ship are read from the scene's camera_dir (relative to the scene file),
// then $SEASIM_CAMERA_DIR, then data/cameras. A missing one names every folder searched and the
// scene's file, line and key.
TEST(SceneParser, CameraDirFindsUserCurvesAndMissingOnesNameTheFolders) {
  fs::path dir = tempDir("cameras");
  fs::create_directories(dir / "my_cameras");
  std::string curves = "nm,r,g,b\n";
  for (int nm = 380; nm <= 780; nm += 10)
    curves += std::to_string(nm) + "," + (nm > 560 ? "1" : "0.1") + "," + (nm > 480 && nm < 600 ? "1" : "0.1") +
              "," + (nm < 500 ? "1" : "0.1") + "\n";
  writeFile(dir / "my_cameras" / "studio_cam.csv", curves);

  const std::string good = "[spectral]\ncount = 8\ncamera_dir = \"my_cameras\"\nsensor = \"studio_cam\"\n";
  Scene s = parseScene(good, (dir / "s.toml").string());
  EXPECT_EQ(s.spectral.camera_dir, (dir / "my_cameras").string());
  EXPECT_EQ(cameraFile("studio_cam", s.spectral.camera_dir), (dir / "my_cameras" / "studio_cam.csv").string());
  const WavelengthGrid g = makeGrid(8, s.spectral.min_nm, s.spectral.max_nm);
  EXPECT_EQ(makeSensor(s.spectral.sensor, g, true, s.spectral.camera_dir).size(), 8u);
  // The shipped cameras are still found with a camera_dir set.
  EXPECT_NO_THROW(parseScene("[spectral]\ncamera_dir = \"my_cameras\"\nsensor = \"nikon_d5100_npl\"\n",
                             (dir / "s.toml").string()));

  // Missing: the message names the scene's file:line:key, the file looked for and each folder searched.
  const std::string scene_file = (dir / "missing.toml").string();
  const std::string missing = "[spectral]\ncount = 8\ncamera_dir = \"my_cameras\"\nsensor = \"camspec_nikon_d700\"\n";
  const std::string msg = errorOf(missing, {}, scene_file);
  EXPECT_NE(msg.find(scene_file + ":4: key 'spectral.sensor': unknown sensor 'camspec_nikon_d700'"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find("camspec_nikon_d700.csv in " + (dir / "my_cameras").string()), std::string::npos) << msg;
  EXPECT_NE(msg.find(dataDir() + "/cameras"), std::string::npos) << msg;
  // A camera_dir that is not a folder is named as such.
  const std::string no_dir = errorOf("[spectral]\ncamera_dir = \"nowhere\"\n", {}, scene_file);
  EXPECT_NE(no_dir.find(scene_file + ":2: key 'spectral.camera_dir': no such folder: " + (dir / "nowhere").string()),
            std::string::npos) << no_dir;

  // $SEASIM_CAMERA_DIR is searched too, and named in the message when it does not have the file.
  ::setenv("SEASIM_CAMERA_DIR", (dir / "my_cameras").c_str(), 1);
  EXPECT_NO_THROW(parseScene("[spectral]\nsensor = \"studio_cam\"\n", scene_file));
  const std::string env_msg = errorOf("[spectral]\nsensor = \"other_cam\"\n", {}, scene_file);
  ::unsetenv("SEASIM_CAMERA_DIR");
  EXPECT_NE(env_msg.find("other_cam.csv in " + (dir / "my_cameras").string() + ", " + dataDir() + "/cameras"),
            std::string::npos) << env_msg;
  EXPECT_THROW(parseScene("[spectral]\nsensor = \"studio_cam\"\n", scene_file), InputError);
  fs::remove_all(dir);
}

TEST(SceneParser, LoadSceneReportsMissingFile) {
  EXPECT_THROW(loadScene("/nonexistent/seasim/none.toml"), InputError);
}

// ---------------------------------------------------------------------------------------------
// Bad inputs: each text must fail with a message containing `expected` (file:line and key).

namespace {

struct BadScene {
  const char* what;
  const char* toml;
  const char* expected;
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const BadScene& c, std::ostream* os) { *os << c.what; }

const BadScene kBadScenes[] = {
    {"unknown caustics mode", "[underwater]\ncaustics = \"fancy\"\n",
     "bad.toml:2: key 'underwater.caustics'"},
    {"caustic map without waves", "[water]\njerlov = \"IB\"\n[underwater]\ncaustics = \"map\"\n",
     "bad.toml:4: key 'underwater.caustics': \"map\" needs a wavy surface"},
    {"froxel far before near", "[underwater]\nfroxel_near_m = 5.0\nfroxel_far_m = 2.0\n",
     "bad.toml:3: key 'underwater.froxel_far_m': must be > froxel_near_m"},
    {"zero caustic period", "[underwater]\ncaustic_period_m = 0\n",
     "bad.toml:2: key 'underwater.caustic_period_m': must be > 0 m"},
    {"string for the point-spread", "[underwater]\npoint_spread = \"yes\"\n",
     "bad.toml:2: key 'underwater.point_spread': expected true or false, got a string"},
    {"typo in point_spread", "[underwater]\npoint_spred = false\n",
     "bad.toml:2: key 'underwater.point_spred': unknown key; did you mean 'point_spread'?"},
    {"odd source streams", "[underwater]\nsource_streams = 17\n",
     "bad.toml:2: key 'underwater.source_streams': must be 0 (the order-3 field's own in-scatter) or an even "
     "number of streams in [8, 64], got 17"},
    {"too many source streams", "[underwater]\nsource_streams = 128\n",
     "bad.toml:2: key 'underwater.source_streams'"},
    {"source streams as a string", "[underwater]\nsource_streams = \"32\"\n",
     "bad.toml:2: key 'underwater.source_streams'"},
    {"a research key under both its names", "[underwater]\nflux_scale = 1.0\nimproved_flux_scale = 1.0\n",
     "bad.toml:3: key 'underwater.improved_flux_scale': is the earlier name of 'flux_scale'"},
    {"odd source streams under the earlier name", "[underwater]\nimproved_source_streams = 17\n",
     "bad.toml:2: key 'underwater.improved_source_streams': must be 0"},
    {"typo in [underwater]", "[underwater]\nsingle_scatering = false\n",
     "bad.toml:2: key 'underwater.single_scatering': unknown key; did you mean 'single_scattering'?"},
    {"typo'd key", "[sun]\nzenith_dg = 40\n",
     "bad.toml:2: key 'sun.zenith_dg': unknown key; did you mean 'zenith_deg'?"},
    {"typo'd table", "[watr]\njerlov = \"IB\"\n",
     "bad.toml:1: key 'watr': unknown table; did you mean 'water'?"},
    {"stray top-level key", "name = \"x\"\n", "bad.toml:1: key 'name': unknown key"},
    {"typo'd key in [water]", "[water]\njerlv = \"IB\"\n",
     "bad.toml:2: key 'water.jerlv': unknown key; did you mean 'jerlov'?"},
    {"g = 1.2", "[water]\njerlov = \"IB\"\ng = 1.2\n", "bad.toml:3: key 'water.g': must satisfy |g| < 1, got 1.2"},
    {"air g = -1", "[air]\nphase = \"hg\"\ng = -1.0\n", "bad.toml:3: key 'air.g': must satisfy |g| < 1"},
    {"air g with shafts phase", "[air]\ng = 0.5\n",
     "bad.toml:2: key 'air.g': unknown key (not used with phase = 'shafts')"},
    {"negative absorption", "[water]\nwavelengths_nm = [400, 500]\na = [0.1, -0.2]\nb = [0.1, 0.1]\n",
     "bad.toml:3: key 'water.a': values must be >= 0, got -0.2"},
    {"negative scattering", "[water]\nwavelengths_nm = [400]\na = [0.1]\nb = [-1]\n",
     "bad.toml:4: key 'water.b': values must be >= 0"},
    {"negative kd", "[water]\nwavelengths_nm = [400]\na = [0.1]\nb = [0.1]\nkd = [-0.5]\n",
     "bad.toml:5: key 'water.kd': values must be >= 0"},
    {"negative extinction", "[air]\nextinction = -0.1\n", "bad.toml:2: key 'air.extinction': must be >= 0"},
    {"negative density", "[air]\n\ndensity = -2\n", "bad.toml:3: key 'air.density': must be >= 0"},
    {"negative irradiance", "[sun]\nirradiance = -1\n", "bad.toml:2: key 'sun.irradiance': must be >= 0"},
    {"negative sky radiance", "[sky]\nradiance = -0.5\n", "bad.toml:2: key 'sky.radiance': must be >= 0"},
    {"albedo 1.5", "[water]\njerlov = \"IB\"\n[bottom]\ndepth = 5\nalbedo = 1.5\n",
     "bad.toml:5: key 'bottom.albedo': must be in [0, 1], got 1.5"},
    {"albedo spectrum above 1", "[[objects]]\ntype = \"sphere\"\nalbedo = { wavelengths_nm = [400, 500], values = [0.5, 1.2] }\n",
     "bad.toml:3: key 'objects[0].albedo.values': values must be in [0, 1], got 1.2"},
    {"typo in albedo spectrum", "[[objects]]\ntype = \"sphere\"\nalbedo = { wavelengths_nm = [400, 500], value = [0.5, 0.2] }\n",
     "bad.toml:3: key 'objects[0].albedo.value': unknown key; did you mean 'values'?"},
    {"ior below 1", "[water]\njerlov = \"II\"\nior = 0.9\n", "bad.toml:3: key 'water.ior': must be in (1, 3)"},
    {"width 0", "[camera]\nwidth = 0\n", "bad.toml:2: key 'camera.width': must be an integer in [1, 16384], got 0"},
    {"height negative", "[camera]\nheight = -270\n", "bad.toml:2: key 'camera.height': must be an integer in [1, 16384]"},
    {"float width", "[camera]\nwidth = 480.5\n",
     "bad.toml:2: key 'camera.width': expected an integer, got a floating-point number"},
    {"string for a number", "[camera]\nfov_deg = \"wide\"\n",
     "bad.toml:2: key 'camera.fov_deg': expected a number, got a string"},
    {"number for a bool", "[sea]\nsecond_order = 1\n",
     "bad.toml:2: key 'sea.second_order': expected true or false, got an integer"},
    {"table for a section value", "camera = 5\n", "bad.toml:1: key 'camera': expected a table, got an integer"},
    {"vector of 2", "[camera]\nposition = [0, 10]\n", "bad.toml:2: key 'camera.position': expected 3 numbers"},
    {"string in a vector", "[camera]\nlook_at = [0, \"x\", 0]\n",
     "bad.toml:2: key 'camera.look_at[1]': expected a number, got a string"},
    {"fov 180", "[camera]\nfov_deg = 180\n", "bad.toml:2: key 'camera.fov_deg': must be in (0, 180) degrees"},
    {"fov 0", "[camera]\nfov_deg = 0\n", "bad.toml:2: key 'camera.fov_deg': must be in (0, 180) degrees"},
    {"position == look_at", "[camera]\nposition = [1, 2, 3]\nlook_at = [1, 2, 3]\n",
     "bad.toml:3: key 'camera.look_at': camera.position and camera.look_at are the same point"},
    {"up parallel to view", "[camera]\nposition = [0, 10, 0]\nlook_at = [0, 0, 0]\nup = [0, 1, 0]\n",
     "bad.toml:4: key 'camera.up': is parallel to the view direction"},
    {"zenith 190", "[sun]\nzenith_deg = 190\n", "bad.toml:2: key 'sun.zenith_deg': must be in [0, 180] degrees, got 190"},
    {"sun radius negative", "[sun]\nangular_radius_deg = -0.1\n", "bad.toml:2: key 'sun.angular_radius_deg': must be in [0, 45]"},
    {"grid not a power of two", "[water]\njerlov = \"IB\"\n[surface]\ntype = \"fft\"\ngrid = 100\n",
     "bad.toml:5: key 'surface.grid': must be a power of two in [16, 2048], got 100"},
    {"grid too large", "[water]\njerlov = \"IB\"\n[surface]\ngrid = 4096\n",
     "bad.toml:4: key 'surface.grid': must be a power of two in [16, 2048], got 4096"},
    {"negative wind", "[water]\njerlov = \"IB\"\n[surface]\nwind_speed = -3\n",
     "bad.toml:4: key 'surface.wind_speed': must be >= 0 m/s"},
    {"zero patch size", "[water]\njerlov = \"IB\"\n[surface]\npatch_size = 0\n",
     "bad.toml:4: key 'surface.patch_size': must be > 0 m"},
    {"negative seed", "[water]\njerlov = \"IB\"\n[surface]\nseed = -1\n",
     "bad.toml:4: key 'surface.seed': must be an integer in [0, 4294967295]"},
    {"unknown surface type", "[water]\njerlov = \"IB\"\n[surface]\ntype = \"fftt\"\n",
     "bad.toml:4: key 'surface.type': 'fftt' is not one of 'flat', 'fft'; did you mean 'fft'?"},
    {"range min >= max", "[spectral]\nrange_nm = [700, 400]\n", "bad.toml:2: key 'spectral.range_nm': min must be < max"},
    {"range below 300 nm", "[spectral]\nrange_nm = [250, 700]\n",
     "bad.toml:2: key 'spectral.range_nm': must lie within [300, 1000] nm"},
    {"range of 3", "[spectral]\nrange_nm = [400, 500, 600]\n", "bad.toml:2: key 'spectral.range_nm': expected [min, max]"},
    {"count 0", "[spectral]\ncount = 0\n", "bad.toml:2: key 'spectral.count': must be an integer in [1, 1000], got 0"},
    {"count 1001", "[spectral]\ncount = 1001\n", "bad.toml:2: key 'spectral.count': must be an integer in [1, 1000], got 1001"},
    {"unknown sensor", "[spectral]\nsensor = \"nikon_d5100\"\n",
     "bad.toml:2: key 'spectral.sensor': unknown sensor 'nikon_d5100'"},
    {"unequal spectra", "[water]\nwavelengths_nm = [400, 500, 600]\na = [0.1, 0.2]\nb = [0.1, 0.1, 0.1]\n",
     "bad.toml:3: key 'water.a': has 2 values but wavelengths_nm has 3"},
    {"wavelengths decreasing", "[water]\nwavelengths_nm = [500, 400]\na = [0.1, 0.2]\nb = [0.1, 0.1]\n",
     "bad.toml:2: key 'water.wavelengths_nm': wavelengths must be strictly increasing (500 then 400)"},
    {"wavelengths repeated", "[water]\nwavelengths_nm = [400, 400]\na = [0.1, 0.2]\nb = [0.1, 0.1]\n",
     "bad.toml:2: key 'water.wavelengths_nm': wavelengths must be strictly increasing"},
    {"missing a", "[water]\nwavelengths_nm = [400]\nb = [0.1]\n",
     "bad.toml:2: key 'water.wavelengths_nm': explicit spectra need a"},
    {"c inconsistent with a + b", "[water]\nwavelengths_nm = [400]\na = [0.1]\nb = [0.1]\nc = [0.5]\n",
     "bad.toml:5: key 'water.c': c must equal a + b"},
    {"c below a", "[water]\nwavelengths_nm = [400]\na = [0.3]\nc = [0.2]\n",
     "bad.toml:4: key 'water.c': c must be >= a"},
    {"unknown Jerlov type", "[water]\njerlov = \"IV\"\n",
     "bad.toml:2: key 'water.jerlov': unknown Jerlov water type 'IV'; valid: I, IA, IB, II, III, 1C, 3C, 5C, 7C, 9C"},
    {"jerlov and explicit spectra", "[water]\njerlov = \"IB\"\nwavelengths_nm = [400]\na = [0.1]\nb = [0.1]\n",
     "bad.toml:3: key 'water.wavelengths_nm': give either jerlov or explicit spectra"},
    {"water without optics", "[water]\ng = 0.8\n", "bad.toml:1: key 'water.jerlov': missing"},
    {"surface without water", "[surface]\ntype = \"fft\"\n", "bad.toml:1: key 'surface': needs a [water] table"},
    {"bottom without water", "[sun]\nzenith_deg = 10\n[bottom]\ndepth = 4\n", "bad.toml:3: key 'bottom': needs a [water] table"},
    {"missing bottom height field", "[water]\njerlov = \"IB\"\n[bottom]\ntype = \"heightfield\"\n",
     "bad.toml:3: key 'bottom.heightfield': missing"},
    {"missing bottom height-field file", "[water]\njerlov = \"IB\"\n[bottom]\ntype = \"heightfield\"\nheightfield = \"x.png\"\n",
     "bad.toml:5: key 'bottom.heightfield': file not found"},
    {"missing sky image", "[sky]\nmodel = \"image\"\nimage = \"nope.exr\"\n", "bad.toml:3: key 'sky.image': file not found"},
    {"image with uniform sky", "[sky]\nimage = \"nope.exr\"\n",
     "bad.toml:2: key 'sky.image': unknown key (not used with model = 'uniform')"},
    {"turbidity too high", "[sky]\nmodel = \"preetham\"\nturbidity = 20\n",
     "bad.toml:3: key 'sky.turbidity': must be in [1.7, 10], got 20"},
    {"turbidity too low", "[sky]\nmodel = \"preetham\"\nturbidity = 1\n",
     "bad.toml:3: key 'sky.turbidity': must be in [1.7, 10], got 1"},
    {"turbidity with uniform sky", "[sky]\nturbidity = 3\n",
     "bad.toml:2: key 'sky.turbidity': unknown key (not used with model = 'uniform')"},
    {"supersample 0", "[quality]\nsea_supersample = 0\n",
     "bad.toml:2: key 'quality.sea_supersample': must be an integer in [1, 1048576], got 0"},
    {"wave filter not a bool", "[quality]\nwave_filter = 2\n",
     "bad.toml:2: key 'quality.wave_filter': expected true or false, got an integer"},
    {"missing light map", "[[spotlights]]\nposition = [0, 5, 0]\nlight_map = \"gobo.png\"\n",
     "bad.toml:3: key 'spotlights[0].light_map': file not found"},
    {"zero spotlight direction", "[[spotlights]]\ndirection = [0, 0, 0]\n",
     "bad.toml:2: key 'spotlights[0].direction': must not be the zero vector"},
    {"falloff beyond cone", "[[spotlights]]\ncone_deg = 10\nfalloff_deg = 12\n",
     "bad.toml:3: key 'spotlights[0].falloff_deg': must be in [0, cone_deg = 10]"},
    {"zero plane normal", "[[objects]]\ntype = \"plane\"\nnormal = [0, 0, 0]\n",
     "bad.toml:3: key 'objects[0].normal': must not be the zero vector"},
    {"box min >= max", "[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 0, 1]\n",
     "bad.toml:4: key 'objects[0].max': every component of max must be greater than min's"},
    {"radius on a box", "[[objects]]\ntype = \"box\"\nmin = [0, 0, 0]\nmax = [1, 1, 1]\nradius = 2\n",
     "bad.toml:5: key 'objects[0].radius': unknown key (not used with type = 'box')"},
    {"negative radius of the second object", "[[objects]]\ntype = \"sphere\"\n\n[[objects]]\ntype = \"sphere\"\nradius = -1\n",
     "bad.toml:6: key 'objects[1].radius': must be > 0 m, got -1"},
    {"object without type", "[[objects]]\nradius = 1\n", "bad.toml:1: key 'objects[0].type': missing"},
    {"unknown object type", "[[objects]]\ntype = \"cone\"\n", "bad.toml:2: key 'objects[0].type': 'cone' is not one of"},
    {"[objects] as a plain table", "[objects]\ntype = \"sphere\"\n",
     "bad.toml:1: key 'objects': expected an array of tables ([[objects]])"},
    {"knob 0", "[quality]\nsea_nz = 0\n", "bad.toml:2: key 'quality.sea_nz': must be an integer in [1, 1048576], got 0"},
    {"sky table 0", "[quality]\nsea_sky_table = 0\n",
     "bad.toml:2: key 'quality.sea_sky_table': must be an integer in [1, 1048576], got 0"},
    {"knob bad string", "[quality]\nsea_nd = \"fast\"\n", "bad.toml:2: key 'quality.sea_nd': expected a positive integer or \"auto\", got 'fast'"},
    {"knob float", "[quality]\nshafts_planes = 30.5\n", "bad.toml:2: key 'quality.shafts_planes': expected a positive integer or \"auto\""},
    {"unknown knob", "[quality]\nshaft_planes = 10\n", "bad.toml:2: key 'quality.shaft_planes': unknown key; did you mean 'shafts_planes'?"},
    {"shallow without water", "[shallow]\nslope_depths_m = [0, 5]\n",
     "bad.toml:1: key 'shallow': needs a [water] table"},
    {"shallow seen from below", "[camera]\nposition = [0, -2, 0]\n[water]\njerlov = \"I\"\n[shallow]\n",
     "bad.toml:5: key 'shallow': the four-flow model renders water seen from above"},
    {"shallow unknown path", "[water]\njerlov = \"I\"\n[shallow]\npath = \"fast\"\n",
     "bad.toml:4: key 'shallow.path': 'fast' is not one of 'table', 'table_eq24', 'exact'"},
    {"shallow slope upside down", "[water]\njerlov = \"I\"\n[shallow]\nslope_depths_m = [5, 1]\n",
     "bad.toml:4: key 'shallow.slope_depths_m': expected [shallow, deep]"},
    {"shallow gamma 0", "[water]\njerlov = \"I\"\n[bottom]\ntype = \"flat\"\n[shallow]\ngamma = 0\n",
     "bad.toml:6: key 'shallow.gamma': must be in (0, 100]"},
    {"shallow typo", "[water]\njerlov = \"I\"\n[shallow]\ngama = 2\nslope_depths_m = [0, 5]\n",
     "bad.toml:4: key 'shallow.gama': unknown key; did you mean 'gamma'?"},
    {"shallow without a bottom", "[water]\njerlov = \"I\"\n[shallow]\ngamma = 2\n",
     "key 'shallow.slope_depths_m': missing: [shallow] needs a bottom"},
    {"von Kries temperature", "[spectral]\nsensor = \"vonkries:hot\"\n",
     "bad.toml:2: key 'spectral.sensor': sensor 'vonkries:hot': expected \"vonkries\" or \"vonkries:<kelvin>\""},
    {"unknown sea model", "[water]\njerlov = \"I\"\n[sea]\nmodel = \"multi\"\n",
     "bad.toml:4: key 'sea.model': 'multi' is not one of 'paper', 'multiple'"},
    {"sea model not a string", "[water]\njerlov = \"I\"\n[sea]\nmodel = 2\n", "bad.toml:4: key 'sea.model'"},
    {"shafts method unknown", "[quality]\nshafts_method = \"rays\"\n",
     "bad.toml:2: key 'quality.shafts_method': 'rays' is not one of 'planes', 'intervals', 'march', 'auto'"},
    {"shafts march without steps", "[quality]\nshafts_march_steps = 0\n", "bad.toml:2: key 'quality.shafts_march_steps'"},
    {"shafts march steps fractional", "[quality]\nshafts_march_steps = 2.5\n",
     "bad.toml:2: key 'quality.shafts_march_steps'"},
    {"shafts method not a string", "[quality]\nshafts_method = 1\n", "bad.toml:2: key 'quality.shafts_method'"},
    {"shafts panel 0", "[quality]\nshafts_panel_deg = 0\n",
     "bad.toml:2: key 'quality.shafts_panel_deg': must be in [0.05, 90] degrees, got 0"},
    {"shafts panel texels", "[quality]\nshafts_panel_texels = 100\n",
     "bad.toml:2: key 'quality.shafts_panel_texels': must be in [0.05, 64] light-map texels, got 100"},
    {"intervals with 16 objects",
     "[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n"
     "[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n"
     "[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n"
     "[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n"
     "[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n[[objects]]\ntype = \"sphere\"\n"
     "[[objects]]\ntype = \"sphere\"\n[quality]\nshafts_method = \"intervals\"\n",
     "bad.toml:34: key 'quality.shafts_method': \"intervals\" handles at most 15 objects, the scene has 16; use "
     "\"planes\" or \"march\""},
    {"TOML syntax error", "[camera]\nwidth = \n", "bad.toml:2: TOML syntax error"},
    {"duplicate key", "[sun]\nzenith_deg = 10\nzenith_deg = 20\n", "bad.toml:3: TOML syntax error"},
};

class BadSceneTest : public ::testing::TestWithParam<BadScene> {};

}  // namespace

TEST_P(BadSceneTest, FailsWithFileLineAndKey) {
  const BadScene& c = GetParam();
  std::string msg = errorOf(c.toml);
  ASSERT_FALSE(msg.empty()) << c.what << ": parsed without error";
  EXPECT_NE(msg.find(c.expected), std::string::npos)
      << c.what << "\n  expected: " << c.expected << "\n  got:      " << msg;
}

INSTANTIATE_TEST_SUITE_P(Table, BadSceneTest, ::testing::ValuesIn(kBadScenes),
                         [](const ::testing::TestParamInfo<BadScene>& info) {
                           std::string n = std::to_string(info.index) + "_";
                           for (const char* p = info.param.what; *p; ++p)
                             n += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
                           return n;
                         });

namespace {

// The discrete-ordinates model's research keys had the prefix improved_; a scene written with those
// names reads as one written with the new ones.
TEST(SceneParser, ResearchKeysReadUnderTheirEarlierNames) {
  const std::string now =
      "[underwater]\ndiffuse = \"two_stream\"\nsource_streams = 16\nmean_cosine_down = 0.7\nmean_cosine_up = 0.4\n"
      "beam_mean_cosine_down = 0.8\nbeam_mean_cosine_up = 0.3\ntwo_stream_closure = \"quadrature\"\n"
      "asymptotic_share = 0.25\nflux_scale = 1.5\n";
  std::string before = now;
  for (const char* key : {"diffuse", "source_streams", "mean_cosine_down", "mean_cosine_up", "beam_mean_cosine_down",
                          "beam_mean_cosine_up", "asymptotic_share", "flux_scale"}) {
    const std::string line = "\n" + std::string(key) + " =";
    before.replace(before.find(line), line.size(), "\nimproved_" + std::string(key) + " =");
  }
  before.replace(before.find("two_stream_closure"), 18, "improved_two_stream");
  const seasim::UnderwaterDesc a = seasim::parseScene(now, "now.toml").underwater;
  const seasim::UnderwaterDesc b = seasim::parseScene(before, "before.toml").underwater;
  EXPECT_EQ(a.diffuse, seasim::UnderwaterDesc::Diffuse::TwoStream);
  EXPECT_EQ(b.diffuse, a.diffuse);
  EXPECT_EQ(b.source_streams, 16);
  EXPECT_EQ(b.mean_cosine_down, 0.7);
  EXPECT_EQ(b.mean_cosine_up, 0.4);
  EXPECT_EQ(b.beam_mean_cosine_down, 0.8);
  EXPECT_EQ(b.beam_mean_cosine_up, 0.3);
  EXPECT_EQ(b.two_stream_closure, seasim::UnderwaterDesc::TwoStream::Quadrature);
  EXPECT_EQ(b.asymptotic_share, 0.25);
  EXPECT_EQ(b.flux_scale, 1.5);
  EXPECT_EQ(a.two_stream_closure, b.two_stream_closure);
  EXPECT_EQ(a.flux_scale, b.flux_scale);
}

TEST(SceneParserLamps, LampsModelByNameWithTheOlderSwitchKept) {
  using seasim::parseScene;
  EXPECT_EQ(parseScene("[quality]\nlamps_model = \"orders\"\n", "l.toml").quality.at("lamps_model").value, 2);
  EXPECT_EQ(parseScene("[quality]\nlamps_model = \"single\"\n", "l.toml").quality.at("lamps_model").value, 0);
  // The older switch: false is "single", true "delta_m"; neither given, "orders" (the default).
  EXPECT_EQ(parseScene("[quality]\nlamps_delta_m = false\n", "l.toml").quality.at("lamps_model").value, 0);
  EXPECT_EQ(parseScene("[quality]\nlamps_delta_m = true\n", "l.toml").quality.at("lamps_model").value, 1);
  EXPECT_EQ(parseScene("", "l.toml").quality.at("lamps_model").value, 2);
  EXPECT_EQ(parseScene("", "l.toml").quality.at("lamps_delta_m").value, 0);
  EXPECT_THROW(parseScene("[quality]\nlamps_model = \"bogus\"\n", "l.toml"), seasim::InputError);
  EXPECT_THROW(parseScene("[quality]\nlamps_model = \"orders\"\nlamps_delta_m = true\n", "l.toml"), seasim::InputError);
  const auto error = [](const std::string& text) { return errorOf(text, {}, "l.toml"); };
  EXPECT_NE(error("[quality]\nlamps_orders = 13\n").find("l.toml:2: key 'quality.lamps_orders'"), std::string::npos);
  EXPECT_NE(error("[quality]\nlamps_orders = 2.5\n").find("quality.lamps_orders"), std::string::npos);
  EXPECT_NE(error("[quality]\nlamps_ms_steps = 0\n").find("quality.lamps_ms_steps"), std::string::npos);
  EXPECT_NE(error("[quality]\nlamps_ms_spread = 0\n").find("must be in (0, 1], got 0"), std::string::npos);
  EXPECT_EQ(error("[quality]\nlamps_ms_spread = 1\n"), "");
  EXPECT_NE(error("[quality]\nlamps_ms_kappa = -1\n").find("must be in [0, 2], got -1"), std::string::npos);
  // The lattice's cell: 0 (every pixel) to 10 degrees.
  EXPECT_NE(error("[quality]\nlamps_ms_cell_deg = -0.5\n").find("l.toml:2: key 'quality.lamps_ms_cell_deg'"),
            std::string::npos);
  EXPECT_NE(error("[quality]\nlamps_ms_cell_deg = 11\n").find("quality.lamps_ms_cell_deg"), std::string::npos);
  EXPECT_EQ(error("[quality]\nlamps_ms_cell_deg = 0\n"), "");
  EXPECT_DOUBLE_EQ(seasim::modelKey(parseScene("[quality]\nlamps_orders = 7\n", "l.toml"), "quality.lamps_orders"), 7);
}

TEST(SceneParserLamps, AModelForScenesBuiltInCodeToo) {
  // Without the parser's quality map: the older switch where it is set, else the parser's default.
  seasim::Scene s;
  EXPECT_STREQ(seasim::underwaterLampsModel(s), "orders");
  s.quality["lamps_delta_m"] = seasim::Knob{false, 1.0};
  EXPECT_STREQ(seasim::underwaterLampsModel(s), "delta_m");
  s.quality["lamps_delta_m"] = seasim::Knob{false, 0.0};
  EXPECT_STREQ(seasim::underwaterLampsModel(s), "single");
  s.quality["lamps_model"] = seasim::Knob{false, 2.0};  // the name wins over the older switch
  EXPECT_STREQ(seasim::underwaterLampsModel(s), "orders");
  EXPECT_STREQ(seasim::underwaterLampsModel(seasim::parseScene("", "l.toml")), "orders");
}

TEST(SceneParserSandShare, StepIsAWholeNumberFromOneToEight) {
  const auto error = [](const std::string& text) { return errorOf(text, {}, "s.toml"); };
  EXPECT_DOUBLE_EQ(seasim::modelKey(parseScene("", "s.toml"), "quality.sand_share_step"), 2);
  EXPECT_NE(error("[quality]\nsand_share_step = 0\n").find("s.toml:2: key 'quality.sand_share_step'"), std::string::npos);
  EXPECT_NE(error("[quality]\nsand_share_step = 9\n").find("quality.sand_share_step"), std::string::npos);
  EXPECT_NE(error("[quality]\nsand_share_step = 1.5\n").find("quality.sand_share_step"), std::string::npos);
  EXPECT_EQ(error("[quality]\nsand_share_step = 1\n"), "");
}

}  // namespace

namespace {

// The underwater models have no height-field floor: with the camera under the surface the key is refused
// by line, where before the floor was silently left out of the render.
TEST(SceneParser, HeightFieldBottomUnderWaterIsRefusedByLine) {
  const std::string floor = "[bottom]\ntype = \"heightfield\"\nheightfield = \"rock.png\"\n";
  const std::string under = "[camera]\nposition = [0, -3, 0]\nlook_at = [0, -4, -8]\n[water]\njerlov = \"IB\"\n";
  const std::string msg = errorOf(under + floor, {}, "uw.toml");
  EXPECT_NE(msg.find("uw.toml:7"), std::string::npos) << msg;
  EXPECT_NE(msg.find("bottom.type"), std::string::npos) << msg;
  EXPECT_NE(msg.find("under"), std::string::npos) << msg;
  // From above (the sea, shallow water) it stays a floor.
  const std::string above = "[camera]\nposition = [0, 5, 0]\nlook_at = [0, 0, -8]\n[water]\njerlov = \"IB\"\n";
  EXPECT_EQ(errorOf(above + floor, {}, "sea.toml").find("bottom.type"), std::string::npos);
}

}  // namespace
