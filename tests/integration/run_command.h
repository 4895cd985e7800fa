// run_command.h — for the CLI tests: a shell command line's exit code and output, `seasim ARGS` run
// the same way, a background `seasim run`, a fresh folder per test, and reading what a run wrote.
#pragma once
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

extern char** environ;

namespace seasim_test {

// The binary runs without a kernel store (build/kernel-store, which `make demo` makes beside it) unless a
// test names one: what the tests check of the caches assumes each program is compiled or cached (ctest
// sets the same; this keeps a test binary run by hand alike).
inline const bool kWithoutKernelStore = [] { return ::setenv("SEASIM_KERNEL_STORE", "", 0) == 0; }();

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

// The seasim binary this test target was built against (SEASIM_BINARY, set by CMake) with `args`,
// through the shell; `env` is a prefix such as "SEASIM_CACHE_DIR=/x ".
inline Result run(const std::string& args, const std::string& env = "") {
  return runCommand(env + SEASIM_BINARY + " " + args);
}

inline bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

inline nlohmann::json readJson(const std::filesystem::path& p) {
  std::ifstream in(p);
  return nlohmann::json::parse(in);
}

// An empty folder <temp>/<prefix><current test's name>, created afresh (per test, so tests of one
// binary can run in parallel processes); the caller removes it in TearDown.
// The pid keeps two checkouts' test runs on one machine (or a rerun while an old one still runs)
// out of each other's folders: two runs of one test once damaged each other's PoCL caches and locks.
inline std::filesystem::path freshTestDir(const std::string& prefix) {
  const std::filesystem::path dir =
      std::filesystem::temp_directory_path() /
      (prefix + ::testing::UnitTest::GetInstance()->current_test_info()->name() + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// Starts `binary run JOB --device pocl` in the background, its stderr silenced; returns its pid
// (-1 when it could not start). The caller waits for it with waitpid.
inline pid_t spawnRun(const std::string& binary, const std::string& job) {
  std::vector<std::string> args = {binary, "run", job, "--device", "pocl"};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = -1;
  const int rc = posix_spawn(&pid, binary.c_str(), &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  return rc == 0 ? pid : -1;
}

}  // namespace seasim_test
