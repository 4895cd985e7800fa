// npy.cpp — the .npy format: magic "\x93NUMPY", version 1.0, a little-endian uint16 header length,
// then a Python dict literal {'descr', 'fortran_order', 'shape'} padded with spaces to a multiple
// of 64 bytes and ended by '\n', then the raw array.
#include "io/npy.h"

#include <bit>
#include <cstring>
#include <fstream>
#include <algorithm>
#include <sstream>

#include "io/atomic_file.h"
#include "util/error.h"

namespace seasim {

static_assert(std::endian::native == std::endian::little, ".npy I/O assumes a little-endian host");

namespace {

const char kMagic[] = "\x93NUMPY";  // 6 bytes

const char* descrOf(NpyType t) {
  switch (t) {
    case NpyType::Float32: return "<f4";
    case NpyType::Float64: return "<f8";
    case NpyType::UInt8: return "|u1";
  }
  return "";
}

std::size_t sizeOf(NpyType t) {
  switch (t) {
    case NpyType::Float32: return 4;
    case NpyType::Float64: return 8;
    case NpyType::UInt8: return 1;
  }
  return 0;
}

std::size_t product(const std::vector<std::size_t>& shape) {
  std::size_t n = 1;
  for (std::size_t s : shape) n *= s;
  return n;
}

std::string headerFor(NpyType type, const std::vector<std::size_t>& shape) {
  std::string dict = std::string("{'descr': '") + descrOf(type) + "', 'fortran_order': False, 'shape': (";
  for (std::size_t i = 0; i < shape.size(); ++i) {
    dict += std::to_string(shape[i]);
    if (shape.size() == 1 || i + 1 < shape.size()) dict += ",";
    if (i + 1 < shape.size()) dict += " ";
  }
  dict += "), }";
  // 6 magic + 2 version + 2 length + dict + padding + '\n' is a multiple of 64.
  const std::size_t unpadded = 10 + dict.size() + 1;
  dict.append((64 - unpadded % 64) % 64, ' ');
  dict += '\n';
  std::string header(kMagic, 6);
  header += '\x01';
  header += '\x00';
  header += static_cast<char>(dict.size() & 0xff);
  header += static_cast<char>((dict.size() >> 8) & 0xff);
  return header + dict;
}

// The value of `key` in the header dict, as raw text up to the next top-level ',' or '}'.
std::string dictValue(const std::string& dict, const std::string& key, const std::string& path) {
  const std::size_t k = dict.find("'" + key + "'");
  if (k == std::string::npos) throw RuntimeError("'" + path + "': .npy header has no '" + key + "'");
  std::size_t p = dict.find(':', k);
  if (p == std::string::npos) throw RuntimeError("'" + path + "': malformed .npy header");
  ++p;
  int depth = 0;
  std::size_t e = p;
  for (; e < dict.size(); ++e) {
    const char ch = dict[e];
    if (ch == '(') ++depth;
    if (ch == ')') --depth;
    if (depth == 0 && (ch == ',' || ch == '}')) break;
  }
  std::string v = dict.substr(p, e - p);
  const std::size_t b = v.find_first_not_of(" '");
  const std::size_t l = v.find_last_not_of(" '");
  return b == std::string::npos ? std::string() : v.substr(b, l - b + 1);
}

}  // namespace

void writeNpyArray(const std::string& path, NpyType type, const std::vector<std::size_t>& shape,
                   const void* data) {
  const std::string header = headerFor(type, shape);
  const std::size_t bytes = product(shape) * sizeOf(type);
  writeFileAtomic(path, [&](const std::string& temp) {
    writeBytes(temp, {{header.data(), header.size()}, {data, bytes}});
  });
}

NpyArray readNpyArray(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError("cannot open '" + path + "' for reading");
  char pre[10];
  in.read(pre, 10);
  if (!in || std::memcmp(pre, kMagic, 6) != 0) throw RuntimeError("'" + path + "' is not a .npy file");
  std::size_t header_len = 0;
  const int major = static_cast<unsigned char>(pre[6]);
  if (major == 1) {
    header_len = static_cast<unsigned char>(pre[8]) | (static_cast<std::size_t>(static_cast<unsigned char>(pre[9])) << 8);
  } else if (major == 2 || major == 3) {
    char more[2];
    in.read(more, 2);
    header_len = static_cast<unsigned char>(pre[8]) |
                 (static_cast<std::size_t>(static_cast<unsigned char>(pre[9])) << 8) |
                 (static_cast<std::size_t>(static_cast<unsigned char>(more[0])) << 16) |
                 (static_cast<std::size_t>(static_cast<unsigned char>(more[1])) << 24);
  } else {
    throw RuntimeError("'" + path + "': unsupported .npy version " + std::to_string(major));
  }
  std::string dict(header_len, '\0');
  in.read(dict.data(), static_cast<std::streamsize>(header_len));
  if (!in) throw RuntimeError("'" + path + "': truncated .npy header");

  NpyArray arr;
  const std::string descr = dictValue(dict, "descr", path);
  if (descr == "<f4") arr.type = NpyType::Float32;
  else if (descr == "<f8") arr.type = NpyType::Float64;
  else if (descr == "|u1" || descr == "<u1") arr.type = NpyType::UInt8;
  else throw RuntimeError("'" + path + "': unsupported .npy dtype '" + descr + "' (expected <f4, <f8 or |u1)");
  if (dictValue(dict, "fortran_order", path) != "False")
    throw RuntimeError("'" + path + "': Fortran-order .npy arrays are not supported");
  std::string shape_text = dictValue(dict, "shape", path);
  for (char& ch : shape_text)
    if (ch == '(' || ch == ')' || ch == ',') ch = ' ';
  std::istringstream ss(shape_text);
  std::size_t dim;
  while (ss >> dim) arr.shape.push_back(dim);

  const std::size_t n = product(arr.shape);
  const std::size_t elem = sizeOf(arr.type);
  // The header is the file's word for its size: check it against the bytes really there before
  // allocating, so a small file claiming a huge shape is refused instead of exhausting memory.
  const std::streamoff data_start = in.tellg();
  in.seekg(0, std::ios::end);
  const auto available = static_cast<std::size_t>(in.tellg() - data_start);
  in.seekg(data_start);
  for (std::size_t d : arr.shape)
    if (d != 0 && n / d > (std::size_t(1) << 40))
      throw RuntimeError("'" + path + "': its header claims an absurd shape");
  if (n > available / elem)
    throw RuntimeError("'" + path + "': its header claims " + std::to_string(n) + " values but the file holds " +
                       std::to_string(available / elem) + " (truncated or corrupt)");
  std::vector<char> raw(n * elem);
  in.read(raw.data(), static_cast<std::streamsize>(raw.size()));
  if (!in) throw RuntimeError("'" + path + "': truncated .npy data");
  arr.values.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const char* p = raw.data() + i * elem;
    if (arr.type == NpyType::Float32) {
      float f;
      std::memcpy(&f, p, 4);
      arr.values[i] = f;
    } else if (arr.type == NpyType::Float64) {
      std::memcpy(&arr.values[i], p, 8);
    } else {
      arr.values[i] = static_cast<unsigned char>(*p);
    }
  }
  return arr;
}

void writeNpy(const std::string& path, const Image& image) {
  if (image.pixels.size() != image.pixelCount() * static_cast<std::size_t>(image.channels))
    throw RuntimeError("cannot write '" + path + "': pixel buffer does not match the image size");
  writeNpyArray(path, NpyType::Float32,
                {static_cast<std::size_t>(image.height), static_cast<std::size_t>(image.width),
                 static_cast<std::size_t>(image.channels)},
                image.pixels.data());
}

ImageHeader readNpyHeader(const std::string& path) {
  // Only the start of the file: the header dict is short (padded to 64 bytes, never 4 KiB).
  std::ifstream in(path, std::ios::binary);
  if (!in) throw RuntimeError("cannot open '" + path + "' for reading");
  std::string head(4096, '\0');
  in.read(head.data(), static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  if (head.size() < 10 || std::memcmp(head.data(), kMagic, 6) != 0)
    throw RuntimeError("'" + path + "' is not a .npy file");
  std::string shape_text = dictValue(head, "shape", path);
  for (char& ch : shape_text)
    if (ch == '(' || ch == ')' || ch == ',') ch = ' ';
  std::istringstream ss(shape_text);
  std::vector<long long> shape;
  long long dim;
  while (ss >> dim) shape.push_back(dim);
  if (shape.size() != 2 && shape.size() != 3)
    throw RuntimeError("'" + path + "': expected a (height, width[, channels]) array");
  ImageHeader h{static_cast<int>(std::min<long long>(shape[1], 1LL << 30)),
                static_cast<int>(std::min<long long>(shape[0], 1LL << 30)),
                shape.size() == 3 ? static_cast<int>(std::min<long long>(shape[2], 1LL << 30)) : 1};
  if (static_cast<long long>(h.width) * h.height > kMaxImagePixels)
    throw RuntimeError("cannot read image '" + path + "': its header claims " + std::to_string(shape[1]) + "x" +
                       std::to_string(shape[0]) + " pixels, more than the limit of " +
                       std::to_string(kMaxImagePixels) + " (16384x16384); use a smaller image");
  return h;
}

Image readNpy(const std::string& path) {
  (void)readNpyHeader(path);
  const NpyArray arr = readNpyArray(path);
  if (arr.shape.size() != 2 && arr.shape.size() != 3)
    throw RuntimeError("'" + path + "': expected a (height, width[, channels]) array, got " +
                       std::to_string(arr.shape.size()) + " dimensions");
  Image img;
  img.resize(static_cast<int>(arr.shape[1]), static_cast<int>(arr.shape[0]),
             arr.shape.size() == 3 ? static_cast<int>(arr.shape[2]) : 1);
  std::copy(arr.values.begin(), arr.values.end(), img.pixels.begin());
  return img;
}

}  // namespace seasim
