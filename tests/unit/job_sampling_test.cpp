// job_sampling_test.cpp — a job's [sample] table: items expand with their keys drawn, the same seed
// gives the same items (whatever the count, the other keys or the order of the table), bounds hold,
// a table of bad specs each with the "file:line: key 'KEY'" its message must contain, the time a
// 1,000-item job takes to expand and validate, and labels.json's content for a scene without water
// and one with explicit spectra (tests/integration/dataset_cli_test.cpp renders Jerlov ones).
#include <gtest/gtest.h>

#include <toml++/toml.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <set>

#include "jobs/item_labels.h"
#include "jobs/job.h"
#include "scene/scene_parser.h"
#include "spectral/jerlov.h"
#include "util/error.h"

namespace fs = std::filesystem;
using namespace seasim;

namespace {

class SampleFiles {
 public:
  explicit SampleFiles(const std::string& name)
      : dir(fs::temp_directory_path() / ("seasim_sample_test_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir / "scenes");
    std::ofstream(dir / "scenes/uw.toml") << "[camera]\nposition = [0, -5, 0]\nlook_at = [0, -6, -10]\nwidth = 16\n"
                                             "height = 8\n[water]\njerlov = \"IB\"\n[bottom]\ntype = \"flat\"\n"
                                             "depth = 12\n[spectral]\ncount = 4\n";
  }
  ~SampleFiles() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  SampleFiles(const SampleFiles&) = delete;
  std::string job() const { return (dir / "job.toml").string(); }
  fs::path dir;
};

const char* kKeys = R"(
[sample.keys]
"water.jerlov" = { choice = ["I", "IB", "II", "1C", "3C"] }
"bottom.depth" = { log_uniform = [2, 30] }
"sun.zenith_deg" = { normal = [35, 10], within = [0, 80] }
"sun.azimuth_deg" = { uniform = [0, 360] }
"camera.position" = { uniform = [[-2, -4, -1], [2, -1, 1]] }
"spectral.count" = { integer = [3, 6] }
)";

std::string sampleJob(long long seed, long long count, const std::string& keys = kKeys) {
  return "[sample]\nscene = \"scenes/uw.toml\"\nname = \"reef\"\nseed = " + std::to_string(seed) +
         "\ncount = " + std::to_string(count) + "\n" + keys;
}

// key -> value text for each item, by name.
std::map<std::string, std::map<std::string, std::string>> drawn(const Job& job) {
  std::map<std::string, std::map<std::string, std::string>> out;
  for (const RenderItem& item : job.items)
    for (const Override& o : item.sampled) out[item.name][o.key] = o.value_toml;
  return out;
}

double number(const std::string& toml_value) {
  toml::table t = toml::parse("v = " + toml_value);
  return t["v"].value<double>().value();
}

}  // namespace

TEST(JobSampling, ItemsExpandWithTheirDrawsWithinBounds) {
  SampleFiles f("expand");
  const Job job = parseJob(sampleJob(7, 40), f.job());
  ASSERT_EQ(job.items.size(), 40u);
  EXPECT_EQ(job.items[0].name, "reef_s0000");
  EXPECT_EQ(job.items[39].name, "reef_s0039");
  std::set<std::string> jerlov, depths;
  for (const RenderItem& item : job.items) {
    ASSERT_EQ(item.sampled.size(), 6u);
    EXPECT_EQ(item.sample_seed, 7u);
    // The drawn keys are the item's last overrides, located at their distributions' lines.
    ASSERT_GE(item.overrides.size(), 6u);
    EXPECT_EQ(item.overrides.back().key, item.sampled.back().key);
    for (const Override& o : item.sampled) {
      EXPECT_GE(o.loc.line, 6) << o.key;
      if (o.key == "water.jerlov") jerlov.insert(o.value_toml);
      if (o.key == "bottom.depth") {
        depths.insert(o.value_toml);
        EXPECT_GE(number(o.value_toml), 2.0);
        EXPECT_LE(number(o.value_toml), 30.0);
      }
      if (o.key == "sun.zenith_deg") {
        EXPECT_GE(number(o.value_toml), 0.0);
        EXPECT_LE(number(o.value_toml), 80.0);
      }
      if (o.key == "spectral.count") EXPECT_TRUE(o.value_toml == "3" || o.value_toml == "4" || o.value_toml == "5" || o.value_toml == "6") << o.value_toml;
      if (o.key == "camera.position") {
        toml::table t = toml::parse("v = " + o.value_toml);
        const toml::array& a = *t["v"].as_array();
        ASSERT_EQ(a.size(), 3u);
        const double lo[] = {-2, -4, -1}, hi[] = {2, -1, 1};
        for (size_t i = 0; i < 3; ++i) {
          EXPECT_GE(a[i].value<double>().value(), lo[i]);
          EXPECT_LE(a[i].value<double>().value(), hi[i]);
        }
      }
    }
  }
  EXPECT_GE(jerlov.size(), 4u) << "40 draws over 5 types";
  EXPECT_EQ(depths.size(), 40u);
}

TEST(JobSampling, SameSeedSameItemsWhateverTheCountOrOtherKeys) {
  SampleFiles f("seed");
  const auto a = drawn(parseJob(sampleJob(7, 30), f.job()));
  const auto b = drawn(parseJob(sampleJob(7, 30), f.job()));
  EXPECT_EQ(a, b);
  // Item i does not depend on how many items there are (a shard sees the same item).
  const auto longer = drawn(parseJob(sampleJob(7, 300), f.job()));
  for (const auto& [name, values] : a) EXPECT_EQ(longer.at(name), values) << name;
  // Nor on the other keys, their order, or TOML's nested spelling of a key.
  const auto one = drawn(parseJob(sampleJob(7, 30, "[sample.keys]\nbottom = { depth = { log_uniform = [2, 30] } }\n"), f.job()));
  for (const auto& [name, values] : one) EXPECT_EQ(values.at("bottom.depth"), a.at(name).at("bottom.depth")) << name;

  const auto other = drawn(parseJob(sampleJob(8, 30), f.job()));
  int same = 0;
  for (const auto& [name, values] : a) same += values.at("bottom.depth") == other.at(name).at("bottom.depth");
  EXPECT_EQ(same, 0) << "another seed draws other depths";
}

TEST(JobSampling, SampledKeysWinOverFixedOverridesAndRunSetWinsOverBoth) {
  SampleFiles f("order");
  JobLoadOptions options;
  options.extra_overrides = {Override{"sun.azimuth_deg", "12.0", {"<command line>", 0}}};
  const Job job = parseJob("[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 2\n"
                           "overrides = { \"sun.azimuth_deg\" = 5, \"water.g\" = 0.8 }\n"
                           "[sample.keys]\n\"sun.azimuth_deg\" = { uniform = [100, 200] }\n",
                           f.job(), options);
  ASSERT_EQ(job.items.size(), 2u);
  EXPECT_EQ(job.items[0].name, "uw_s0000");
  const auto& o = job.items[0].overrides;
  ASSERT_GE(o.size(), 3u);
  EXPECT_EQ(o[o.size() - 2].key, "sun.azimuth_deg");  // drawn, after the fixed 5
  EXPECT_GE(number(o[o.size() - 2].value_toml), 100.0);
  EXPECT_EQ(o.back().value_toml, "12.0");  // --set last
}

TEST(JobSampling, AThousandItemsExpandAndValidateQuickly) {
  SampleFiles f("thousand");
  const auto t0 = std::chrono::steady_clock::now();
  const Job job = parseJob(sampleJob(3, 1000), f.job());
  const double with_scenes = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  JobLoadOptions no_scenes;
  no_scenes.check_scenes = false;
  const auto t1 = std::chrono::steady_clock::now();
  const Job bare = parseJob(sampleJob(3, 1000), f.job(), no_scenes);
  const double expand = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  ASSERT_EQ(job.items.size(), 1000u);
  EXPECT_EQ(job.items[999].name, "reef_s0999");
  EXPECT_EQ(bare.items.size(), 1000u);
  std::printf("1,000 sampled items: expanded in %.3f s; expanded and every scene validated in %.3f s\n", expand,
              with_scenes);
  // A bound for a quadratic slip, not a benchmark (the shared test machine is slow and loaded).
  EXPECT_LT(expand, 2.0);
  EXPECT_LT(with_scenes, 30.0);
}

TEST(JobSampling, CountOverTenThousandWidensTheNames) {
  SampleFiles f("wide");
  JobLoadOptions no_scenes;
  no_scenes.check_scenes = false;
  const Job job = parseJob(sampleJob(3, 12000, "[sample.keys]\n\"sun.zenith_deg\" = { uniform = [0, 10] }\n"), f.job(), no_scenes);
  EXPECT_EQ(job.items.front().name, "reef_s00000");
  EXPECT_EQ(job.items.back().name, "reef_s11999");
}

TEST(JobSampling, ValidateLooksPastABadDistributionToTheNextError) {
  // `seasim validate` parses again with the failing key ignored: the key's whole distribution is
  // then left out, with no second message about it.
  SampleFiles f("validate");
  const std::string text = "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 2\n[sample.keys]\n"
                           "\"bottom.depth\" = { log_uniform = [0, 3] }\n\"water.g\" = { uniform = [0.5, 0.2] }\n";
  JobLoadOptions options;
  options.ignored_keys = {"sample.keys.bottom.depth.log_uniform"};
  std::string msg;
  try {
    parseJob(text, f.job(), options);
  } catch (const InputError& e) {
    msg = e.what();
  }
  EXPECT_NE(msg.find("job.toml:7: key 'sample.keys.water.g.uniform': lo must be < hi"), std::string::npos) << msg;
  options.ignored_keys.push_back("sample.keys.water.g.uniform");
  const Job job = parseJob(text, f.job(), options);
  EXPECT_EQ(job.items.size(), 2u);
  EXPECT_TRUE(job.items[0].sampled.empty());
}

TEST(JobSampling, IsJobFileKnowsSampleTables) {
  SampleFiles f("isjob");
  std::ofstream(f.job()) << sampleJob(1, 2);
  EXPECT_TRUE(isJobFile(f.job()));
  std::ofstream(f.job()) << "[sample]\nseed = \n";  // broken TOML: judged by the header
  EXPECT_TRUE(isJobFile(f.job()));
}

// ---------------------------------------------------------------------------------------------
// Bad [sample] tables: each must fail with a message containing `expected`.

namespace {

struct BadSample {
  const char* what;
  const char* toml;
  const char* expected;
};
void PrintTo(const BadSample& c, std::ostream* os) { *os << c.what; }

#define HEAD "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 3\n[sample.keys]\n"
const BadSample kBadSamples[] = {
    {"no seed", "[sample]\nscene = \"scenes/uw.toml\"\ncount = 3\n[sample.keys]\n\"water.g\" = { uniform = [0, 0.5] }\n",
     "job.toml:1: key 'sample.seed': missing"},
    {"negative seed", "[sample]\nscene = \"scenes/uw.toml\"\nseed = -1\ncount = 3\n[sample.keys]\n\"water.g\" = { uniform = [0, 0.5] }\n",
     "job.toml:3: key 'sample.seed': must be an integer in [0, "},
    {"no count", "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\n[sample.keys]\n\"water.g\" = { uniform = [0, 0.5] }\n",
     "job.toml:1: key 'sample.count': missing"},
    {"count 0", "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 0\n[sample.keys]\n\"water.g\" = { uniform = [0, 0.5] }\n",
     "job.toml:4: key 'sample.count': must be an integer in [1, 100000], got 0"},
    {"no keys", "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 3\n", "job.toml:1: key 'sample.keys': missing"},
    {"typo in [sample]", "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 3\nsed = 2\n[sample.keys]\n\"water.g\" = { uniform = [0, 0.5] }\n",
     "job.toml:5: key 'sample.sed': unknown key"},
    {"no distribution", HEAD "\"water.g\" = { unifrom = [0, 0.5] }\n",
     "job.toml:6: key 'sample.keys.water.g': names no distribution"},
    {"a bare value", HEAD "\"water.g\" = 0.5\n", "job.toml:6: key 'sample.keys.water.g': expected a distribution"},
    {"two distributions", HEAD "\"water.g\" = { uniform = [0, 0.5], normal = [0, 1] }\n",
     "job.toml:6: key 'sample.keys.water.g.normal': give one distribution per key, not both 'uniform' and 'normal'"},
    {"lo >= hi", HEAD "\"water.g\" = { uniform = [0.5, 0.5] }\n",
     "job.toml:6: key 'sample.keys.water.g.uniform': lo must be < hi"},
    {"bound not a number", HEAD "\"water.g\" = { uniform = [0, \"x\"] }\n",
     "job.toml:6: key 'sample.keys.water.g.uniform[1]': expected a number, got a string"},
    {"three bounds", HEAD "\"water.g\" = { uniform = [0, 0.1, 0.2] }\n",
     "job.toml:6: key 'sample.keys.water.g.uniform': expected [lo, hi]"},
    {"arrays of two lengths", HEAD "\"camera.position\" = { uniform = [[0, 0], [1, 1, 1]] }\n",
     "job.toml:6: key 'sample.keys.camera.position.uniform': both must be numbers, or arrays of the same length"},
    {"component lo >= hi", HEAD "\"camera.position\" = { uniform = [[0, 0, 0], [1, -1, 1]] }\n",
     "job.toml:6: key 'sample.keys.camera.position.uniform': lo must be < hi (component 1)"},
    {"log-uniform from 0", HEAD "\"bottom.depth\" = { log_uniform = [0, 10] }\n",
     "job.toml:6: key 'sample.keys.bottom.depth.log_uniform': lo must be > 0"},
    {"sd 0", HEAD "\"bottom.depth\" = { normal = [5, 0] }\n",
     "job.toml:6: key 'sample.keys.bottom.depth.normal': sd must be > 0"},
    {"bounds beyond 30 sd", HEAD "\"bottom.depth\" = { normal = [5, 0.1], within = [10, 20] }\n",
     "job.toml:6: key 'sample.keys.bottom.depth.within': the bounds lie more than 30 sd from the mean"},
    {"within reversed", HEAD "\"bottom.depth\" = { normal = [5, 1], within = [20, 10] }\n",
     "job.toml:6: key 'sample.keys.bottom.depth.within': lo must be < hi"},
    {"within outside normal", HEAD "\"bottom.depth\" = { uniform = [5, 10], within = [1, 2] }\n",
     "job.toml:6: key 'sample.keys.bottom.depth.within': unknown key"},
    {"integer bounds not integers", HEAD "\"spectral.count\" = { integer = [3, 6.5] }\n",
     "job.toml:6: key 'sample.keys.spectral.count.integer': bounds must be integers"},
    {"empty choice", HEAD "\"water.jerlov\" = { choice = [] }\n",
     "job.toml:6: key 'sample.keys.water.jerlov.choice': must list at least one value"},
    {"weights of another length", HEAD "\"water.jerlov\" = { choice = [\"I\", \"II\"], weights = [1] }\n",
     "job.toml:6: key 'sample.keys.water.jerlov.weights': expected an array of 2 numbers"},
    {"weight 0", HEAD "\"water.jerlov\" = { choice = [\"I\", \"II\"], weights = [1, 0] }\n",
     "job.toml:6: key 'sample.keys.water.jerlov.weights[1]': must be > 0"},
    {"key sampled twice", HEAD "\"bottom.depth\" = { uniform = [5, 10] }\nbottom.depth = { uniform = [5, 10] }\n",
     "key 'sample.keys.bottom.depth': 'bottom.depth' is sampled twice"},
    {"unknown scene key", HEAD "\"sun.zenith\" = { uniform = [0, 10] }\n",
     "job.toml:6: key 'sun.zenith': unknown key; did you mean 'zenith_deg'?"},
    {"draws the scene rejects", HEAD "\"water.g\" = { uniform = [1.5, 2] }\n",
     "job.toml:6: key 'water.g': must satisfy |g| < 1"},
    {"a choice the scene rejects", HEAD "\"water.jerlov\" = { choice = [\"IV\"] }\n",
     "job.toml:6: key 'water.jerlov': unknown Jerlov water type 'IV'"},
    {"too many items", "[sample]\nscene = \"scenes/uw.toml\"\nseed = 1\ncount = 100000\n[sample.keys]\n\"water.g\" = { uniform = [0, 0.5] }\n"
                       "[[render]]\nscene = \"scenes/uw.toml\"\n",
     "job.toml:4: key 'sample.count': 100000 items (1 before it) are more than a job may hold"},
    {"names clash with a render", "[[render]]\nname = \"uw_s0001\"\nscene = \"scenes/uw.toml\"\n" HEAD "\"water.g\" = { uniform = [0, 0.5] }\n",
     "item name 'uw_s0001' is used twice"},
};
#undef HEAD

class BadSampleTest : public ::testing::TestWithParam<BadSample> {};

}  // namespace

TEST_P(BadSampleTest, FailsWithFileLineAndKey) {
  static const SampleFiles files("bad");
  const BadSample& c = GetParam();
  std::string msg;
  try {
    parseJob(c.toml, files.job());
  } catch (const InputError& e) {
    msg = e.what();
  }
  ASSERT_FALSE(msg.empty()) << c.what << ": parsed without error";
  EXPECT_NE(msg.find(c.expected), std::string::npos) << c.what << "\n  expected: " << c.expected << "\n  got:      " << msg;
}

INSTANTIATE_TEST_SUITE_P(Table, BadSampleTest, ::testing::ValuesIn(kBadSamples),
                         [](const ::testing::TestParamInfo<BadSample>& info) {
                           std::string n = std::to_string(info.index) + "_";
                           for (const char* p = info.param.what; *p; ++p)
                             n += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
                           return n;
                         });

// ---------------------------------------------------------------------------------------------
// labels.json's content for scenes the dataset test does not render: no water, explicit spectra.

TEST(ItemLabels, ASceneWithoutWaterAndOneWithExplicitSpectra) {
  SampleFiles f("labels");
  std::ofstream(f.dir / "scenes/dry.toml") << "[camera]\nwidth = 64\nheight = 32\nfov_deg = 40\n[sun]\nzenith_deg = 60\n";
  std::ofstream(f.dir / "scenes/explicit.toml")
      << "[camera]\nposition = [0, -2, 0]\nlook_at = [0, -2, -10]\n[water]\nwavelengths_nm = [400, 700]\n"
         "a = [0.1, 0.5]\nb = [0.2, 0.1]\ng = 0.85\n[spectral]\ncount = 3\n[sun]\nzenith_deg = 40\n";
  const Job job = parseJob("[sample]\nscene = \"scenes/dry.toml\"\nseed = 5\ncount = 2\n[sample.keys]\n"
                           "\"sun.azimuth_deg\" = { uniform = [0, 90] }\n",
                           f.job());
  const RenderItem& item = job.items[1];
  const nlohmann::json dry = itemLabels(loadScene(item.scene_file, item.overrides), item);
  EXPECT_EQ(dry["water"]["present"], false);
  EXPECT_FALSE(dry["water"].contains("a"));
  EXPECT_EQ(dry["index"], 1);
  EXPECT_EQ(dry["seed"], 5);
  EXPECT_NEAR(dry["sun"]["azimuth_deg"].get<double>(), dry["sampled"]["sun.azimuth_deg"].get<double>(), 1e-9);
  EXPECT_NEAR(dry["camera"]["fov_y_deg"].get<double>(), 40.0, 1e-12);
  // fov_x from fov_y and the 2:1 aspect: 2 atan(2 tan 20°) = 72.1°.
  EXPECT_NEAR(dry["camera"]["fov_x_deg"].get<double>(), 72.104777, 1e-5);
  EXPECT_EQ(dry["camera"]["depth_m"], 0.0);
  EXPECT_TRUE(dry["camera"]["sensor_file"].is_null());
  EXPECT_FALSE(labelsRecordOtherDraws(item, (f.dir / "nowhere").string()));

  const Scene wet = loadScene((f.dir / "scenes/explicit.toml").string());
  const nlohmann::json labels = itemLabels(wet, item);
  const nlohmann::json& w = labels["water"];
  EXPECT_TRUE(w["jerlov"].is_null());
  ASSERT_EQ(w["bands_nm"].size(), 3u);
  EXPECT_NEAR(w["bands_nm"][1].get<double>(), 550.0, 1e-12);
  EXPECT_NEAR(w["a"][1].get<double>(), 0.3, 1e-12);  // linear between 400 and 700 nm
  EXPECT_NEAR(w["c"][1].get<double>(), 0.45, 1e-12);
  // K_d from a and b (Solonenko & Mobley eq. 3) at the refracted sun's cosine, recorded beside it.
  const double mu = w["kd_sun_cosine"].get<double>();
  EXPECT_NEAR(mu, std::cos(std::asin(std::sin(40 * 3.14159265358979323846 / 180) / 1.333)), 1e-12);
  EXPECT_NEAR(w["kd"][1].get<double>(), kdFromIops(0.3, 0.15, 550.0, mu), 1e-12);
  EXPECT_EQ(w["phase"]["g"], 0.85);
  EXPECT_NEAR(labels["camera"]["depth_m"].get<double>(), 2.0, 1e-12);
  EXPECT_NEAR(labels["sun"]["direction_water"][1].get<double>(), mu, 1e-12);
}
