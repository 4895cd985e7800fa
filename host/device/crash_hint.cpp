#include "device/crash_hint.h"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <cstring>

namespace seasim {

namespace {

// A signal handler can reach only static data, and may only call async-signal-safe functions
// (write, signal, raise): the message is formatted here beforehand. This is the one piece of
// process-wide state in the device layer, live only while a CrashHint exists.
char g_message[2048];
size_t g_length = 0;
char g_marker[4096];  // "" when no marker file is named
struct sigaction g_previous[3];
constexpr int kSignals[3] = {SIGABRT, SIGSEGV, SIGBUS};

void onCrash(int sig) {
  ssize_t ignored = ::write(STDERR_FILENO, g_message, g_length);
  (void)ignored;
  if (g_marker[0] != '\0') {  // open and close are async-signal-safe
    const int fd = ::open(g_marker, O_WRONLY | O_CREAT | O_CLOEXEC, 0644);
    if (fd >= 0) ::close(fd);
  }
  ::signal(sig, SIG_DFL);
  ::raise(sig);
}

}  // namespace

CrashHint::CrashHint(const std::string& what, const std::string& hint, const std::string& marker) {
  g_marker[0] = '\0';
  if (marker.size() < sizeof g_marker) std::memcpy(g_marker, marker.c_str(), marker.size() + 1);
  const std::string text = "\nseasim: the OpenCL driver crashed while " + what + ". " + hint + "\n";
  g_length = std::min(text.size(), sizeof g_message);
  std::memcpy(g_message, text.data(), g_length);
  struct sigaction action {};
  action.sa_handler = onCrash;
  sigemptyset(&action.sa_mask);
  for (int i = 0; i < 3; ++i) ::sigaction(kSignals[i], &action, &g_previous[i]);
}

CrashHint::~CrashHint() {
  for (int i = 0; i < 3; ++i) ::sigaction(kSignals[i], &g_previous[i], nullptr);
}

}  // namespace seasim
