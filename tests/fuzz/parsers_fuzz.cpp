// parsers_fuzz.cpp — libFuzzer target over the scene and job parsers and the override syntax.
// Built only with clang and -DSEASIM_FUZZ=ON (tests/fuzz/README.md). The first byte of an input
// picks the parser:
//   0: a scene file                         parseScene(text)
//   1: a job file (anchored in jobs/, so the seeds' ../scenes paths resolve; its items' overrides
//      are applied to their scenes)         parseJob(text)
//   2: "key=value\n" then a scene file      parseScene(text, {Override{key, value}}) (a job's override)
//   3: "key=value\n" then a scene file      parseScene(text, {parseSetOption(line)}) (the command line's --set)
// Bad input must end in InputError (or RuntimeError, for files the input names); any other
// exception escapes and libFuzzer reports it, as it does crashes, leaks and sanitizer findings.
#include <cstddef>
#include <cstdint>
#include <string>

#include "jobs/job.h"
#include "scene/model_keys.h"
#include "scene/scene_parser.h"
#include "scene/set_option.h"
#include "util/error.h"

// The parsers alone are linked, not the passes whose descriptors declare the models' scene keys
// (scene/model_keys.h): the fuzzer declares one key of each type in its place, so that the parser's
// reading of declared keys is fuzzed too.
const std::vector<seasim::ModelKey>& seasim::modelSceneKeys() {
  static const std::vector<ModelKey> keys = {
      {"surface", "fuzz_switch", ModelKey::Type::Boolean, 0.0, 0.0, 0.0, ""},
      {"sea", "fuzz_number", ModelKey::Type::Number, 1.0, 0.0, 10.0, "m"},
      {"quality", "fuzz_integer", ModelKey::Type::Integer, 4.0, 1.0, 12.0, ""},
      {"quality", "fuzz_open", ModelKey::Type::Number, 0.5, 0.0, 1.0, "", true}};
  return keys;
}

// The same for the passes' [quality] count knobs (plan/pass_descriptor.cpp gives the shipped ones).
const std::vector<seasim::KnobDefault>& seasim::qualityCountKnobs() {
  static const std::vector<KnobDefault> knobs = {{"fuzz_count", 8}};
  return knobs;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const int mode = data[0] % 4;
  std::string text(reinterpret_cast<const char*>(data) + 1, size - 1);
  const std::string scene_path = std::string(SEASIM_SOURCE_DIR) + "/scenes/fuzz_input.toml";
  const std::string job_path = std::string(SEASIM_SOURCE_DIR) + "/jobs/fuzz_input.toml";
  try {
    if (mode == 0) {
      (void)seasim::parseScene(text, scene_path);
    } else if (mode == 1) {
      (void)seasim::parseJob(text, job_path);
    } else if (mode == 3) {
      const size_t nl = text.find('\n');
      const seasim::Override o = seasim::parseSetOption(text.substr(0, nl));
      (void)seasim::parseScene(nl == std::string::npos ? "" : text.substr(nl + 1), scene_path, {o});
    } else {
      const size_t nl = text.find('\n');
      const std::string line = text.substr(0, nl);
      const size_t eq = line.find('=');
      if (eq == std::string::npos) return 0;
      const seasim::Override o{line.substr(0, eq), line.substr(eq + 1), {"<fuzz --set>", 0}};
      (void)seasim::parseScene(nl == std::string::npos ? "" : text.substr(nl + 1), scene_path, {o});
    }
  } catch (const seasim::InputError&) {
  } catch (const seasim::RuntimeError&) {
  }
  return 0;
}
