#include "py_device.h"

#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include "util/error.h"

namespace nb = nanobind;

namespace seasim::py {

namespace {

const char* kNoPlatform =
    "no OpenCL platform found. seasim needs an OpenCL runtime: on Debian or Ubuntu a CPU one is "
    "`sudo apt-get install pocl-opencl-icd` (with the loader ocl-icd-libopencl1), or without system "
    "packages `pip install seasim[cpu]` (Intel's OpenCL CPU runtime from PyPI, found on import); on a GPU machine, "
    "the vendor driver's OpenCL ICD (NVIDIA, AMD ROCm, Intel compute-runtime). An OpenCL loader "
    "finds runtimes through /etc/OpenCL/vendors/*.icd or the OCL_ICD_VENDORS variable.";

}  // namespace

DeviceInfo pickDevice(const std::string& selector) {
  if (listDevices().empty()) throw DeviceError(kNoPlatform);
  return chooseDevice(selector);
}

void bindDevices(nb::module_& m) {
  nb::class_<DeviceInfo>(m, "DeviceInfo", "One OpenCL device (seasim devices).")
      .def_ro("platform_index", &DeviceInfo::platform_index)
      .def_ro("device_index", &DeviceInfo::device_index)
      .def_ro("platform_name", &DeviceInfo::platform_name)
      .def_ro("name", &DeviceInfo::name)
      .def_ro("vendor", &DeviceInfo::vendor)
      .def_ro("version", &DeviceInfo::version)
      .def_ro("driver", &DeviceInfo::driver)
      .def_ro("is_gpu", &DeviceInfo::is_gpu)
      .def_ro("is_pocl", &DeviceInfo::is_pocl)
      .def_ro("has_fp64", &DeviceInfo::has_fp64)
      .def_ro("compute_units", &DeviceInfo::compute_units)
      .def_ro("global_mem_bytes", &DeviceInfo::global_mem_bytes)
      .def_prop_ro("label", &DeviceInfo::label)
      .def("__repr__", [](const DeviceInfo& d) { return "<seasim.DeviceInfo " + d.label() + ">"; });
  m.def("devices", &listDevices, "Every OpenCL device, platform by platform (empty when there is no OpenCL platform).");
  m.def("device", &pickDevice, nb::arg("selector") = "",
        "The device a selector picks, as --device does: '' or 'auto' (first GPU, else PoCL), 'cpu', 'gpu', "
        "'pocl:N', 'nvidia:N' or part of a device name. Raises seasim.DeviceError.");
}

}  // namespace seasim::py
