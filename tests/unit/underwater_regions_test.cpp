// underwater_regions_test.cpp — the region judge of `seasim underwater-regions` and the
// pixel-centre ray cast beneath it (reference/pixel_centre_hits.h): a level camera 2 m above a flat
// bottom with a sphere straight ahead, whose regions follow from the geometry by hand.
#include <gtest/gtest.h>

#include <string>

#include "reference/pixel_centre_hits.h"
#include "reference/underwater_regions.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "underwater/underwater_setup.h"

namespace {

using namespace seasim;

// 64x36, 60° vertical fov, looking level along -z from 3 m deep; the bottom 5 m deep (2 m below the
// camera); a sphere of radius 0.6 m 5 m ahead on the axis.
const char* kScene = R"([scene]
name = "regions"
[camera]
position = [0, -3, 0]
look_at = [0, -3, -10]
fov_deg = 60
width = 64
height = 36
[water]
jerlov = "IB"
[bottom]
type = "flat"
depth = 5
[[objects]]
type = "sphere"
center = [0, -3, -5]
radius = 0.6
albedo = 0.2
[underwater]
caustics = "none"
)";

UnderwaterSetup setupOf(const std::string& text) {
  const WavelengthGrid grid = makeGrid(1, 559.5, 560.5);
  return makeUnderwaterSetup(parseScene(text, "regions.toml"), grid, makeSensor("cie1931", grid, true, ""));
}

UwRegion at(const std::vector<UwRegion>& r, int x, int y) { return r[size_t(y) * 64 + x]; }

TEST(UnderwaterRegions, FollowTheGeometry) {
  const std::vector<UwRegion> r = underwaterRegions(setupOf(kScene));
  ASSERT_EQ(r.size(), 64u * 36u);
  EXPECT_EQ(at(r, 32, 18), UwRegion::Objects);    // the sphere straight ahead
  EXPECT_EQ(at(r, 5, 0), UwRegion::WaterUp);      // the top row looks 29° up, at the surface
  EXPECT_EQ(at(r, 32, 35), UwRegion::BottomNear); // the bottom row meets the bottom 2 / sin 29.3° = 4.1 m away
  EXPECT_EQ(at(r, 5, 18), UwRegion::BottomFar);   // just below the horizon: the bottom > 100 m away
}

TEST(UnderwaterRegions, WithoutABottomTheWaterLooksDown) {
  std::string text = kScene;
  text.replace(text.find("type = \"flat\"\ndepth = 5"), 23, "type = \"none\"");
  const std::vector<UwRegion> r = underwaterRegions(setupOf(text));
  EXPECT_EQ(at(r, 32, 35), UwRegion::WaterDown);
  EXPECT_EQ(at(r, 5, 18), UwRegion::WaterDown);
  EXPECT_EQ(at(r, 5, 0), UwRegion::WaterUp);
  EXPECT_EQ(at(r, 32, 18), UwRegion::Objects);
}

TEST(PixelCentreHits, DistancesMaterialsAndDirections) {
  const std::vector<PixelCentreHit> h = pixelCentreHits(setupOf(kScene));
  const PixelCentreHit& sphere = h[size_t(18) * 64 + 32];
  EXPECT_EQ(sphere.material, 0);                   // the first object
  EXPECT_NEAR(sphere.distance, 4.4, 0.02);         // its near side, 5 - 0.6 m ahead (a pixel off the axis)
  const PixelCentreHit& floor = h[size_t(35) * 64 + 32];
  EXPECT_EQ(floor.material, UW_MAT_BOTTOM);
  EXPECT_LT(floor.dir_y, 0.0);
  EXPECT_NEAR(floor.distance, 2.0 / -floor.dir_y, 1e-9);  // 2 m down along the ray
  EXPECT_GT(h[5].dir_y, 0.0);                      // the top row looks up
}

}  // namespace
