#include "jobs/job_sampling.h"

#include <cmath>
#include <limits>
#include <map>

#include "math/portable_sampling.h"

namespace seasim {

namespace {

const std::vector<std::string> kKinds = {"uniform", "log_uniform", "normal", "integer", "choice"};
constexpr double kInf = std::numeric_limits<double>::infinity();

// A number node (integer or float), else an error at it.
double numberAt(const TomlSource& src, const toml::node& n, const std::string& where) {
  if (auto* i = n.as_integer()) return static_cast<double>(i->get());
  if (auto* f = n.as_floating_point()) {
    if (!std::isfinite(f->get())) src.fail(&n, where, "must be finite");
    return f->get();
  }
  src.fail(&n, where, "expected a number, got " + typeName(n));
}

// One bound of a pair: a number, or an array of numbers (one per component of the key's value).
std::vector<double> boundAt(const TomlSource& src, const toml::node& n, const std::string& where, bool& is_array) {
  if (const toml::array* a = n.as_array()) {
    if (a->empty()) src.fail(&n, where, "must not be empty");
    std::vector<double> v;
    for (size_t i = 0; i < a->size(); ++i) v.push_back(numberAt(src, *a->get(i), where + "[" + std::to_string(i) + "]"));
    is_array = true;
    return v;
  }
  is_array = false;
  return {numberAt(src, n, where)};
}

// `kind = [first, second]`: two numbers, or two arrays of numbers of one length.
void pairAt(const TomlSource& src, const toml::node& n, const std::string& where, const std::string& what,
            std::vector<double>& first, std::vector<double>& second, bool& is_array) {
  const toml::array* a = n.as_array();
  if (!a || a->size() != 2) src.fail(&n, where, "expected " + what);
  bool array0 = false, array1 = false;
  first = boundAt(src, *a->get(0), where + "[0]", array0);
  second = boundAt(src, *a->get(1), where + "[1]", array1);
  if (array0 != array1 || first.size() != second.size())
    src.fail(&n, where, "both must be numbers, or arrays of the same length (one value per component)");
  is_array = array0;
}

std::string component(const SampledKey& k, size_t i) {
  return k.is_array ? " (component " + std::to_string(i) + ")" : "";
}

SampledKey readDistribution(const TomlSource& src, const toml::table& t, const std::string& key,
                            const std::string& path) {
  TableReader r(src, t, path);
  SampledKey k;
  k.key = key;
  k.loc = src.locOf(&t);
  std::string kind;
  for (size_t i = 0; i < kKinds.size(); ++i) {
    if (!r.has(kKinds[i])) continue;
    if (!kind.empty())
      r.fail(kKinds[i], "give one distribution per key, not both '" + kind + "' and '" + kKinds[i] + "'");
    kind = kKinds[i];
    k.kind = static_cast<SampledKey::Kind>(i);
  }
  const toml::node* n = kind.empty() ? nullptr : r.get(kind);
  const std::string where = r.path(kind);
  if (kind == "uniform" || kind == "log_uniform" || kind == "integer") {
    pairAt(src, *n, where, "[lo, hi]", k.lo, k.hi, k.is_array);
    for (size_t i = 0; i < k.lo.size(); ++i) {
      r.check(k.lo[i] < k.hi[i], kind, "lo must be < hi" + component(k, i));
      if (kind == "log_uniform")
        r.check(k.lo[i] > 0, kind, "lo must be > 0: a log-uniform draw spans ln lo .. ln hi" + component(k, i));
      if (kind == "integer") {
        r.check(k.lo[i] == std::floor(k.lo[i]) && k.hi[i] == std::floor(k.hi[i]), kind,
                "bounds must be integers" + component(k, i));
        r.check(std::fabs(k.lo[i]) <= 0x1p52 && std::fabs(k.hi[i]) <= 0x1p52, kind,
                "bounds must lie within ±2^52" + component(k, i));
      }
    }
  } else if (kind == "normal") {
    pairAt(src, *n, where, "[mean, sd]", k.mean, k.sd, k.is_array);
    k.lo.assign(k.mean.size(), -kInf);
    k.hi.assign(k.mean.size(), kInf);
    if (const toml::node* w = r.get("within")) {
      bool arr = false;
      pairAt(src, *w, r.path("within"), "[lo, hi]: the bounds the draw is truncated to", k.lo, k.hi, arr);
      r.check(arr == k.is_array && k.lo.size() == k.mean.size(), "within",
              "must have the shape of normal's [mean, sd] (numbers, or arrays of the same length)");
    }
    for (size_t i = 0; i < k.mean.size(); ++i) {
      r.check(k.sd[i] > 0, kind, "sd must be > 0" + component(k, i));
      r.check(k.lo[i] < k.hi[i], "within", "lo must be < hi" + component(k, i));
      // Beyond 30 sd the normal has no mass a double can hold: the bounds would be a constant.
      const double near = std::min(std::fabs(k.lo[i] - k.mean[i]), std::fabs(k.hi[i] - k.mean[i]));
      const bool mean_inside = k.lo[i] <= k.mean[i] && k.mean[i] <= k.hi[i];
      r.check(mean_inside || near <= 30 * k.sd[i], "within",
              "the bounds lie more than 30 sd from the mean, where the normal has no probability left" +
                  component(k, i));
    }
  } else if (kind == "choice") {
    const toml::array* a = n->as_array();
    if (!a) r.fail(kind, "expected an array of values to choose from, got " + typeName(*n));
    r.check(!a->empty(), kind, "must list at least one value");
    for (size_t i = 0; i < a->size(); ++i) {
      const toml::node& v = *a->get(i);
      if (v.is_table() || (v.is_array() && v.as_array()->is_array_of_tables()))
        src.fail(&v, where + "[" + std::to_string(i) + "]", "expected a value (string, number, boolean or array), got a table");
      k.choices.push_back(valueText(v));
    }
    double total = 0;
    if (const toml::node* w = r.get("weights")) {
      const toml::array* wa = w->as_array();
      if (!wa || wa->size() != a->size())
        r.fail("weights", "expected an array of " + std::to_string(a->size()) + " numbers, one per choice");
      for (size_t i = 0; i < wa->size(); ++i) {
        const std::string wi = r.path("weights") + "[" + std::to_string(i) + "]";
        const double weight = numberAt(src, *wa->get(i), wi);
        if (!(weight > 0)) src.fail(wa->get(i), wi, "must be > 0");
        total += weight;
        k.cumulative.push_back(total);
      }
    } else {
      for (size_t i = 0; i < a->size(); ++i) k.cumulative.push_back(static_cast<double>(i + 1));
    }
  } else {
    src.fail(&t, path,
             "names no distribution: give one of uniform = [lo, hi], log_uniform = [lo, hi], normal = [mean, sd] "
             "(with within = [lo, hi]), integer = [lo, hi], choice = [values...]");
  }
  r.finish();  // `within` outside normal, `weights` outside choice, typos: unknown keys
  return k;
}

// "water.jerlov" = {...} and water.jerlov = {...} (a TOML nested key) both name the scene key
// "water.jerlov": a table holding a distribution's name is a distribution, any other table nests.
void collect(const TomlSource& src, const toml::table& t, const std::string& prefix, const std::string& path,
             std::vector<SampledKey>& out, std::map<std::string, SourceLoc>& seen) {
  for (auto&& [name, v] : t) {
    const std::string key = prefix.empty() ? std::string(name.str()) : prefix + "." + std::string(name.str());
    const std::string where = path + "." + std::string(name.str());
    if (src.ignored(where)) continue;
    const toml::table* sub = v.as_table();
    if (!sub)
      src.fail(&v, where,
               "expected a distribution, e.g. " + std::string(name.str()) +
                   " = { uniform = [lo, hi] }; a fixed value belongs in [sample] overrides");
    bool is_distribution = false, kind_ignored = false;
    for (const std::string& kind : kKinds) {
      is_distribution = is_distribution || sub->contains(kind);
      kind_ignored = kind_ignored || src.ignored(where + "." + kind);
    }
    if (kind_ignored) continue;  // `validate` looking past an error in this distribution: skip the key
    if (!is_distribution && !sub->empty() && sub->begin()->second.is_table()) {
      collect(src, *sub, key, where, out, seen);
      continue;
    }
    auto [it, fresh] = seen.emplace(key, src.locOf(sub));
    if (!fresh)
      src.fail(sub, where, "'" + key + "' is sampled twice (also at " + it->second.file + ":" +
                               std::to_string(it->second.line) + ")");
    out.push_back(readDistribution(src, *sub, key, where));
  }
}

std::string numberText(const SampledKey& k, double x) {
  return k.kind == SampledKey::Kind::Integer ? std::to_string(static_cast<long long>(x)) : floatText(x);
}

}  // namespace

std::vector<SampledKey> readSampledKeys(const TomlSource& src, const toml::table& keys, const std::string& path) {
  std::vector<SampledKey> out;
  std::map<std::string, SourceLoc> seen;
  collect(src, keys, "", path, out, seen);
  return out;
}

std::string sampledValue(const SampledKey& k, std::uint64_t seed, std::uint64_t index) {
  const std::uint64_t key_hash = nameHash(k.key);
  if (k.kind == SampledKey::Kind::Choice)
    return k.choices[weightedIndex(unitOpen(drawBits(seed, index, key_hash, 0)), k.cumulative)];
  std::string text;
  for (size_t i = 0; i < k.lo.size(); ++i) {
    const double u = unitOpen(drawBits(seed, index, key_hash, i));
    double x = 0;
    switch (k.kind) {
      case SampledKey::Kind::Uniform:
        x = uniformIn(u, k.lo[i], k.hi[i]);
        break;
      case SampledKey::Kind::LogUniform:
        x = logUniformIn(u, k.lo[i], k.hi[i]);
        break;
      case SampledKey::Kind::Normal:
        x = normalIn(u, k.mean[i], k.sd[i], k.lo[i], k.hi[i]);
        break;
      case SampledKey::Kind::Integer:
        x = static_cast<double>(integerIn(u, static_cast<long long>(k.lo[i]), static_cast<long long>(k.hi[i])));
        break;
      case SampledKey::Kind::Choice:
        break;
    }
    text += (i ? ", " : "") + numberText(k, x);
  }
  return k.is_array ? "[" + text + "]" : text;
}

}  // namespace seasim
