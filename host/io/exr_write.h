// exr_write.h — writing float OpenEXR files through OpenEXR's own library (Imf::OutputFile), without
// OpenImageIO: single part, scan lines, 32-bit float channels, ZIP compression (16 lines a block).
// OpenImageIO binds ~240 more shared libraries on first use, most of a short render's wall time
// (results/BENCHMARKS.md, "Fixed cost per process"); OpenEXR's library is four (Imf, Iex, IlmThread,
// Imath) and zlib. The file holds what OpenImageIO's EXR writer wrote for the same image: the same
// channels, header attributes and ZIP blocks byte for byte, less OpenImageIO's capDate (so a render
// writes the same bytes every time). OpenImageIO still reads them (image_io_oiio.cpp).
#pragma once
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

namespace seasim {

// One float channel of an image in memory: pixel (x, y) holds first[(y * width + x) * stride], top row
// first. Several channels usually point into one interleaved buffer (first = data + c, stride = the
// channel count).
struct ExrChannel {
  std::string name;    // 1..255 bytes, unique in the file; names over 31 bytes set OpenEXR's long-names flag
  const float* first;  // pixel (0, 0)
  std::size_t stride;  // floats from one pixel's value to the next one's
};

// Writes the channels (stored sorted by name, as OpenEXR requires) and any extra header attributes of
// type "string" (e.g. spectralLayoutVersion = "1.0") to the NEW file `path`: call it on
// writeFileAtomic's temporary name. OpenEXR encodes the file in memory, compressing its blocks on
// OpenEXR's thread pool; io/atomic_file.h's writeBytes then writes it, checking every write and the close
// (OpenEXR's own file stream writes the line offset table in its destructor, which drops any error).
// Throws RuntimeError naming `path` on bad input (a repeated or empty channel name) or a failed write.
void writeExrFile(const std::string& path, int width, int height, const std::vector<ExrChannel>& channels,
                  const std::vector<std::pair<std::string, std::string>>& string_attributes = {});

}  // namespace seasim
