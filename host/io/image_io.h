// image_io.h — image files. Two implementations, CMake compiles exactly one:
//   SEASIM_IMAGE_IO=ON (the default): the writers in image_write.cpp, EXR and spectral EXR through
//                      OpenEXR's library (exr_write.h), PNG through libpng (png_write.h); the readers
//                      through OpenImageIO (image_io_oiio.cpp, a module dlopened on the first read:
//                      any format OpenImageIO knows). The only file that includes OIIO.
//   image_io_npy.cpp   (SEASIM_IMAGE_IO=OFF, builds carried to GPU machines, docs/gpu.md):
//                      every writer writes NumPy arrays beside the requested name instead:
//                        writeExr(p)         -> p + ".npy"  float32 (h, w, c), linear
//                        writePng(p)         -> p + ".npy"  uint8   (h, w, c), the PNG's bytes
//                        writeSpectralExr(p) -> p + ".npy"  float32 (h, w, n) and
//                                               p + ".wavelengths_nm.npy" float64 (n)
//                      and the readers read those back (so `seasim compare a.exr b.exr` still
//                      works on them). Convert on a machine with Python:
//                        imageio.imwrite("a.png", numpy.load("a.png.npy"))
// Every writer returns the path it actually wrote, for manifests and logs.
//
// All writes are atomic (io/atomic_file.h): a temporary file in the target folder renamed onto the
// final name; parent folders are created; on failure nothing is left behind and a RuntimeError
// names the path. `.npy` paths (writeNpy, readImage("x.npy")) work in both builds.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include "io/image.h"
#include "io/npy.h"  // writeNpy / readNpy: float32 (height, width, channels), both builds

namespace seasim {

// True when this build writes and reads real EXR/PNG files, false for the .npy fallback.
bool imageIoAvailable();

// Linear float EXR, zip compression, 32-bit float channels. Channel names: the image's
// channel_names when given (one per channel), else Y / Y,A / R,G,B / R,G,B,A / C0,C1,...
std::string writeExr(const std::string& path, const Image& image);

// Tone-mapped 8-bit sRGB PNG through io/tonemap.h (1, 2, 3 or 4 channels). NaN/Inf show as 0;
// count them beforehand with toneMapImage if the caller must fail on them.
std::string writePng(const std::string& path, const Image& linear_rgb, double exposure_ev);

// 8-bit values written as they are, no tone map (a screenshot of the preview window): `bytes` holds
// width x height x channels (1..4) values, interleaved, top row first.
std::string writePngBytes(const std::string& path, int width, int height, int channels,
                          const std::vector<std::uint8_t>& bytes);

// Spectral EXR in the layout of Fichet, Pacanowski & Wilkie, "An OpenEXR Layout for Spectral
// Images", JCGT 10(3), 2021: one float channel per band named "S0.<int>,<6 decimals>nm" (emissive,
// Stokes component 0, decimal comma), e.g. "S0.550,000000nm", and the header attributes
// spectralLayoutVersion = "1.0" and emissiveUnits = "W.m^-2.sr^-1". `data` is pixel-major:
// data[(y * width + x) * n + i] is band i (wavelengths_nm[i]) of pixel (x, y), top row first.
// `layers` (same size; null: none): more channels after the bands under their own names, the per-band
// ground-truth layers "<layer>.S0.<nm>" (io/spectral_layout.h spectralLayerChannelName).
std::string writeSpectralExr(const std::string& path, int width, int height,
                             const std::vector<double>& wavelengths_nm, const std::vector<float>& data,
                             const Image* layers = nullptr);

// Reads only the header of an image file (or .npy): its size and channel count. Throws
// RuntimeError naming the file when it cannot be opened, is not an image, or has more than
// kMaxImagePixels pixels. Cheap: used by `validate` and at job start to check inputs.
ImageHeader readImageHeader(const std::string& path);

// Any image file (EXR, PNG, ... or .npy) as float values: EXR as stored (linear), 8-bit formats as
// their encoded values scaled to [0,1] (NOT linearised; compare renders through EXR files).
// Channel names are the file's. The header is checked first (readImageHeader). In the .npy build, readImage("x.png") gives the stand-in's bytes
// as 0..255 floats. OpenEXR stores channels sorted by name; this returns them in the
// file's order (R,G,B,A first when present).
Image readImage(const std::string& path);

// A string attribute of an image file's header ("" when absent, or in a build without OIIO),
// e.g. "spectralLayoutVersion" of a spectral EXR, "compression" of any EXR.
std::string readImageAttribute(const std::string& path, const std::string& name);

struct SpectralImage {
  int width = 0, height = 0;
  std::vector<double> wavelengths_nm;  // ascending
  std::vector<float> data;             // pixel-major, as writeSpectralExr takes it
};

// Reads the emissive S0 bands of a spectral EXR (other channels, e.g. an RGB preview, are
// ignored). Channels come back from the file sorted by name ("S0.1000,..." before "S0.400,...");
// this parses each name's wavelength (nm, µm, m ... or Hz as the layout allows) and returns the
// bands sorted by wavelength with the data reordered to match.
SpectralImage readSpectralExr(const std::string& path);

}  // namespace seasim
