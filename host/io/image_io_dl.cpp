// image_io_dl.cpp — image_io.h's readers in builds with OpenImageIO: forwards to libseasim_oiio.so,
// loaded on the first image read (image_io_module.h says why). `.npy` paths never load it; the writers
// are image_write.cpp's and never load it either.
#include <filesystem>
#include <mutex>

#include "io/image_io.h"
#include "io/image_io_module.h"
#include "io/npy.h"
#include "util/error.h"
#include "util/module_loader.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

bool isNpy(const std::string& path) { return fs::path(path).extension() == ".npy"; }

const ImageIoModule& module() {
  static const ImageIoModule* table = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
#ifdef SEASIM_OIIO_MODULE_DIR
    const std::string build_dir = SEASIM_OIIO_MODULE_DIR;
#else
    const std::string build_dir;
#endif
    std::string tried;
    table = loadModuleTable<ImageIoModule>(moduleCandidates(SEASIM_IMAGE_IO_MODULE_FILE, build_dir),
                                           SEASIM_IMAGE_IO_MODULE_ENTRY, kImageIoModuleVersion, "image", tried);
    if (!table) failure = "cannot load the OpenImageIO module " SEASIM_IMAGE_IO_MODULE_FILE ":" + tried;
  });
  if (!table) throw RuntimeError(failure);
  return *table;
}

}  // namespace

bool imageIoAvailable() { return true; }

ImageHeader readImageHeader(const std::string& path) {
  if (isNpy(path)) return readNpyHeader(path);  // as the module would, without loading it
  return module().readImageHeader(path);
}

Image readImage(const std::string& path) {
  if (isNpy(path)) return readNpy(path);  // as the module would, without loading it
  return module().readImage(path);
}

std::string readImageAttribute(const std::string& path, const std::string& name) {
  return module().readImageAttribute(path, name);
}

SpectralImage readSpectralExr(const std::string& path) { return module().readSpectralExr(path); }

}  // namespace seasim
