// io_test.cpp — host/io: atomic writes, tone map, .npy, CSV, EXR/PNG/spectral EXR round trips.
// Built with image I/O (SEASIM_IMAGE_IO=1) the round trips go through real EXR/PNG files (written by
// OpenEXR's library and libpng, read by OpenImageIO); without it they go through the .npy files that
// stand in for them (image_io.h).
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include "io/atomic_file.h"
#include "io/csv.h"
#include "io/image_io.h"
#include "io/npy.h"
#include "io/spectral_layout.h"
#include "io/tonemap.h"
#include "util/error.h"

#ifndef SEASIM_IMAGE_IO
#define SEASIM_IMAGE_IO 1
#endif

namespace seasim {
namespace {

namespace fs = std::filesystem;

class IoTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() /
           ("seasim_io_test_" + std::to_string(::getpid()) + "_" +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  // Every file under the test folder (recursively), as paths relative to it.
  std::vector<std::string> listing() const {
    std::vector<std::string> out;
    for (const auto& e : fs::recursive_directory_iterator(dir_))
      if (e.is_regular_file()) out.push_back(fs::relative(e.path(), dir_).string());
    std::sort(out.begin(), out.end());
    return out;
  }
  static std::string slurp(const std::string& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  }
  fs::path dir_;
};

Image rampImage(int w, int h, int c) {
  Image img;
  img.resize(w, h, c);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int k = 0; k < c; ++k) img.at(x, y, k) = 0.37f * x - 1.25f * y + 0.1f * k + 1.0f / 3.0f;
  return img;
}

bool bitEqual(float a, float b) { return std::memcmp(&a, &b, sizeof a) == 0; }

// ---------------------------------------------------------------- atomic writes

TEST_F(IoTest, TempNameIsHiddenInTheTargetFolderWithThePid) {
  EXPECT_EQ(atomicTempPath("/a/b/out.exr"), "/a/b/.out.exr.tmp-" + std::to_string(::getpid()));
  EXPECT_EQ(atomicTempPath("out.csv"), ".out.csv.tmp-" + std::to_string(::getpid()));
}

TEST_F(IoTest, TextWriteCreatesFoldersAndLeavesNoTempFile) {
  const std::string p = path("x/y/report.txt");
  writeTextAtomic(p, "hello\nworld\n");
  EXPECT_EQ(slurp(p), "hello\nworld\n");
  EXPECT_EQ(listing(), std::vector<std::string>{"x/y/report.txt"});
  writeTextAtomic(p, "second");  // replacing an existing file
  EXPECT_EQ(slurp(p), "second");
  EXPECT_EQ(listing(), std::vector<std::string>{"x/y/report.txt"});
}

TEST_F(IoTest, FailingWriterLeavesOldTargetAndNoTemp) {
  const std::string p = path("keep.txt");
  writeTextAtomic(p, "old complete contents");
  try {
    writeFileAtomic(p, [](const std::string& temp) {
      std::ofstream(temp) << "half a fi";  // a partial file, then the writer dies
      throw std::runtime_error("simulated crash in the encoder");
    });
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find(p), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("simulated crash"), std::string::npos) << e.what();
  }
  EXPECT_EQ(slurp(p), "old complete contents");
  EXPECT_EQ(listing(), std::vector<std::string>{"keep.txt"});
}

TEST_F(IoTest, WriteUnderARegularFileThrowsAndLeavesNothing) {
  writeTextAtomic(path("plain"), "x");
  const std::string bad = path("plain/sub/out.exr");  // "plain" is a file, not a folder
  try {
    writeExr(bad, rampImage(4, 3, 3));
    FAIL() << "expected RuntimeError";
  } catch (const RuntimeError& e) {
    EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
  }
  EXPECT_THROW(writeTextAtomic(bad, "x"), RuntimeError);
  EXPECT_EQ(listing(), std::vector<std::string>{"plain"});
}

TEST_F(IoTest, RenameOntoAFolderFailsAndRemovesTheTemp) {
  fs::create_directories(path("taken/inner"));
  EXPECT_THROW(writeTextAtomic(path("taken"), "x"), RuntimeError);
  EXPECT_THROW(writeNpy(path("taken"), rampImage(2, 2, 1)), RuntimeError);
  EXPECT_TRUE(listing().empty());
  EXPECT_TRUE(fs::is_directory(path("taken/inner")));
}

TEST_F(IoTest, BadImageBufferThrowsBeforeWriting) {
  Image img = rampImage(4, 4, 3);
  img.pixels.pop_back();
  EXPECT_THROW(writeExr(path("a.exr"), img), RuntimeError);
  EXPECT_THROW(writePng(path("a.png"), img, 0.0), RuntimeError);
  EXPECT_THROW(writeSpectralExr(path("s.exr"), 2, 2, {500.0, 600.0}, std::vector<float>(7)), RuntimeError);
  EXPECT_TRUE(listing().empty());
}

// ---------------------------------------------------------------- tone map

TEST(ToneMap, SrgbCurveKnownPoints) {
  EXPECT_DOUBLE_EQ(srgbEncode(0.0), 0.0);
  EXPECT_DOUBLE_EQ(srgbEncode(1.0), 1.0);
  EXPECT_NEAR(srgbEncode(0.5), 0.735356983, 1e-8);      // 1.055 * 0.5^(1/2.4) - 0.055
  EXPECT_NEAR(srgbEncode(0.002), 12.92 * 0.002, 1e-15);  // linear toe below 0.0031308
  for (double v = 0.0; v <= 1.0; v += 0.01) EXPECT_NEAR(srgbDecode(srgbEncode(v)), v, 1e-12);
  EXPECT_EQ(toByte(0.0f), 0);
  EXPECT_EQ(toByte(1.0f), 255);
  EXPECT_EQ(toByte(0.5f), 128);  // 127.5 rounds up
  EXPECT_EQ(toByte(2.0f), 255);
  EXPECT_EQ(toByte(-1.0f), 0);
  EXPECT_EQ(toByte(std::numeric_limits<float>::quiet_NaN()), 0);
}

TEST(ToneMap, ReinhardOnLuminanceWithExposure) {
  float out[3];
  const float grey1[3] = {1, 1, 1};  // Y = 1 -> 1/(1+1) = 0.5 linear on the display
  EXPECT_EQ(toneMapRgb(grey1, 1.0, out), 0);
  for (float v : out) EXPECT_NEAR(v, srgbEncode(0.5), 1e-6);
  const float grey_half[3] = {0.5f, 0.5f, 0.5f};  // +1 EV doubles it back to Y = 1
  toneMapRgb(grey_half, std::exp2(1.0), out);
  for (float v : out) EXPECT_NEAR(v, srgbEncode(0.5), 1e-6);
  // Never clips to flat white: a 1e6 highlight is still below a 1e7 one.
  const float hi1[3] = {1e6f, 1e6f, 1e6f}, hi2[3] = {1e7f, 1e7f, 1e7f};
  float o1[3], o2[3];
  toneMapRgb(hi1, 1.0, o1);
  toneMapRgb(hi2, 1.0, o2);
  EXPECT_LT(o1[0], o2[0]);
  EXPECT_LE(o2[0], 1.0f);
  // A bright saturated blue (small Y) stays in gamut with its R:G:B ratio kept (before the OETF).
  const float blue[3] = {0.0f, 1.0f, 40.0f};
  toneMapRgb(blue, 1.0, out);
  EXPECT_FLOAT_EQ(out[2], 1.0f);
  EXPECT_NEAR(srgbDecode(out[1]) / srgbDecode(out[2]), 1.0 / 40.0, 1e-5);
  EXPECT_EQ(out[0], 0.0f);
  // Negative (out-of-gamut) components are clamped to 0, not counted as bad.
  const float neg[3] = {-0.2f, 0.3f, 0.3f};
  EXPECT_EQ(toneMapRgb(neg, 1.0, out), 0);
  EXPECT_EQ(out[0], 0.0f);
}

TEST(ToneMap, NonFiniteValuesAreCountedAndShownAsZero) {
  Image img;
  img.resize(3, 1, 4);
  const float nan = std::numeric_limits<float>::quiet_NaN(), inf = std::numeric_limits<float>::infinity();
  const float px[12] = {nan, 0.5f, 0.5f, 1.0f, inf, -inf, 0.2f, nan, 0.25f, 0.25f, 0.25f, 0.5f};
  std::copy(px, px + 12, img.pixels.begin());
  Image shown;
  EXPECT_EQ(toneMapImage(img, 0.0, shown), 4);  // NaN, +Inf, -Inf, and a NaN alpha
  EXPECT_EQ(shown.at(0, 0, 0), 0.0f);
  EXPECT_GT(shown.at(0, 0, 1), 0.0f);
  EXPECT_EQ(shown.at(0, 0, 3), 1.0f);  // alpha passes through, clamped
  EXPECT_EQ(shown.at(1, 0, 0), 0.0f);
  EXPECT_EQ(shown.at(1, 0, 1), 0.0f);
  EXPECT_EQ(shown.at(1, 0, 3), 0.0f);  // NaN alpha -> 0
  EXPECT_FLOAT_EQ(shown.at(2, 0, 3), 0.5f);
  for (float v : shown.pixels) EXPECT_TRUE(v >= 0.0f && v <= 1.0f);
  std::vector<std::uint8_t> bytes;
  EXPECT_EQ(toneMapImage8(img, 0.0, bytes), 4);
  EXPECT_EQ(bytes.size(), 12u);
  EXPECT_EQ(bytes[0], 0);
  Image five;
  five.resize(1, 1, 5);
  EXPECT_THROW(toneMapImage(five, 0.0, shown), RuntimeError);
}

// ---------------------------------------------------------------- spectral channel names

TEST(SpectralLayout, ChannelNamesFollowTheLayout) {
  EXPECT_EQ(spectralChannelName(550.0), "S0.550,000000nm");
  EXPECT_EQ(spectralChannelName(1000.0), "S0.1000,000000nm");
  EXPECT_EQ(spectralChannelName(412.5), "S0.412,500000nm");
  EXPECT_THROW(spectralChannelName(0.0), RuntimeError);
  EXPECT_THROW(spectralChannelName(-5.0), RuntimeError);
  EXPECT_THROW(spectralChannelName(std::nan("")), RuntimeError);
  double nm = 0;
  ASSERT_TRUE(parseSpectralChannelName("S0.550,000000nm", nm));
  EXPECT_EQ(nm, 550.0);
  ASSERT_TRUE(parseSpectralChannelName("S0.412,5nm", nm));
  EXPECT_EQ(nm, 412.5);
  ASSERT_TRUE(parseSpectralChannelName("S0.0,55um", nm));
  EXPECT_NEAR(nm, 550.0, 1e-9);
  ASSERT_TRUE(parseSpectralChannelName("S0.5,5e-7m", nm));
  EXPECT_NEAR(nm, 550.0, 1e-9);
  ASSERT_TRUE(parseSpectralChannelName("S0.545,077196THz", nm));  // c / 545.077 THz = 550 nm
  EXPECT_NEAR(nm, 550.0, 1e-4);
  EXPECT_FALSE(parseSpectralChannelName("R", nm));
  EXPECT_FALSE(parseSpectralChannelName("S1.550,000000nm", nm));  // polarisation component
  EXPECT_FALSE(parseSpectralChannelName("T.550,000000nm", nm));   // reflective
  EXPECT_FALSE(parseSpectralChannelName("S0.abcnm", nm));
  EXPECT_FALSE(parseSpectralChannelName("S0.550,0", nm));
}

// ---------------------------------------------------------------- .npy

TEST_F(IoTest, NpyRoundTripAndHeader) {
  const Image img = rampImage(5, 3, 2);
  writeNpy(path("a.npy"), img);
  const std::string raw = slurp(path("a.npy"));
  ASSERT_GT(raw.size(), 10u);
  EXPECT_EQ(raw.substr(0, 6), std::string("\x93NUMPY", 6));
  const std::size_t header = 10 + (static_cast<unsigned char>(raw[8]) | (static_cast<unsigned char>(raw[9]) << 8));
  EXPECT_EQ(header % 64, 0u);
  EXPECT_EQ(raw[header - 1], '\n');
  EXPECT_NE(raw.find("'descr': '<f4', 'fortran_order': False, 'shape': (3, 5, 2)"), std::string::npos);
  EXPECT_EQ(raw.size(), header + 5 * 3 * 2 * 4);
  const Image back = readNpy(path("a.npy"));
  ASSERT_EQ(back.width, 5);
  ASSERT_EQ(back.height, 3);
  ASSERT_EQ(back.channels, 2);
  for (std::size_t i = 0; i < img.pixels.size(); ++i) EXPECT_TRUE(bitEqual(back.pixels[i], img.pixels[i]));
  const std::vector<double> wl = {400.5, 700.25};
  writeNpyArray(path("w.npy"), NpyType::Float64, {2}, wl.data());
  const NpyArray arr = readNpyArray(path("w.npy"));
  EXPECT_EQ(arr.shape, std::vector<std::size_t>{2});
  EXPECT_EQ(arr.values, wl);
  EXPECT_NE(slurp(path("w.npy")).find("'shape': (2,)"), std::string::npos);
  writeTextAtomic(path("bad.npy"), "not numpy");
  EXPECT_THROW(readNpy(path("bad.npy")), RuntimeError);
}

// ---------------------------------------------------------------- CSV

TEST_F(IoTest, CsvQuotingNumbersAndAtomicWrite) {
  EXPECT_EQ(csvQuote("plain"), "plain");
  EXPECT_EQ(csvQuote("a,b"), "\"a,b\"");
  EXPECT_EQ(csvQuote("say \"hi\""), "\"say \"\"hi\"\"\"");
  EXPECT_EQ(csvQuote("two\nlines"), "\"two\nlines\"");
  EXPECT_EQ(csvQuote(" padded"), "\" padded\"");
  CsvWriter t({"setting", "time_ms", "rmse_8bit", "count"});
  t.addRow({"n_z=12, n_d=128", 0.1, 2.5e-7, 42});
  t.addRow({std::string("x"), 1.0 / 3.0, std::numeric_limits<double>::quiet_NaN(), std::size_t{7}});
  t.addRow({"inf", std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(), -3});
  EXPECT_THROW(t.addRow({"too", "few"}), RuntimeError);
  const std::string expected =
      "setting,time_ms,rmse_8bit,count\n"
      "\"n_z=12, n_d=128\",0.1,2.5e-07,42\n"
      "x,0.3333333333333333,nan,7\n"
      "inf,inf,-inf,-3\n";
  EXPECT_EQ(t.str(), expected);
  EXPECT_EQ(std::stod("0.3333333333333333"), 1.0 / 3.0);  // shortest form reads back exactly
  t.write(path("out/sweep.csv"));
  EXPECT_EQ(slurp(path("out/sweep.csv")), expected);
  EXPECT_EQ(listing(), std::vector<std::string>{"out/sweep.csv"});
}

// ---------------------------------------------------------------- image files

TEST_F(IoTest, ExrRoundTripIsBitExact) {
  Image img = rampImage(7, 5, 3);
  img.at(0, 0, 0) = 1e-40f;   // denormal
  img.at(1, 0, 1) = -3.5e7f;  // negative, large
  img.at(2, 0, 2) = 6.1e-5f;
  const std::string written = writeExr(path("frame.exr"), img);
  EXPECT_EQ(written, SEASIM_IMAGE_IO ? path("frame.exr") : path("frame.exr.npy"));
  EXPECT_EQ(listing(), std::vector<std::string>{fs::path(written).filename().string()});
  const Image back = readImage(path("frame.exr"));
  ASSERT_EQ(back.width, 7);
  ASSERT_EQ(back.height, 5);
  ASSERT_EQ(back.channels, 3);
  for (std::size_t i = 0; i < img.pixels.size(); ++i)
    ASSERT_TRUE(bitEqual(back.pixels[i], img.pixels[i])) << i << ": " << back.pixels[i] << " vs " << img.pixels[i];
#if SEASIM_IMAGE_IO
  EXPECT_EQ(back.channel_names, (std::vector<std::string>{"R", "G", "B"}));
  EXPECT_EQ(readImageAttribute(path("frame.exr"), "compression"), "zip");
  // RGBA and custom names.
  Image rgba = rampImage(3, 2, 4);
  writeExr(path("rgba.exr"), rgba);
  EXPECT_EQ(readImage(path("rgba.exr")).channel_names, (std::vector<std::string>{"R", "G", "B", "A"}));
  Image depth = rampImage(3, 2, 1);
  depth.channel_names = {"Z"};
  writeExr(path("depth.exr"), depth);
  const Image dback = readImage(path("depth.exr"));
  EXPECT_EQ(dback.channel_names, std::vector<std::string>{"Z"});
  for (std::size_t i = 0; i < depth.pixels.size(); ++i) EXPECT_TRUE(bitEqual(dback.pixels[i], depth.pixels[i]));
#endif
  EXPECT_THROW(readImage(path("missing.exr")), RuntimeError);
}

// Fills rows [0, rows) of every channel with random bit patterns (no NaN or Inf): values that zlib cannot
// shrink, so those ZIP blocks are stored raw, beside rows that it can.
void fillWithNoise(std::vector<float>& values, std::size_t count, std::uint32_t seed) {
  for (std::size_t i = 0; i < count; ++i) {
    seed = seed * 1664525u + 1013904223u;
    std::uint32_t bits = seed;
    if ((bits & 0x7f800000u) == 0x7f800000u) bits &= ~0x00800000u;
    std::memcpy(&values[i], &bits, sizeof bits);
  }
}

TEST_F(IoTest, ExrOfManyBlocksAndChannelsRoundTripsBitExact) {
  // 37 x 41: three full 16-line ZIP blocks and a short one; noise in the top 20 rows next to a smooth
  // ramp; channels given out of name order (OpenEXR stores them sorted), one name longer than 31 bytes
  // (the file then needs OpenEXR's long-names flag). Real files only: the .npy stand-in keeps no names.
#if SEASIM_IMAGE_IO
  Image img = rampImage(37, 41, 5);
  fillWithNoise(img.pixels, 20 * 37 * 5, 12345);
  img.channel_names = {"z.depth", "B", "a_channel_name_longer_than_31_bytes", "A", "normal.x"};
  writeExr(path("many.exr"), img);
  EXPECT_EQ(listing(), std::vector<std::string>{"many.exr"});
  EXPECT_EQ(readImageAttribute(path("many.exr"), "compression"), "zip");
  const Image back = readImage(path("many.exr"));
  ASSERT_EQ(back.width, 37);
  ASSERT_EQ(back.height, 41);
  ASSERT_EQ(back.channels, 5);
  for (int c = 0; c < 5; ++c) {
    const auto at = std::find(back.channel_names.begin(), back.channel_names.end(), img.channel_names[c]);
    ASSERT_NE(at, back.channel_names.end()) << img.channel_names[c];
    const int k = static_cast<int>(at - back.channel_names.begin());
    for (int y = 0; y < 41; ++y)
      for (int x = 0; x < 37; ++x)
        ASSERT_TRUE(bitEqual(back.at(x, y, k), img.at(x, y, c))) << img.channel_names[c] << " " << x << "," << y;
  }
  img.channel_names = {"R", "G", "R", "A", "B"};  // a repeated name: refused, nothing written
  EXPECT_THROW(writeExr(path("dup.exr"), img), RuntimeError);
  img.channel_names = {"R", "G", "", "A", "B"};  // an empty one
  EXPECT_THROW(writeExr(path("empty.exr"), img), RuntimeError);
  img.channel_names = {"R", "G", std::string(256, 'x'), "A", "B"};  // longer than OpenEXR keeps
  EXPECT_THROW(writeExr(path("long.exr"), img), RuntimeError);
  EXPECT_EQ(listing(), std::vector<std::string>{"many.exr"});
#endif
}

TEST_F(IoTest, SpectralExrWithLayersOfManyBlocksRoundTripsBitExact) {
  // A render's spectral.exr: 31 bands (400..700 nm) and two per-band ground-truth layers, 93 channels,
  // 23 x 35 pixels (two full ZIP blocks and a short one). Every channel comes back bit for bit under its
  // name; readSpectralExr takes the bands and leaves the layers' "<layer>.S0.<nm>" channels alone. Real
  // files only: the .npy stand-in keeps no names.
#if SEASIM_IMAGE_IO
  std::vector<double> wl;
  for (int nm = 400; nm <= 700; nm += 10) wl.push_back(nm);
  const int w = 23, h = 35;
  const std::size_t n = wl.size(), pixels = static_cast<std::size_t>(w) * h;
  std::vector<float> data(pixels * n);
  for (std::size_t i = 0; i < data.size(); ++i) data[i] = 0.001f * static_cast<float>(i % 977) + 1.0f / 7.0f;
  fillWithNoise(data, pixels * n / 3, 777);
  Image layers;
  layers.resize(w, h, static_cast<int>(2 * n));
  for (const char* layer : {"direct", "backscatter"})
    for (double nm : wl) layers.channel_names.push_back(spectralLayerChannelName(layer, nm));
  fillWithNoise(layers.pixels, layers.pixels.size(), 4242);
  writeSpectralExr(path("spectral.exr"), w, h, wl, data, &layers);
  const SpectralImage bands = readSpectralExr(path("spectral.exr"));
  ASSERT_EQ(bands.wavelengths_nm, wl);
  ASSERT_EQ(bands.data.size(), data.size());
  for (std::size_t i = 0; i < data.size(); ++i) ASSERT_TRUE(bitEqual(bands.data[i], data[i])) << i;
  EXPECT_EQ(readImageAttribute(path("spectral.exr"), "spectralLayoutVersion"), "1.0");
  EXPECT_EQ(readImageAttribute(path("spectral.exr"), "emissiveUnits"), "W.m^-2.sr^-1");
  EXPECT_EQ(readImageAttribute(path("spectral.exr"), "compression"), "zip");
  const Image back = readImage(path("spectral.exr"));
  ASSERT_EQ(back.channels, static_cast<int>(3 * n));
  for (std::size_t c = 0; c < 2 * n; ++c) {
    const auto at = std::find(back.channel_names.begin(), back.channel_names.end(), layers.channel_names[c]);
    ASSERT_NE(at, back.channel_names.end()) << layers.channel_names[c];
    const int k = static_cast<int>(at - back.channel_names.begin());
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x)
        ASSERT_TRUE(bitEqual(back.at(x, y, k), layers.at(x, y, static_cast<int>(c))))
            << layers.channel_names[c] << " " << x << "," << y;
  }
  // A layer named like a band: refused, nothing written.
  layers.channel_names[5] = spectralChannelName(wl[2]);
  EXPECT_THROW(writeSpectralExr(path("clash.exr"), w, h, wl, data, &layers), RuntimeError);
  EXPECT_EQ(listing(), std::vector<std::string>{"spectral.exr"});
#endif
}

TEST_F(IoTest, PngBytesRoundTripForOneToFourChannels) {
  for (int channels = 1; channels <= 4; ++channels) {
    const int w = 9, h = 7;
    std::vector<std::uint8_t> bytes(w * h * channels);
    for (std::size_t i = 0; i < bytes.size(); ++i) bytes[i] = static_cast<std::uint8_t>(i * 37 + channels);
    // Opaque alpha: OpenImageIO's reader premultiplies colour by alpha, the file holds them unassociated.
    if (channels % 2 == 0)
      for (std::size_t i = channels - 1; i < bytes.size(); i += channels) bytes[i] = 255;
    const std::string name = "shot" + std::to_string(channels) + ".png";
    writePngBytes(path(name), w, h, channels, bytes);
    const Image back = readImage(path(name));
    ASSERT_EQ(back.width, w);
    ASSERT_EQ(back.height, h);
    ASSERT_EQ(back.channels, channels);
    const double to_byte = SEASIM_IMAGE_IO ? 255.0 : 1.0;
    for (std::size_t i = 0; i < bytes.size(); ++i) ASSERT_EQ(std::lround(back.pixels[i] * to_byte), bytes[i]) << i;
#if SEASIM_IMAGE_IO
    EXPECT_EQ(readImageAttribute(path(name), "oiio:ColorSpace"), "sRGB");  // the file's sRGB chunk
#endif
  }
  EXPECT_THROW(writePngBytes(path("bad.png"), 2, 2, 5, std::vector<std::uint8_t>(20)), RuntimeError);
  EXPECT_FALSE(fs::exists(path("bad.png")) || fs::exists(path("bad.png.npy")));
}

TEST_F(IoTest, PngHoldsTheToneMappedBytes) {
  Image img;
  img.resize(16, 4, 3);
  for (int y = 0; y < 4; ++y)
    for (int x = 0; x < 16; ++x) {
      img.at(x, y, 0) = 0.05f * x * (y + 1);
      img.at(x, y, 1) = 0.02f * x;
      img.at(x, y, 2) = 3.0f / (1 + x);
    }
  img.at(3, 2, 1) = std::numeric_limits<float>::quiet_NaN();
  const double ev = 1.5;
  std::vector<std::uint8_t> expected;
  EXPECT_EQ(toneMapImage8(img, ev, expected), 1);
  const std::string written = writePng(path("frame.png"), img, ev);
  EXPECT_EQ(written, SEASIM_IMAGE_IO ? path("frame.png") : path("frame.png.npy"));
  EXPECT_EQ(listing(), std::vector<std::string>{fs::path(written).filename().string()});
  const Image back = readImage(path("frame.png"));
  ASSERT_EQ(back.width, 16);
  ASSERT_EQ(back.height, 4);
  ASSERT_EQ(back.channels, 3);
  // OIIO gives 8-bit values as v/255; the .npy stand-in keeps the bytes 0..255.
  const double to_byte = SEASIM_IMAGE_IO ? 255.0 : 1.0;
  for (std::size_t i = 0; i < expected.size(); ++i)
    ASSERT_EQ(std::lround(back.pixels[i] * to_byte), expected[i]) << "value " << i;
  EXPECT_EQ(expected[back.index(3, 2, 1)], 0);  // the NaN shows as black
}

TEST_F(IoTest, SpectralExrRoundTripSortsBandsByWavelength) {
  // 13 bands from 400 to 1000 nm: alphabetically "S0.1000,..." sorts before "S0.400,...", and
  // "S0.950,..." after "S0.1000,...". Written in a shuffled order to check the reordering too.
  std::vector<double> wl;
  for (double nm = 400; nm <= 1000; nm += 50) wl.push_back(nm);
  ASSERT_EQ(wl.size(), 13u);
  std::vector<double> shuffled = wl;
  std::swap(shuffled[0], shuffled[12]);
  std::swap(shuffled[3], shuffled[7]);
  const int w = 4, h = 3;
  const std::size_t n = shuffled.size();
  auto value = [](double nm, int x, int y) { return static_cast<float>(nm + 0.25 * x + 2000.0 * y); };
  std::vector<float> data(w * h * n);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (std::size_t i = 0; i < n; ++i) data[(y * w + x) * n + i] = value(shuffled[i], x, y);
  writeSpectralExr(path("cube.exr"), w, h, shuffled, data);
  const SpectralImage back = readSpectralExr(path("cube.exr"));
  ASSERT_EQ(back.width, w);
  ASSERT_EQ(back.height, h);
  ASSERT_EQ(back.wavelengths_nm, wl);
  ASSERT_EQ(back.data.size(), data.size());
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (std::size_t i = 0; i < n; ++i)
        ASSERT_EQ(back.data[(y * w + x) * n + i], value(wl[i], x, y)) << x << "," << y << " band " << wl[i];
#if SEASIM_IMAGE_IO
  EXPECT_EQ(listing(), std::vector<std::string>{"cube.exr"});
  const Image raw = readImage(path("cube.exr"));
  ASSERT_EQ(raw.channels, 13);
  EXPECT_EQ(raw.channel_names.front(), "S0.1000,000000nm");  // the file's (alphabetical) order
  EXPECT_NE(std::find(raw.channel_names.begin(), raw.channel_names.end(), "S0.550,000000nm"), raw.channel_names.end());
  EXPECT_EQ(readImageAttribute(path("cube.exr"), "spectralLayoutVersion"), "1.0");
  EXPECT_EQ(readImageAttribute(path("cube.exr"), "emissiveUnits"), "W.m^-2.sr^-1");
  EXPECT_THROW(readSpectralExr(path("nope.exr")), RuntimeError);
  writeExr(path("rgb.exr"), rampImage(2, 2, 3));
  EXPECT_THROW(readSpectralExr(path("rgb.exr")), RuntimeError);  // no S0 channels
#endif
  // Two wavelengths that name the same channel are refused (in either build nothing is written).
  EXPECT_THROW(writeSpectralExr(path("dup.exr"), 1, 1, {500.0, 500.0}, {1.0f, 2.0f}), RuntimeError);
  EXPECT_THROW(writeSpectralExr(path("neg.exr"), 1, 1, {-1.0, 500.0}, {1.0f, 2.0f}), RuntimeError);
  EXPECT_FALSE(fs::exists(path("dup.exr")) || fs::exists(path("dup.exr.npy")));
  EXPECT_FALSE(fs::exists(path("neg.exr")) || fs::exists(path("neg.exr.npy")));
}

}  // namespace
}  // namespace seasim
