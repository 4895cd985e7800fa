// py_renderer.h — binds seasim.Renderer and seasim.Frame (py_renderer.cpp).
#pragma once
#include <nanobind/nanobind.h>

namespace seasim::py {

void bindRenderer(nanobind::module_& m);

}  // namespace seasim::py
