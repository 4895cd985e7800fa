// data_files_test.cpp — data files read once per process (io/data_files.h): a second request for a
// path reads nothing, a file changed on disk is read again, a missing file fails with its reader's
// message and keeps nothing, and the scene's readers (camera curves, lamp spectra) go through it.
#include <gtest/gtest.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>

#include "io/data_files.h"
#include "spectral/lamp_spectrum.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "util/error.h"

namespace {

namespace fs = std::filesystem;

std::string tempCsv(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

TEST(DataFiles, ReadsAPathOnceAndAgainWhenItChanges) {
  const std::string path = tempCsv("data_files_a.csv", "nm,v\n400,1\n700,2\n");
  seasim::DataFiles files;
  EXPECT_EQ(files.csv(path).rows(), 2u);
  EXPECT_EQ(files.csv(path).rows(), 2u);
  EXPECT_EQ(files.reads(), 1);
  // A changed file (other size, later time) is read again.
  std::ofstream(path) << "nm,v\n400,1\n550,3\n700,2\n";
  fs::last_write_time(path, fs::last_write_time(path) + std::chrono::seconds(2));
  EXPECT_EQ(files.csv(path).rows(), 3u);
  EXPECT_EQ(files.reads(), 2);
  // A missing file: the reader's error, nothing kept.
  EXPECT_THROW(files.csv(path + ".missing"), seasim::RuntimeError);
  EXPECT_EQ(files.reads(), 2);
}

TEST(DataFiles, CameraCurvesAndLampSpectraGoThroughIt) {
  seasim::DataFiles files;
  const seasim::WavelengthGrid grid = seasim::makeGrid(8, 400, 700);
  const seasim::Sensor a = seasim::makeSensor("nikon_d5100_npl", grid, true, "", &files);
  const seasim::Sensor b = seasim::makeSensor("nikon_d5100_npl", seasim::makeGrid(16, 400, 700), false, "", &files);
  EXPECT_EQ(files.reads(), 1);  // one camera file, read once for both grids
  EXPECT_EQ(a.to_r, seasim::makeSensor("nikon_d5100_npl", grid, true).to_r);  // the same weights as a direct read
  seasim::SpotlightDesc lamp;
  lamp.spectrum = tempCsv("data_files_lamp.csv", "nm,power\n400,1\n700,1\n");
  (void)seasim::lampSpectralIntensity(lamp, grid, &files);
  (void)seasim::lampSpectralIntensity(lamp, grid, &files);
  EXPECT_EQ(files.reads(), 2);
  (void)b;
}

}  // namespace
