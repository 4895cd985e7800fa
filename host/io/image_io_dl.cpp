// image_io_dl.cpp — image_io.h in builds with OpenImageIO: forwards to libseasim_oiio.so, loaded on
// the first image read or write (image_io_module.h says why). `.npy` paths never load it.
#include <dlfcn.h>

#include <filesystem>
#include <mutex>

#include "io/image_io.h"
#include "io/image_io_module.h"
#include "io/npy.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

bool isNpy(const std::string& path) { return fs::path(path).extension() == ".npy"; }

// Where the module may be, in order: $SEASIM_LIB_DIR, the folder of the running binary (the build
// folder puts the module beside seasim and the test binaries), <prefix>/lib/seasim beside an
// installed binary, the build folder CMake configured.
std::vector<fs::path> moduleCandidates() {
  std::vector<fs::path> out;
  if (const char* dir = std::getenv("SEASIM_LIB_DIR"); dir && *dir) out.push_back(fs::path(dir) / SEASIM_IMAGE_IO_MODULE_FILE);
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (!ec) {
    out.push_back(exe.parent_path() / SEASIM_IMAGE_IO_MODULE_FILE);
    // An installed binary (<prefix>/bin/seasim) keeps it in <prefix>/lib/seasim (CMakeLists.txt install).
    out.push_back(exe.parent_path().parent_path() / "lib" / "seasim" / SEASIM_IMAGE_IO_MODULE_FILE);
  }
#ifdef SEASIM_OIIO_MODULE_DIR
  out.push_back(fs::path(SEASIM_OIIO_MODULE_DIR) / SEASIM_IMAGE_IO_MODULE_FILE);
#endif
  return out;
}

const ImageIoModule& module() {
  static const ImageIoModule* table = nullptr;
  static std::string failure;
  static std::once_flag once;
  std::call_once(once, [] {
    std::string tried;
    for (const fs::path& path : moduleCandidates()) {
      if (!fs::exists(path)) {
        tried += "\n  " + path.string() + ": not there";
        continue;
      }
      // Never dlclose'd: the table's functions are used until exit.
      void* handle = dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL);
      if (!handle) {
        tried += "\n  " + path.string() + ": " + dlerror();
        continue;
      }
      using Entry = const ImageIoModule* (*)();
      auto entry = reinterpret_cast<Entry>(dlsym(handle, SEASIM_IMAGE_IO_MODULE_ENTRY));
      const ImageIoModule* t = entry ? entry() : nullptr;
      if (!t || t->version != kImageIoModuleVersion) {
        tried += "\n  " + path.string() + ": not a matching seasim image module (rebuild it with this binary)";
        continue;
      }
      table = t;
      return;
    }
    failure = "cannot load the OpenImageIO module " SEASIM_IMAGE_IO_MODULE_FILE ":" + tried;
  });
  if (!table) throw RuntimeError(failure);
  return *table;
}

}  // namespace

bool imageIoAvailable() { return true; }

std::string writeExr(const std::string& path, const Image& image) { return module().writeExr(path, image); }

std::string writePng(const std::string& path, const Image& linear_rgb, double exposure_ev) {
  return module().writePng(path, linear_rgb, exposure_ev);
}

std::string writePngBytes(const std::string& path, int width, int height, int channels,
                          const std::vector<std::uint8_t>& bytes) {
  return module().writePngBytes(path, width, height, channels, bytes);
}

std::string writeSpectralExr(const std::string& path, int width, int height, const std::vector<double>& wavelengths_nm,
                             const std::vector<float>& data) {
  return module().writeSpectralExr(path, width, height, wavelengths_nm, data);
}

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
