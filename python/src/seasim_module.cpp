// seasim_module.cpp — the extension module seasim._seasim: a thin binding of seasim_core, the library
// the command line links (DESIGN.md: the Python module is never a second implementation). The
// package seasim (python/seasim/__init__.py) re-exports it with the Python-side conveniences.
#include <nanobind/nanobind.h>

#include "py_device.h"
#include "py_renderer.h"
#include "py_scene.h"
#include "py_tools.h"

NB_MODULE(_seasim, m) {
  m.doc() = "seasim's C++ core (use the package seasim).";
  seasim::py::registerErrors();
  seasim::py::bindDevices(m);
  seasim::py::bindScene(m);
  seasim::py::bindRenderer(m);
  seasim::py::bindTools(m);
}
