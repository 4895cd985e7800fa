#include "jobs/test_hooks.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <thread>

namespace seasim {
namespace {

// The file named after "<item name>:" in the variable, or "" when it names another item or is unset.
std::string hookFileFor(const char* variable, const std::string& item_name) {
  const char* spec = std::getenv(variable);
  if (!spec || !*spec) return {};
  const std::string text = spec;
  const size_t colon = text.find(':');
  if (colon == std::string::npos || text.substr(0, colon) != item_name) return {};
  return text.substr(colon + 1);
}

}  // namespace

void killMidItemIfAsked(const std::string& item_name) {
  const std::string marker = hookFileFor("SEASIM_TEST_KILL_MID_ITEM", item_name);
  if (marker.empty()) return;
  // O_EXCL: of two processes racing here, one kills itself.
  const int fd = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return;
  ::close(fd);
  std::fprintf(stderr, "seasim: SEASIM_TEST_KILL_MID_ITEM: killing this process in the middle of item '%s'\n",
               item_name.c_str());
  std::fflush(stderr);
  ::kill(::getpid(), SIGKILL);
}

void holdItemIfAsked(const std::string& item_name) {
  const std::string release = hookFileFor("SEASIM_TEST_HOLD_ITEM", item_name);
  if (release.empty()) return;
  std::fprintf(stderr, "seasim: SEASIM_TEST_HOLD_ITEM: holding item '%s' until %s exists\n", item_name.c_str(),
               release.c_str());
  std::fflush(stderr);
  const auto give_up = std::chrono::steady_clock::now() + std::chrono::seconds(100);
  std::error_code ec;
  while (!std::filesystem::exists(release, ec) && std::chrono::steady_clock::now() < give_up)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
}

}  // namespace seasim
