// run_command.h — runs a shell command line for the CLI tests and returns its exit code and output.
#pragma once
#include <sys/wait.h>

#include <cstdio>
#include <string>

namespace seasim_test {

struct Result {
  int code;
  std::string output;  // stdout and stderr
};

inline Result runCommand(const std::string& cmd) {
  FILE* pipe = popen((cmd + " 2>&1").c_str(), "r");
  std::string out;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out.append(buf, n);
  const int status = pclose(pipe);
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, out};
}

}  // namespace seasim_test
