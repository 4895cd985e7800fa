// water_phase_test.cpp — the [water] phase keys (host/scene/water_phase.*): each phase parses and sets
// g to its own first moment, a table resolves against the scene file, and every misuse is an InputError
// naming the file, line and key.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "scene/scene_parser.h"
#include "scene/water_phase.h"
#include "util/error.h"

namespace {

using namespace seasim;
namespace fs = std::filesystem;

std::string errorOf(const std::string& text, const std::string& path = "bad.toml") {
  try {
    parseScene(text, path);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(WaterPhase, EachPhaseParsesWithItsOwnG) {
  const Scene hg = parseScene("[water]\njerlov = \"IB\"\ng = 0.8\n", "s.toml");
  EXPECT_EQ(hg.water.phase, "hg");
  EXPECT_DOUBLE_EQ(hg.water.g, 0.8);
  const Scene petzold = parseScene("[water]\njerlov = \"IB\"\nphase = \"petzold\"\n", "s.toml");
  EXPECT_NEAR(petzold.water.g, 0.924, 0.003);
  const Scene ff = parseScene("[water]\njerlov = \"IB\"\nphase = \"fournier_forand\"\nbb_ratio = 0.01\n", "s.toml");
  EXPECT_DOUBLE_EQ(ff.water.bb_ratio, 0.01);
  EXPECT_NEAR(waterPhase(ff.water).backscatterRatio(), 0.01, 1e-4);
  EXPECT_GT(ff.water.g, 0.9);
  const Scene rl = parseScene("[water]\njerlov = \"IB\"\nphase = \"rayleigh_like\"\n", "s.toml");
  EXPECT_NEAR(rl.water.g, 0.0, 1e-6);
}

TEST(WaterPhase, TableResolvesAgainstTheSceneFile) {
  const fs::path dir = fs::temp_directory_path() / ("seasim_water_phase_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "peak.csv") << "angle_deg,phase_per_sr\n1,100\n10,1\n180,0.1\n";
  const Scene s = parseScene("[water]\njerlov = \"II\"\nphase = \"table\"\nphase_file = \"peak.csv\"\n",
                             (dir / "scene.toml").string());
  EXPECT_EQ(s.water.phase_file, (dir / "peak.csv").string());
  EXPECT_GT(s.water.g, 0.2);  // forward: 100 at 1°, 1 at 10°, 0.1 at 180° (g = 0.37)
  std::ofstream(dir / "bad.csv") << "angle_deg,phase_per_sr\n1,100\n10,-1\n";
  const std::string e = errorOf("[water]\njerlov = \"II\"\nphase = \"table\"\nphase_file = \"bad.csv\"\n",
                                (dir / "scene.toml").string());
  EXPECT_NE(e.find("phase_file"), std::string::npos) << e;
  EXPECT_NE(e.find("bad.csv:3"), std::string::npos) << e;
  fs::remove_all(dir);
}

TEST(WaterPhase, MisuseNamesFileLineAndKey) {
  std::string e = errorOf("[water]\njerlov = \"IB\"\nphase = \"mie\"\n");
  EXPECT_NE(e.find("bad.toml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("phase"), std::string::npos) << e;
  e = errorOf("[water]\njerlov = \"IB\"\nphase = \"petzold\"\ng = 0.9\n");
  EXPECT_NE(e.find("bad.toml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("water.g"), std::string::npos) << e;
  e = errorOf("[water]\njerlov = \"IB\"\nphase = \"fournier_forand\"\nbb_ratio = 0.9\n");
  EXPECT_NE(e.find("bad.toml:4"), std::string::npos) << e;
  EXPECT_NE(e.find("[0.001, 0.5]"), std::string::npos) << e;
  e = errorOf("[water]\njerlov = \"IB\"\nbb_ratio = 0.02\n");
  EXPECT_NE(e.find("bad.toml:3"), std::string::npos) << e;
  EXPECT_NE(e.find("bb_ratio"), std::string::npos) << e;
  e = errorOf("[water]\njerlov = \"IB\"\nphase = \"table\"\n");
  EXPECT_NE(e.find("phase_file"), std::string::npos) << e;
  e = errorOf("[water]\njerlov = \"IB\"\nphase = \"table\"\nphase_file = \"/nonexistent/p.csv\"\n");
  EXPECT_NE(e.find("bad.toml:4"), std::string::npos) << e;
}

}  // namespace
