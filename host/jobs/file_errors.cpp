#include "jobs/file_errors.h"

#include <algorithm>
#include <cstdlib>
#include <exception>
#include <functional>

#include "jobs/job.h"
#include "util/error.h"

namespace seasim {

namespace {

// Generous: a file with more distinct bad keys than this has a bigger problem than the list shows.
constexpr int kMaxErrors = 100;

// "a.b[2].c" -> "a.b[2]" -> "a.b" -> "a" -> "": the key's enclosing table or array.
std::string parentKey(const std::string& key) {
  const size_t cut = key.find_last_of(".[");
  return cut == std::string::npos ? std::string() : key.substr(0, cut);
}

void addOnce(std::vector<std::string>& list, const std::string& message) {
  if (std::find(list.begin(), list.end(), message) == list.end()) list.push_back(message);
}

// "FILE:LINE: ..." -> LINE (0 when there is none), to list a file's errors top to bottom.
int lineOf(const std::string& message) {
  const size_t colon = message.find(':');
  if (colon == std::string::npos) return 0;
  return std::atoi(message.c_str() + colon + 1);
}

// Calls parse(ignored) until it succeeds, each InputError's key added to `ignored`. A key already
// ignored (the error did not go away) is widened to its parent; an error without a key ends it.
void collect(const std::function<void(const std::vector<std::string>&)>& parse, std::vector<std::string>& errors) {
  std::vector<std::string> ignored;
  for (int round = 0; round < kMaxErrors; ++round) {
    try {
      parse(ignored);
      return;
    } catch (const InputError& e) {
      addOnce(errors, e.what());
      std::string key = e.key();
      while (!key.empty() && std::find(ignored.begin(), ignored.end(), key) != ignored.end()) key = parentKey(key);
      if (key.empty()) return;
      ignored.push_back(key);
    } catch (const std::exception& e) {  // not an input error (I/O): report it, nothing to step past
      addOnce(errors, e.what());
      return;
    }
  }
}

// Overrides whose key is ignored are left out too: an override's own errors (a key the scene does
// not have) are raised while it is applied, before any key is read.
std::vector<Override> without(const std::vector<Override>& overrides, const std::vector<std::string>& ignored) {
  std::vector<Override> kept;
  for (const Override& o : overrides)
    if (std::find(ignored.begin(), ignored.end(), o.key) == ignored.end()) kept.push_back(o);
  return kept;
}

}  // namespace

std::vector<std::string> sceneFileErrors(const std::string& path, const std::vector<Override>& overrides) {
  std::vector<std::string> errors;
  collect([&](const std::vector<std::string>& ignored) { (void)loadScene(path, without(overrides, ignored), ignored); },
          errors);
  std::stable_sort(errors.begin(), errors.end(),
                   [](const std::string& a, const std::string& b) { return lineOf(a) < lineOf(b); });
  return errors;
}

std::vector<std::string> jobFileErrors(const std::string& path) {
  std::vector<std::string> errors;
  Job job;
  collect(
      [&](const std::vector<std::string>& ignored) {
        JobLoadOptions options;
        options.ignored_keys = ignored;
        options.check_scenes = false;
        job = loadJob(path, options);
      },
      errors);
  for (const RenderItem& item : job.items)
    for (const std::string& e : sceneFileErrors(item.scene_file, item.overrides)) addOnce(errors, e);
  return errors;
}

}  // namespace seasim
