// png_write.cpp — encodePng (png_write.h) through libpng's write API into memory.
#include "io/png_write.h"

#include <png.h>

#include <csetjmp>
#include <cstdio>
#include <string>

#include "util/error.h"

namespace seasim {

namespace {

struct PngSink {
  std::vector<std::uint8_t>* out;
  char message[200];
};

void appendBytes(png_structp png, png_bytep data, png_size_t size) {
  auto* sink = static_cast<PngSink*>(png_get_io_ptr(png));
  sink->out->insert(sink->out->end(), data, data + size);
}

void flushNothing(png_structp) {}

// libpng reports an error by longjmp out of its own frames (throwing through C code is not safe):
// keep the message, then jump back to encodeRows' setjmp.
void onError(png_structp png, png_const_charp message) {
  auto* sink = static_cast<PngSink*>(png_get_error_ptr(png));
  std::snprintf(sink->message, sizeof sink->message, "%s", message ? message : "unknown error");
  png_longjmp(png, 1);
}

void onWarning(png_structp, png_const_charp) {}

// Everything between setjmp and the jump back is C and trivially destructible; returns false with
// sink->message set on a libpng error.
bool encodeRows(PngSink* sink, int width, int height, int color_type, png_bytep* rows) {
  png_structp png = png_create_write_struct(PNG_LIBPNG_VER_STRING, sink, onError, onWarning);
  if (!png) {
    std::snprintf(sink->message, sizeof sink->message, "out of memory");
    return false;
  }
  png_infop info = png_create_info_struct(png);
  if (!info || setjmp(png_jmpbuf(png))) {
    if (!info) std::snprintf(sink->message, sizeof sink->message, "out of memory");
    png_destroy_write_struct(&png, info ? &info : nullptr);
    return false;
  }
  png_set_write_fn(png, sink, appendBytes, flushNothing);
  png_set_IHDR(png, info, static_cast<png_uint_32>(width), static_cast<png_uint_32>(height), 8, color_type,
               PNG_INTERLACE_NONE, PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  png_set_sRGB_gAMA_and_cHRM(png, info, PNG_sRGB_INTENT_ABSOLUTE);  // the chunks OpenImageIO wrote
  png_write_info(png, info);
  png_write_image(png, rows);
  png_write_end(png, info);
  png_destroy_write_struct(&png, &info);
  return true;
}

}  // namespace

std::vector<std::uint8_t> encodePng(int width, int height, int channels, const std::vector<std::uint8_t>& bytes) {
  if (width <= 0 || height <= 0 || channels < 1 || channels > 4 ||
      bytes.size() != static_cast<std::size_t>(width) * height * channels)
    throw RuntimeError(std::to_string(bytes.size()) + " bytes are not a " + std::to_string(width) + "x" +
                       std::to_string(height) + "x" + std::to_string(channels) + " 8-bit image");
  static constexpr int kColorType[] = {PNG_COLOR_TYPE_GRAY, PNG_COLOR_TYPE_GRAY_ALPHA, PNG_COLOR_TYPE_RGB,
                                       PNG_COLOR_TYPE_RGB_ALPHA};
  std::vector<png_bytep> rows(height);
  for (int y = 0; y < height; ++y)
    rows[y] = const_cast<png_bytep>(bytes.data() + static_cast<std::size_t>(y) * width * channels);
  std::vector<std::uint8_t> out;
  out.reserve(bytes.size() / 2 + 1024);
  PngSink sink{&out, {}};
  if (!encodeRows(&sink, width, height, kColorType[channels - 1], rows.data()))
    throw RuntimeError(std::string("libpng could not encode it: ") + sink.message);
  return out;
}

}  // namespace seasim
