// first_hour_cli_test.cpp — what a newcomer meets first, through the real binary: `validate` lists
// every error of a file; `run --set` makes every item of a job smaller (and --resume renders again
// what was rendered with other settings); `farm slurm --submit` without
// a Slurm configuration says how to start a local cluster; and every text of every plot the
// commands write (bench, sweep, ocean --bench, ocean's caustic PDF, seashore-study,
// underwater-study) lies inside its canvas (tests/unit/svg_layout_check.h).
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "../unit/svg_layout_check.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

using seasim_test::run;

class FirstHourCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_first_hour_"); }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  std::string write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name) << text;
    return path(name);
  }
  fs::path dir_;
};

std::string readText(const std::string& p) {
  std::ifstream in(p);
  return std::string((std::istreambuf_iterator<char>(in)), {});
}

void expectTextInside(const std::string& svg_path) {
  ASSERT_TRUE(fs::exists(svg_path)) << svg_path;
  const std::string svg = readText(svg_path);
  EXPECT_GT(seasim_test::svgTextBoxes(svg).size(), 5u) << svg_path;
  const auto bad = seasim_test::textOutsideCanvas(svg);
  EXPECT_TRUE(bad.empty()) << svg_path << ": " << bad.size() << " text(s) outside the canvas, first "
                           << (bad.empty() ? "" : bad.front());
}

TEST_F(FirstHourCli, ValidateListsEveryErrorOfAFile) {
  const std::string bad = write("bad.toml", "[water]\njerlov = \"IB\"\ng = 1.2\n[sun]\nzenit_deg = 40\n[camera]\nwidth = -5\n");
  const auto r = run("validate " + bad);
  EXPECT_NE(r.code, 0);
  for (const char* e : {"bad.toml:3: key 'water.g'", "bad.toml:5: key 'sun.zenit_deg'", "bad.toml:7: key 'camera.width'",
                        "bad.toml: 3 errors"})
    EXPECT_NE(r.output.find(e), std::string::npos) << e << " in\n" << r.output;
}

TEST_F(FirstHourCli, RunSetAppliesToEveryItem) {
  const std::string cmd = "cd " + kRepo + " && " + kBinary + " run jobs/quickstart.toml -o " + path("q") +
                    " --device pocl --set camera.width=40 --set camera.height=24 --set spectral.count=4";
  const auto q = seasim_test::runCommand(cmd);
  ASSERT_EQ(q.code, 0) << q.output;
  int items = 0;
  for (const auto& e : fs::directory_iterator(path("q"))) {
    if (!fs::exists(e.path() / "report.json")) continue;
    ++items;
    const auto report = nlohmann::json::parse(readText((e.path() / "report.json").string()));
    EXPECT_EQ(report["settings"]["width"], 40) << e.path();
    EXPECT_EQ(report["settings"]["height"], 24) << e.path();
    EXPECT_EQ(report["settings"]["wavelength_count"], 4) << e.path();
  }
  EXPECT_GE(items, 2) << q.output;
  // The run's contact sheet shows every item's PNG, found on disk.
  EXPECT_NE(q.output.find("contact sheet: " + path("q") + "/index.html"), std::string::npos) << q.output;
  const std::string sheet = readText(path("q") + "/index.html");
  for (const auto& e : fs::directory_iterator(path("q")))
    if (fs::exists(e.path() / "image.png"))
      EXPECT_NE(sheet.find("<img src=\"" + e.path().filename().string() + "/image.png\""), std::string::npos)
          << e.path() << "\n" << sheet;
  EXPECT_NE(sheet.find("all done"), std::string::npos);
  // --resume keeps what was rendered with these settings and renders again what was not.
  const auto same = seasim_test::runCommand(cmd + " --resume");
  ASSERT_EQ(same.code, 0) << same.output;
  EXPECT_NE(same.output.find("job done: 0 rendered, " + std::to_string(items) + " finished earlier"), std::string::npos)
      << same.output;
  const auto wider = seasim_test::runCommand(cmd + " --set camera.width=44 --resume");
  ASSERT_EQ(wider.code, 0) << wider.output;
  EXPECT_NE(wider.output.find("rendered with width = 40, now 44: rendering it again"), std::string::npos) << wider.output;
  EXPECT_NE(wider.output.find("job done: " + std::to_string(items) + " rendered, 0 finished earlier"), std::string::npos)
      << wider.output;
}

TEST_F(FirstHourCli, SubmitWithoutSlurmConfigurationSaysHowToStartALocalCluster) {
  // A stand-in sbatch that fails as Slurm's does on a machine with the client but no slurm.conf.
  const std::string bin = path("bin");
  fs::create_directories(bin);
  write("bin/sbatch",
        "#!/bin/sh\necho 'sbatch: error: resolve_ctls_from_dns_srv: res_nsearch error: Unknown host' >&2\n"
        "echo 'sbatch: error: fetch_config: DNS SRV lookup failed' >&2\n"
        "echo 'sbatch: error: _establish_config_source: failed to fetch config' >&2\n"
        "echo 'sbatch: fatal: Could not establish a configuration source' >&2\nexit 1\n");
  fs::permissions(bin + "/sbatch", fs::perms::owner_all);
  const std::string job = write("job.toml", "[job]\nname = \"t\"\noutput_dir = \"out\"\n[[render]]\nname = \"a\"\nscene = \"" +
                                                kRepo + "/scenes/flat_sea.toml\"\n");
  const auto r = seasim_test::runCommand("PATH=" + bin + ":$PATH " + kBinary + " farm slurm " + job + " --tasks 1 --submit");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("Could not establish a configuration source"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("seasim farm local-cluster start"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("SLURM_CONF="), std::string::npos) << r.output;
  // The command it names exists and finds its script (it fails here only for want of root or daemons).
  const auto env = run("farm local-cluster env " + path("cluster"));
  EXPECT_EQ(env.code, 0) << env.output;
  EXPECT_NE(env.output.find("export SLURM_CONF=" + path("cluster") + "/slurm.conf"), std::string::npos) << env.output;
}

// `bench` under water times raycast + kd_multiple against the C++ peers and says whether they did the same
// work: the peers cast their own rays without caustics and leave the froxels' single scattering out.
TEST_F(FirstHourCli, BenchUnderWaterSaysWhetherThePeerDidTheSameWork) {
  const std::string seabed = kRepo + "/scenes/seabed.toml";
  const std::string small = " --set camera.width=32 --set camera.height=18 --set 'underwater.model=\"thesis\"'";
  auto r = run("bench --scene " + seabed + " --wavelengths 3,8 --repeat 1" + small);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("fit (C++/oneTBB vectorised)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("peer: not the same work (OpenCL also evaluates the caustics at each hit, the froxel "
                          "volume's read per pixel)"),
            std::string::npos)
      << r.output;
  r = run("bench --scene " + seabed + " --wavelengths 3,8 --repeat 1" + small +
          " --set 'underwater.caustics=\"none\"' --set underwater.single_scattering=false");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("peer: the same work as raycast + kd_multiple"), std::string::npos) << r.output;
}

TEST_F(FirstHourCli, EveryTextOfEveryPlotTheCommandsWriteLiesInsideTheCanvas) {
  const std::string flat = kRepo + "/scenes/flat_sea.toml";
  const std::string small = " --set camera.width=32 --set camera.height=18";
  auto r = run("bench --scene " + flat + " --wavelengths 3,8 --repeat 1 --plot " + path("bench.svg") + small);
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("bench.svg"));
  r = run("bench --scene " + kRepo + "/scenes/stage.toml --lights 1,2 --repeat 1 --plot " + path("lights.svg") + small);
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("lights.svg"));
  r = run("sweep " + flat + " --param spectral.count=3,6 --reference " + path("ref.exr") + " --csv " + path("s.csv") +
          " --plot " + path("sweep.svg") + small);
  if (r.code != 0) {  // no reference yet: make it, then sweep
    ASSERT_EQ(run("reference " + flat + " -o " + path("ref.exr") + " --steps 50" + small).code, 0);
    r = run("sweep " + flat + " --param spectral.count=3,6 --reference " + path("ref.exr") + " --csv " + path("s.csv") +
            " --plot " + path("sweep.svg") + small);
  }
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("sweep.svg"));
  expectTextInside(path("sweep_steps.svg"));
  r = run("ocean " + kRepo + "/scenes/wavy_sea.toml -o " + path("ocean") + " --bench --sizes 32,64 --repeat 1");
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("ocean/bench_ocean.svg"));
  r = run("ocean " + kRepo + "/scenes/wavy_sea.toml -o " + path("caustics") + " --caustic-depths 1,4 --set surface.grid=64");
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("caustics/caustic_pdf.svg"));
  r = run("seashore-study " + kRepo + "/scenes/seashore.toml --width 32 --height 18 --max-depths 2,6 --plot " +
          path("shore.svg") + " --csv " + path("shore.csv"));
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("shore.svg"));
  r = run("underwater-study " + kRepo + "/scenes/seabed.toml --waters IB,3C --depths 3,9 --cameras nikon_d5100_npl --width 16 "
          "--height 9 --bands 4 --reference-bands 4 --spp 4 --plot " + path("study.svg") + " --csv " + path("study.csv"));
  ASSERT_EQ(r.code, 0) << r.output;
  expectTextInside(path("study.svg"));
  const std::string study = readText(path("study.svg"));
  EXPECT_NE(study.find(">IB, 3\u00a0m</text>"), std::string::npos) << "one labelled tick per water and depth";
  EXPECT_NE(study.find(">3C, 9\u00a0m</text>"), std::string::npos);
}

}  // namespace
