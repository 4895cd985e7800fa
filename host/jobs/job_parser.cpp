// job_parser.cpp — TOML job files -> Job: renders, frame ranges and sweeps expanded into a flat
// list of uniquely named items, each validated with its scene. Format: scenes/README.md ("Job
// files").
#include <cstdio>
#include <filesystem>
#include <limits>
#include <fstream>
#include <map>
#include <regex>
#include <sstream>

#include "jobs/job.h"
#include "jobs/job_sampling.h"
#include "scene/toml_limits.h"
#include "scene/toml_reader.h"
#include "util/error.h"
#include "util/paths.h"

namespace fs = std::filesystem;

namespace seasim {
namespace {

const std::vector<std::string> kOutputs = {"exr", "png", "spectral_exr", "npy"};

// Item and job names become file and folder names on every platform a farm may use.
bool safeFileName(const std::string& s) {
  if (s.empty() || s.size() > 200 || s[0] == '.' || s[0] == '-') return false;
  for (char c : s) {
    bool ok = std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
              c == '=' || c == '+';
    if (!ok) return false;
  }
  return true;
}
// Most items one job may expand to. Each item is validated with its scene and kept with its
// overrides (about 3 KB): a sweep of 10^6 values took 3.1 GB and 16 s in `validate`. Checked
// before a sweep or frame range is expanded. 100,000 frames is 69 minutes of film at 24 fps.
constexpr size_t kMaxJobItems = 100000;

const char* kSafeNameRule = "letters, digits and _ - . = + only, not starting with '.' or '-'";

// Names the runner keeps for itself in the output folder: the manifests (manifest.json,
// manifest-<i>of<N>.json) and their locks, and the farm's folder (shard plans, scripts, logs, the
// merged report). An item of that name would overwrite them.
bool reservedName(const std::string& s) {
  std::string lower;
  for (char c : s) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return lower.rfind("manifest", 0) == 0 || lower == "farm";
}

// A sweep value as it appears in an item name: strings bare, numbers shortest, arrays joined by _.
std::string nameText(const toml::node& n) {
  if (auto* s = n.as_string()) return s->get();
  if (auto* f = n.as_floating_point()) return formatNumber(f->get());
  if (auto* a = n.as_array()) {
    std::string out;
    for (size_t i = 0; i < a->size(); ++i) out += (i ? "_" : "") + nameText(*a->get(i));
    return out;
  }
  return valueText(n);
}

// An item before its scene is checked, with the node that gave it its name (for duplicate errors).
struct PendingItem {
  RenderItem item;
  const toml::node* name_node;
  std::string name_key;
};

class JobParser {
 public:
  JobParser(const TomlSource& src, Job& job) : src_(src), job_(job) {}

  std::vector<PendingItem> parse(const toml::table& root_table) {
    TableReader root(src_, root_table, "");
    for (const char* k : {"job", "render", "sweep", "sample"}) root.has(k);
    root.finish();

    job_.name = fs::path(job_.file).stem().string();
    toml::table empty;
    const toml::table* jt = root.subtable("job");
    TableReader r(src_, jt ? *jt : empty, "job");
    job_.name = r.string("name", job_.name);
    r.check(safeFileName(job_.name), "name",
            "'" + job_.name + "' is not a safe folder name (" + kSafeNameRule + ")");
    if (r.has("output_dir")) {
      std::string dir = r.string("output_dir", "");
      r.check(!dir.empty(), "output_dir", "must not be empty");
      job_.output_dir = resolveRelativeTo(job_.file, dir);
      const std::string problem = outputDirProblem(job_.output_dir);
      r.check(problem.empty(), "output_dir", "cannot write results to '" + job_.output_dir + "': " + problem);
    } else {
      job_.output_dir = (fs::current_path() / "results" / job_.name).lexically_normal().string();
    }
    job_.device = r.string("device", "");
    overrides(r, job_overrides_);
    r.finish();

    std::vector<PendingItem> items;
    for (const auto& [i, t] : root.arrayOfTables("render")) render(*t, i, items);
    for (const auto& [i, t] : root.arrayOfTables("sweep")) sweep(*t, i, items);
    if (const toml::table* t = root.subtable("sample")) sample(*t, items);
    if (items.empty())
      src_.fail(&root_table, "", "the job has no [[render]] or [[sweep]] tables (nor [sample]), so nothing to do");
    return items;
  }

 private:
  const TomlSource& src_;
  Job& job_;
  std::vector<Override> job_overrides_;


  // overrides = { "sun.zenith_deg" = 40, water.g = 0.8 }: quoted dotted keys and TOML's own
  // nested (dotted) keys both end up as one Override per leaf value, located at that value.
  void flatten(const toml::table& t, const std::string& prefix, std::vector<Override>& out) {
    for (auto&& [k, v] : t) {
      std::string key = prefix.empty() ? std::string(k.str()) : prefix + "." + std::string(k.str());
      if (auto* sub = v.as_table())
        flatten(*sub, key, out);
      else
        out.push_back(Override{key, valueText(v), src_.locOf(&v)});
    }
  }
  void overrides(TableReader& r, std::vector<Override>& out) {
    if (const toml::table* t = r.subtable("overrides")) flatten(*t, "", out);
  }

  static std::string tooMany(size_t before, size_t more) {
    return std::to_string(more) + " items (" + std::to_string(before) + " before it) are more than a job may hold (" +
           std::to_string(kMaxJobItems) + "); split the sweep or frames over several job files";
  }

  std::string existingFile(TableReader& r, const char* key) {
    std::string p = r.string(key, "");
    r.check(!p.empty(), key, "must not be empty");
    std::string abs = resolveRelativeTo(job_.file, p);
    const std::string problem = inputFileProblem(abs);
    r.check(problem.empty(), key, problem);
    return abs;
  }

  // The fields [[render]] and [[sweep]] share: scene, name, overrides, outputs, reference.
  PendingItem common(TableReader& r, const toml::table& t) {
    PendingItem p;
    RenderItem& item = p.item;
    item.loc = src_.locOf(&t);
    r.check(r.has("scene"), "scene",
            "missing: the scene file to render (relative to the job file)");
    item.scene_file = existingFile(r, "scene");
    item.name = r.string("name", fs::path(item.scene_file).stem().string());
    p.name_node = t.get("name") ? t.get("name") : static_cast<const toml::node*>(&t);
    p.name_key = r.path("name");
    item.overrides = job_overrides_;
    overrides(r, item.overrides);
    item.outputs = {"exr", "png"};
    if (const toml::node* n = r.get("outputs")) {
      const toml::array* a = n->as_array();
      if (!a) r.fail("outputs", "expected an array of strings, got " + typeName(*n));
      r.check(!a->empty(), "outputs", "must name at least one of exr, png, spectral_exr, npy");
      item.outputs.clear();
      for (size_t i = 0; i < a->size(); ++i) {
        const toml::node& e = *a->get(i);
        std::string where = r.path("outputs") + "[" + std::to_string(i) + "]";
        const auto* s = e.as_string();
        if (!s) src_.fail(&e, where, "expected a string, got " + typeName(e));
        if (std::find(kOutputs.begin(), kOutputs.end(), s->get()) == kOutputs.end())
          src_.fail(&e, where,
                    "unknown output '" + s->get() + "'" + suggestion(s->get(), kOutputs));
        if (std::find(item.outputs.begin(), item.outputs.end(), s->get()) != item.outputs.end())
          src_.fail(&e, where, "output '" + s->get() + "' is listed twice");
        item.outputs.push_back(s->get());
      }
    }
    if (r.has("reference")) {
      item.reference = existingFile(r, "reference");
      item.reference_loc = src_.locOf(r.get("reference"));
      item.reference_key = r.path("reference");
    }
    return p;
  }

  void render(const toml::table& t, size_t index, std::vector<PendingItem>& items) {
    TableReader r(src_, t, "render[" + std::to_string(index) + "]");
    PendingItem base = common(r, t);

    // resolution = [w, h]: shorthand for camera.width / camera.height overrides.
    if (const toml::node* n = r.get("resolution")) {
      const toml::array* a = n->as_array();
      r.check(a && a->size() == 2, "resolution", "expected [width, height] in pixels");
      const char* keys[] = {"camera.width", "camera.height"};
      for (size_t i = 0; i < 2; ++i)
        base.item.overrides.push_back(
            Override{keys[i], valueText(*a->get(i)), src_.locOf(a->get(i))});
    }

    long long frames = r.integerIn("frames", 1, 1, 100000);
    const toml::node* time_node = r.get("time");
    std::vector<double> time;
    if (time_node) {
      time = r.numbers("time");
      r.check(time.size() == 2, "time", "expected [t0, t1] in seconds");
      if (frames > 1) r.check(time[1] > time[0], "time", "t1 must be > t0");
    } else {
      r.check(frames == 1, "frames", "frames > 1 needs time = [t0, t1] (seconds of surface time)");
    }
    r.finish();

    r.check(items.size() + static_cast<size_t>(frames) <= kMaxJobItems, "frames", tooMany(items.size(), frames));
    SourceLoc time_loc = src_.locOf(time_node);
    if (frames == 1) {
      if (time_node)
        base.item.overrides.push_back(
            Override{"surface.time", valueText(toml::value<double>(time[0])), time_loc});
      items.push_back(base);
      return;
    }
    // Frame f at t0 + f (t1 - t0) / (frames - 1): both ends included.
    for (long long f = 0; f < frames; ++f) {
      PendingItem p = base;
      char suffix[32];
      std::snprintf(suffix, sizeof suffix, "_f%04lld", f);
      p.item.name += suffix;
      double t_f =
          time[0] + (time[1] - time[0]) * static_cast<double>(f) / static_cast<double>(frames - 1);
      p.item.overrides.push_back(
          Override{"surface.time", valueText(toml::value<double>(t_f)), time_loc});
      items.push_back(p);
    }
  }

  void sweep(const toml::table& t, size_t index, std::vector<PendingItem>& items) {
    TableReader r(src_, t, "sweep[" + std::to_string(index) + "]");
    PendingItem base = common(r, t);
    r.check(r.has("param"), "param",
            "missing: the dotted scene key to sweep, e.g. \"sun.zenith_deg\"");
    std::string param = r.string("param", "");
    r.check(!param.empty(), "param", "must not be empty");
    r.check(r.has("values"), "values", "missing: the array of values to give " + param);
    const toml::node* vn = r.get("values");
    const toml::array* values = vn->as_array();
    if (!values) r.fail("values", "expected an array, got " + typeName(*vn));
    r.check(!values->empty(), "values", "must not be empty");
    r.check(items.size() + values->size() <= kMaxJobItems, "values", tooMany(items.size(), values->size()));
    r.finish();

    // Item "<name>_<last part of param>=<value>"; the override sits at the value, so a bad value
    // (or a param the scene does not know) is reported on its line.
    std::string last =
        param.substr(param.rfind('.') == std::string::npos ? 0 : param.rfind('.') + 1);
    for (size_t i = 0; i < values->size(); ++i) {
      const toml::node& v = *values->get(i);
      PendingItem p = base;
      p.item.name = base.item.name + "_" + last + "=" + nameText(v);
      p.item.overrides.push_back(Override{param, valueText(v), src_.locOf(&v)});
      p.name_node = &v;
      p.name_key = r.path("values") + "[" + std::to_string(i) + "]";
      items.push_back(p);
    }
  }

  // [sample]: `count` items named <name>_s<index>, each with its [sample.keys] drawn for its index
  // (jobs/job_sampling.h). An override sits at its key's distribution, so a value the scene
  // rejects is reported on that line.
  void sample(const toml::table& t, std::vector<PendingItem>& items) {
    TableReader r(src_, t, "sample");
    PendingItem base = common(r, t);
    r.check(r.has("seed"), "seed", "missing: the integer every draw derives from (the same seed gives the same items)");
    const long long seed = r.integerIn("seed", 0, 0, std::numeric_limits<long long>::max());
    r.check(r.has("count"), "count", "missing: how many items to draw");
    const long long count = r.integerIn("count", 1, 1, static_cast<long long>(kMaxJobItems));
    r.check(items.size() + static_cast<size_t>(count) <= kMaxJobItems, "count", tooMany(items.size(), count));
    const toml::table* keys = r.subtable("keys");
    r.check(keys && !keys->empty(), "keys",
            "missing: [sample.keys] with a distribution per scene key, e.g. \"sun.zenith_deg\" = { uniform = [20, 60] }");
    const std::vector<SampledKey> sampled = readSampledKeys(src_, *keys, r.path("keys"));
    r.finish();

    size_t width = 4;  // zero-padded so that item names sort in draw order
    for (long long n = count - 1; n >= 10000; n /= 10) ++width;
    for (long long i = 0; i < count; ++i) {
      PendingItem p = base;
      const std::string index = std::to_string(i);
      p.item.name += "_s" + std::string(width > index.size() ? width - index.size() : 0, '0') + index;
      p.item.sample_seed = static_cast<std::uint64_t>(seed);
      p.item.sample_index = static_cast<std::uint64_t>(i);
      for (const SampledKey& k : sampled) {
        Override o{k.key, sampledValue(k, p.item.sample_seed, p.item.sample_index), k.loc};
        p.item.overrides.push_back(o);
        p.item.sampled.push_back(std::move(o));
      }
      items.push_back(std::move(p));
    }
  }
};

}  // namespace

Job parseJob(const std::string& toml_text, const std::string& path, const JobLoadOptions& options) {
  toml::table root = parseTomlText(toml_text, path);
  TomlSource src(path);
  for (const std::string& key : options.ignored_keys) src.ignore(key);
  Job job;
  job.file = fs::absolute(path).lexically_normal().string();
  std::vector<PendingItem> items = JobParser(src, job).parse(root);

  std::map<std::string, SourceLoc> seen;
  for (const PendingItem& p : items) {
    SourceLoc loc = src.locOf(p.name_node);
    if (!safeFileName(p.item.name))
      throw InputError(
          loc.file, loc.line, p.name_key,
          "item name '" + p.item.name + "' is not a safe file name (" + kSafeNameRule + ")");
    if (reservedName(p.item.name))
      throw InputError(loc.file, loc.line, p.name_key,
                       "item name '" + p.item.name +
                           "' is reserved: names starting with 'manifest', and 'farm', are the job's own files; rename the item");
    auto [it, fresh] = seen.emplace(p.item.name, loc);
    if (!fresh)
      throw InputError(loc.file, loc.line, p.name_key,
                       "item name '" + p.item.name + "' is used twice (also at " + it->second.file +
                           ":" + std::to_string(it->second.line) + "); names must be unique");
  }
  // Validate every item's scene with its overrides now, so a bad job fails before anything renders.
  for (PendingItem& p : items) {
    p.item.overrides.insert(p.item.overrides.end(), options.extra_overrides.begin(), options.extra_overrides.end());
    if (options.check_scenes) loadScene(p.item.scene_file, p.item.overrides);
    job.items.push_back(p.item);
  }
  return job;
}

Job loadJob(const std::string& path, const JobLoadOptions& options) {
  std::ifstream in(path, std::ios::binary);
  if (std::error_code ec; !in || fs::is_directory(path, ec)) throw InputError(path, 1, "", "cannot open job file");
  std::stringstream text;
  text << in.rdbuf();
  return parseJob(text.str(), path, options);
}

bool isJobFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return false;
  std::stringstream text;
  text << in.rdbuf();
  checkTomlLimits(text.str(), path);  // toml++ would recurse into a key of thousands of parts
  try {
    toml::table t = toml::parse(text.str(), std::string_view(path));
    return t.contains("job") || t.contains("render") || t.contains("sweep") || t.contains("sample");
  } catch (const toml::parse_error&) {
    // Broken TOML: decide from the table headers so the right parser reports the syntax error.
    static const std::regex header(R"(^\s*(\[\s*(job|sample)\s*\]|\[\[\s*(render|sweep)\s*\]\]))");
    std::string line;
    std::istringstream lines(text.str());
    while (std::getline(lines, line))
      if (std::regex_search(line, header)) return true;
    return false;
  }
}

}  // namespace seasim
