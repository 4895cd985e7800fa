// test_device.h — the OpenCL device the kernel tests run on: PoCL by default (CI and the CPU
// machines); SEASIM_TEST_DEVICE selects another (e.g. "gpu", or "intel" for Intel's OpenCL CPU
// runtime, which ctest's intel.* copies of these tests use) with the chooseDevice() syntax.
// One device (one context) for the whole test executable, never destroyed: releasing an OpenCL
// context from a static destructor runs after some drivers have torn themselves down at exit
// (Oclgrind 21.10 then aborts with "corrupted double-linked list"), and the process is ending anyway.
#pragma once
#include <cstdlib>
#include <string>

#include "device/device.h"
#include "util/error.h"

namespace seasim::test {

inline Device& testDevice() {
  static Device* device = new Device([] {
    const char* env = std::getenv("SEASIM_TEST_DEVICE");
    const std::string selector = env && *env ? env : "pocl";
    try {
      return chooseDevice(selector);
    } catch (const DeviceError& e) {
      if (selector != "intel") throw;
      throw DeviceError(std::string(e.what()) +
                        "\nIntel's OpenCL CPU runtime is not visible: `make intel-opencl` installs it into "
                        "build/intel-opencl (docs/install.md); ctest sets OCL_ICD_VENDORS and LD_LIBRARY_PATH to it");
    }
  }());
  return *device;
}

}  // namespace seasim::test
