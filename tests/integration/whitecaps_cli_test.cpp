// whitecaps_cli_test.cpp — `seasim plan` shows the whitecaps pass when the scene asks for foam on an
// FFT sea and not otherwise; a bad value of its key fails naming the key.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "run_command.h"

namespace {

const std::string kBinary = SEASIM_BINARY;
const std::string kScenes = std::string(SEASIM_SOURCE_DIR) + "/scenes/";

bool plansWhitecaps(const std::string& args) {
  const seasim_test::Result r = seasim_test::runCommand(kBinary + " plan " + args);
  EXPECT_EQ(r.code, 0) << r.output;
  return r.output.find("whitecaps") != std::string::npos &&
         r.output.find("kernels/whitecaps.cl") != std::string::npos;
}

TEST(WhitecapsCli, PlanShowsThePassOnlyWhenAskedOnAWavySea) {
  EXPECT_TRUE(plansWhitecaps(kScenes + "whitecaps.toml"));
  EXPECT_FALSE(plansWhitecaps(kScenes + "whitecaps.toml --set surface.whitecaps=false"));
  EXPECT_FALSE(plansWhitecaps(kScenes + "tropical_lagoon.toml"));
  EXPECT_TRUE(plansWhitecaps(kScenes + "ocean_noon.toml"));
  EXPECT_FALSE(plansWhitecaps(kScenes + "flat_sea.toml --set surface.whitecaps=true"));
}

TEST(WhitecapsCli, ABadValueNamesTheKey) {
  const seasim_test::Result r =
      seasim_test::runCommand(kBinary + " plan " + kScenes + "whitecaps.toml --set surface.whitecaps=2");
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.output.find("surface.whitecaps"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("expected true or false"), std::string::npos) << r.output;
}

}  // namespace
