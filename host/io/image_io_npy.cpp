// image_io_npy.cpp — image "files" for builds without OpenImageIO (SEASIM_IMAGE_IO=OFF): every
// writer writes NumPy arrays next to the requested name (see image_io.h for the mapping), so a
// GPU-machine run still leaves every result on disk, readable with numpy and convertible later.
#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <set>
#include <string>

#include "io/image_io.h"
#include "io/npy.h"
#include "io/spectral_layout.h"
#include "io/tonemap.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

void checkImage(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    throw RuntimeError("cannot write '" + path + "': empty image");
  if (image.pixels.size() != image.pixelCount() * static_cast<std::size_t>(image.channels))
    throw RuntimeError("cannot write '" + path + "': pixel buffer does not match the image size");
}

std::size_t sz(int v) { return static_cast<std::size_t>(v); }

// "x.exr" -> "x.exr.npy"; a path already ending in .npy is used as it is.
std::string npyPathFor(const std::string& path) {
  return fs::path(path).extension() == ".npy" ? path : path + ".npy";
}

std::string wavelengthsPathFor(const std::string& path) { return path + ".wavelengths_nm.npy"; }

}  // namespace

bool imageIoAvailable() { return false; }

std::string writeExr(const std::string& path, const Image& image) {
  checkImage(path, image);
  const std::string out = npyPathFor(path);
  writeNpy(out, image);
  return out;
}

std::string writePng(const std::string& path, const Image& linear_rgb, double exposure_ev) {
  checkImage(path, linear_rgb);
  std::vector<std::uint8_t> bytes;
  toneMapImage8(linear_rgb, exposure_ev, bytes);
  const std::string out = npyPathFor(path);
  writeNpyArray(out, NpyType::UInt8, {sz(linear_rgb.height), sz(linear_rgb.width), sz(linear_rgb.channels)},
                bytes.data());
  return out;
}

std::string writePngBytes(const std::string& path, int width, int height, int channels,
                          const std::vector<std::uint8_t>& bytes) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 || bytes.size() != sz(width) * sz(height) * sz(channels))
    throw RuntimeError("cannot write '" + path + "': the bytes are not a " + std::to_string(width) + "x" +
                       std::to_string(height) + "x" + std::to_string(channels) + " image");
  const std::string out = npyPathFor(path);
  writeNpyArray(out, NpyType::UInt8, {sz(height), sz(width), sz(channels)}, bytes.data());
  return out;
}

std::string writeSpectralExr(const std::string& path, int width, int height,
                             const std::vector<double>& wavelengths_nm, const std::vector<float>& data,
                             const Image* layers) {
  const std::size_t n = wavelengths_nm.size();
  if (width <= 0 || height <= 0 || n == 0 || data.size() != sz(width) * sz(height) * n)
    throw RuntimeError("cannot write '" + path + "': spectral data does not match " + std::to_string(width) +
                       "x" + std::to_string(height) + "x" + std::to_string(n));
  // Same checks as the EXR writer: positive finite wavelengths, one channel name per band.
  std::set<std::string> names;
  for (double nm : wavelengths_nm) {
    std::string name;
    try {
      name = spectralChannelName(nm);
    } catch (const RuntimeError& e) {
      throw RuntimeError("cannot write '" + path + "': " + e.what());
    }
    if (!names.insert(name).second)
      throw RuntimeError("cannot write '" + path + "': two bands share the wavelength " + std::to_string(nm) + " nm");
  }
  const std::string out = npyPathFor(path);
  // Wavelengths first: the data file is what marks the output as finished.
  writeNpyArray(wavelengthsPathFor(out), NpyType::Float64, {n}, wavelengths_nm.data());
  if (layers && layers->channels > 0) {  // the layers' channels after the bands, as in the EXR
    const std::size_t k = sz(layers->channels), pixels = sz(width) * sz(height);
    if (layers->width != width || layers->height != height)
      throw RuntimeError("cannot write '" + path + "': its layers are not " + std::to_string(width) + "x" +
                         std::to_string(height));
    const std::vector<float> all = bandsThenLayers(data, n, layers->pixels, k, pixels);
    writeNpyArray(out, NpyType::Float32, {sz(height), sz(width), n + k}, all.data());
  } else {
    writeNpyArray(out, NpyType::Float32, {sz(height), sz(width), n}, data.data());
  }
  return out;
}

ImageHeader readImageHeader(const std::string& path) {
  const std::string npy = npyPathFor(path);
  if (fs::exists(npy)) return readNpyHeader(npy);
  throw RuntimeError("cannot read image '" + path + "': this build has no OpenImageIO (SEASIM_IMAGE_IO=OFF) "
                     "and there is no '" + npy + "' beside it");
}

Image readImage(const std::string& path) {
  const std::string npy = npyPathFor(path);
  if (fs::exists(npy)) return readNpy(npy);
  throw RuntimeError("cannot read image '" + path + "': this build has no OpenImageIO (SEASIM_IMAGE_IO=OFF) "
                     "and there is no '" + npy + "' beside it");
}

std::string readImageAttribute(const std::string& path, const std::string& name) { return ""; }

SpectralImage readSpectralExr(const std::string& path) {
  const std::string npy = npyPathFor(path);
  if (!fs::exists(npy) || !fs::exists(wavelengthsPathFor(npy)))
    throw RuntimeError("cannot read spectral image '" + path + "': this build has no OpenImageIO "
                       "(SEASIM_IMAGE_IO=OFF) and '" + npy + "' with its wavelengths file is missing");
  const NpyArray cube = readNpyArray(npy);
  const NpyArray wl = readNpyArray(wavelengthsPathFor(npy));
  if (cube.shape.size() != 3 || wl.shape.size() != 1 || wl.shape[0] != cube.shape[2])
    throw RuntimeError("'" + npy + "': expected a (height, width, bands) array matching its wavelengths file");
  const std::size_t n = wl.shape[0];
  std::vector<std::size_t> order(n);
  for (std::size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return wl.values[a] < wl.values[b]; });
  SpectralImage out;
  out.height = static_cast<int>(cube.shape[0]);
  out.width = static_cast<int>(cube.shape[1]);
  for (std::size_t i : order) out.wavelengths_nm.push_back(wl.values[i]);
  const std::size_t pixels = cube.shape[0] * cube.shape[1];
  out.data.resize(pixels * n);
  for (std::size_t p = 0; p < pixels; ++p)
    for (std::size_t i = 0; i < n; ++i) out.data[p * n + i] = static_cast<float>(cube.values[p * n + order[i]]);
  return out;
}

}  // namespace seasim
