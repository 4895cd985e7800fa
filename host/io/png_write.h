// png_write.h — 8-bit PNG encoding through libpng, without OpenImageIO (exr_write.h says why).
#pragma once
#include <cstdint>
#include <vector>

namespace seasim {

// The PNG file of `bytes` (width x height x channels values, interleaved, top row first; channels 1
// gray, 2 gray + alpha, 3 RGB, 4 RGBA), 8 bits per sample, tagged sRGB with the gAMA and cHRM chunks
// that stand for it (the values are display-encoded sRGB, io/tonemap.h; OpenImageIO tagged them so).
// Throws RuntimeError on a size mismatch or a libpng error. The caller writes the bytes
// (io/atomic_file.h's writeBytes checks every write; libpng's stdio writer would not report a full disk).
std::vector<std::uint8_t> encodePng(int width, int height, int channels, const std::vector<std::uint8_t>& bytes);

}  // namespace seasim
