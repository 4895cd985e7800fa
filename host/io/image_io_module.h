// image_io_module.h — the boundary between the seasim binary and its OpenImageIO module.
//
// OpenImageIO pulls in a tree of ~260 shared libraries whose binding costs most of a `seasim --help`
// or `seasim validate` (0.9 s, 74 % of it the dynamic linker). So image_io_oiio.cpp is built
// as a loadable module (libseasim_oiio.so beside the binary) and image_io_dl.cpp, linked into the
// core, dlopens it the first time an image is read or written. The module exports one C symbol,
// kImageIoModuleEntry, returning this table of the image_io.h functions. Both sides are built by the
// same CMake run with the same compiler, so C++ types cross the boundary unchanged; the version
// guards against a stale module left beside a newer binary.
#pragma once
#include <string>
#include <vector>

#include "io/image_io.h"

namespace seasim {

constexpr int kImageIoModuleVersion = 4;
#define SEASIM_IMAGE_IO_MODULE_ENTRY "seasim_image_io_module_v4"
#define SEASIM_IMAGE_IO_MODULE_FILE "libseasim_oiio.so"

struct ImageIoModule {
  int version;
  std::string (*writeExr)(const std::string& path, const Image& image);
  std::string (*writePng)(const std::string& path, const Image& linear_rgb, double exposure_ev);
  std::string (*writePngBytes)(const std::string& path, int width, int height, int channels,
                               const std::vector<std::uint8_t>& bytes);
  std::string (*writeSpectralExr)(const std::string& path, int width, int height,
                                  const std::vector<double>& wavelengths_nm, const std::vector<float>& data,
                                  const Image* layers);
  ImageHeader (*readImageHeader)(const std::string& path);
  Image (*readImage)(const std::string& path);
  std::string (*readImageAttribute)(const std::string& path, const std::string& name);
  SpectralImage (*readSpectralExr)(const std::string& path);
};

}  // namespace seasim
