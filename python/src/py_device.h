// py_device.h — seasim.devices() and seasim.device(selector): OpenCL devices by the names --device
// takes; when the machine has no OpenCL platform at all, an error that says how to get one.
#pragma once
#include <nanobind/nanobind.h>

#include <string>

#include "device/device.h"

namespace seasim::py {

// chooseDevice(selector), or a DeviceError saying how to install a CPU OpenCL runtime when no
// platform is found.
DeviceInfo pickDevice(const std::string& selector);

void bindDevices(nanobind::module_& m);

}  // namespace seasim::py
