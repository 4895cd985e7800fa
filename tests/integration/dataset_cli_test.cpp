// dataset_cli_test.cpp — a [sample] job through the real binary: the same items (PNG and labels byte
// for byte, EXR pixels bit for bit) from one run and from four shards merged; labels.json beside
// each item's images, parsed and compared with the scene the item rendered (its report.json and an
// independent resolution of its water); and labels.json guarded like an image by resume and
// `farm merge`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "io/image_io.h"
#include "jobs/job.h"
#include "run_command.h"
#include "scene/scene_parser.h"
#include "spectral/jerlov.h"
#include "util/hash.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

seasim_test::Result run(const std::string& args) { return seasim_test::runCommand(kBinary + " " + args); }
bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

nlohmann::json readJson(const fs::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

class DatasetCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_dataset_cli_"); }
  void TearDown() override { fs::remove_all(dir_); }
  // Eight small seabed items over Jerlov types, bottom depths, the sun and two sensors.
  std::string job(const std::string& out) {
    std::ostringstream t;
    t << "[job]\nname = \"ds\"\noutput_dir = \"" << out << "\"\n"
      << "[sample]\nscene = \"" << kRepo << "/scenes/seabed.toml\"\nname = \"reef\"\nseed = 11\ncount = 8\n"
      << "outputs = [\"exr\", \"png\"]\n"
      << "overrides = { \"camera.width\" = 24, \"camera.height\" = 16, \"spectral.count\" = 4 }\n"
      << "[sample.keys]\n"
      << "\"water.jerlov\" = { choice = [\"IB\", \"II\", \"1C\", \"3C\"] }\n"
      << "\"bottom.depth\" = { log_uniform = [4.5, 12] }\n"
      << "\"sun.zenith_deg\" = { normal = [30, 15], within = [0, 70] }\n"
      << "\"camera.position\" = { uniform = [[-0.5, -3.9, -0.5], [0.5, -3.0, 0.5]] }\n"
      << "\"spectral.sensor\" = { choice = [\"cie1931\", \"nikon_d5100_npl\"] }\n";
    const std::string path = (dir_ / (out + ".toml")).string();
    std::ofstream(path) << t.str();
    return path;
  }
  fs::path dir_;
};

// The files of each item but report.json (which records timings): name -> checksum of the file, or
// for an EXR of its size, channels and pixels (its header records when it was written).
std::map<std::string, std::string> itemFiles(const fs::path& out) {
  std::map<std::string, std::string> files;
  for (const auto& item : fs::directory_iterator(out)) {
    if (!item.is_directory() || item.path().filename() == "farm") continue;
    for (const auto& f : fs::directory_iterator(item.path())) {
      const std::string name = item.path().filename().string() + "/" + f.path().filename().string();
      if (f.path().filename() == "report.json") continue;
      if (f.path().extension() == ".exr") {
        const seasim::Image image = seasim::readImage(f.path().string());
        std::ostringstream text;
        text << image.width << "x" << image.height << "x" << image.channels << ":";
        for (const std::string& c : image.channel_names) text << c << ",";
        text.write(reinterpret_cast<const char*>(image.pixels.data()),
                   static_cast<std::streamsize>(image.pixels.size() * sizeof(float)));
        files[name] = "pixels:" + seasim::hex64(seasim::fnv1a64(text.str()));
      } else {
        files[name] = seasim::fileChecksum(f.path().string());
      }
    }
  }
  return files;
}

}  // namespace

TEST_F(DatasetCli, WholeRunAndFourShardsGiveTheSameItemsAndLabels) {
  const std::string whole = job("whole");
  seasim_test::Result r = run("run " + whole + " --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;

  const std::string sharded = job("sharded");
  for (int i = 0; i < 4; ++i) {
    r = run("run " + sharded + " --shard " + std::to_string(i) + "/4 --device pocl");
    ASSERT_EQ(r.code, 0) << r.output;
  }
  r = run("farm merge " + sharded);
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "all 8 items present with intact files")) << r.output;

  const auto a = itemFiles(dir_ / "whole"), b = itemFiles(dir_ / "sharded");
  EXPECT_EQ(a.size(), 8u * 3u) << "image.exr, image.png and labels.json per item";
  EXPECT_EQ(a, b);
  EXPECT_TRUE(a.count("reef_s0007/labels.json"));

  // The manifest lists labels.json with its checksum, like the images.
  const nlohmann::json manifest = readJson(dir_ / "whole" / "manifest.json");
  EXPECT_TRUE(contains(manifest.dump(), "reef_s0003/labels.json")) << manifest.dump(1);
}

TEST_F(DatasetCli, LabelsParseAndMatchTheRenderedScene) {
  const std::string j = job("out");
  seasim_test::Result r = run("run " + j + " --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  const seasim::Job parsed = seasim::loadJob(j);
  ASSERT_EQ(parsed.items.size(), 8u);
  std::set<std::string> types;
  for (const seasim::RenderItem& item : parsed.items) {
    const fs::path folder = dir_ / "out" / item.name;
    const nlohmann::json labels = readJson(folder / "labels.json");
    const nlohmann::json settings = readJson(folder / "report.json")["settings"];
    EXPECT_EQ(labels["format"], "seasim-labels-1");
    EXPECT_EQ(labels["item"], item.name);
    EXPECT_EQ(labels["seed"], 11);
    EXPECT_EQ(labels["index"], item.sample_index);
    // What was drawn, and what the render recorded it rendered.
    const nlohmann::json& s = labels["sampled"];
    ASSERT_EQ(s.size(), 5u) << s.dump();
    EXPECT_EQ(settings["water"], "Jerlov " + s["water.jerlov"].get<std::string>());
    EXPECT_EQ(labels["water"]["jerlov"], s["water.jerlov"]);
    EXPECT_NEAR(labels["sun"]["zenith_deg"].get<double>(), s["sun.zenith_deg"].get<double>(), 1e-9);
    EXPECT_NEAR(labels["sun"]["zenith_deg"].get<double>(), settings["sun_zenith_deg"].get<double>(), 1e-9);
    EXPECT_NEAR(labels["sun"]["azimuth_deg"].get<double>(), settings["sun_azimuth_deg"].get<double>(), 1e-9);
    EXPECT_NEAR(labels["bottom"]["depth_m"].get<double>(), s["bottom.depth"].get<double>(), 1e-12);
    for (int c = 0; c < 3; ++c) {
      EXPECT_NEAR(labels["camera"]["position"][c].get<double>(), s["camera.position"][c].get<double>(), 1e-12);
      EXPECT_NEAR(labels["camera"]["position"][c].get<double>(), settings["camera_position_m"][c].get<double>(), 1e-12);
    }
    EXPECT_NEAR(labels["camera"]["depth_m"].get<double>(), -s["camera.position"][1].get<double>(), 1e-12);
    EXPECT_NEAR(labels["camera"]["fov_y_deg"].get<double>(), settings["camera_fov_deg"].get<double>(), 1e-9);
    EXPECT_EQ(labels["camera"]["sensor"], settings["sensor"]);
    EXPECT_EQ(labels["camera"]["width"], 24);
    if (s["spectral.sensor"] == "nikon_d5100_npl")
      EXPECT_TRUE(contains(labels["camera"]["sensor_file"].get<std::string>(), "nikon_d5100_npl.csv"));
    else
      EXPECT_TRUE(labels["camera"]["sensor_file"].is_null());
    // The water per band, against the Jerlov tables read here, at the band centres of the grid.
    const seasim::WaterSpectra w = seasim::jerlovWater(s["water.jerlov"].get<std::string>());
    const nlohmann::json& water = labels["water"];
    ASSERT_EQ(water["bands_nm"].size(), 4u);
    EXPECT_NEAR(water["bands_nm"][0].get<double>(), 437.5, 1e-9);  // 400-700 nm in 4 bands
    for (size_t i = 0; i < 4; ++i) {
      const double nm = water["bands_nm"][i].get<double>();
      EXPECT_NEAR(water["a"][i].get<double>(), w.a.at(nm), 1e-12);
      EXPECT_NEAR(water["b"][i].get<double>(), w.b.at(nm), 1e-12);
      EXPECT_NEAR(water["c"][i].get<double>(), w.a.at(nm) + w.b.at(nm), 1e-12);
      EXPECT_NEAR(water["kd"][i].get<double>(), w.kd.at(nm), 1e-12);
    }
    EXPECT_EQ(water["phase"]["name"], "henyey_greenstein");
    EXPECT_NEAR(water["phase"]["g"].get<double>(), 0.9, 1e-12);
    // The sun's direction in air is unit and agrees with its zenith angle.
    EXPECT_NEAR(labels["sun"]["direction_air"][1].get<double>(),
                std::cos(labels["sun"]["zenith_deg"].get<double>() * 3.14159265358979323846 / 180), 1e-12);
    types.insert(s["water.jerlov"].get<std::string>());
  }
  EXPECT_GE(types.size(), 2u);
}

TEST_F(DatasetCli, ResumeRendersAgainWhenLabelsAreDamagedMissingOrDrawnOtherwise) {
  const std::string j = job("out");
  seasim_test::Result r = run("run " + j + " --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  const fs::path out = dir_ / "out";
  std::ofstream(out / "reef_s0002" / "labels.json", std::ios::app) << " ";
  fs::remove(out / "reef_s0005" / "labels.json");
  r = run("farm merge " + j);
  EXPECT_EQ(r.code, 1) << r.output;
  EXPECT_TRUE(contains(r.output, "reef_s0002 (damaged: 'reef_s0002/labels.json' does not match its checksum)")) << r.output;
  EXPECT_TRUE(contains(r.output, "reef_s0005 (damaged: 'reef_s0005/labels.json' is missing)")) << r.output;
  r = run("run " + j + " --resume --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "2 rendered, 6 finished earlier")) << r.output;
  r = run("farm merge " + j);
  EXPECT_EQ(r.code, 0) << r.output;

  // An edited distribution of a key report.json's settings do not record: the labels tell.
  std::ifstream in(j);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::string before = "log_uniform = [4.5, 12]";
  ASSERT_NE(text.find(before), std::string::npos);
  text.replace(text.find(before), before.size(), "log_uniform = [6, 12]");
  std::ofstream(j) << text;
  r = run("run " + j + " --resume --device pocl");
  ASSERT_EQ(r.code, 0) << r.output;
  EXPECT_TRUE(contains(r.output, "reef_s0000: drawn with other values ([sample] changed): rendering it again")) << r.output;
  EXPECT_TRUE(contains(r.output, "8 rendered, 0 finished earlier")) << r.output;
}
