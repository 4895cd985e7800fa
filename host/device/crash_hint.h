// crash_hint.h — a last word when the OpenCL driver crashes inside a call. PoCL aborts (an
// assertion in pocl_llvm_build_program) or segfaults when its own kernel cache is damaged; that
// cannot be caught, but the user can be told which folder to clear before the process dies.
#pragma once
#include <string>

namespace seasim {

// While alive, SIGABRT, SIGSEGV and SIGBUS print "seasim: the OpenCL driver crashed while <what>.
// <hint>" to stderr, create the file `marker` when one is named (the next run sees it: PoCL's
// cache is cleared then, device/pocl_cache_check.h), and die as they would have (default action,
// same signal). Not nested.
class CrashHint {
 public:
  CrashHint(const std::string& what, const std::string& hint, const std::string& marker = "");
  ~CrashHint();
  CrashHint(const CrashHint&) = delete;
  CrashHint& operator=(const CrashHint&) = delete;
};

}  // namespace seasim
