// underwater_regions_dump_test.cpp — `seasim underwater-regions --dump DIR`: one CSV per case
// with every pixel's region, ray direction, the reference, each model's render and the discrete-ordinates model's
// terms, and the terms add up to the model (the render and the reference the files hold are the ones
// the region ratios were taken from).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "io/npy.h"
#include "run_command.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

std::vector<std::string> splitCsv(const std::string& line) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  std::string f;
  while (std::getline(ss, f, ',')) out.push_back(f);
  return out;
}

// A CSV file the command wrote (text and numbers, no quoting): its header, each name's column and the
// rows. (host's loadCsv reads numeric tables only.)
struct CsvRows {
  std::vector<std::string> header;
  std::map<std::string, size_t> col;
  std::vector<std::vector<std::string>> rows;
};
CsvRows readCsvRows(const fs::path& file) {
  CsvRows t;
  std::ifstream in(file);
  std::string line;
  if (!std::getline(in, line)) return t;
  t.header = splitCsv(line);
  for (size_t i = 0; i < t.header.size(); ++i) t.col[t.header[i]] = i;
  while (std::getline(in, line)) t.rows.push_back(splitCsv(line));
  return t;
}

class UnderwaterRegionsDump : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_uwdump_"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(UnderwaterRegionsDump, WritesEveryPixelWithRegionReferenceRendersAndTermsThatAddUp) {
  const fs::path dump = dir_ / "dump";
  // Clear water at g = 0 over 5 m, level: bottom near and far, objects and the water looking up (the
  // surface under total internal reflection), 4 paths per pixel (the test needs the files, not accuracy).
  const seasim_test::Result r = seasim_test::runCommand(
      kBinary + " underwater-regions " + kRepo + "/tests/perf/underwater_regions.toml --waters 0.03:0.05 --g 0" +
      " --depths 5 --views level,up --models thesis,improved --spp 4 --device pocl --set camera.width=32" +
      " --set camera.height=18 --cache " + (dir_ / "cache").string() + " --dump " + dump.string());
  ASSERT_EQ(r.code, 0) << r.output;
  std::vector<double> reference_sums;  // per case, from the CSV
  for (const char* view : {"level", "up"}) {
    const fs::path file = dump / (std::string("a0.03_b0.05_g0_d5_") + view + ".csv");
    ASSERT_TRUE(fs::exists(file)) << file;
    CsvRows csv = readCsvRows(file);
    ASSERT_FALSE(csv.header.empty()) << file;
    const std::vector<std::string>& header = csv.header;
    std::map<std::string, size_t>& col = csv.col;
    for (const char* c : {"x", "y", "region", "d_y", "cos_sun", "reference", "reference_se", "fast_thesis",
                          "fast_improved", "inscatter_modes", "inscatter_beam", "inscatter_tms", "aureole", "froxel_ss", "window",
                          "reflected_inscatter", "reflected_bottom", "reflected_froxel_ss", "reflected_object", "lambert",
                          "model_total", "forward"})
      ASSERT_TRUE(col.count(c)) << "column " << c << " in " << file;
    const std::vector<std::vector<std::string>>& rows = csv.rows;
    ASSERT_EQ(rows.size(), 32u * 18u) << "one row per pixel";
    std::map<std::string, int> regions;
    double fast = 0, total = 0, reference = 0, window = 0, reflected = 0;
    for (size_t i = 0; i < rows.size(); ++i) {
      const auto& row = rows[i];
      ASSERT_EQ(row.size(), header.size());
      EXPECT_EQ(std::stoi(row[col["x"]]), int(i % 32));
      EXPECT_EQ(std::stoi(row[col["y"]]), int(i / 32));
      ++regions[row[col["region"]]];
      auto v = [&](const char* c) { return std::stod(row[col[c]]); };
      for (const auto& h : header)
        if (h != "region") ASSERT_TRUE(std::isfinite(std::stod(row[col[h]]))) << h;
      // Where the surface is seen, the ray goes up; the sky through Snell's window only inside it.
      if (v("window") > 0 || v("reflected_inscatter") > 0) EXPECT_GT(v("d_y"), 0.0);
      if (v("d_y") < std::sqrt(1 - 1 / (1.33 * 1.33)) - 0.01) EXPECT_EQ(v("window"), 0.0) << "TIR";
      // At g = 0 delta-M moves nothing: no small-angle part (UnderwaterRegionsDump.ForwardIs… at g = 0.9).
      EXPECT_EQ(v("forward"), 0.0);
      // The terms add up to the model's total wherever its in-scatter is not clamped at 0.
      const double inscatter =
          v("inscatter_modes") + v("inscatter_beam") + v("inscatter_tms") + v("aureole") - v("froxel_ss");
      if (inscatter > 0) {
        const double sum = inscatter + v("froxel_ss") + v("window") + v("reflected_inscatter") +
                           v("reflected_bottom") + v("lambert");
        EXPECT_NEAR(sum, v("model_total"), 1e-9 + 1e-9 * std::fabs(sum));
      }
      fast += v("fast_improved");
      total += v("model_total");
      reference += v("reference");
      window += v("window");
      reflected += v("reflected_inscatter") + v("reflected_bottom");
    }
    // The render is the model (float, froxel shadows and their grid: a few per cent at most).
    EXPECT_NEAR(fast / total, 1.0, 0.02) << view;
    EXPECT_GT(reference, 0.0);
    reference_sums.push_back(reference);
    EXPECT_GT(reflected, 0.0) << view << ": the surface's reflected ray";
    if (std::string(view) == "level") {
      EXPECT_GT(regions["bottom_near"], 0);
      EXPECT_GT(regions["water_up"], 0);
      EXPECT_EQ(window, 0.0) << "level: every upward ray is beyond the critical angle";
    } else {
      EXPECT_GT(window, 0.0) << "30° up: Snell's window is in view";
    }
  }
  // The reference column is the cached path-traced image, summed over its channels.
  std::vector<double> npy_sums;
  for (const auto& e : fs::directory_iterator(dir_ / "cache"))
    if (e.path().string().ends_with(".rgb.npy")) {
      double sum = 0;
      for (float p : seasim::readNpy(e.path().string()).pixels) sum += p;
      npy_sums.push_back(sum);
    }
  ASSERT_EQ(npy_sums.size(), 2u) << "one reference per case";
  for (double s : reference_sums) {
    const double d0 = std::fabs(s - npy_sums[0]), d1 = std::fabs(s - npy_sums[1]);
    EXPECT_LT(std::min(d0, d1), 1e-4 * s) << "the CSV's reference is a cached reference";
  }
}

// The study's reference goes through each pixel's centre, the one ray the fast models shade and the
// regions are classified by; `--jitter` traces over the pixel's area as `seasim reference` does.
// On an object's edge a jittered pixel mixes in the sand beside it, which the model's centre ray never
// sees: there the model misses the jittered reference by far more than the centre one.
TEST_F(UnderwaterRegionsDump, ReferenceRaysGoThroughThePixelCentreUnlessJittered) {
  // Per pixel: region and |fast_improved / reference - 1|, from a dump.
  auto read = [](const fs::path& file) {
    CsvRows csv = readCsvRows(file);
    std::vector<std::pair<std::string, double>> px;
    for (const auto& row : csv.rows)
      px.emplace_back(row[csv.col["region"]], std::fabs(std::stod(row[csv.col["fast_improved"]]) /
                                                            std::stod(row[csv.col["reference"]]) - 1));
    return px;
  };
  const int w = 32, h = 18;
  std::vector<double> edge_error;  // centre, then jittered
  for (const char* mode : {"", " --jitter"}) {
    const fs::path dump = dir_ / (std::string("dump") + (*mode ? "_jitter" : "_centre"));
    const seasim_test::Result r = seasim_test::runCommand(
        kBinary + " underwater-regions " + kRepo + "/tests/perf/underwater_regions.toml --waters 0.03:0.05 --g 0" +
        " --depths 2 --views level --models improved --spp 256 --device pocl --set camera.width=32" +
        " --set camera.height=18 --cache " + (dir_ / "cache").string() + " --dump " + dump.string() + mode);
    ASSERT_EQ(r.code, 0) << r.output;
    const auto px = read(dump / "a0.03_b0.05_g0_d2_level.csv");
    ASSERT_EQ(px.size(), size_t(w * h));
    // An object pixel with a 4-neighbour of another region.
    double sum = 0;
    int n = 0;
    for (int y = 1; y + 1 < h; ++y)
      for (int x = 1; x + 1 < w; ++x) {
        const int i = y * w + x;
        if (px[i].first != "objects") continue;
        bool edge = false;
        for (int j : {i - 1, i + 1, i - w, i + w}) edge = edge || px[j].first != "objects";
        if (!edge) continue;
        sum += px[i].second;
        ++n;
      }
    ASSERT_GT(n, 10) << "the rocks' outlines are in view";
    edge_error.push_back(sum / n);
  }
  int cached = 0;
  for (const auto& e : fs::directory_iterator(dir_ / "cache")) cached += e.path().string().ends_with(".rgb.npy");
  EXPECT_EQ(cached, 2) << "a centre-ray reference and a jittered one are different cache entries";
  EXPECT_LT(edge_error[0], 0.6 * edge_error[1])
      << "edge pixels: model vs centre-ray reference " << edge_error[0] << ", vs jittered " << edge_error[1];
}

// --target-noise: a case whose judged region is noisier than the target is traced again at the path
// count that reaches it (the CSV's reference_spp says which, and both references are cached); one that
// would need more than --max-spp keeps --spp.
TEST_F(UnderwaterRegionsDump, NoisyReferencesAreTracedAgainWithinTheBudget) {
  auto run = [&](const std::string& name, const std::string& max_spp) {
    const fs::path csv = dir_ / (name + ".csv");
    const seasim_test::Result r = seasim_test::runCommand(
        kBinary + " underwater-regions " + kRepo + "/tests/perf/underwater_regions.toml --waters 0.1:0.3 --g 0.5" +
        " --depths 5 --views level --models improved --spp 4 --target-noise 0.05 --max-spp " + max_spp +
        " --device pocl --set camera.width=32 --set camera.height=18 --cache " + (dir_ / name).string() +
        " --csv " + csv.string());
    EXPECT_EQ(r.code, 0) << r.output;
    const CsvRows table = readCsvRows(csv);
    EXPECT_EQ(table.rows.size(), 1u) << "one case, one model";
    const std::vector<std::string>& h = table.header;
    const std::vector<std::string> v = table.rows.empty() ? std::vector<std::string>{} : table.rows[0];
    int spp = -1;
    double worst_noise = 0;
    for (size_t i = 0; i < h.size() && i < v.size(); ++i) {
      if (h[i] == "reference_spp") spp = std::stoi(v[i]);
      if (h[i].ends_with("_ref_rel_se") && !v[i].empty() && std::stoi(v[i - 2]) >= 40)
        worst_noise = std::max(worst_noise, std::stod(v[i]));
    }
    int cached = 0;
    for (const auto& e : fs::directory_iterator(dir_ / name)) cached += e.path().string().ends_with(".rgb.npy");
    return std::tuple{spp, worst_noise, cached};
  };
  // 4 paths leave the regions' noise at several per cent: 0.05 needs a few times more, within 1024.
  const auto [spp, noise, cached] = run("roomy", "1024");
  EXPECT_GT(spp, 4);
  EXPECT_LE(spp, 1024);
  EXPECT_EQ(spp & (spp - 1), 0) << "a power of two";
  EXPECT_EQ(cached, 2) << "the first reference and the one traced again";
  EXPECT_LT(noise, 0.05 * 1.3) << "near the target (the noise estimate is itself noisy)";
  // Without the budget for that, the case keeps its 4 paths and its noise.
  const auto [spp_tight, noise_tight, cached_tight] = run("tight", "5");
  EXPECT_EQ(spp_tight, 4);
  EXPECT_GT(noise_tight, 0.05);
  EXPECT_EQ(cached_tight, 1);
}

// Bad values of the new options are refused before any tracing, naming the option.
TEST_F(UnderwaterRegionsDump, BadTargetNoiseOrMaxSppIsRefusedNamingTheOption) {
  for (const auto& [option, name] : {std::pair{"--target-noise 2", "--target-noise"},
                                     std::pair{"--target-noise -0.1", "--target-noise"},
                                     std::pair{"--max-spp 0", "--max-spp"}}) {
    const seasim_test::Result r = seasim_test::runCommand(
        kBinary + " underwater-regions " + kRepo + "/tests/perf/underwater_regions.toml --waters 0.1:0.3 --g 0.5" +
        " --depths 5 --views level --models improved --spp 4 " + option + " --device pocl --cache " +
        (dir_ / "cache").string() + " --csv " + (dir_ / "bad.csv").string());
    EXPECT_NE(r.code, 0) << option;
    EXPECT_NE(r.output.find(name), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir_ / "bad.csv")) << option;
    EXPECT_FALSE(fs::exists(dir_ / "cache")) << option << ": nothing traced";
  }
}

// At g = 0.9 the small-angle part of a hit's light (the forward column) is a real part of it: positive
// where there is a hit, never more than the hit's light, none without one.
TEST_F(UnderwaterRegionsDump, ForwardIsThePartOfTheHitsLightDeltaMCountsAsUnscattered) {
  const fs::path dump = dir_ / "dump_g09";
  const seasim_test::Result r = seasim_test::runCommand(
      kBinary + " underwater-regions " + kRepo + "/tests/perf/underwater_regions.toml --waters 0.1:0.3 --g 0.9" +
      " --depths 5 --views level --models improved --spp 4 --device pocl --set camera.width=32" +
      " --set camera.height=18 --cache " + (dir_ / "cache_g09").string() + " --dump " + dump.string());
  ASSERT_EQ(r.code, 0) << r.output;
  CsvRows csv = readCsvRows(dump / "a0.1_b0.3_g0.9_d5_level.csv");
  ASSERT_EQ(csv.rows.size(), 32u * 18u);
  double forward = 0, hit = 0;
  for (const auto& row : csv.rows) {
    auto v = [&](const char* c) { return std::stod(row[csv.col[c]]); };
    const double hit_light = v("lambert") + v("window") + v("reflected_inscatter") + v("reflected_bottom");
    EXPECT_GE(v("forward"), 0.0);
    EXPECT_LE(v("forward"), hit_light * (1 + 1e-9) + 1e-15);
    if (hit_light > 0) EXPECT_GT(v("forward"), 0.0);
    forward += v("forward");
    hit += hit_light;
  }
  // c - c' = b g³ = 0.219/m over a few metres: a sizeable share.
  EXPECT_GT(forward, 0.2 * hit);
  EXPECT_LT(forward, 0.95 * hit);
}

// --views sun turns the camera to the refracted sun: the frame's centre looks along the sun's direction in
// the water (Snell's law from the scene's sun, 30° from the zenith, and its water's n = 1.333), so every
// pixel sees the surface; an unknown view is refused, naming the ones there are.
TEST_F(UnderwaterRegionsDump, SunViewLooksAtTheRefractedSun) {
  const fs::path dump = dir_ / "dump_sun";
  const std::string common = kBinary + " underwater-regions " + kRepo +
                             "/tests/perf/underwater_regions.toml --waters 0.1:0.3 --g 0.5 --depths 5 --models improved"
                             " --spp 4 --device pocl --set camera.width=32 --set camera.height=18 --cache " +
                             (dir_ / "cache_sun").string();
  const seasim_test::Result r = seasim_test::runCommand(common + " --views sun --dump " + dump.string());
  ASSERT_EQ(r.code, 0) << r.output;
  CsvRows csv = readCsvRows(dump / "a0.1_b0.3_g0.5_d5_sun.csv");
  ASSERT_EQ(csv.rows.size(), 32u * 18u);
  const double sin_w = 0.5 / 1.333, mu_w = std::sqrt(1 - sin_w * sin_w);
  double centre = 0;
  int centre_pixels = 0;
  for (const auto& row : csv.rows) {
    EXPECT_EQ(row[csv.col["region"]], "water_up");
    const int x = std::stoi(row[csv.col["x"]]), y = std::stoi(row[csv.col["y"]]);
    if ((x == 15 || x == 16) && (y == 8 || y == 9)) {
      centre += std::stod(row[csv.col["d_y"]]);
      ++centre_pixels;
      EXPECT_GT(std::stod(row[csv.col["cos_sun"]]), std::cos(4 * 3.14159265358979 / 180)) << "the sun at the centre";
    }
  }
  ASSERT_EQ(centre_pixels, 4);
  EXPECT_NEAR(centre / 4, mu_w, 0.03);
  const seasim_test::Result bad = seasim_test::runCommand(common + " --views sideways");
  EXPECT_NE(bad.code, 0);
  EXPECT_NE(bad.output.find("unknown view 'sideways' (level, up, down, sun)"), std::string::npos) << bad.output;
}

}  // namespace
