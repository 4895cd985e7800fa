// npy.h — NumPy .npy files (format version 1.0, little endian, C order): the raw output of builds
// without OpenImageIO (SEASIM_IMAGE_IO=OFF, for GPU machines; see docs/gpu.md) and a format
// any Python with numpy reads: `numpy.load("frame.exr.npy")`. Compiled in every build.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "io/image.h"

namespace seasim {

enum class NpyType { Float32, Float64, UInt8 };

// Writes an array atomically (io/atomic_file.h). `data` holds product(shape) values of `type`.
void writeNpyArray(const std::string& path, NpyType type, const std::vector<std::size_t>& shape,
                   const void* data);

struct NpyArray {
  NpyType type = NpyType::Float32;
  std::vector<std::size_t> shape;
  std::vector<double> values;  // converted to double (exact for all three types), C order
};

// Reads '<f4', '<f8' or '|u1' arrays in C order; anything else is a RuntimeError naming the file.
NpyArray readNpyArray(const std::string& path);

// The (h, w[, c]) shape of a .npy image, read from its header only; a RuntimeError when the file
// is not one, or its header claims more than kMaxImagePixels or more data than the file holds.
ImageHeader readNpyHeader(const std::string& path);

// An image as float32 with shape (height, width, channels).
void writeNpy(const std::string& path, const Image& image);
// A 2-D (h, w) or 3-D (h, w, c) array as an Image (uint8 values stay 0..255, not rescaled).
Image readNpy(const std::string& path);

}  // namespace seasim
