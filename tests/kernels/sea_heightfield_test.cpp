// sea_heightfield_test.cpp — the height-field sea floor (000 §5.4) in kernels/sea_single.cl and
// kernels/sea_second.cl on PoCL (float): single scattering + bottom reflection against the double
// reference (its own fine march of the floor, not the kernels' cell walk); a constant height field
// against the flat-bottom path (single, and single + second order); second order (depth tables) against
// the direct double integration; the floor touching the surface and grazing views give finite output;
// the depth tables come back from the on-disk cache unchanged.
#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <vector>

#include "io/image_io.h"
#include "quality/render_frame.h"
#include "passes/sea_heightfield.h"
#include "passes/sea_second_pass.h"
#include "plan/plan.h"
#include "reference/sea_reference.h"
#include "reference/sea_second_reference.h"
#include "scene/scene_parser.h"
#include "spectral/sensor.h"
#include "spectral/wavelength_grid.h"
#include "test_device.h"

namespace {

namespace fs = std::filesystem;

seasim::Device& device() { return seasim::test::testDevice(); }

seasim::Override set(const char* key, const std::string& value) { return {key, value, {"test", 1}}; }

// A folder per process for the floor images and scene files (tests run in parallel processes).
fs::path tempDir() {
  static const fs::path dir = [] {
    const fs::path d = fs::temp_directory_path() / ("seasim_heightfield_" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
  }();
  return dir;
}

// Grey image -> floor as scenes/README.md says: 0 -> max_depth, 1 -> min_depth.
std::string writeFloor(const std::string& name, int n, const std::vector<float>& grey) {
  seasim::Image img;
  img.resize(n, n, 1);
  img.pixels = grey;
  const std::string path = (tempDir() / name).string();
  seasim::writeExr(path, img);
  return path;
}

// A shelf falling away from the camera (grey 1 near, 0 far), a mound rising to 1 m below the surface
// and ripples: 33 x 33 nodes over 60 m. With touch = true the mound's top reaches the surface.
std::string shoreFloor(bool touch) {
  const int n = 33;
  std::vector<float> g(n * n);
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n; ++i) {
      const double x = -30.0 + 60.0 * i / (n - 1), z = -30.0 + 60.0 * j / (n - 1);
      double v = 0.15 + 0.8 * (z + 30.0) / 60.0 + 0.03 * std::sin(0.9 * x + 0.4 * z);
      v += 0.6 * std::exp(-((x - 4) * (x - 4) + (z - 2) * (z - 2)) / 30.0);
      g[j * n + i] = float(std::clamp(v, 0.0, 1.0));
    }
  }
  if (touch) g[16 * n + 18] = 1.0f;  // a rock at the surface (min_depth = 0)
  return writeFloor(touch ? "touch.exr" : "shore.exr", n, g);
}

std::string constantFloor() { return writeFloor("constant.exr", 5, std::vector<float>(25, 0.5f)); }

std::string sceneText(const std::string& floor_path, double min_depth, double max_depth, int w, int h, int bands) {
  return R"(
[camera]
position = [0, 6, 24]
look_at = [0, 0, -10]
fov_deg = 60
width = )" + std::to_string(w) + "\nheight = " + std::to_string(h) + R"(
[sun]
zenith_deg = 40
azimuth_deg = 240
[water]
jerlov = "1C"
[bottom]
type = "heightfield"
heightfield = ")" + floor_path + R"("
min_depth = )" + std::to_string(min_depth) + "\nmax_depth = " + std::to_string(max_depth) + R"(
extent = 60
albedo = 0.35
[spectral]
count = )" + std::to_string(bands) + "\n";
}

// The scene with the default sea model ("multiple"), its bands kept (spectral_exr) for render()'s check.
seasim::Scene parse(const std::string& text, std::vector<seasim::Override> o = {}) {
  o.insert(o.begin(), set("spectral.spectral_exr", "true"));
  return seasim::parseScene(text, (tempDir() / "scene.toml").string(), o);
}

// Paper 000's model, pinned where a test checks it against its own double reference (eq. 5 and 9 over
// the floor, §5.4) or its second order (depth tables): "multiple" has no second order, and its reference
// (the path tracer) has no height-field floor.
seasim::Scene parseModel(const std::string& model, const std::string& text, std::vector<seasim::Override> o = {}) {
  o.insert(o.begin(), seasim::Override{"sea.model", "\"" + model + "\"", {"test", 0}});
  return parse(text, o);
}
seasim::Scene parsePaper(const std::string& text, std::vector<seasim::Override> o = {}) {
  return parseModel("paper", text, std::move(o));
}

// Both models of the sea seen from above, where a test holds for either.
const std::vector<std::string> kModels = {"paper", "multiple"};

// Renders and checks: no NaN/Inf anywhere, and no negative radiance in any band. Linear sRGB itself may
// be negative: the default sensor (CIE 1931 -> sRGB matrix) takes a band spectrum outside the sRGB gamut
// to R < 0. "multiple" over the shore's shallow end does so: cyan-green water over the sand, every band
// positive (437 / 512 / 587 / 662 nm: 0.013 / 0.025 / 0.008 / 0.0036) and R = -0.0018; it stays below 0
// at 8, 16 and 32 bands and is >= 0 through a camera's curves (no matrix), so it is the colour, not the
// sea's terms (tests/unit/sea_multiple_test.cpp holds those >= 0 at their stiff inputs).
seasim::FrameResult render(const seasim::Scene& s) {
  seasim::FrameResult f = seasim::renderFrame(device(), s, seasim::makePlan(s));
  EXPECT_EQ(f.nonfinite, 0);
  for (float v : f.rgb.pixels) EXPECT_TRUE(std::isfinite(v));
  if (s.spectral.spectral_exr) {
    EXPECT_EQ(f.spectral.size(), f.rgb.pixels.size() / 3 * size_t(s.spectral.count));
    for (float v : f.spectral) EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
  }
  return f;
}

// Max over pixels and channels of |a - ref| / (|ref| + 1e-3 * peak), and how many exceed `limit`.
double maxRelativeError(const std::vector<double>& a, const std::vector<double>& ref, double limit, int* over) {
  double peak = 0, worst = 0;
  for (double v : ref) peak = std::max(peak, std::fabs(v));
  *over = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    const double e = std::fabs(a[i] - ref[i]) / (std::fabs(ref[i]) + 1e-3 * peak);
    worst = std::max(worst, e);
    *over += e > limit;
  }
  return worst;
}
std::vector<double> values(const seasim::Image& img) { return {img.pixels.begin(), img.pixels.end()}; }
std::vector<double> values(const seasim::FrameResult& f) { return values(f.rgb); }

TEST(SeaHeightFieldKernel, SingleScatteringAndBottomMatchDoubleReference) {
  // The kernel walks the floor's cells in float; the reference marches it in 1/64-cell steps in double
  // and integrates eq. 5 by quadrature. Both meet the same bilinear floor, so they agree like the
  // flat-bottom test (2e-4) except where a view ray grazes a crest: there the floor point jumps
  // between the crest and the water behind it, and a float rounding picks a side. At most 1% of
  // the values may differ by more.
  const seasim::Scene s = parsePaper(sceneText(shoreFloor(false), 1.0, 15.0, 48, 27, 4));
  const seasim::FrameResult frame = render(s);
  const seasim::Image ref = seasim::renderSeaReference(s, 4000);
  int over = 0;
  const double worst = maxRelativeError(values(frame), values(ref), 2e-4, &over);
  std::printf("single + bottom vs double reference: max rel %.3g, %d of %zu values over 2e-4\n", worst, over,
              ref.pixels.size());
  EXPECT_LE(over, int(ref.pixels.size() / 100));
  // The floor shows: the shallow end (bottom rows) differs from deep water without a bottom.
  const seasim::FrameResult deep = render(parsePaper(sceneText(shoreFloor(false), 1.0, 15.0, 48, 27, 4),
                                                {set("bottom", "{ type = \"none\" }")}));
  double shallow = 0, open = 0;
  for (int x = 0; x < 48; ++x)
    for (int c = 0; c < 3; ++c) shallow += frame.rgb.at(x, 26, c), open += deep.rgb.at(x, 26, c);
  EXPECT_GT(std::fabs(shallow - open), 0.05 * open);
}

TEST(SeaHeightFieldKernel, ConstantHeightFieldIsTheFlatBottom) {
  // Grey 0.5 between 0 and 16 m: 8 m everywhere. Eq. 5 and 9 with z_Q = 8 m and the normal +y must be
  // the flat path (exact eq. 5 on both sides: the height field never uses the LUT), and the second
  // order from the depth tables must be the flat scattering maps: the tables' sampling-ray lengths
  // are linear in depth there, so the interpolation between nodes is exact. "multiple" reads z_Q the
  // same way (its closed form has no second-order pass: second_order plans nothing there).
  const std::string text = sceneText(constantFloor(), 0.0, 16.0, 24, 14, 3);
  const std::vector<seasim::Override> flat = {
      set("bottom", "{ type = \"flat\", depth = 8.0, albedo = 0.35 }"), set("quality.sea_lut_size", "1")};
  // 128 directions are 8 whole runs of the scattering map's vector lanes (sea_bottom_lanes.h); 50 (5 x 10)
  // are padded to 64, the last run 2 directions and 14 of weight 0.
  struct Case {
    bool second;
    const char* nd;
  };
  for (const std::string& model : kModels)
    for (const Case& c : {Case{false, "128"}, Case{true, "128"}, Case{true, "50"}}) {
      const bool second = c.second;
      std::vector<seasim::Override> o = {set("sea.second_order", second ? "true" : "false"),
                                         set("quality.sea_map_size", "16"), set("quality.sea_nd", c.nd)};
      std::vector<seasim::Override> of = o;
      of.insert(of.end(), flat.begin(), flat.end());
      const seasim::FrameResult hf = render(parseModel(model, text, o));
      const seasim::FrameResult fl = render(parseModel(model, text, of));
      int over = 0;
      const double worst = maxRelativeError(values(hf), values(fl), 1e-4, &over);
      std::printf("constant height field vs flat bottom (%s, %s, %s directions): max rel %.3g\n", model.c_str(),
                  second ? "single + second" : "single", c.nd, worst);
      EXPECT_LT(worst, 1e-4);
    }
}

TEST(SeaHeightFieldKernel, SecondOrderMatchesDirectIntegration) {
  // The scattering maps read eq. 7 from the depth tables at map points and interpolate to pixels;
  // the reference walks every sampling ray to the floor from every quadrature node along each
  // pixel's own view ray (no planes, maps or tables). Measured at these settings: mean ratio 1.016,
  // 92% of values within 5%, the worst 11% on the three pixels over the mound's crest (1 m deep
  // between 5–9 m of water): a map point beside the crest sees the deeper floor below it, and the
  // 16 x 16 maps interpolate across the edge (map size 32 halves it; the paper's 64 for height
  // fields). n_d = 512 -> 2048 moves the mean ratio to 0.995 (the azimuthal sampling near the
  // horizon row); the reference itself moves by 0.3% from 16 to 32 angle steps.
  // 19 bands as well: the accumulation's vector lanes (16, with the planes' shares above the floor per
  // lane) over bands padded to 32, the last run 3 bands and 13 of padding.
  for (const int bands : {3, 19}) {
    std::vector<seasim::Override> o = {set("quality.sea_nd", "512"), set("quality.sea_nz", "16"),
                                       set("quality.sea_map_size", "16")};
    const std::string text = sceneText(shoreFloor(false), 1.0, 15.0, 16, 9, bands);
    o.push_back(set("sea.second_order", "true"));
    const seasim::FrameResult with = render(parsePaper(text, o));
    o.back() = set("sea.second_order", "false");
    const seasim::FrameResult without = render(parsePaper(text, o));
    std::vector<double> second(with.rgb.pixels.size());
    for (size_t i = 0; i < second.size(); ++i) second[i] = double(with.rgb.pixels[i]) - without.rgb.pixels[i];
    const seasim::Image ref = seasim::renderSeaSecondReference(parsePaper(text, o), {32, 16});
    double peak = 0, sum_k = 0, sum_r = 0;
    for (size_t i = 0; i < second.size(); ++i) peak = std::max(peak, double(ref.pixels[i])), sum_k += second[i],
                                                   sum_r += ref.pixels[i];
    ASSERT_GT(peak, 0.0);
    int over = 0;
    const double worst = maxRelativeError(second, values(ref), 0.05, &over);
    std::printf("second order over a height field vs direct integration, %d bands: max rel %.3g, mean ratio %.4f, %d "
                "of %zu values over 5%%\n",
                bands, worst, sum_k / sum_r, over, second.size());
    EXPECT_NEAR(sum_k / sum_r, 1.0, 0.025);
    EXPECT_LE(over, int(second.size() / 10));
    EXPECT_LT(worst, 0.15);
  }
}

TEST(SeaHeightFieldKernel, FloorAtTheSurfaceAndGrazingViewsStayFinite) {
  // min_depth = 0: a rock reaches the surface (z_Q -> 0 and sampling rays of length 0); grazing views
  // along the horizon (sampling points far outside the floor's square); a grazing sun; a sun below
  // the horizon (the bottom and second-order terms add exactly nothing). Both models.
  const std::string text = sceneText(shoreFloor(true), 0.0, 15.0, 20, 12, 3);
  for (const std::string& model : kModels)
    for (const auto& extra : std::vector<std::vector<seasim::Override>>{
             {},
             {set("camera.look_at", "[0, 6, -100]")},
             {set("camera.look_at", "[4, 0, 8]")},  // straight down onto the rock
             {set("sun.zenith_deg", "89.99")},
             {set("sun.zenith_deg", "100")}}) {
      std::vector<seasim::Override> o = extra;
      o.push_back(set("sea.second_order", "true"));
      o.push_back(set("quality.sea_map_size", "8"));
      o.push_back(set("quality.sea_nd", "32"));
      SCOPED_TRACE(model + (extra.empty() ? std::string(", the test's own view")
                                          : ", " + extra[0].key + " = " + extra[0].value_toml));
      const seasim::FrameResult f = render(parseModel(model, text, o));
      ASSERT_EQ(f.rgb.pixels.size(), size_t(20 * 12 * 3));
    }
  // The shore of the first test with the default model: its bands >= 0 (render's check) where its
  // linear sRGB goes below 0 (render's comment says why).
  {
    const seasim::FrameResult shore = render(parse(sceneText(shoreFloor(false), 1.0, 15.0, 48, 27, 4)));
    const long below = std::count_if(shore.rgb.pixels.begin(), shore.rgb.pixels.end(), [](float v) { return v < 0; });
    std::printf("[ measured ] shore, \"multiple\": %ld of %zu linear sRGB values below 0, no band below 0\n", below,
                shore.rgb.pixels.size());
  }
  // The floor at the surface everywhere (grey 1, min_depth 0): no water column at all. Single and
  // second-order scattering vanish; what is left is the sky's reflection plus the dry floor's sunlit
  // Lambert reflection through the surface, and nothing is NaN (the planes' cells are empty).
  const std::string dry = writeFloor("dry.exr", 3, std::vector<float>(9, 1.0f));
  for (const std::string& model : kModels) {
    SCOPED_TRACE(model + ", the floor at the surface everywhere");
    const seasim::FrameResult f = render(parseModel(model, sceneText(dry, 0.0, 5.0, 20, 12, 3),
                                                    {set("sea.second_order", "true"), set("quality.sea_map_size", "8"),
                                                     set("quality.sea_nd", "32")}));
    const seasim::FrameResult single = render(parseModel(model, sceneText(dry, 0.0, 5.0, 20, 12, 3),
                                                         {set("sea.second_order", "false")}));
    EXPECT_EQ(f.rgb.pixels, single.rgb.pixels);  // the second order adds exactly nothing
  }
}

TEST(SeaHeightFieldKernel, DepthTablesComeBackFromTheCache) {
  // Second run of the same scene: the tables are read from $SEASIM_CACHE_DIR (no table kernel) and
  // the frame is bit-identical.
  const std::string cache = (tempDir() / "cache").string();
  const char* before = std::getenv("SEASIM_CACHE_DIR");
  const std::string saved = before ? before : "";
  ::setenv("SEASIM_CACHE_DIR", cache.c_str(), 1);
  const seasim::Scene s = parsePaper(sceneText(shoreFloor(false), 1.0, 15.0, 12, 8, 3),
                                {set("spectral.spectral_exr", "false"), set("sea.second_order", "true"),
                                 set("quality.sea_map_size", "8"), set("quality.sea_nd", "32"),
                                 set("quality.sea_nz", "4")});
  const seasim::WavelengthGrid grid = seasim::makeGrid(s.spectral.count, s.spectral.min_nm, s.spectral.max_nm);
  const seasim::Sensor sensor = seasim::makeSensor(s.spectral.sensor, grid, s.spectral.white_balance, s.spectral.camera_dir);
  const seasim::Plan plan = seasim::makePlan(s);
  std::vector<float> first, second;
  for (std::vector<float>* out : {&first, &second}) {
    cl::Buffer rgb(device().context(), CL_MEM_READ_WRITE, sizeof(float) * 3 * 12 * 8);
    std::vector<float> zero(3 * 12 * 8, 0.0f);
    device().queue().enqueueWriteBuffer(rgb, CL_TRUE, 0, sizeof(float) * zero.size(), zero.data());
    seasim::SeaSecondPass pass(device(), s, *plan.find("sea_second"), seasim::SeaSecondPass::configFromScene(s), grid,
                               sensor, rgb, nullptr);
    pass.run();
    if (out == &first) EXPECT_GT(pass.depthTableMs(), 0.0);
    else EXPECT_EQ(pass.depthTableMs(), 0.0);  // from the cache
    out->resize(zero.size());
    device().queue().enqueueReadBuffer(rgb, CL_TRUE, 0, sizeof(float) * out->size(), out->data());
  }
  if (before) ::setenv("SEASIM_CACHE_DIR", saved.c_str(), 1);
  else ::unsetenv("SEASIM_CACHE_DIR");
  EXPECT_EQ(first, second);
  EXPECT_TRUE(fs::exists(fs::path(cache) / "sea_depth_tables"));
}

}  // namespace
