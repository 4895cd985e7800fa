// image_io_module.h — the boundary between the seasim binary and its OpenImageIO module.
//
// OpenImageIO pulls in a tree of ~260 shared libraries whose binding costs most of a `seasim --help`
// or `seasim validate` (0.9 s, 74 % of it the dynamic linker). So image_io_oiio.cpp is built
// as a loadable module (libseasim_oiio.so beside the binary) and image_io_dl.cpp, linked into the
// core, dlopens it the first time an image is read. The module exports one C symbol,
// kImageIoModuleEntry, returning this table of image_io.h's readers. Both sides are built by the
// same CMake run with the same compiler, so C++ types cross the boundary unchanged; the version
// guards against a stale module left beside a newer binary. Writing needs no module: the writers
// (image_write.cpp) use OpenEXR's library (io/exr_write.h) and libpng (io/png_write.h) directly, so a
// render that writes its EXR and PNG never binds OpenImageIO's tree.
#pragma once
#include <string>
#include <vector>

#include "io/image_io.h"

namespace seasim {

constexpr int kImageIoModuleVersion = 5;
#define SEASIM_IMAGE_IO_MODULE_ENTRY "seasim_image_io_module_v5"
#define SEASIM_IMAGE_IO_MODULE_FILE "libseasim_oiio.so"

struct ImageIoModule {
  int version;
  ImageHeader (*readImageHeader)(const std::string& path);
  Image (*readImage)(const std::string& path);
  std::string (*readImageAttribute)(const std::string& path, const std::string& name);
  SpectralImage (*readSpectralExr)(const std::string& path);
};

}  // namespace seasim
