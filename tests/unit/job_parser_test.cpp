// job_parser_test.cpp — job files: renders, frame ranges and sweeps expanded into named items with
// their overrides in order, defaults, isJobFile, and a table of bad jobs each with the exact
// "file:line: key 'KEY'" its message must contain (the job's line for anything the job wrote).
#include <gtest/gtest.h>

#include <ostream>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>

#include <unistd.h>

#include "jobs/job.h"
#include "util/error.h"

namespace fs = std::filesystem;
using namespace seasim;

namespace {

// A temp folder (per process: ctest may run these tests in parallel processes) with a valid sea scene, a scene without water, and a reference image.
class JobFiles {
 public:
  explicit JobFiles(const std::string& name)
      : dir(fs::temp_directory_path() /
            ("seasim_job_test_" + name + "_" + std::to_string(::getpid()))) {
    fs::remove_all(dir);
    fs::create_directories(dir / "scenes");
    write("scenes/sea.toml",
          "[water]\njerlov = \"IB\"\n[surface]\ntype = \"fft\"\n[sun]\nzenith_deg = 30\n");
    write("scenes/dry.toml", "[camera]\nwidth = 64\nheight = 32\n");
    write("scenes/broken.toml", "[water]\njerlov = \"IB\"\ng = 3\n");
    write("ref.exr", "x");
  }
  ~JobFiles() {
    std::error_code ec;
    fs::remove_all(dir, ec);
  }
  JobFiles(const JobFiles&) = delete;
  void write(const std::string& rel, const std::string& text) const {
    std::ofstream(dir / rel, std::ios::binary) << text;
  }
  std::string job() const { return (dir / "job.toml").string(); }
  fs::path dir;
};

std::string errorOf(const JobFiles& f, const std::string& text) {
  try {
    parseJob(text, f.job());
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

const Override* findOverride(const RenderItem& item, const std::string& key) {
  const Override* last = nullptr;  // the one applied last wins
  for (const auto& o : item.overrides)
    if (o.key == key) last = &o;
  return last;
}

}  // namespace

TEST(JobParser, RendersFramesAndSweepsExpand) {
  JobFiles f("good");
  const std::string text = R"([job]
name = "nightly"
output_dir = "out/here"
device = "pocl:0"
overrides = { "sun.azimuth_deg" = 45 }

[[render]]
name = "still"
scene = "scenes/sea.toml"
overrides = { "water.g" = 0.8, sun.zenith_deg = 60 }
outputs = ["exr", "spectral_exr"]
reference = "ref.exr"
resolution = [320, 180]

[[render]]
name = "anim"
scene = "scenes/sea.toml"
frames = 3
time = [1.0, 2.0]

[[sweep]]
name = "zen"
scene = "scenes/sea.toml"
param = "sun.zenith_deg"
values = [10, 20.5]

[[render]]
scene = "scenes/dry.toml"
)";
  Job job = parseJob(text, f.job());
  EXPECT_EQ(job.name, "nightly");
  EXPECT_EQ(job.file, fs::path(f.job()).lexically_normal().string());
  EXPECT_EQ(job.output_dir, (f.dir / "out" / "here").string());
  EXPECT_EQ(job.device, "pocl:0");

  std::vector<std::string> names;
  for (const auto& it : job.items) names.push_back(it.name);
  // Renders first, in file order, then sweeps (each [[...]] array in order).
  const std::vector<std::string> expected = {"still", "anim_f0000", "anim_f0001", "anim_f0002", "dry",
                                             "zen_zenith_deg=10", "zen_zenith_deg=20.5"};
  EXPECT_EQ(names, expected);

  const RenderItem& still = job.items[0];
  EXPECT_EQ(still.scene_file, (f.dir / "scenes" / "sea.toml").string());
  EXPECT_EQ(still.reference, (f.dir / "ref.exr").string());
  EXPECT_EQ(still.outputs, (std::vector<std::string>{"exr", "spectral_exr"}));
  EXPECT_EQ(still.loc.line, 7);
  // Job-level overrides come first, then the item's (nested dotted keys flattened), then resolution.
  ASSERT_EQ(still.overrides.size(), 5u);
  EXPECT_EQ(still.overrides[0].key, "sun.azimuth_deg");
  EXPECT_EQ(still.overrides[0].loc.line, 5);
  EXPECT_EQ(findOverride(still, "water.g")->value_toml, "0.8");
  EXPECT_EQ(findOverride(still, "water.g")->loc.line, 10);
  EXPECT_EQ(findOverride(still, "sun.zenith_deg")->value_toml, "60");
  EXPECT_EQ(findOverride(still, "camera.width")->value_toml, "320");
  EXPECT_EQ(findOverride(still, "camera.height")->loc.line, 13);

  // Frames: t_f = t0 + f (t1 - t0) / (frames - 1), both ends included.
  const double times[] = {1.0, 1.5, 2.0};
  for (int fr = 0; fr < 3; ++fr) {
    const RenderItem& it = job.items[1 + fr];
    const Override* t = findOverride(it, "surface.time");
    ASSERT_NE(t, nullptr);
    EXPECT_EQ(t->loc.line, 19);
    Scene s = loadScene(it.scene_file, it.overrides);
    EXPECT_DOUBLE_EQ(s.surface.time, times[fr]);
    EXPECT_NEAR(s.sun.azimuth, 45 * std::numbers::pi / 180, 1e-12);
    EXPECT_EQ(it.outputs, (std::vector<std::string>{"exr", "png"}));  // default
  }

  // A render without name takes its scene's file stem.
  EXPECT_EQ(job.items[4].scene_file, (f.dir / "scenes" / "dry.toml").string());

  // Sweeps: one item per value, the override located at the value.
  const RenderItem& z2 = job.items[6];
  const Override* zo = findOverride(z2, "sun.zenith_deg");
  ASSERT_NE(zo, nullptr);
  EXPECT_EQ(zo->value_toml, "20.5");
  EXPECT_EQ(zo->loc.line, 25);
  Scene s = loadScene(z2.scene_file, z2.overrides);
  EXPECT_NEAR(s.sun.zenith, 20.5 * std::numbers::pi / 180, 1e-12);
  Scene still_scene = loadScene(still.scene_file, still.overrides);
  EXPECT_DOUBLE_EQ(still_scene.water.g, 0.8);
  EXPECT_EQ(still_scene.camera.width, 320);
}

TEST(JobParser, Defaults) {
  JobFiles f("defaults");
  Job job = parseJob("[[render]]\nscene = \"scenes/sea.toml\"\n", f.job());
  EXPECT_EQ(job.name, "job");  // the file stem
  EXPECT_EQ(job.output_dir, (fs::current_path() / "results" / "job").lexically_normal().string());
  EXPECT_EQ(job.device, "");
  ASSERT_EQ(job.items.size(), 1u);
  EXPECT_EQ(job.items[0].name, "sea");
  EXPECT_TRUE(job.items[0].overrides.empty());
  EXPECT_TRUE(job.items[0].reference.empty());
  EXPECT_EQ(job.items[0].outputs, (std::vector<std::string>{"exr", "png"}));
}

TEST(JobParser, LoadJobAndIsJobFile) {
  JobFiles f("files");
  f.write("job.toml", "[[sweep]]\nscene = \"scenes/sea.toml\"\nparam = \"water.jerlov\"\nvalues = [\"I\", \"IB\", \"9C\"]\n");
  Job job = loadJob(f.job());
  ASSERT_EQ(job.items.size(), 3u);
  EXPECT_EQ(job.items[2].name, "sea_jerlov=9C");
  EXPECT_EQ(job.items[2].overrides.back().value_toml, "\"9C\"");
  EXPECT_TRUE(isJobFile(f.job()));
  EXPECT_FALSE(isJobFile((f.dir / "scenes" / "sea.toml").string()));
  f.write("broken_job.toml", "[job]\nname = \n[[render]]\n");
  EXPECT_TRUE(isJobFile((f.dir / "broken_job.toml").string()));
  EXPECT_FALSE(isJobFile((f.dir / "missing.toml").string()));
  EXPECT_THROW(loadJob((f.dir / "missing.toml").string()), InputError);
  // The repository's quickstart job validates.
  Job quick = loadJob(std::string(SEASIM_SOURCE_DIR) + "/jobs/quickstart.toml");
  EXPECT_FALSE(quick.items.empty());
}

// ---------------------------------------------------------------------------------------------
// Bad jobs: each must fail with a message containing `expected`. Scene paths are relative to the
// job file in the temp folder; "sea.toml" there is valid, "broken.toml" has water.g = 3 on line 3.

namespace {

struct BadJob {
  const char* what;
  const char* toml;
  const char* expected;
};
// The case as gtest prints it (its name, not the struct's bytes).
void PrintTo(const BadJob& c, std::ostream* os) { *os << c.what; }

const BadJob kBadJobs[] = {
    {"typo'd key in [[render]]", "[[render]]\nscene = \"scenes/sea.toml\"\nframe = 3\n",
     "job.toml:3: key 'render[0].frame': unknown key; did you mean 'frames'?"},
    {"typo'd table", "[[renders]]\nscene = \"scenes/sea.toml\"\n",
     "job.toml:1: key 'renders': unknown key; did you mean 'render'?"},
    {"typo'd key in [job]", "[job]\noutput = \"x\"\n[[render]]\nscene = \"scenes/sea.toml\"\n",
     "job.toml:2: key 'job.output': unknown key; did you mean 'output_dir'?"},
    {"duplicate item names",
     "[[render]]\nname = \"a\"\nscene = \"scenes/sea.toml\"\n[[render]]\nname = \"a\"\nscene = \"scenes/sea.toml\"\n",
     "job.toml:5: key 'render[1].name': item name 'a' is used twice (also at "},
    {"duplicate name from a sweep", "[[sweep]]\nname = \"z\"\nscene = \"scenes/sea.toml\"\nparam = \"sun.zenith_deg\"\nvalues = [10,\n 10]\n",
     "job.toml:6: key 'sweep[0].values[1]': item name 'z_zenith_deg=10' is used twice"},
    {"bad sweep param", "[[sweep]]\nscene = \"scenes/sea.toml\"\nparam = \"sun.zenth_deg\"\nvalues = [10, 20]\n",
     "job.toml:4: key 'sun.zenth_deg': unknown key; did you mean 'zenith_deg'?"},
    {"bad sweep value", "[[sweep]]\nscene = \"scenes/sea.toml\"\nparam = \"water.g\"\nvalues = [0.5,\n  1.5]\n",
     "job.toml:5: key 'water.g': must satisfy |g| < 1, got 1.5"},
    {"sweep without values", "[[sweep]]\nscene = \"scenes/sea.toml\"\nparam = \"water.g\"\n",
     "job.toml:1: key 'sweep[0].values': missing"},
    {"sweep with empty values", "[[sweep]]\nscene = \"scenes/sea.toml\"\nparam = \"water.g\"\nvalues = []\n",
     "job.toml:4: key 'sweep[0].values': must not be empty"},
    {"sweep value making an unsafe name", "[[sweep]]\nscene = \"scenes/sea.toml\"\nparam = \"scene.name\"\nvalues = [\"a/b\"]\n",
     "job.toml:4: key 'sweep[0].values[0]': item name 'sea_name=a/b' is not a safe file name"},
    {"bad item override", "[[render]]\nscene = \"scenes/sea.toml\"\noverrides = { \"water.g\" = 1.5 }\n",
     "job.toml:3: key 'water.g': must satisfy |g| < 1, got 1.5"},
    {"unknown key in an override", "[[render]]\nscene = \"scenes/sea.toml\"\noverrides = { \"sun.zenith\" = 10 }\n",
     "job.toml:3: key 'sun.zenith': unknown key; did you mean 'zenith_deg'?"},
    {"bad job-level override", "[job]\noverrides = { \"camera.width\" = 0 }\n[[render]]\nscene = \"scenes/sea.toml\"\n",
     "job.toml:2: key 'camera.width': must be an integer in [1, 16384], got 0"},
    {"error inside the scene file", "[[render]]\nscene = \"scenes/broken.toml\"\n",
     "broken.toml:3: key 'water.g': must satisfy |g| < 1, got 3"},
    {"missing scene file", "[[render]]\nscene = \"scenes/nope.toml\"\n",
     "job.toml:2: key 'render[0].scene': file not found"},
    {"no scene key", "[[render]]\nname = \"x\"\n", "job.toml:1: key 'render[0].scene': missing"},
    {"scene is a number", "[[render]]\nscene = 5\n", "job.toml:2: key 'render[0].scene': expected a string, got an integer"},
    {"unknown output", "[[render]]\nscene = \"scenes/sea.toml\"\noutputs = [\"exr\", \"tiff\"]\n",
     "job.toml:3: key 'render[0].outputs[1]': unknown output 'tiff'"},
    {"output twice", "[[render]]\nscene = \"scenes/sea.toml\"\noutputs = [\"png\", \"png\"]\n",
     "job.toml:3: key 'render[0].outputs[1]': output 'png' is listed twice"},
    {"missing reference", "[[render]]\nscene = \"scenes/sea.toml\"\nreference = \"nope.exr\"\n",
     "job.toml:3: key 'render[0].reference': file not found"},
    {"frames 0", "[[render]]\nscene = \"scenes/sea.toml\"\nframes = 0\n",
     "job.toml:3: key 'render[0].frames': must be an integer in [1, 100000], got 0"},
    {"frames without time", "[[render]]\nscene = \"scenes/sea.toml\"\nframes = 4\n",
     "job.toml:3: key 'render[0].frames': frames > 1 needs time"},
    {"time reversed", "[[render]]\nscene = \"scenes/sea.toml\"\nframes = 4\ntime = [2, 1]\n",
     "job.toml:4: key 'render[0].time': t1 must be > t0"},
    {"frames on a scene without water", "[[render]]\nscene = \"scenes/dry.toml\"\nframes = 2\ntime = [0, 1]\n",
     "job.toml:4: key 'surface': needs a [water] table"},
    {"bad resolution", "[[render]]\nscene = \"scenes/sea.toml\"\nresolution = [0, 100]\n",
     "job.toml:3: key 'camera.width': must be an integer in [1, 16384], got 0"},
    {"unsafe item name", "[[render]]\nname = \"a b\"\nscene = \"scenes/sea.toml\"\n",
     "job.toml:2: key 'render[0].name': item name 'a b' is not a safe file name"},
    {"unsafe job name", "[job]\nname = \"../x\"\n[[render]]\nscene = \"scenes/sea.toml\"\n",
     "job.toml:2: key 'job.name': '../x' is not a safe folder name"},
    {"no items", "[job]\nname = \"empty\"\n", "job.toml:1: the job has no [[render]] or [[sweep]] tables"},
    {"[render] as a plain table", "[render]\nscene = \"scenes/sea.toml\"\n",
     "job.toml:1: key 'render': expected an array of tables ([[render]])"},
    {"TOML syntax error", "[[render]]\nscene = \"scenes/sea.toml\n", "job.toml:2: TOML syntax error"},
};

class BadJobTest : public ::testing::TestWithParam<BadJob> {};

}  // namespace

TEST_P(BadJobTest, FailsWithFileLineAndKey) {
  static const JobFiles files("bad");
  const BadJob& c = GetParam();
  std::string msg = errorOf(files, c.toml);
  ASSERT_FALSE(msg.empty()) << c.what << ": parsed without error";
  EXPECT_NE(msg.find(c.expected), std::string::npos)
      << c.what << "\n  expected: " << c.expected << "\n  got:      " << msg;
}

INSTANTIATE_TEST_SUITE_P(Table, BadJobTest, ::testing::ValuesIn(kBadJobs),
                         [](const ::testing::TestParamInfo<BadJob>& info) {
                           std::string n = std::to_string(info.index) + "_";
                           for (const char* p = info.param.what; *p; ++p)
                             n += std::isalnum(static_cast<unsigned char>(*p)) ? *p : '_';
                           return n;
                         });
