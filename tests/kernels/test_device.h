// test_device.h — the OpenCL device the kernel tests run on: PoCL by default (CI and the CPU
// machines); SEASIM_TEST_DEVICE selects another (e.g. "gpu") with the chooseDevice() syntax.
// One device (one context) for the whole test executable.
#pragma once
#include <cstdlib>

#include "device/device.h"

namespace seasim::test {

inline Device& testDevice() {
  static Device device(chooseDevice([] {
    const char* selector = std::getenv("SEASIM_TEST_DEVICE");
    return std::string(selector && *selector ? selector : "pocl");
  }()));
  return device;
}

}  // namespace seasim::test
