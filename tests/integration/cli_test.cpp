// cli_test.cpp — the real `seasim` binary end to end: devices, validate (errors with file:line, nothing
// written), plan (different scenes, different passes), run (EXR/PNG/report.json, manifest), resume
// after a kill, shards, render of an unimplemented pass, compare, sweep, reference.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>

#include <fcntl.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

using seasim_test::run;
using seasim_test::readJson;

using seasim_test::Result;

class Cli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = seasim_test::freshTestDir("seasim_cli_");
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  // A job of `n` renders of the repository's flat sea scene at a small size.
  std::string smallJob(int n, const std::string& extra_overrides = "") {
    std::ostringstream job;
    job << "[job]\nname = \"t\"\noutput_dir = \"out\"\n";
    for (int i = 0; i < n; ++i) {
      job << "[[render]]\nname = \"item" << i << "\"\nscene = \"" << kRepo << "/scenes/flat_sea.toml\"\n"
          << "overrides = { \"camera.width\" = 64, \"camera.height\" = 36, \"sun.zenith_deg\" = " << 20 + 5 * i
          << extra_overrides << " }\n";
    }
    return write("job.toml", job.str());
  }
  fs::path dir_;
};

TEST_F(Cli, DevicesListsPocl) {
  const Result r = run("devices");
  EXPECT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("pocl:0"), std::string::npos) << r.output;
}

TEST_F(Cli, ValidateAcceptsTheShippedScenesAndJobs) {
  const Result r = run("validate " + kRepo + "/scenes/flat_sea.toml " + kRepo + "/scenes/deep_ocean.toml " + kRepo +
                       "/jobs/quickstart.toml");
  EXPECT_EQ(r.code, 0) << r.output;
}

TEST_F(Cli, ValidateTypoAndBadAsymmetryNameFileLineAndKey) {
  const std::string typo = write("typo.toml", "[water]\njerlov = \"IB\"\n[sun]\nzenit_deg = 40\n");
  Result r = run("validate " + typo);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("typo.toml:4: key 'sun.zenit_deg'"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("zenith_deg"), std::string::npos) << "suggests the right key: " << r.output;

  const std::string bad_g = write("bad_g.toml", "[water]\njerlov = \"IB\"\ng = 1.2\n");
  r = run("validate " + bad_g);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("bad_g.toml:3: key 'water.g'"), std::string::npos) << r.output;

  // Rendering a bad scene writes nothing.
  r = run("render " + bad_g + " -o " + (dir_ / "out").string());
  EXPECT_NE(r.code, 0);
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

TEST_F(Cli, PlansDifferBetweenScenes) {
  const Result flat = run("plan " + kRepo + "/scenes/flat_sea.toml");
  const Result deep = run("plan " + kRepo + "/scenes/deep_ocean.toml");
  ASSERT_EQ(flat.code, 0) << flat.output;
  ASSERT_EQ(deep.code, 0) << deep.output;
  EXPECT_NE(flat.output, deep.output);
  EXPECT_NE(flat.output.find("SEASIM_HAS_BOTTOM=1"), std::string::npos);
  EXPECT_NE(deep.output.find("SEASIM_HAS_BOTTOM=0"), std::string::npos);
  EXPECT_EQ(flat.output.find("sea_second"), std::string::npos);
  EXPECT_NE(deep.output.find("sea_second"), std::string::npos);
  EXPECT_EQ(flat.output.find("shafts"), std::string::npos);
  // Each states the error its model was measured to have in the nearest study case: the quickstart's
  // sea runs "multiple" (the default), deep_ocean pins paper 000's model.
  EXPECT_NE(flat.output.find("expected error (sea multiple, against all orders)"), std::string::npos) << flat.output;
  EXPECT_NE(deep.output.find("expected error (sea paper, against all orders)"), std::string::npos) << deep.output;  // Lamps under water state their own model's error beside the daylight one's: rov_lights runs the
  // orders model (the default), measured on the scene itself.
  const Result rov = run("plan " + kRepo + "/scenes/rov_lights.toml");
  ASSERT_EQ(rov.code, 0) << rov.output;
  EXPECT_NE(rov.output.find("expected error (underwater discrete_ordinates"), std::string::npos) << rov.output;
  EXPECT_NE(rov.output.find("expected error (lamps orders, spotlights["), std::string::npos) << rov.output;
  EXPECT_NE(rov.output.find("rov_lights_lamps_tiles.csv (rov_lights)"), std::string::npos) << rov.output;
}

TEST_F(Cli, RenderThatCannotBeDoneFailsNamingTheKeyAndWritesNothing) {
  // Spotlights cannot light a height-field object (the shafts ray caster has no height fields): the
  // render stops before writing anything, naming file, line and key.
  const std::string scene = write("hf_spot.toml", "[air]\ndensity = 0.04\n[camera]\nwidth = 32\nheight = 24\n"
                                                  "[[spotlights]]\nposition = [0, 5, -1]\n[[objects]]\n"
                                                  "type = \"heightfield\"\nheightfield = \"" +
                                                      kRepo + "/scenes/textures/polka_dot.png\"\n");
  const Result r = run("render " + scene + " --device pocl -o " + (dir_ / "hf").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("hf_spot.toml:8: key 'objects[0].type'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "hf" / "report.json"));
  EXPECT_FALSE(fs::exists(dir_ / "hf" / "image.exr"));
}

TEST_F(Cli, LampAboveTheSurfaceUnderWaterIsRefusedNamingItsPosition) {
  // Spotlights under water must be in the water: a lamp above y = 0 would light the water
  // through the refracting surface, which is not modelled. Refused before anything is written.
  const std::string scene = write("lamp_above.toml", "[camera]\nposition = [0, -2, 0]\nwidth = 32\nheight = 24\n"
                                                     "[water]\njerlov = \"IB\"\n[[spotlights]]\n"
                                                     "position = [0, 1, 0]\ntemperature_k = 3200\n");
  const Result r = run("render " + scene + " --device pocl -o " + (dir_ / "above").string());
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("lamp_above.toml:8: key 'spotlights[0].position'"), std::string::npos) << r.output;
  EXPECT_FALSE(fs::exists(dir_ / "above" / "report.json"));
  // Moved below the surface it renders, with the lamps' pass after the underwater shading.
  const std::string below = write("lamp_below.toml", "[camera]\nposition = [0, -2, 0]\nwidth = 32\nheight = 24\n"
                                                     "[water]\njerlov = \"IB\"\n[[spotlights]]\n"
                                                     "position = [0, -1, 0]\ntemperature_k = 3200\n");
  const Result ok = run("render " + below + " --device pocl -o " + (dir_ / "below").string());
  EXPECT_EQ(ok.code, 0) << ok.output;
  EXPECT_TRUE(fs::exists(dir_ / "below" / "report.json"));
}

TEST_F(Cli, WavySeaRenderRunsTheOceanBeforeTheSeaPass) {
  // FFT waves seen from above: the ocean's normals feed sea_single.
  const Result r = run("render " + kRepo + "/scenes/deep_ocean.toml --set 'surface.type=\"fft\"' --set surface.grid=64 "
                       "--set camera.width=48 --set camera.height=27 --device pocl -o " + (dir_ / "deep").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json report = readJson(dir_ / "deep" / "report.json");
  EXPECT_EQ(report["nonfinite"], 0);
  for (const char* pass : {"ocean_fft", "sea_single"}) EXPECT_TRUE(report["pass_ms"].contains(pass)) << pass;
}

TEST_F(Cli, UnderwaterRenderRunsRaycastFroxelAndKdPasses) {
  const Result r = run("render " + kRepo +
                       "/scenes/seabed.toml --set camera.width=48 --set camera.height=27 --set quality.froxel_z=16 "
                       "--device pocl -o " + (dir_ / "seabed").string());
  ASSERT_EQ(r.code, 0) << r.output;
  const nlohmann::json report = readJson(dir_ / "seabed" / "report.json");
  EXPECT_EQ(report["nonfinite"], 0);
  for (const char* pass : {"raycast", "froxel_inject", "froxel_integrate", "kd_multiple"})
    EXPECT_TRUE(report["pass_ms"].contains(pass)) << pass;
  EXPECT_TRUE(fs::exists(dir_ / "seabed" / "image.png"));
}

TEST_F(Cli, RunWritesImagesReportsAndManifestThenResumeSkipsAndRepairs) {
  const std::string job = smallJob(3);
  Result r = run("run " + job + " --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  for (int i = 0; i < 3; ++i) {
    const fs::path item = dir_ / "out" / ("item" + std::to_string(i));
    EXPECT_TRUE(fs::exists(item / "image.exr"));
    EXPECT_TRUE(fs::exists(item / "image.png"));
    const nlohmann::json report = readJson(item / "report.json");
    EXPECT_EQ(report["nonfinite"], 0);
    EXPECT_GT(report["pass_ms"]["sea_single"].get<double>(), 0.0);
    EXPECT_TRUE(report.contains("kernel_build_ms"));
    EXPECT_EQ(report["plan"][0]["kernel"], "kernels/sea_single.cl");
    ASSERT_EQ(report["expected_error"].size(), 1u);
    EXPECT_EQ(report["expected_error"][0]["view"], "sea");
    EXPECT_TRUE(report["expected_error"][0]["table"].get<std::string>().rfind("results/sea_allorders/", 0) == 0);
  }
  EXPECT_EQ(readJson(dir_ / "out" / "manifest.json")["items"].size(), 3u);

  r = run("run " + job + " --resume");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("0 rendered, 3 finished earlier"), std::string::npos) << r.output;

  // A damaged output no longer matches its checksum: resume renders that item again, only that one.
  std::ofstream(dir_ / "out" / "item1" / "image.png", std::ios::app) << "x";
  r = run("run " + job + " --resume");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("1 rendered, 2 finished earlier"), std::string::npos) << r.output;
}

TEST_F(Cli, KilledRunResumesWithoutRedoingFinishedItems) {
  // Big items so the run is still going when we kill it after the first finishes.
  const std::string job = smallJob(4, ", \"spectral.count\" = 120");
  std::ifstream check(job);
  std::string text((std::istreambuf_iterator<char>(check)), {});
  for (size_t p; (p = text.find("\"camera.width\" = 64")) != std::string::npos;)
    text.replace(p, 19, "\"camera.width\" = 900");
  for (size_t p; (p = text.find("\"camera.height\" = 36")) != std::string::npos;)
    text.replace(p, 20, "\"camera.height\" = 600");
  std::ofstream(job) << text;

  const pid_t pid = seasim_test::spawnRun(kBinary, job);
  ASSERT_GT(pid, 0);
  const fs::path manifest = dir_ / "out" / "manifest.json";
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(240);
  size_t done_before = 0;
  while (std::chrono::steady_clock::now() < deadline) {
    if (fs::exists(manifest)) {
      done_before = readJson(manifest)["items"].size();
      if (done_before >= 1) break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  done_before = readJson(manifest)["items"].size();
  ASSERT_GE(done_before, 1u);
  ASSERT_LT(done_before, 4u) << "the run finished before it could be killed; make the items bigger";
  const auto first_report_time = fs::last_write_time(dir_ / "out" / "item0" / "report.json");

  const Result r = run("run " + job + " --resume --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string expect = std::to_string(4 - done_before) + " rendered, " + std::to_string(done_before) +
                             " finished earlier";
  EXPECT_NE(r.output.find(expect), std::string::npos) << r.output;
  EXPECT_EQ(fs::last_write_time(dir_ / "out" / "item0" / "report.json"), first_report_time);
  EXPECT_EQ(readJson(manifest)["items"].size(), 4u);
  for (int i = 0; i < 4; ++i) EXPECT_TRUE(fs::exists(dir_ / "out" / ("item" + std::to_string(i)) / "report.json"));
}

TEST_F(Cli, ShardsSplitTheItems) {
  const std::string job = smallJob(3);
  Result a = run("run " + job + " --shard 0/2");
  Result b = run("run " + job + " --shard 1/2");
  ASSERT_EQ(a.code, 0) << a.output;
  ASSERT_EQ(b.code, 0) << b.output;
  EXPECT_NE(a.output.find("2 rendered, 0 finished earlier, 1 left to other shards"), std::string::npos) << a.output;
  EXPECT_NE(b.output.find("1 rendered, 0 finished earlier, 2 left to other shards"), std::string::npos) << b.output;
  EXPECT_EQ(readJson(dir_ / "out" / "manifest-0of2.json")["items"].size(), 2u);
  EXPECT_EQ(readJson(dir_ / "out" / "manifest-1of2.json")["items"].size(), 1u);
  EXPECT_NE(run("run " + job + " --shard 2/2").code, 0);
}

TEST_F(Cli, ReferenceCompareAndSweepMeasureErrorAgainstTime) {
  const std::string scene = kRepo + "/scenes/flat_sea.toml";
  const std::string small = " --set camera.width=64 --set camera.height=36";
  const std::string ref = (dir_ / "ref.exr").string();
  Result r = run("reference " + scene + " -o " + ref + " --steps 2000" + small + " --set spectral.count=64");
  ASSERT_EQ(r.code, 0) << r.output;

  r = run("render " + scene + " -o " + (dir_ / "r").string() + small + " --set spectral.count=64");
  ASSERT_EQ(r.code, 0) << r.output;
  r = run("compare " + (dir_ / "r" / "image.exr").string() + " " + ref);
  ASSERT_EQ(r.code, 0) << r.output;
  double rmse = -1;
  ASSERT_EQ(std::sscanf(r.output.c_str(), "rmse_8bit %lf", &rmse), 1) << r.output;
  EXPECT_LT(rmse, 0.05) << "same model, same bands: only float vs double and quadrature differ";

  const std::string csv = (dir_ / "sweep.csv").string(), svg = (dir_ / "sweep.svg").string();
  r = run("sweep " + scene + " --param spectral.count=2,4,16 --reference " + ref + " --csv " + csv + " --plot " + svg +
          small);
  ASSERT_EQ(r.code, 0) << r.output;
  std::ifstream in(csv);
  std::string header, line;
  std::getline(in, header);
  EXPECT_NE(header.find("rmse_8bit"), std::string::npos);
  EXPECT_NE(header.find("kernel_ms"), std::string::npos);
  std::vector<double> errors;
  while (std::getline(in, line)) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    errors.push_back(std::stod(cells.at(3)));
  }
  ASSERT_EQ(errors.size(), 3u);
  EXPECT_GT(errors[0], errors[2]) << "more wavelength bands must get closer to the 64-band reference";
  std::ifstream plot(svg);
  std::string svg_text((std::istreambuf_iterator<char>(plot)), {});
  EXPECT_NE(svg_text.find("<svg"), std::string::npos);
}

// Reads a CSV written by the binary: the header's cells, then each row's.
std::vector<std::vector<std::string>> readCsv(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string c; std::getline(ss, c, ',');) cells.push_back(c);
    rows.push_back(cells);
  }
  return rows;
}

TEST_F(Cli, SweepReportsFastMathAgainstExactMathsBesideTheTime) {
  const std::string scene = kRepo + "/scenes/flat_sea.toml";
  const std::string small = " --set camera.width=48 --set camera.height=27";
  Result r = run("render " + scene + " -o " + (dir_ / "exact").string() + small + " --set quality.fast_math=false");
  ASSERT_EQ(r.code, 0) << r.output;
  const std::string csv = (dir_ / "fast.csv").string();
  r = run("sweep " + scene + " --param quality.fast_math=false,true --reference " + (dir_ / "exact" / "image.exr").string() +
          " --csv " + csv + small);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_NE(r.output.find("fast maths vs exact"), std::string::npos) << r.output;
  const auto rows = readCsv(csv);
  ASSERT_EQ(rows.size(), 3u);
  auto column = [&](const std::string& name) {
    for (size_t i = 0; i < rows[0].size(); ++i)
      if (rows[0][i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return size_t(0);
  };
  const size_t fast = column("fast_math"), max_diff = column("fast_vs_exact_max_8bit"), ms = column("kernel_ms");
  EXPECT_EQ(std::stod(rows[1][fast]), 0.0);
  EXPECT_EQ(std::stod(rows[1][max_diff]), 0.0);
  EXPECT_EQ(std::stod(rows[2][fast]), 1.0);
  EXPECT_GT(std::stod(rows[2][ms]), 0.0);
  // The fast image is compared with the exact one: a measured, small, non-negative difference.
  const double d = std::stod(rows[2][max_diff]);
  EXPECT_GE(d, 0.0);
  EXPECT_LT(d, 1.0);
}

TEST_F(Cli, CacheWarmBuildsEachDistinctPlanOnceIntoTheCaches) {
  // Three renders that differ only in the sun share one plan: one warm-up frame. Fresh caches.
  const fs::path seasim_cache = dir_ / "seasim_cache", pocl_cache = dir_ / "pocl_cache";
  const std::string env = "SEASIM_CACHE_DIR=" + seasim_cache.string() + " POCL_CACHE_DIR=" + pocl_cache.string() + " ";
  const std::string job = smallJob(3);
  const std::string cmd = env + kBinary + " cache warm " + job + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  ASSERT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << out;
  EXPECT_NE(out.find("1 distinct plan(s) of 3 render(s)"), std::string::npos) << out;
  // The program binaries (sea_single.cl and the NaN check) and PoCL's work-group functions are there.
  int programs = 0;
  for (const auto& e : fs::directory_iterator(seasim_cache)) programs += e.path().extension() == ".bin";
  EXPECT_GE(programs, 2) << out;
  int pocl_files = 0;
  for (const auto& e : fs::recursive_directory_iterator(pocl_cache)) pocl_files += e.is_regular_file();
  EXPECT_GT(pocl_files, 0);
  // Nothing but the caches was written: no output folder.
  EXPECT_FALSE(fs::exists(dir_ / "out"));
}

// quality.shafts_method = "auto": `cache warm` measures the method (and caches it), `plan` then shows the
// measured method, and a render reads the cache instead of searching.
TEST_F(Cli, CacheWarmMeasuresTheShaftsMethodForPlanAndRender) {
  const fs::path seasim_cache = dir_ / "seasim_cache", pocl_cache = dir_ / "pocl_cache";
  const std::string env = "SEASIM_CACHE_DIR=" + seasim_cache.string() + " POCL_CACHE_DIR=" + pocl_cache.string() + " ";
  const std::string sets =
      " --set 'quality.shafts_method=\"auto\"' --set camera.width=96 --set camera.height=64 2>&1";
  auto shell = [&](const std::string& args) {
    FILE* pipe = popen((env + kBinary + " " + args + sets).c_str(), "r");
    std::string out;
    char buf[4096];
    while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
    const int status = pclose(pipe);
    EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << args << "\n" << out;
    return out;
  };
  const std::string scene = kRepo + "/scenes/spot_sphere.toml";
  const std::string planned_before = shell("plan " + scene);
  EXPECT_NE(planned_before.find("not measured yet"), std::string::npos) << planned_before;
  const std::string warm = shell("cache warm " + scene);
  EXPECT_NE(warm.find("shafts: method auto:"), std::string::npos) << warm;  // searched here
  int entries = 0;
  for (const auto& e : fs::directory_iterator(seasim_cache / "shafts_auto"))
    entries += e.path().filename().string().rfind("method_", 0) == 0;
  EXPECT_EQ(entries, 1);
  const std::string planned = shell("plan " + scene);
  EXPECT_NE(planned.find("measured on"), std::string::npos) << planned;
  EXPECT_EQ(planned.find("not measured yet"), std::string::npos) << planned;
  const std::string rendered = shell("render " + scene + " -o " + (dir_ / "out").string());
  EXPECT_EQ(rendered.find("shafts: method auto:"), std::string::npos) << rendered;  // read from the cache
  EXPECT_TRUE(fs::exists(dir_ / "out" / "image.exr"));
}

// The preview itself runs under Xvfb in preview_cli_test.cpp; here only what needs no display.
TEST_F(Cli, PreviewNeedsAScene) {
  const Result r = run("preview");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("scene is required"), std::string::npos) << r.output;
  const Result bad = run("preview " + kRepo + "/scenes/flat_sea.toml --size 10x10 --frames 1");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("--size expects WIDTHxHEIGHT"), std::string::npos) << bad.output;
}

}  // namespace
