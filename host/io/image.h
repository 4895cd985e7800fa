// image.h — a plain float image, the one pixel container host/io and host/reference share.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

namespace seasim {

struct Image {
  int width = 0, height = 0, channels = 0;
  std::vector<float> pixels;               // row-major, top row first, channels interleaved
  std::vector<std::string> channel_names;  // empty = the writer's default (Y / R,G,B / R,G,B,A)

  float at(int x, int y, int c) const { return pixels[index(x, y, c)]; }
  float& at(int x, int y, int c) { return pixels[index(x, y, c)]; }
  std::size_t index(int x, int y, int c) const {
    return (static_cast<std::size_t>(y) * width + x) * channels + c;
  }
  // Sets the size and zero-fills the pixels (channel names are left alone).
  void resize(int w, int h, int c) {
    width = w;
    height = h;
    channels = c;
    pixels.assign(static_cast<std::size_t>(w) * h * c, 0.0f);
  }
  std::size_t pixelCount() const { return static_cast<std::size_t>(width) * height; }
  // A black w x h image with channels R, G, B.
  static Image rgb(int w, int h) {
    Image img;
    img.resize(w, h, 3);
    img.channel_names = {"R", "G", "B"};
    return img;
  }
};

// The most pixels (width x height) an input image may have. Readers check the header against it
// before decoding, so a small file whose header claims 60000 x 60000 is refused instead of asking
// for gigabytes. 16384^2 is also the largest render (camera.width/height).
constexpr long long kMaxImagePixels = 16384LL * 16384LL;

struct ImageHeader {
  int width = 0, height = 0, channels = 0;
};

}  // namespace seasim
