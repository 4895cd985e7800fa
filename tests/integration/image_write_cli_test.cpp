// image_write_cli_test.cpp — the real `seasim` binary: a render that writes EXR and PNG binds no
// OpenImageIO (its ~260 libraries were most of a short render's wall time; OpenEXR's library and libpng
// write them, host/io/image_write.cpp), and reading an image (compare) still loads the module. The
// dynamic loader lists what it loads under LD_DEBUG=files.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_command.h"

namespace fs = std::filesystem;

namespace {

using seasim_test::contains;
const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

class ImageWriteCli : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = seasim_test::freshTestDir("seasim_image_write_"); }
  void TearDown() override { fs::remove_all(dir_); }
  fs::path dir_;
};

TEST_F(ImageWriteCli, RenderWritesExrAndPngWithoutLoadingOpenImageIO) {
  if (!SEASIM_IMAGE_IO) GTEST_SKIP() << "a build without image I/O writes .npy files";
  const std::string out = (dir_ / "o").string();
  const seasim_test::Result r = seasim_test::runCommand(
      "LD_DEBUG=files " + kBinary + " render " + kRepo + "/scenes/flat_sea.toml --set camera.width=64 " +
      "--set camera.height=36 --set spectral.spectral_exr=true --output exr,png,spectral_exr --device pocl -o " + out);
  ASSERT_EQ(r.code, 0) << r.output;
  for (const char* file : {"image.exr", "image.png", "spectral.exr"})
    EXPECT_TRUE(fs::is_regular_file(out + "/" + file)) << file;
  EXPECT_FALSE(contains(r.output, "libseasim_oiio.so")) << "the image module was loaded to write";
  EXPECT_FALSE(contains(r.output, "libOpenImageIO")) << "OpenImageIO was loaded to write";
  // Reading them back (compare) is the module's job, and finds them equal.
  const seasim_test::Result c = seasim_test::runCommand("LD_DEBUG=files " + kBinary + " compare " + out +
                                                        "/image.exr " + out + "/image.exr");
  EXPECT_EQ(c.code, 0) << c.output;
  EXPECT_TRUE(contains(c.output, "libseasim_oiio.so")) << c.output.substr(0, 2000);
}

}  // namespace
