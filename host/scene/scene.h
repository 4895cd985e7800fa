// scene.h — a parsed, validated scene: plain structs in SI units (metres, radians inside code,
// nm for wavelengths). Files say degrees and nm; the parser (scene_parser.cpp) converts.
// scenes/README.md documents every key, its unit and its default; keep the two in step.
#pragma once
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scene/output_layers.h"
#include "math/vec3.h"
#include "io/tonemap_eq18.h"
#include "spectral/spectrum.h"

namespace seasim {

class DataFiles;  // io/data_files.h

// Where a value came from, for error messages and reports ("scenes/a.toml:12").
struct SourceLoc {
  std::string file;
  int line = 0;
};

struct CameraDesc {
  Vec3 position{0, 10, 0};   // m
  Vec3 look_at{0, 0, -100};  // m
  Vec3 up{0, 1, 0};
  double fov_y = 0.0;        // radians (file: fov_deg, default 60)
  int width = 640;           // pixels
  int height = 360;
  double exposure_ev = 0.0;  // image scale 2^exposure_ev
};

struct SunDesc {
  bool enabled = true;
  double zenith = 0.0;         // radians (file: zenith_deg, default 45)
  double azimuth = 0.0;        // radians from +x towards +z (file: azimuth_deg, default 0)
  double irradiance = 1.0;     // scale on the D65 spectral irradiance (W m^-2 nm^-1 at 560 nm = scale)
  double angular_radius = 0.004654;  // radians (file: angular_radius_deg, default 0.2667)
};

struct SkyDesc {
  enum class Model { Uniform, Analytic, Image, Preetham };
  Model model = Model::Uniform;
  double radiance = 0.05;      // scale on D65 radiance (W m^-2 sr^-1 nm^-1 at 560 nm) for uniform
  std::string image;           // environment image (lat-long), resolved absolute path, for Image
  double turbidity = 3.0;      // Preetham: atmospheric turbidity T (1.7 very clear … 10 hazy)
  bool chromaticity_on_daylight_locus = false;  // Preetham: sky.chromaticity = "daylight_locus" (common/sky.h)
};

// Water inherent optical properties. Either a Jerlov type (a, b, Kd from data/) or explicit spectra.
struct WaterDesc {
  bool present = false;
  std::string jerlov;          // "I", "IA", "IB", "II", "III", "1C", "3C", "5C", "7C", "9C" or empty
  Spectrum a;                  // absorption, 1/m
  Spectrum b;                  // scattering, 1/m
  Spectrum kd;                 // diffuse downwelling attenuation, 1/m (optional when explicit)
  double g = 0.9;              // Henyey–Greenstein asymmetry for single scattering, |g| < 1; with
                               // phase other than "hg", the phase's own g (its first moment)
  double ior = 1.333;          // refractive index of water relative to air
  // The phase function (host/radiometry/phase_function.h): "hg" (of g), "petzold", "fournier_forand"
  // (of bb_ratio), "rayleigh_like" or "table" (phase_file, resolved).
  std::string phase = "hg";
  std::string phase_file;
  double bb_ratio = 0.0183;    // b_b/b of fournier_forand, in [0.001, 0.5]
};

struct AirDesc {
  enum class Phase { Shafts, HenyeyGreenstein };  // 001 eq. 4, or HG
  bool present = false;
  double density = 1.0;        // rho, particle density (001 eq. 1), dimensionless scale
  double extinction = 0.05;    // kappa, extinction cross-section, 1/m per unit density
  Phase phase = Phase::Shafts;
  double g = 0.0;              // HG asymmetry when phase = "hg"
};

struct SurfaceDesc {
  enum class Type { Flat, Fft };
  Type type = Type::Flat;
  double wind_speed = 10.0;           // m/s
  double wind_direction = 0.0;        // radians (file: wind_direction_deg)
  double patch_size = 100.0;          // L, m
  int grid = 256;                     // N, power of two 16..2048
  double choppiness = 0.0;            // lambda (004 eq. 29)
  double directional_exponent = 2.0;  // p in |k.w|^p (004 eq. 23)
  double small_wave = 0.0;            // l, m (004 eq. 24)
  double depth = 0.0;                 // D for finite-depth dispersion, m; 0 = deep water
  double loop_period = 0.0;           // T, s (004 eq. 18); 0 = no loop
  double time = 0.0;                  // s
  unsigned seed = 1;
};

struct BottomDesc {
  enum class Type { None, Flat, HeightField };
  Type type = Type::None;   // None: deep water, no bottom terms
  double depth = 10.0;      // m (flat)
  Spectrum albedo = Spectrum::constant(0.3);  // Lambertian reflectance
  std::string heightfield;  // image path (resolved); grey 0..1 maps to max_depth..min_depth
  double min_depth = 1.0;   // m
  double max_depth = 40.0;  // m
  double extent = 100.0;    // m, side of the square the height field covers, centred at x=z=0
};

struct ObjectDesc {
  enum class Type { Sphere, Box, Plane, HeightField };
  Type type = Type::Sphere;
  Vec3 center{};       // sphere
  double radius = 1.0;
  Vec3 box_min{}, box_max{};  // box (axis aligned)
  Vec3 point{}, normal{0, 1, 0};  // plane
  std::string heightfield;     // height-field image (resolved)
  double extent = 10.0;        // height field: side length, m
  double height = 1.0;         // height field: grey 1 -> height m above `point`
  Spectrum albedo = Spectrum::constant(0.5);
  SourceLoc loc;
};

struct SpotlightDesc {
  Vec3 position{0, 5, 0};
  Vec3 direction{0, -1, 0};   // normalised by the parser
  double cone = 0.0;          // half angle, radians (file: cone_deg, default 20)
  double falloff = 0.0;       // penumbra width, radians (file: falloff_deg, default 5)
  double intensity = 100.0;   // W/sr on the axis
  Vec3 color{1, 1, 1};        // linear RGB tint
  std::string light_map;      // image path (resolved), optional: the lamp's intensity distribution
  // The lamp's spectrum (spectral/lamp_spectrum.h): a relative spectral distribution normalised to 1 at
  // 560 nm, intensity then being W sr^-1 nm^-1 there. temperature_k > 0: Planck's law at that colour
  // temperature; spectrum: a CSV (nm, relative power; resolved path). Neither: equal energy.
  double temperature_k = 0.0;
  std::string spectrum;
  bool has_color = false;     // `color` was written in the file (under water it is an error)
  SourceLoc loc;
};

struct SpectralDesc {
  int count = 3;              // wavelength bands, 1..1000
  double min_nm = 400.0;
  double max_nm = 700.0;
  std::string sensor = "cie1931";  // "cie1931" or a camera name: a file stem in a folder of cameraDirs()
  std::string camera_dir;          // file: camera_dir (resolved, absolute); "" = $SEASIM_CAMERA_DIR, data/cameras
  bool white_balance = true;
  bool spectral_exr = false;  // also write one channel per band
};

// A quality knob: a number, or "auto" (the method picks the cheapest setting under its error budget).
struct Knob {
  bool automatic = false;
  double value = 0.0;
  // Written in the scene or by --set, not the default. The count knobs and quality.shafts_method set
  // it: an "auto" search keeps a knob the user gave fixed and searches the defaulted ones.
  bool given = false;
};

struct SeaDesc {
  // sea.model: "multiple" (the default) = all orders in closed form (kernels/common/sea_multiple.h),
  // which leaves out the second-order pass; "paper" = 000's eq. 5 (+ eq. 6-8 with second_order) and
  // eq. 9, what a reproduction of paper 000 pins (results/BENCHMARKS.md: 0.97-1.02 of all orders
  // against the paper's 0.17-1.00).
  enum class Model { Paper, Multiple };
  Model model = Model::Multiple;
  bool single_scattering = true;
  bool second_order = false;
  bool bottom_caustics = false;  // the FFT ocean's caustics on the bottom (needs surface.type = "fft")
  bool reflection = true;
};

// [underwater]: the terms of the underwater model (paper 002) and their settings.
struct UnderwaterDesc {
  enum class Caustics { None, Texture, Map };
  enum class Injection { Spectral, Rgb };
  enum class Model { Thesis, DiscreteOrdinates };
  Model model = Model::DiscreteOrdinates;     // "discrete_ordinates" (the default): common/underwater_ordinates.h; "thesis":
                                     // 002 eq. 4.7, what a reproduction of the thesis pins
  bool multiple_scattering = true;   // L_MS by K_d (002 eq. 4.7)
  bool single_scattering = true;     // froxel single scattering of the sun beam (002 §5)
  Caustics caustics = Caustics::Texture;  // texture: two scrolling textures (002 §5.3); map: caustics.cl
  double caustic_period = 4.0;       // m, tile size of the caustic texture (file: caustic_period_m)
  double caustic_speed = 0.5;        // m/s, scroll speed (file: caustic_speed_mps)
  Injection injection = Injection::Spectral;  // froxel light injection per band or in sensor RGB
  double froxel_near = 0.1;          // m, first froxel slice (file: froxel_near_m)
  double froxel_far = 60.0;          // m, last froxel slice (file: froxel_far_m)
  // "discrete_ordinates" only: how its diffuse field is solved (underwater_ordinates_solver.h): "discrete_ordinates"
  // (the default) or "two_stream" (the two-stream with its fitted tables, below). file: diffuse
  enum class Diffuse { DiscreteOrdinates, TwoStream };
  // "discrete_ordinates" only: the light delta-M counts as unscattered is put back blurred by the phase's small
  // angles (the water_spread pass, kernels/common/water_spread.h). file: point_spread
  bool point_spread = true;
  Diffuse diffuse = Diffuse::DiscreteOrdinates;
  // "discrete_ordinates" with diffuse = "discrete_ordinates" only: the streams (and delta-M order) of the solution the view rays'
  // source table is fitted to (underwater/ordinates_high_order.h); 0: the order-3 field's own in-scatter.
  // Even, 8-64, or 0 (default kOrdinatesHighOrderStreams). file: source_streams
  int source_streams = 32;
  // "discrete_ordinates" with diffuse = "two_stream" only: the diffuse streams' mean cosines in its in-scatter source; 0 = the fitted table
  // (diffuseMeanCosines, underwater_ordinates_setup.h). Set to refit it (tests/perf/underwater_regions_fit.sh).
  double mean_cosine_down = 0.0;  // file: mean_cosine_down
  double mean_cosine_up = 0.0;    // file: mean_cosine_up
  double beam_mean_cosine_down = 0.0;  // file: beam_mean_cosine_down (the beam's offspring)
  double beam_mean_cosine_up = 0.0;    // file: beam_mean_cosine_up
  // "discrete_ordinates" only: the two-stream's closure (TwoStreamClosure, underwater_ordinates_setup.h); Default:
  // the model's own (diffuseMeanCosines' table). For refitting. file: two_stream_closure
  enum class TwoStream { Default, Quadrature, Asymptotic };
  TwoStream two_stream_closure = TwoStream::Default;
  // "discrete_ordinates" only: the asymptotic mode's share w in the diffuse k over the camera's depth
  // (depthMeanDiffuseK); < 0: the model's own (diffuseAsymptoticShare). file: asymptotic_share
  double asymptotic_share = -1.0;
  // "discrete_ordinates" with diffuse = "two_stream" only: the scale of its first-order in-scatter's flux term
  // (diffuseFluxScale); < 0: the model's own. For refitting. file: flux_scale
  double flux_scale = -1.0;
};

// [shallow]: shallow water with a visible bottom by the four-flow model (paper 003), seen from above a
// flat water surface. Present only when the scene has the table; then the planner runs the fourflow
// pass instead of the sea model.
struct ShallowDesc {
  enum class Path { Table, TableEq24, Exact };
  bool present = false;
  Path path = Path::Table;       // "table": RGB tables + blend (003 eq. 22); "table_eq24": the
                                 // pre-converted blend of eq. 24; "exact": eq. 20 per band
  double gamma = 1.0;            // 003 eq. 23 transition exponent
  double texture_scale = 2.0;    // m, feature size of the procedural bottom texture (file: texture_scale_m)
  double dark_albedo = 0.04;     // albedo of the texture's second (dark) bottom material
  double dark_fraction = 0.35;   // share of the bottom the dark material covers on average
  // A bottom sloping along -z between two depths (file: slope_depths_m), in place of the [bottom]
  // geometry ([bottom] albedo still applies), over a square of side slope_extent (file: slope_extent_m).
  bool slope = false;
  double slope_shallow = 0.0;    // m, depth at z = +extent/2 (the shore)
  double slope_deep = 15.0;      // m, depth at z = -extent/2
  double slope_extent = 100.0;   // m
};

// An image file the scene reads (sky, height field, light map), with where it was named, so that
// host/scene/scene_inputs.h can check it before rendering and point at the key.
struct ImageInputRef {
  std::string key;   // dotted key, e.g. "spotlights[0].light_map"
  std::string path;  // absolute
  SourceLoc loc;
};

struct Scene {
  std::string file;  // absolute path of the scene file
  std::string name;
  CameraDesc camera;
  SunDesc sun;
  SkyDesc sky;
  WaterDesc water;
  AirDesc air;
  SurfaceDesc surface;
  BottomDesc bottom;
  SeaDesc sea;
  UnderwaterDesc underwater;
  ShallowDesc shallow;
  std::vector<ObjectDesc> objects;
  std::vector<SpotlightDesc> spotlights;
  SpectralDesc spectral;
  OutputsDesc outputs;  // [outputs]: the ground-truth layers to write (scene/output_layers.h)
  DisplayDesc display;  // [display]: the PNG's tone map (io/tonemap.h or 003 eq. 18, io/tonemap_eq18.h)
  // Every known knob with its value or "auto"; defaults filled in by the parser. Keys are documented
  // in scenes/README.md ([quality]).
  std::map<std::string, Knob> quality;
  // The keys models declare in their descriptors (scene/model_keys.h), by dotted key
  // ("surface.whitecaps"), every declared key with its value or default; booleans as 0 or 1. Read
  // through modelKey().
  std::map<std::string, double> model_keys;
  std::vector<ImageInputRef> images;  // every image file named above, in file order
  // The data files (camera curves, lamp spectra, light maps, sky images, height fields) as read once
  // for this process (io/data_files.h); shared by the copies of a scene. Null: each reader reads the
  // file itself (the Renderer makes one for a scene that has none).
  std::shared_ptr<DataFiles> files;
};

}  // namespace seasim
