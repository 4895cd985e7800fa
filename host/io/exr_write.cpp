// exr_write.cpp — writeExrFile (exr_write.h): an Imf::OutputFile over a stream in memory, then the
// checked writeBytes.
#include "io/exr_write.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfIO.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>

#include <cstdint>
#include <cstring>
#include <exception>
#include <mutex>
#include <set>
#include <thread>

#include "io/atomic_file.h"
#include "util/error.h"

namespace seasim {

namespace {

// The whole file in memory. OpenEXR writes the header, a placeholder line offset table, the blocks, and
// then seeks back to fill in the table.
class MemoryStream : public Imf::OStream {
 public:
  explicit MemoryStream(const std::string& path) : Imf::OStream(path.c_str()) {}
  void write(const char c[], int n) override {
    const std::size_t end = at_ + static_cast<std::size_t>(n);
    if (end > bytes_.size()) bytes_.resize(end);
    std::memcpy(bytes_.data() + at_, c, static_cast<std::size_t>(n));
    at_ = end;
  }
  std::uint64_t tellp() override { return at_; }
  void seekp(std::uint64_t pos) override { at_ = static_cast<std::size_t>(pos); }
  const std::vector<char>& bytes() const { return bytes_; }

 private:
  std::vector<char> bytes_;
  std::size_t at_ = 0;
};

// OpenEXR compresses a file's blocks on its global thread pool, which has no threads unless asked for
// (then every block is compressed by the caller). One thread per core, as OpenImageIO's EXR writer had.
int compressionThreads() {
  static std::once_flag once;
  std::call_once(once, [] {
    const unsigned cores = std::thread::hardware_concurrency();
    if (Imf::globalThreadCount() == 0 && cores > 1) Imf::setGlobalThreadCount(static_cast<int>(cores));
  });
  return Imf::globalThreadCount();
}

}  // namespace

void writeExrFile(const std::string& path, int width, int height, const std::vector<ExrChannel>& channels,
                  const std::vector<std::pair<std::string, std::string>>& string_attributes) {
  auto fail = [&](const std::string& why) { throw RuntimeError("cannot write '" + path + "': " + why); };
  if (width <= 0 || height <= 0 || channels.empty()) fail("empty EXR image");
  MemoryStream stream(path);
  try {
    // Header(w, h): display window = data window from (0, 0), pixel aspect 1, screen window (0, 0) and
    // 1, increasing y; each as OpenImageIO wrote them.
    Imf::Header header(width, height);
    header.compression() = Imf::ZIP_COMPRESSION;
    Imf::FrameBuffer frame;
    std::set<std::string> names;
    for (const ExrChannel& c : channels) {
      // OpenEXR keeps names in 256-byte buffers (a longer one would be cut short) and its channel list is
      // a map (a second channel of one name would replace the first): both without a word.
      if (c.name.empty() || c.name.size() > 255 || c.name.find('\0') != std::string::npos)
        fail("the EXR channel name '" + c.name + "' must be 1 to 255 bytes without NUL");
      if (!names.insert(c.name).second) fail("two EXR channels are named '" + c.name + "'");
      header.channels().insert(c.name, Imf::Channel(Imf::FLOAT));
      const std::size_t x_stride = c.stride * sizeof(float);
      frame.insert(c.name, Imf::Slice(Imf::FLOAT, reinterpret_cast<char*>(const_cast<float*>(c.first)), x_stride,
                                      x_stride * static_cast<std::size_t>(width)));
    }
    for (const auto& [name, text] : string_attributes) {
      if (header.find(name) != header.end()) fail("EXR attribute '" + name + "' given twice");
      header.insert(name, Imf::StringAttribute(text));
    }
    Imf::OutputFile file(stream, header, compressionThreads());
    file.setFrameBuffer(frame);
    file.writePixels(height);
  } catch (const RuntimeError&) {
    throw;
  } catch (const std::exception& e) {  // Iex::BaseExc: e.g. an image too large for OpenEXR
    fail(std::string("OpenEXR cannot encode it: ") + e.what());
  }
  writeBytes(path, stream.bytes().data(), stream.bytes().size());
}

}  // namespace seasim
