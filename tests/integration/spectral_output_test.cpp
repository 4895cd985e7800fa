// spectral_output_test.cpp — `sensor = "identity"` through the CLI: image.exr holds the raw
// bands, the same values as spectral.exr, one channel per band; image.png is the grey luminance preview.
#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <string>

#include "io/image_io.h"

namespace fs = std::filesystem;

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kRepo = SEASIM_SOURCE_DIR;

int runCli(const std::string& args, std::string* out) {
  FILE* pipe = popen((kBinary + " " + args + " 2>&1").c_str(), "r");
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, pipe)) out->append(buf, n);
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

TEST(SpectralOutput, IdentitySensorWritesTheRawBandsAsTheImage) {
  const fs::path dir = fs::temp_directory_path() / "seasim_identity_sensor";
  fs::remove_all(dir);
  for (const char* scene : {"flat_sea.toml", "seabed.toml"}) {
    const fs::path out = dir / scene;
    std::string log;
    ASSERT_EQ(runCli("render " + kRepo + "/scenes/" + scene + " -o " + out.string() +
                         " --set camera.width=16 --set camera.height=9 --set spectral.count=6"
                         " --set 'spectral.sensor=\"identity\"' --output exr,png,spectral_exr --device pocl",
                     &log),
              0)
        << log;
    const seasim::SpectralImage bands = seasim::readSpectralExr((out / "spectral.exr").string());
    const seasim::SpectralImage image = seasim::readSpectralExr((out / "image.exr").string());
    ASSERT_EQ(image.wavelengths_nm.size(), 6u) << scene;
    EXPECT_EQ(image.wavelengths_nm, bands.wavelengths_nm);
    EXPECT_EQ(image.data, bands.data) << scene << ": image.exr is the raw bands";
    double sum = 0;
    for (float v : image.data) sum += v;
    EXPECT_GT(sum, 0) << scene;
    EXPECT_TRUE(fs::exists(out / "image.png"));
  }
  std::string log;
  EXPECT_NE(runCli("render " + kRepo + "/scenes/flat_sea.toml -o " + (dir / "bad").string() +
                       " --set 'spectral.sensor=\"identity\"' --set spectral.spectral_exr=false --device pocl",
                   &log),
            0);
  EXPECT_NE(log.find("spectral_exr"), std::string::npos) << log;
  EXPECT_FALSE(fs::exists(dir / "bad" / "image.exr"));
  fs::remove_all(dir);
}

}  // namespace
