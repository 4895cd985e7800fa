#include "device/kernel_source.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "device/embedded_kernels.h"
#include "util/error.h"

namespace seasim {

std::string readKernelFile(const std::string& relative_path) {
  if (const char* dir = std::getenv("SEASIM_KERNEL_DIR"); dir && *dir) {
    std::filesystem::path p = std::filesystem::path(dir) / relative_path;
    std::ifstream in(p);
    if (!in) throw DeviceError("kernel file not found: " + p.string() + " (SEASIM_KERNEL_DIR is set)");
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  for (const auto& f : embeddedKernelFiles()) {
    if (relative_path == f.path) return f.text;
  }
  throw DeviceError("kernel file not embedded in this binary: kernels/" + relative_path);
}

namespace {

void inlineFile(const std::string& path, KernelSource& out, std::set<std::string>& seen) {
  if (!seen.insert(path).second) return;
  out.files.push_back(path);
  const std::string marker_file = " \"kernels/" + path + "\"\n";
  static const std::regex include_re(R"(^\s*#\s*include\s*"([^"]+)\"\s*$)");
  std::istringstream in(readKernelFile(path));
  std::string line;
  int line_no = 0;
  out.text += "#line 1" + marker_file;
  while (std::getline(in, line)) {
    ++line_no;
    std::smatch m;
    if (std::regex_match(line, m, include_re)) {
      inlineFile(m[1].str(), out, seen);
      out.text += "#line " + std::to_string(line_no + 1) + marker_file;
    } else {
      out.text += line + "\n";
    }
  }
}

}  // namespace

KernelSource assembleKernelSource(const std::string& kernel_file) {
  KernelSource out;
  std::set<std::string> seen;
  inlineFile(kernel_file, out, seen);
  return out;
}

}  // namespace seasim
