// kernel_source.h — finds kernel files (embedded, or $SEASIM_KERNEL_DIR) and inlines their
// `#include "common/x.h"` lines once each, with #line markers so compiler messages name real files.
#pragma once
#include <string>
#include <vector>

namespace seasim {

struct KernelSource {
  std::string text;                 // the single translation unit handed to clCreateProgramWithSource
  std::vector<std::string> files;   // the files inlined, in order (relative to kernels/)
};

// Raw text of kernels/<relative_path>; throws DeviceError when it does not exist.
std::string readKernelFile(const std::string& relative_path);

// The kernel file with its includes inlined (each header once, like #pragma once).
KernelSource assembleKernelSource(const std::string& kernel_file);

}  // namespace seasim
