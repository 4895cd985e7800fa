// image_io_oiio.cpp — image files through OpenImageIO 2.4 (built when SEASIM_IMAGE_IO=ON).
// The only file in the project that includes OpenImageIO; see image_io.h for the contract.
// Built into the loadable module libseasim_oiio.so, not into the binary (image_io_module.h says why);
// the binary reaches these functions through the table at the end of this file.
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <set>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/image_io_module.h"
#include "io/spectral_layout.h"
#include "io/tonemap.h"
#include "util/error.h"

namespace seasim {

namespace {

namespace fs = std::filesystem;

bool hasNpyExtension(const std::string& path) { return fs::path(path).extension() == ".npy"; }

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

// Encodes one image in memory and writes the bytes with writeBytes: OpenImageIO's PNG writer does
// not report a full disk (it left a truncated image.png), so the file is written by code that checks
// every write. Used for PNG, whose encoded size is small next to the float data.
void writeThroughMemory(const std::string& temp, const char* format, const OIIO::ImageSpec& spec,
                        OIIO::TypeDesc data_type, const void* data) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
  if (!out) throw RuntimeError(std::string("OpenImageIO has no '") + format + "' writer: " + OIIO::geterror());
  if (!out->supports("ioproxy"))
    throw RuntimeError(std::string("OpenImageIO's '") + format + "' writer cannot write to memory");
  std::vector<unsigned char> encoded;
  OIIO::Filesystem::IOVecOutput proxy(encoded);
  out->set_ioproxy(&proxy);
  if (!out->open(temp, spec)) throw RuntimeError("OpenImageIO cannot encode it: " + out->geterror());
  if (!out->write_image(data_type, data)) {
    const std::string err = out->geterror();
    out->close();
    throw RuntimeError("OpenImageIO encoding failed: " + err);
  }
  if (!out->close()) throw RuntimeError("OpenImageIO close failed: " + out->geterror());
  if (encoded.empty()) throw RuntimeError("OpenImageIO produced no bytes");
  writeBytes(temp, encoded.data(), encoded.size());
}

// OpenImageIO's file proxy that remembers why a write failed. OpenEXR reports a full disk as "File
// output failed" and nothing more, and IOFile::close() drops fflush's error, so the last buffer of
// a file could be lost unreported. Here every write and the final flush keep errno.
class CheckedFile : public OIIO::Filesystem::IOFile {
 public:
  CheckedFile(const std::string& path) : IOFile(path, IOProxy::Write) {
    if (!opened()) error_ = errno ? errno : EIO;
  }
  size_t write(const void* buf, size_t size) override { return note(IOFile::write(buf, size), size); }
  size_t pwrite(const void* buf, size_t size, int64_t offset) override {
    return note(IOFile::pwrite(buf, size, offset), size);
  }
  void close() override {
    if (opened() && handle() && std::fflush(handle()) != 0 && error_ == 0) error_ = errno;
    IOFile::close();
  }
  int error() const { return error_; }

 private:
  size_t note(size_t done, size_t size) {
    if (done < size && error_ == 0) error_ = errno ? errno : EIO;
    return done;
  }
  int error_ = 0;
};

// Writes one image to `temp` in the named OIIO format through CheckedFile; throws with the system's
// reason (No space left on device, ...) when a write failed, else OpenImageIO's message.
void writeWithOiio(const std::string& temp, const char* format, const OIIO::ImageSpec& spec,
                   OIIO::TypeDesc data_type, const void* data) {
  std::unique_ptr<OIIO::ImageOutput> out = OIIO::ImageOutput::create(format);
  if (!out) throw RuntimeError(std::string("OpenImageIO has no '") + format + "' writer: " + OIIO::geterror());
  std::unique_ptr<CheckedFile> proxy;
  if (out->supports("ioproxy")) {
    errno = 0;
    proxy = std::make_unique<CheckedFile>(temp);
    if (proxy->error() != 0) throw RuntimeError("cannot create '" + temp + "': " + std::strerror(proxy->error()));
    out->set_ioproxy(proxy.get());
  }
  const auto fail = [&](const std::string& what, std::string err) {
    if (proxy && proxy->error() != 0) err = std::strerror(proxy->error());
    throw RuntimeError("cannot write '" + temp + "': " + what + ": " + err);
  };
  if (!out->open(temp, spec)) fail("OpenImageIO cannot open it", out->geterror());
  if (!out->write_image(data_type, data)) {
    const std::string err = out->geterror();
    out->close();
    if (proxy) proxy->close();
    fail("OpenImageIO write failed", err);
  }
  const bool closed = out->close();
  if (proxy) proxy->close();  // flushes: a full disk often shows only here
  if (!closed || (proxy && proxy->error() != 0)) fail("OpenImageIO close failed", out->geterror());
}

}  // namespace

std::string writeExr(const std::string& path, const Image& image) {
  checkImage(path, image);
  OIIO::ImageSpec spec(image.width, image.height, image.channels, OIIO::TypeDesc::FLOAT);
  spec.channelnames = channelNamesFor(image);
  spec.alpha_channel = -1;
  for (int c = 0; c < image.channels; ++c)
    if (spec.channelnames[c] == "A") spec.alpha_channel = c;
  spec.attribute("compression", "zip");
  spec.attribute("oiio:ColorSpace", "Linear");
  writeFileAtomic(path, [&](const std::string& temp) {
    writeWithOiio(temp, "openexr", spec, OIIO::TypeDesc::FLOAT, image.pixels.data());
  });
  return path;
}

std::string writePng(const std::string& path, const Image& linear_rgb, double exposure_ev) {
  checkImage(path, linear_rgb);
  std::vector<std::uint8_t> bytes;
  toneMapImage8(linear_rgb, exposure_ev, bytes);
  OIIO::ImageSpec spec(linear_rgb.width, linear_rgb.height, linear_rgb.channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  writeFileAtomic(path, [&](const std::string& temp) {
    writeThroughMemory(temp, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
  });
  return path;
}

std::string writePngBytes(const std::string& path, int width, int height, int channels,
                          const std::vector<std::uint8_t>& bytes) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      bytes.size() != static_cast<std::size_t>(width) * height * channels)
    throw RuntimeError("cannot write '" + path + "': " + std::to_string(bytes.size()) + " bytes are not a " +
                       std::to_string(width) + "x" + std::to_string(height) + "x" + std::to_string(channels) + " image");
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  writeFileAtomic(path, [&](const std::string& temp) {
    writeThroughMemory(temp, "png", spec, OIIO::TypeDesc::UINT8, bytes.data());
  });
  return path;
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
  const std::size_t k = layers ? static_cast<std::size_t>(layers->channels) : 0;
  if (layers && (layers->width != width || layers->height != height || layers->channel_names.size() != k))
    throw RuntimeError("cannot write '" + path + "': its layers are not a " + std::to_string(width) + "x" +
                       std::to_string(height) + " image with named channels");
  OIIO::ImageSpec spec(width, height, static_cast<int>(n + k), OIIO::TypeDesc::FLOAT);
  std::set<std::string> seen;
  for (std::size_t i = 0; i < n; ++i) {
    try {
      spec.channelnames[i] = spectralChannelName(wavelengths_nm[i]);
    } catch (const RuntimeError& e) {
      throw RuntimeError("cannot write '" + path + "': " + e.what());
    }
    if (!seen.insert(spec.channelnames[i]).second)
      throw RuntimeError("cannot write '" + path + "': two bands share the channel name '" +
                         spec.channelnames[i] + "'");
  }
  for (std::size_t c = 0; c < k; ++c) {
    spec.channelnames[n + c] = layers->channel_names[c];
    if (!seen.insert(spec.channelnames[n + c]).second)
      throw RuntimeError("cannot write '" + path + "': two channels are named '" + spec.channelnames[n + c] + "'");
  }
  spec.alpha_channel = -1;
  spec.attribute("compression", "zip");
  spec.attribute("spectralLayoutVersion", kSpectralLayoutVersion);
  spec.attribute("emissiveUnits", kSpectralEmissiveUnits);
  const std::vector<float> all =
      k > 0 ? bandsThenLayers(data, n, layers->pixels, k, static_cast<std::size_t>(width) * height) : std::vector<float>{};
  writeFileAtomic(path, [&](const std::string& temp) {
    writeWithOiio(temp, "openexr", spec, OIIO::TypeDesc::FLOAT, k > 0 ? all.data() : data.data());
  });
  return path;
}

namespace {

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
extern "C" __attribute__((visibility("default"))) const seasim::ImageIoModule* seasim_image_io_module_v4() {
  static const seasim::ImageIoModule table{seasim::kImageIoModuleVersion, &seasim::writeExr,
                                           &seasim::writePng,              &seasim::writePngBytes,
                                           &seasim::writeSpectralExr,
                                           &seasim::readImageHeader,       &seasim::readImage,
                                           &seasim::readImageAttribute,    &seasim::readSpectralExr};
  return &table;
}
