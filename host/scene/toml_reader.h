// toml_reader.h — reading TOML scene and job files with validation (STYLE.md 6): each key is read
// with an explicit default and a type check, every key never asked for is an error ("did you
// mean"), and every error is an InputError naming file:line and the dotted key. Nodes written by an
// override carry the override's location, so its errors point at the job file or command line.
#pragma once
#include <toml++/toml.h>

#include <algorithm>
#include <string>
#include <string_view>
#include <unordered_map>
#include <vector>

#include "math/vec3.h"
#include "scene/scene_parser.h"

namespace seasim {

// The file a TOML tree came from, plus the locations of nodes that overrides wrote into it.
class TomlSource {
 public:
  explicit TomlSource(std::string file) : file_(std::move(file)) {}
  const std::string& file() const { return file_; }
  // Where a node was written: the override's location, else file:line (null: the file's line 1).
  SourceLoc locOf(const toml::node* n) const;
  bool isOverride(const toml::node* n) const { return n && override_locs_.count(n) > 0; }
  [[noreturn]] void fail(const toml::node* n, const std::string& key,
                         const std::string& message) const;
  // Records `n` and everything under it as written at `loc` / drops that record before `n` dies.
  void markOverride(const toml::node& n, const SourceLoc& loc);
  void forget(const toml::node& n);
  // Keys (dotted paths as errors name them) read as absent and never reported unknown: how
  // `validate` finds the next error after one, by parsing again without the key that failed.
  void ignore(const std::string& dotted_key) { ignored_.push_back(dotted_key); }
  bool ignored(const std::string& dotted_key) const {
    return std::find(ignored_.begin(), ignored_.end(), dotted_key) != ignored_.end();
  }

 private:
  std::string file_;
  std::vector<std::string> ignored_;
  std::unordered_map<const toml::node*, SourceLoc> override_locs_;
};

// Parses TOML text; a syntax error becomes InputError(file, line, "", "TOML syntax error: ...").
toml::table parseTomlText(std::string_view text, const std::string& file);

// Sets `o.value_toml` at the dotted path `o.key` in `root`, creating tables on the way. A path
// segment may index an array of tables ("objects[1].radius", 0-based). Errors name o.loc.
void applyOverride(toml::table& root, const Override& o, TomlSource& source);

// Reads one table. Every get/has/typed read marks the key as known; finish() reports the rest.
class TableReader {
 public:
  // `path` is the dotted name of this table in messages ("" for the root, "objects[2]");
  // `note` is added to unknown-key messages (e.g. "not used with type = 'box'").
  TableReader(const TomlSource& source, const toml::table& table, std::string path,
              std::string note = "");

  const toml::node* get(std::string_view key);  // null when absent
  bool has(std::string_view key) { return get(key) != nullptr; }
  // The key to read a renamed value under: `key`, or `earlier` (its former name, still accepted) when
  // only that one is given; both given is an error naming the two.
  std::string_view renamed(std::string_view key, std::string_view earlier);
  std::string path(std::string_view key) const;
  const toml::table& table() const { return table_; }
  const TomlSource& source() const { return source_; }

  // Typed reads: the default when absent, an InputError on a wrong type. Integers are accepted
  // where numbers are expected; numbers must be finite.
  double number(std::string_view key, double def);
  long long integer(std::string_view key, long long def);
  // An integer in [lo, hi].
  long long integerIn(std::string_view key, long long def, long long lo, long long hi);
  bool boolean(std::string_view key, bool def);
  std::string string(std::string_view key, const std::string& def);
  // A string that must be one of `options`; the message lists them.
  std::string choice(std::string_view key, const std::string& def,
                     const std::vector<std::string>& options);
  Vec3 vec3(std::string_view key, Vec3 def);
  // An array of numbers (empty when absent).
  std::vector<double> numbers(std::string_view key);
  // A sub-table (null when absent; an error when the key holds something else).
  const toml::table* subtable(std::string_view key);
  // The tables of an array of tables ([[key]]) with their indices; empty when absent.
  std::vector<std::pair<size_t, const toml::table*>> arrayOfTables(std::string_view key);

  // Throws at the key's node (else at this table) unless ok.
  void check(bool ok, std::string_view key, const std::string& message) {
    if (!ok) fail(key, message);
  }
  [[noreturn]] void fail(std::string_view key, const std::string& message) const;
  // Every key present but never asked for is an error, with the closest known key suggested.
  void finish();

 private:
  const TomlSource& source_;
  const toml::table& table_;
  std::string path_;
  std::string note_;
  std::vector<std::string> known_;
};

// Helpers shared by the scene and job parsers.
std::string typeName(const toml::node& n);   // "a string", "an integer", ...
std::string formatNumber(double v);          // shortest text that reads back the same
std::string floatText(double v);             // a finite double as TOML float text ("40.0", not "40")
std::string valueText(const toml::node& n);  // a node as TOML value text (for Override)
std::string closestMatch(const std::string& word, const std::vector<std::string>& candidates);
// "; did you mean 'x'?" or "; valid: a, b, c" (first `max_list` of them) for a message.
std::string suggestion(const std::string& word, const std::vector<std::string>& candidates,
                       size_t max_list = 12);

}  // namespace seasim
