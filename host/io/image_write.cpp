// image_write.cpp — image_io.h's writers in builds with image I/O (SEASIM_IMAGE_IO=ON): EXR through
// OpenEXR's library (io/exr_write.h), PNG through libpng (io/png_write.h). Neither loads OpenImageIO,
// which only the readers need (image_io_dl.cpp): a render that writes its EXR and PNG binds a handful of
// libraries instead of OpenImageIO's ~260 (results/BENCHMARKS.md, "Fixed cost per process").
#include <set>

#include "io/atomic_file.h"
#include "io/exr_write.h"
#include "io/image_io.h"
#include "io/png_write.h"
#include "io/spectral_layout.h"
#include "io/tonemap.h"
#include "util/error.h"

namespace seasim {

namespace {

void checkImage(const std::string& path, const Image& image) {
  if (image.width <= 0 || image.height <= 0 || image.channels <= 0)
    throw RuntimeError("cannot write '" + path + "': empty image (" + std::to_string(image.width) + "x" +
                       std::to_string(image.height) + "x" + std::to_string(image.channels) + ")");
  if (image.pixels.size() != image.pixelCount() * static_cast<std::size_t>(image.channels))
    throw RuntimeError("cannot write '" + path + "': pixel buffer holds " +
                       std::to_string(image.pixels.size()) + " values, the size needs " +
                       std::to_string(image.pixelCount() * image.channels));
  if (!image.channel_names.empty() && image.channel_names.size() != static_cast<std::size_t>(image.channels))
    throw RuntimeError("cannot write '" + path + "': " + std::to_string(image.channel_names.size()) +
                       " channel names for " + std::to_string(image.channels) + " channels");
}

std::vector<std::string> channelNamesFor(const Image& image) {
  if (!image.channel_names.empty()) return image.channel_names;
  switch (image.channels) {
    case 1: return {"Y"};
    case 2: return {"Y", "A"};
    case 3: return {"R", "G", "B"};
    case 4: return {"R", "G", "B", "A"};
    default: {
      std::vector<std::string> names;
      for (int c = 0; c < image.channels; ++c) names.push_back("C" + std::to_string(c));
      return names;
    }
  }
}

std::string writePngFile(const std::string& path, int width, int height, int channels,
                         const std::vector<std::uint8_t>& bytes) {
  std::vector<std::uint8_t> encoded;
  try {
    encoded = encodePng(width, height, channels, bytes);
  } catch (const RuntimeError& e) {
    throw RuntimeError("cannot write '" + path + "': " + e.what());
  }
  writeFileAtomic(path, [&](const std::string& temp) { writeBytes(temp, encoded.data(), encoded.size()); });
  return path;
}

// A spectral EXR's channels: the n bands ("S0.<nm>"), then the layers' channels ("<layer>.S0.<nm>"), each
// read in place from its own buffer (no interleaved copy). Throws on a bad wavelength or a repeated name.
std::vector<ExrChannel> spectralChannels(const std::string& path, const std::vector<double>& wavelengths_nm,
                                         const std::vector<float>& data, const Image* layers) {
  const std::size_t n = wavelengths_nm.size();
  std::vector<ExrChannel> channels;
  std::set<std::string> seen;
  for (std::size_t i = 0; i < n; ++i) {
    std::string name;
    try {
      name = spectralChannelName(wavelengths_nm[i]);
    } catch (const RuntimeError& e) {
      throw RuntimeError("cannot write '" + path + "': " + e.what());
    }
    if (!seen.insert(name).second)
      throw RuntimeError("cannot write '" + path + "': two bands share the channel name '" + name + "'");
    channels.push_back({name, data.data() + i, n});
  }
  const std::size_t k = layers ? static_cast<std::size_t>(layers->channels) : 0;
  for (std::size_t c = 0; c < k; ++c) {
    const std::string& name = layers->channel_names[c];
    if (!seen.insert(name).second)
      throw RuntimeError("cannot write '" + path + "': two channels are named '" + name + "'");
    channels.push_back({name, layers->pixels.data() + c, k});
  }
  return channels;
}

}  // namespace

std::string writeExr(const std::string& path, const Image& image) {
  checkImage(path, image);
  const std::vector<std::string> names = channelNamesFor(image);
  std::vector<ExrChannel> channels;
  for (int c = 0; c < image.channels; ++c)
    channels.push_back({names[c], image.pixels.data() + c, static_cast<std::size_t>(image.channels)});
  writeFileAtomic(path, [&](const std::string& temp) { writeExrFile(temp, image.width, image.height, channels); });
  return path;
}

std::string writePng(const std::string& path, const Image& linear_rgb, double exposure_ev) {
  checkImage(path, linear_rgb);
  std::vector<std::uint8_t> bytes;
  toneMapImage8(linear_rgb, exposure_ev, bytes);
  return writePngFile(path, linear_rgb.width, linear_rgb.height, linear_rgb.channels, bytes);
}

std::string writePngBytes(const std::string& path, int width, int height, int channels,
                          const std::vector<std::uint8_t>& bytes) {
  return writePngFile(path, width, height, channels, bytes);
}

std::string writeSpectralExr(const std::string& path, int width, int height,
                             const std::vector<double>& wavelengths_nm, const std::vector<float>& data,
                             const Image* layers) {
  const std::size_t n = wavelengths_nm.size();
  if (width <= 0 || height <= 0 || n == 0)
    throw RuntimeError("cannot write '" + path + "': empty spectral image (" + std::to_string(width) + "x" +
                       std::to_string(height) + ", " + std::to_string(n) + " bands)");
  if (data.size() != static_cast<std::size_t>(width) * height * n)
    throw RuntimeError("cannot write '" + path + "': spectral data holds " + std::to_string(data.size()) +
                       " values, " + std::to_string(width) + "x" + std::to_string(height) + "x" +
                       std::to_string(n) + " needed");
  if (layers && (layers->width != width || layers->height != height ||
                 layers->channel_names.size() != static_cast<std::size_t>(layers->channels) ||
                 layers->pixels.size() != layers->pixelCount() * layers->channels))
    throw RuntimeError("cannot write '" + path + "': its layers are not a " + std::to_string(width) + "x" +
                       std::to_string(height) + " image with named channels");
  const std::vector<ExrChannel> channels = spectralChannels(path, wavelengths_nm, data, layers);
  const std::vector<std::pair<std::string, std::string>> attributes = {
      {"spectralLayoutVersion", kSpectralLayoutVersion}, {"emissiveUnits", kSpectralEmissiveUnits}};
  writeFileAtomic(path, [&](const std::string& temp) { writeExrFile(temp, width, height, channels, attributes); });
  return path;
}

}  // namespace seasim
