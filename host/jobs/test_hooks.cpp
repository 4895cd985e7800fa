#include "jobs/test_hooks.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>

namespace seasim {

void killMidItemIfAsked(const std::string& item_name) {
  const char* spec = std::getenv("SEASIM_TEST_KILL_MID_ITEM");
  if (!spec || !*spec) return;
  const std::string text = spec;
  const size_t colon = text.find(':');
  if (colon == std::string::npos || text.substr(0, colon) != item_name) return;
  const std::string marker = text.substr(colon + 1);
  // O_EXCL: of two processes racing here, one kills itself.
  const int fd = ::open(marker.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0644);
  if (fd < 0) return;
  ::close(fd);
  std::fprintf(stderr, "seasim: SEASIM_TEST_KILL_MID_ITEM: killing this process in the middle of item '%s'\n",
               item_name.c_str());
  std::fflush(stderr);
  ::kill(::getpid(), SIGKILL);
}

}  // namespace seasim
