// image_io_oiio.cpp — reading image files through OpenImageIO 2.4 (built when SEASIM_IMAGE_IO=ON):
// EXR, PNG and every other format OpenImageIO knows. The only file in the project that includes
// OpenImageIO; see image_io.h for the contract. Writing does not come here (image_write.cpp).
// Built into the loadable module libseasim_oiio.so, not into the binary (image_io_module.h says why);
// the binary reaches these functions through the table at the end of this file.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <memory>

#include "io/image_io.h"
#include "io/image_io_module.h"
#include "io/spectral_layout.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

bool hasNpyExtension(const std::string& path) { return fs::path(path).extension() == ".npy"; }

// Opens an image and checks its header against kMaxImagePixels before anything is decoded.
std::unique_ptr<OIIO::ImageInput> openChecked(const std::string& path) {
  if (!fs::exists(path)) throw RuntimeError("cannot read image '" + path + "': no such file");
  if (!fs::is_regular_file(path)) throw RuntimeError("cannot read image '" + path + "': not a regular file");
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) throw RuntimeError("cannot read image '" + path + "': not an image OpenImageIO can read (" +
                              OIIO::geterror() + ")");
  const OIIO::ImageSpec& spec = in->spec();
  const long long pixels = static_cast<long long>(spec.width) * spec.height;
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0)
    throw RuntimeError("cannot read image '" + path + "': its header gives an empty size");
  if (pixels > kMaxImagePixels)
    throw RuntimeError("cannot read image '" + path + "': its header claims " + std::to_string(spec.width) + "x" +
                       std::to_string(spec.height) + " pixels, more than the limit of " +
                       std::to_string(kMaxImagePixels) + " (16384x16384); use a smaller image");
  return in;
}

}  // namespace

ImageHeader readImageHeader(const std::string& path) {
  if (hasNpyExtension(path)) return readNpyHeader(path);
  std::unique_ptr<OIIO::ImageInput> in = openChecked(path);
  ImageHeader h{in->spec().width, in->spec().height, in->spec().nchannels};
  in->close();
  return h;
}

Image readImage(const std::string& path) {
  if (hasNpyExtension(path)) return readNpy(path);
  std::unique_ptr<OIIO::ImageInput> in = openChecked(path);
  const OIIO::ImageSpec& spec = in->spec();
  Image image;
  image.resize(spec.width, spec.height, spec.nchannels);
  image.channel_names = spec.channelnames;
  if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, image.pixels.data()))
    throw RuntimeError("cannot read image '" + path + "': " + in->geterror());
  in->close();
  return image;
}

std::string readImageAttribute(const std::string& path, const std::string& name) {
  std::unique_ptr<OIIO::ImageInput> in = OIIO::ImageInput::open(path);
  if (!in) throw RuntimeError("cannot read image '" + path + "': " + OIIO::geterror());
  const std::string value = in->spec().get_string_attribute(name);
  in->close();
  return value;
}

SpectralImage readSpectralExr(const std::string& path) {
  const Image file = readImage(path);
  std::vector<std::pair<double, int>> bands;  // (wavelength, file channel)
  for (int c = 0; c < file.channels; ++c) {
    double nm = 0.0;
    if (c < static_cast<int>(file.channel_names.size()) && parseSpectralChannelName(file.channel_names[c], nm))
      bands.emplace_back(nm, c);
  }
  if (bands.empty())
    throw RuntimeError("'" + path + "' is not a spectral EXR: no channel named like S0.550,000000nm");
  std::sort(bands.begin(), bands.end());
  SpectralImage out;
  out.width = file.width;
  out.height = file.height;
  const std::size_t n = bands.size();
  for (const auto& b : bands) out.wavelengths_nm.push_back(b.first);
  out.data.resize(file.pixelCount() * n);
  for (std::size_t p = 0; p < file.pixelCount(); ++p)
    for (std::size_t i = 0; i < n; ++i)
      out.data[p * n + i] = file.pixels[p * file.channels + bands[i].second];
  return out;
}

}  // namespace seasim

// The module's one entry point (image_io_module.h).
extern "C" __attribute__((visibility("default"))) const seasim::ImageIoModule* seasim_image_io_module_v5() {
  static const seasim::ImageIoModule table{seasim::kImageIoModuleVersion, &seasim::readImageHeader,
                                           &seasim::readImage, &seasim::readImageAttribute,
                                           &seasim::readSpectralExr};
  return &table;
}
