// py_tools.h — binds the module's functions over the CLI's code paths (py_tools.cpp): compare,
// read_image, reference, run_job, data_dir, version; and the translation of seasim's C++ errors
// into the exceptions of seasim/errors.py.
#pragma once
#include <nanobind/nanobind.h>

namespace seasim::py {

void bindTools(nanobind::module_& m);
void registerErrors();

}  // namespace seasim::py
