// job_sampling.h — a job's [sample] table: `count` items, each with its scene keys drawn from
// distributions. Format: scenes/README.md ("Job files") and docs/datasets.md.
//
//   [sample]
//   scene = "../scenes/underwater_seabed.toml"
//   name = "reef"          # items reef_s0000, reef_s0001, ...
//   seed = 7
//   count = 1000
//   [sample.keys]          # dotted scene keys, as `--set` and `overrides` write them
//   "water.jerlov" = { choice = ["IB", "II", "1C", "3C"] }
//   "bottom.depth" = { log_uniform = [2, 30] }
//   "sun.zenith_deg" = { normal = [35, 10], within = [0, 80] }
//   "camera.position" = { uniform = [[-2, -3, 0], [2, -1, 0]] }   # per component
//   "spectral.count" = { integer = [8, 16] }
//   "spectral.sensor" = { choice = ["cie1931", "nikon_d5100_npl"], weights = [1, 3] }
//
// Item i's value of a key is a function of (seed, i, the key's name, the component) only
// (math/portable_sampling.h): the same on every machine, whichever shard renders the item, and
// unchanged when another key is added to or removed from the table.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "scene/scene_parser.h"
#include "scene/toml_reader.h"

namespace seasim {

struct SampledKey {
  enum class Kind { Uniform, LogUniform, Normal, Integer, Choice };
  Kind kind = Kind::Uniform;
  std::string key;         // dotted scene key
  SourceLoc loc;           // where its distribution was written (overrides' errors point there)
  bool is_array = false;   // numeric kinds: bounds given as arrays, one value per component
  // Numeric kinds, per component: uniform / log_uniform / integer draw in [lo, hi]; normal draws
  // N(mean, sd²) truncated to [lo, hi] (±inf without `within`).
  std::vector<double> lo, hi, mean, sd;
  std::vector<std::string> choices;  // Choice: each value as TOML text
  std::vector<double> cumulative;    // Choice: running sums of the weights (all 1 without `weights`)
};

// Reads [sample.keys] (`path` is its dotted name in messages): every leaf a distribution table.
// Errors (InputError at the file, line and key): no or two distribution kinds in a table, a bound
// of the wrong type, lo >= hi, lo <= 0 for log_uniform, sd <= 0, bounds with no mass (both over
// 30 sd from the mean), empty choices, weights that do not match, a key given twice.
std::vector<SampledKey> readSampledKeys(const TomlSource& src, const toml::table& keys, const std::string& path);

// Item `index`'s value of `k` as TOML value text ("12.5", "[1.0, -2.0, 0.0]", "\"IB\"", "9").
std::string sampledValue(const SampledKey& k, std::uint64_t seed, std::uint64_t index);

}  // namespace seasim
