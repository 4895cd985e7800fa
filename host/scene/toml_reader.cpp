#include "scene/toml_reader.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "scene/toml_limits.h"
#include "util/error.h"

namespace seasim {

// ---------------------------------------------------------------------------------------------
// TomlSource

SourceLoc TomlSource::locOf(const toml::node* n) const {
  if (n) {
    auto it = override_locs_.find(n);
    if (it != override_locs_.end()) return it->second;
    int line = static_cast<int>(n->source().begin.line);
    return {file_, std::max(line, 1)};
  }
  return {file_, 1};
}

void TomlSource::fail(const toml::node* n, const std::string& key,
                      const std::string& message) const {
  SourceLoc loc = locOf(n);
  throw InputError(loc.file, loc.line, key, message);
}

void TomlSource::markOverride(const toml::node& n, const SourceLoc& loc) {
  override_locs_[&n] = loc;
  if (auto* t = n.as_table()) {
    for (auto&& [k, v] : *t) markOverride(v, loc);
  } else if (auto* a = n.as_array()) {
    for (auto& v : *a) markOverride(v, loc);
  }
}

void TomlSource::forget(const toml::node& n) {
  override_locs_.erase(&n);
  if (auto* t = n.as_table()) {
    for (auto&& [k, v] : *t) forget(v);
  } else if (auto* a = n.as_array()) {
    for (auto& v : *a) forget(v);
  }
}

// ---------------------------------------------------------------------------------------------
// Parsing and overrides

toml::table parseTomlText(std::string_view text, const std::string& file) {
  checkTomlLimits(text, file);
  try {
    return toml::parse(text, std::string_view(file));
  } catch (const toml::parse_error& e) {
    int line = std::max(static_cast<int>(e.source().begin.line), 1);
    throw InputError(file, line, "", "TOML syntax error: " + std::string(e.description()));
  }
}

namespace {

struct PathSegment {
  std::string name;
  long index = -1;  // >= 0 for "name[index]"
};

// "objects[1].radius" -> {objects,1}, {radius}. Quoted keys are not supported.
std::vector<PathSegment> splitKeyPath(const Override& o) {
  std::vector<PathSegment> out;
  auto bad = [&](const std::string& why) -> std::vector<PathSegment> {
    throw InputError(o.loc.file, o.loc.line, o.key, "cannot use this override key: " + why);
  };
  if (std::count(o.key.begin(), o.key.end(), '.') >= kMaxTomlKeyParts) {
    // The key itself would be a page long in the message: its start is enough to find it.
    const std::string start = o.key.substr(0, 40) + "...";
    throw InputError(o.loc.file, o.loc.line, start,
                     "cannot use this override key: it has more than " + std::to_string(kMaxTomlKeyParts) +
                         " parts; scene keys have a few");
  }
  std::stringstream ss(o.key);
  std::string part;
  while (std::getline(ss, part, '.')) {
    PathSegment seg;
    size_t br = part.find('[');
    seg.name = part.substr(0, br);
    if (br != std::string::npos) {
      if (part.back() != ']') return bad("expected 'name[index]' in '" + part + "'");
      std::string idx = part.substr(br + 1, part.size() - br - 2);
      if (idx.empty() || !std::all_of(idx.begin(), idx.end(), ::isdigit))
        return bad("the index in '" + part + "' must be a non-negative integer");
      // No scene has a million objects or lights; longer digit strings would overflow stol.
      if (idx.size() > 6) return bad("the index in '" + part + "' is too large (at most 999999)");
      seg.index = std::stol(idx);
    }
    bool ok = !seg.name.empty() && std::all_of(seg.name.begin(), seg.name.end(), [](char c) {
      return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
    });
    if (!ok) return bad("'" + part + "' is not a plain key (letters, digits, _ and -)");
    out.push_back(seg);
  }
  if (out.empty() || o.key.back() == '.') return bad("empty key");
  if (out.back().index >= 0) return bad("it must end in a key, not an array index");
  return out;
}

}  // namespace

void applyOverride(toml::table& root, const Override& o, TomlSource& source) {
  std::vector<PathSegment> segs = splitKeyPath(o);

  checkTomlLimits(o.value_toml, o.loc.file, o.loc.line);
  toml::table parsed;
  try {
    parsed = toml::parse("v = " + o.value_toml, std::string_view(o.loc.file));
  } catch (const toml::parse_error& e) {
    throw InputError(o.loc.file, o.loc.line, o.key,
                     "cannot read override value '" + o.value_toml +
                         "' as TOML: " + std::string(e.description()));
  }
  if (parsed.size() != 1 || !parsed.contains("v"))
    throw InputError(o.loc.file, o.loc.line, o.key,
                     "override value '" + o.value_toml + "' must be a single TOML value");

  std::string walked;
  toml::table* cur = &root;
  for (size_t i = 0; i + 1 < segs.size(); ++i) {
    const PathSegment& s = segs[i];
    walked += (walked.empty() ? "" : ".") + s.name;
    toml::node* n = cur->get(s.name);
    if (s.index >= 0) {
      toml::array* arr = n ? n->as_array() : nullptr;
      size_t count = arr ? arr->size() : 0;
      if (!arr || static_cast<size_t>(s.index) >= count)
        throw InputError(o.loc.file, o.loc.line, o.key,
                         "the scene has no " + walked + "[" + std::to_string(s.index) +
                             "] (it has " + std::to_string(count) + "; indices start at 0)");
      walked += "[" + std::to_string(s.index) + "]";
      cur = (*arr)[static_cast<size_t>(s.index)].as_table();
      if (!cur) throw InputError(o.loc.file, o.loc.line, o.key, "'" + walked + "' is not a table");
      continue;
    }
    if (!n || !n->is_table()) {
      // Absent: create it. A value in the way (e.g. albedo = 0.3 overridden by its spectrum
      // form) is replaced, so the override wins as it would for a leaf.
      if (n) source.forget(*n);
      auto [it, inserted] = cur->insert_or_assign(s.name, toml::table{});
      source.markOverride(it->second, o.loc);
      n = &it->second;
    }
    cur = n->as_table();
  }

  const std::string& leaf = segs.back().name;
  if (toml::node* old = cur->get(leaf)) source.forget(*old);
  toml::node& value = *parsed.get("v");
  toml::node* inserted = nullptr;
  value.visit([&](auto& v) { inserted = &cur->insert_or_assign(leaf, v).first->second; });
  source.markOverride(*inserted, o.loc);
}

// ---------------------------------------------------------------------------------------------
// Helpers

std::string typeName(const toml::node& n) {
  switch (n.type()) {
    case toml::node_type::table:
      return "a table";
    case toml::node_type::array:
      return "an array";
    case toml::node_type::string:
      return "a string";
    case toml::node_type::integer:
      return "an integer";
    case toml::node_type::floating_point:
      return "a floating-point number";
    case toml::node_type::boolean:
      return "a boolean";
    case toml::node_type::date:
      return "a date";
    case toml::node_type::time:
      return "a time";
    case toml::node_type::date_time:
      return "a date-time";
    default:
      return "nothing";
  }
}

std::string formatNumber(double v) {
  char buf[64];
  auto res = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, res.ptr);
}

std::string floatText(double v) {
  std::string s = formatNumber(v);
  // Keep it a float in TOML ("40" would read back as an integer).
  if (s.find_first_of(".eE") == std::string::npos) s += ".0";
  return s;
}

std::string valueText(const toml::node& n) {
  if (auto* f = n.as_floating_point()) {
    double v = f->get();
    if (!std::isfinite(v)) return std::isnan(v) ? "nan" : (v > 0 ? "inf" : "-inf");
    return floatText(v);
  }
  if (auto* str = n.as_string()) {
    // A TOML basic string: "..." with \ " and control characters escaped.
    std::string s = "\"";
    for (char ch : str->get()) {
      unsigned char u = static_cast<unsigned char>(ch);
      if (ch == '"' || ch == '\\') {
        s += '\\';
        s += ch;
      } else if (u < 0x20 || u == 0x7f) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04X", u);
        s += buf;
      } else {
        s += ch;
      }
    }
    return s + "\"";
  }
  if (auto* a = n.as_array()) {
    std::string s = "[";
    for (size_t i = 0; i < a->size(); ++i) s += (i ? ", " : "") + valueText(*a->get(i));
    return s + "]";
  }
  if (auto* t = n.as_table()) {
    std::string s = "{";
    bool first = true;
    for (auto&& [k, v] : *t) {
      s += (first ? " " : ", ") + std::string(k.str()) + " = " + valueText(v);
      first = false;
    }
    return s + " }";
  }
  std::ostringstream os;
  n.visit([&](auto& v) { os << v; });
  return os.str();
}

namespace {

size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) prev[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    cur[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      bool same = std::tolower(static_cast<unsigned char>(a[i - 1])) ==
                  std::tolower(static_cast<unsigned char>(b[j - 1]));
      cur[j] = std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (same ? 0 : 1)});
    }
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

}  // namespace

std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_d = static_cast<size_t>(-1);
  for (const auto& c : candidates) {
    size_t d = editDistance(word, c);
    // A prefix ("zenith" for "zenith_deg") counts as close.
    if (word.size() >= 3 && (c.rfind(word, 0) == 0 || word.rfind(c, 0) == 0))
      d = std::min<size_t>(d, 1);
    if (d < best_d) best_d = d, best = c;
  }
  size_t limit = std::max<size_t>(2, word.size() / 3);
  return best_d <= limit ? best : "";
}

std::string suggestion(const std::string& word, const std::vector<std::string>& candidates,
                       size_t max_list) {
  std::string close = closestMatch(word, candidates);
  if (!close.empty()) return "; did you mean '" + close + "'?";
  if (candidates.empty()) return "";
  // A part of a long name ("canon_5d" of "camspec_canon_5dmarkii").
  std::vector<std::string> containing;
  for (const auto& c : candidates)
    if (word.size() >= 3 && c.find(word) != std::string::npos) containing.push_back(c);
  if (!containing.empty() && containing.size() <= 5) {
    std::string s = "; did you mean ";
    for (size_t i = 0; i < containing.size(); ++i) s += (i ? " or '" : "'") + containing[i] + "'";
    return s + "?";
  }
  std::string s = "; valid: ";
  for (size_t i = 0; i < candidates.size() && i < max_list; ++i)
    s += (i ? ", " : "") + candidates[i];
  if (candidates.size() > max_list) s += ", ... (" + std::to_string(candidates.size()) + " in all)";
  return s;
}

// ---------------------------------------------------------------------------------------------
// TableReader

TableReader::TableReader(const TomlSource& source, const toml::table& table, std::string path,
                         std::string note)
    : source_(source), table_(table), path_(std::move(path)), note_(std::move(note)) {}

std::string TableReader::path(std::string_view key) const {
  return path_.empty() ? std::string(key) : path_ + "." + std::string(key);
}

const toml::node* TableReader::get(std::string_view key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.emplace_back(key);
  if (source_.ignored(path(key))) return nullptr;
  return table_.get(key);
}

std::string_view TableReader::renamed(std::string_view key, std::string_view earlier) {
  const bool now = get(key) != nullptr, before = get(earlier) != nullptr;
  if (now && before)
    fail(earlier, "is the earlier name of '" + std::string(key) + "'; give the value once, as '" + std::string(key) + "'");
  return before ? earlier : key;
}

void TableReader::fail(std::string_view key, const std::string& message) const {
  const toml::node* n = table_.get(key);
  source_.fail(n ? n : &table_, path(key), message);
}

namespace {

// The kernels compute in single precision (largest value 3.4e38). A finite double such as 1e300
// would be infinite there, and 1e38 overflows at the first product, which showed as NaN images
// reported as a bug. Every number in a file must lie within these magnitudes (or be 0), leaving
// twenty orders of magnitude of head room for the products a kernel forms.
constexpr double kMaxMagnitude = 1e15;
constexpr double kMinMagnitude = 1e-15;

// "" when v is usable, else the reason.
std::string magnitudeProblem(double v) {
  if (!std::isfinite(v)) return "must be a finite number";
  const double a = std::fabs(v);
  if (a > kMaxMagnitude)
    return "is " + formatNumber(v) +
           ", too large for the single-precision kernels (they overflow): |value| must be <= 1e15";
  if (a != 0 && a < kMinMagnitude)
    return "is " + formatNumber(v) +
           ", too small for the single-precision kernels (it would become 0): use 0 or |value| >= 1e-15";
  return "";
}

}  // namespace

double TableReader::number(std::string_view key, double def) {
  const toml::node* n = get(key);
  if (!n) return def;
  double v;
  if (auto* i = n->as_integer()) {
    v = static_cast<double>(i->get());
  } else if (auto* f = n->as_floating_point()) {
    v = f->get();
  } else {
    fail(key, "expected a number, got " + typeName(*n));
  }
  const std::string problem = magnitudeProblem(v);
  check(problem.empty(), key, problem);
  return v;
}

long long TableReader::integer(std::string_view key, long long def) {
  const toml::node* n = get(key);
  if (!n) return def;
  if (auto* i = n->as_integer()) return i->get();
  fail(key, "expected an integer, got " + typeName(*n));
}

long long TableReader::integerIn(std::string_view key, long long def, long long lo, long long hi) {
  long long v = integer(key, def);
  check(v >= lo && v <= hi, key,
        "must be an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "], got " +
            std::to_string(v));
  return v;
}

bool TableReader::boolean(std::string_view key, bool def) {
  const toml::node* n = get(key);
  if (!n) return def;
  if (auto* b = n->as_boolean()) return b->get();
  fail(key, "expected true or false, got " + typeName(*n));
}

std::string TableReader::string(std::string_view key, const std::string& def) {
  const toml::node* n = get(key);
  if (!n) return def;
  if (auto* s = n->as_string()) {
    // TOML allows "\u0000"; C file APIs would cut the string there and use another name.
    check(s->get().find('\0') == std::string::npos, key, "contains a NUL byte (\\u0000); remove it");
    return s->get();
  }
  fail(key, "expected a string, got " + typeName(*n));
}

std::string TableReader::choice(std::string_view key, const std::string& def,
                                const std::vector<std::string>& options) {
  std::string v = string(key, def);
  if (std::find(options.begin(), options.end(), v) != options.end()) return v;
  std::string list;
  for (size_t i = 0; i < options.size(); ++i) list += (i ? ", " : "") + ("'" + options[i] + "'");
  std::string close = closestMatch(v, options);
  fail(key, "'" + v + "' is not one of " + list +
                (close.empty() ? "" : "; did you mean '" + close + "'?"));
}

std::vector<double> TableReader::numbers(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return {};
  const toml::array* a = n->as_array();
  if (!a) fail(key, "expected an array of numbers, got " + typeName(*n));
  std::vector<double> out;
  for (size_t i = 0; i < a->size(); ++i) {
    const toml::node& e = *a->get(i);
    std::string where = path(key) + "[" + std::to_string(i) + "]";
    double v = 0;
    if (auto* iv = e.as_integer()) {
      v = static_cast<double>(iv->get());
    } else if (auto* fv = e.as_floating_point()) {
      v = fv->get();
    } else {
      source_.fail(&e, where, "expected a number, got " + typeName(e));
    }
    if (const std::string problem = magnitudeProblem(v); !problem.empty()) source_.fail(&e, where, problem);
    out.push_back(v);
  }
  return out;
}

Vec3 TableReader::vec3(std::string_view key, Vec3 def) {
  if (!has(key)) return def;
  std::vector<double> v = numbers(key);
  check(v.size() == 3, key, "expected 3 numbers [x, y, z], got " + std::to_string(v.size()));
  return {v[0], v[1], v[2]};
}

std::vector<std::pair<size_t, const toml::table*>> TableReader::arrayOfTables(std::string_view key) {
  std::vector<std::pair<size_t, const toml::table*>> out;
  const toml::node* n = get(key);
  if (!n) return out;
  const toml::array* a = n->as_array();
  if (!a || (!a->empty() && !a->is_array_of_tables()))
    fail(key, "expected an array of tables ([[" + std::string(key) + "]]), got " + typeName(*n));
  for (size_t i = 0; i < a->size(); ++i) out.emplace_back(i, a->get(i)->as_table());
  return out;
}

const toml::table* TableReader::subtable(std::string_view key) {
  const toml::node* n = get(key);
  if (!n) return nullptr;
  if (auto* t = n->as_table()) return t;
  fail(key, "expected a table, got " + typeName(*n));
}

void TableReader::finish() {
  for (auto&& [k, v] : table_) {
    std::string key(k.str());
    if (std::find(known_.begin(), known_.end(), key) != known_.end() || source_.ignored(path(key))) continue;
    std::string what = v.is_table() ? "unknown table" : "unknown key";
    if (!note_.empty()) what += " (" + note_ + ")";
    source_.fail(&v, path(key), what + suggestion(key, known_));
  }
}

}  // namespace seasim
