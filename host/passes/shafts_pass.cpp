#include "passes/shafts_pass.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdio>

#include "device/enqueue.h"
#include "geometry/kernel_camera.h"
#include "math/kernel_math.h"
#include "geometry/shafts_geometry_k.h"
#include "passes/shafts_features.h"
#include "plan/shafts_method.h"
#include "spectral/lamp_spectrum.h"
#include "util/error.h"

extern "C" {
#include "common/shafts_params.h"
}

namespace seasim {

// The kernel reads these structs with OpenCL C layout; float/int are 4 bytes on both sides.
static_assert(sizeof(ShaftsParams) == 4 * 16 + 11 * 4 + 9 * 4, "ShaftsParams layout changed: update shafts.cl users");
static_assert(offsetof(ShaftsParams, tan_half_fov_y) == 64);
static_assert(offsetof(ShaftsParams, width) == 112);
static_assert(offsetof(ShaftsParams, table_size) == 140);
static_assert(sizeof(ShaftsLight) == 5 * 16 + 8 * 4, "ShaftsLight must stay 112 bytes");
static_assert(offsetof(ShaftsLight, cos_cone) == 80);
static_assert(offsetof(ShaftsLight, shadow_offset) == 104);
static_assert(sizeof(ShaftsObject) == 64, "ShaftsObject must stay 64 bytes");
static_assert(offsetof(ShaftsObject, type) == 48);
static_assert(sizeof(ShaftsOccluder) == 16 * SHAFTS_OCCLUDER_PLANES + 2 * 16 + 4 * 4, "ShaftsOccluder must stay 192 bytes");
static_assert(offsetof(ShaftsOccluder, plane_count) == 176);
static_assert(SHAFTS_OCCLUDER_PLANES == SHAFTS_OCC_PLANES, "shafts_params.h and shafts_intervals.h disagree");
static_assert(kShaftsIntervalsMaxObjects == SHAFTS_MAX_PIECES - 1, "plan/shafts_method.h and shafts_intervals.h disagree");

namespace {

int knob(const Scene& scene, const char* name, int fallback) {
  const auto it = scene.quality.find(name);
  if (it == scene.quality.end() || it->second.automatic) return fallback;
  return static_cast<int>(it->second.value);
}

ShaftsParams shaftsParams(const Scene& scene, const ShaftsPass::Config& config, const ShaftsRange& range,
                          int light_count) {
  const CameraDesc& cam = scene.camera;
  ShaftsParams p{};
  setKernelCamera(p, cam);
  p.tan_half_fov_y = static_cast<float>(std::tan(cam.fov_y / 2));
  p.aspect = static_cast<float>(cam.width) / static_cast<float>(cam.height);
  const double rho = scene.air.density, sigma_t = scene.air.density * scene.air.extinction;
  p.rho = static_cast<float>(rho);
  p.sigma_t = static_cast<float>(sigma_t);
  p.hg_g = static_cast<float>(scene.air.g);
  p.s_min = static_cast<float>(kShaftsLampRadius);
  p.table_s_max = static_cast<float>(range.s_max);
  p.table_t_max = static_cast<float>(range.t_max);
  p.panel_rad = static_cast<float>(config.panel_deg * M_PI / 180);
  p.march_steps = config.march_steps;
  p.map_panel_texels = static_cast<float>(config.panel_texels);
  p.width = cam.width;
  p.height = cam.height;
  p.light_count = light_count;
  p.object_count = static_cast<int>(scene.objects.size());
  p.planes = config.planes;
  p.subplanes = config.subplanes;
  p.shadow_map_size = config.shadow_map_size;
  p.table_size = config.table_size;
  return p;
}

// The lights, their light maps (appended to maps, one float RGB buffer) and shadow-map offsets.
std::vector<ShaftsLight> shaftsLights(const Scene& scene, int shadow_map_size, std::vector<float>& maps) {
  std::vector<ShaftsLight> lights(scene.spotlights.size());
  for (size_t i = 0; i < lights.size(); ++i) {
    const SpotlightDesc& l = scene.spotlights[i];
    ShaftsLight& L = lights[i];
    Vec3 lr, lu;
    shaftsLightBasis(l, lr, lu);
    set4(L.position, l.position);
    set4(L.direction, normalize(l.direction));
    set4(L.right, lr);
    set4(L.up, lu);
    set4(L.color, shaftsLampRgb(l, scene.spectral, scene.files.get()));  // spectral/lamp_spectrum.h
    L.cos_cone = static_cast<float>(std::cos(l.cone));
    L.cos_inner = static_cast<float>(std::cos(std::max(0.0, l.cone - l.falloff)));
    L.tan_cone = static_cast<float>(std::tan(l.cone));
    L.light_map_offset = -1;
    if (!l.light_map.empty()) {
      const LightMap map = loadLightMap(l.light_map, scene.files.get());
      L.light_map_offset = static_cast<int>(maps.size());
      L.light_map_width = map.width;
      L.light_map_height = map.height;
      maps.insert(maps.end(), map.rgb.begin(), map.rgb.end());
    }
    L.shadow_offset = static_cast<int>(i) * shadow_map_size * shadow_map_size;
  }
  return lights;
}

std::vector<ShaftsObject> shaftsObjects(const Scene& scene) {
  std::vector<ShaftsObject> objects;
  for (const ObjectDesc& o : scene.objects) {
    ShaftsObject ob{};
    set4(ob.albedo, objectAlbedoRgb(o));
    if (o.type == ObjectDesc::Type::Sphere) {
      ob.type = SHAFTS_SPHERE;
      set4(ob.a, o.center, o.radius);
    } else if (o.type == ObjectDesc::Type::Box) {
      ob.type = SHAFTS_BOX;
      set4(ob.a, o.box_min);
      set4(ob.b, o.box_max);
    } else if (o.type == ObjectDesc::Type::Plane) {
      ob.type = SHAFTS_PLANE;
      set4(ob.a, o.point);
      set4(ob.b, normalize(o.normal));
    } else {
      throw RuntimeError(o.loc.file + ":" + std::to_string(o.loc.line) +
                         ": height-field objects are not supported in spotlight (shafts) scenes yet");
    }
    objects.push_back(ob);
  }
  return objects;
}

// Intervals method: each object's shadow volume from each lamp, in double, then float
// (kernels/common/shafts_intervals.h), indexed [light * object_count + object].
std::vector<ShaftsOccluder> shaftsOccluders(const Scene& scene) {
  std::vector<ShaftsOccluder> occluders(scene.spotlights.size() * scene.objects.size(), ShaftsOccluder{});
  for (size_t i = 0; i < scene.spotlights.size(); ++i) {
    const kmath_d::real3 lamp = toReal3(scene.spotlights[i].position);
    for (size_t k = 0; k < scene.objects.size(); ++k) {
      const ObjectDesc& o = scene.objects[k];
      kmath_d::ShaftsShadowVolume v;
      if (o.type == ObjectDesc::Type::Sphere) v = kmath_d::shafts_sphere_shadow(lamp, toReal3(o.center), o.radius);
      else if (o.type == ObjectDesc::Type::Box) v = kmath_d::shafts_box_shadow(lamp, toReal3(o.box_min), toReal3(o.box_max));
      else v = kmath_d::shafts_plane_shadow(lamp, toReal3(o.point), toReal3(normalize(o.normal)));
      ShaftsOccluder& oc = occluders[i * scene.objects.size() + k];
      for (int j = 0; j < v.plane_count; ++j)
        set4(oc.planes[j], Vec3{v.n[j].x, v.n[j].y, v.n[j].z}, v.b[j]);
      set4(oc.apex, Vec3{v.apex.x, v.apex.y, v.apex.z});
      set4(oc.axis, Vec3{v.axis.x, v.axis.y, v.axis.z}, v.cos_cone);
      oc.plane_count = v.plane_count;
      oc.has_cone = v.has_cone;
      oc.always = v.always;
    }
  }
  return occluders;
}

// 001 eq. 6 tables: F over α ∈ [0, π]; ĥ = s² h = ρ exp(-ρκ(s + t)) over [0, s_max] x [0, t_max].
void shaftsTables(int n, const ShaftsRange& range, double rho, double sigma_t, bool use_hg, double g,
                  std::vector<float>& f_table, std::vector<float>& h_table) {
  for (int i = 0; i < n; ++i) {
    const double alpha = M_PI * i / (n - 1);
    f_table[i] = static_cast<float>(kmath_d::shafts_phase_fn(std::cos(alpha), use_hg, g));
  }
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double s = range.s_max * i / (n - 1), t = range.t_max * j / (n - 1);
      h_table[size_t(j) * n + i] = static_cast<float>(kmath_d::shafts_h_scaled(s, t, rho, sigma_t));
    }
}

}  // namespace

ShaftsPass::Config ShaftsPass::configFromScene(const Scene& scene) {
  Config c;
  c.planes = knob(scene, "shafts_planes", 30);
  c.subplanes = knob(scene, "shafts_subplanes", 6);
  c.shadow_map_size = knob(scene, "shadow_map_size", 512);
  c.table_size = std::max(2, knob(scene, "shafts_table_size", 256));
  const auto real_knob = [&](const char* name, double fallback) {
    const auto it = scene.quality.find(name);
    return it == scene.quality.end() ? fallback : it->second.value;
  };
  c.panel_deg = real_knob("shafts_panel_deg", kShaftsPanelDegDefault);
  c.panel_texels = real_knob("shafts_panel_texels", kShaftsPanelTexelsDefault);
  c.march_steps = knob(scene, "shafts_march_steps", kShaftsMarchStepsDefault);
  return c;
}

ShaftsRange ShaftsPass::rangeFor(const Scene& scene) { return shaftsTableRange(scene); }

ShaftsPass::ShaftsPass(Device& device, const Scene& scene, const PassPlan& plan, const Config& config)
    : device_(device),
      width_(scene.camera.width),
      height_(scene.camera.height),
      light_count_(static_cast<int>(scene.spotlights.size())),
      shadow_size_(config.shadow_map_size),
      has_objects_(!scene.objects.empty()) {
  if (config.planes < 1 || config.subplanes < 1 || config.shadow_map_size < 1) {
    throw RuntimeError("shafts: planes, sub-planes and shadow-map size must be at least 1");
  }
  range_ = rangeFor(scene);
  const ShaftsFeatures& features = plan.featuresAs<ShaftsFeatures>();
  const bool exact = features.exact;
  const bool use_hg = features.henyey_greenstein;
  const bool intervals = features.intervals;
  planes_ = features.planes();
  if (intervals && static_cast<int>(scene.objects.size()) > kShaftsIntervalsMaxObjects) {
    throw RuntimeError("shafts: the intervals method handles at most " + std::to_string(kShaftsIntervalsMaxObjects) +
                       " objects (quality.shafts_method = \"planes\" has no such limit)");
  }
  if (intervals && !(config.panel_deg > 0 && config.panel_texels > 0)) {
    throw RuntimeError("shafts: panel width and panel texels must be positive");
  }
  if (features.march && config.march_steps < 1) throw RuntimeError("shafts: the march needs at least 1 step");

  const ShaftsParams p = shaftsParams(scene, config, range_, light_count_);
  std::vector<float> maps;  // the light maps, one float RGB buffer
  const std::vector<ShaftsLight> lights = shaftsLights(scene, config.shadow_map_size, maps);
  if (!maps.empty() && !features.light_map) {
    throw RuntimeError("shafts: the plan has no light_map feature (SEASIM_HAS_LIGHT_MAP) but a spotlight has a light map");
  }
  const std::vector<ShaftsObject> objects = shaftsObjects(scene);
  const std::vector<ShaftsOccluder> occluders =
      intervals && !scene.objects.empty() ? shaftsOccluders(scene) : std::vector<ShaftsOccluder>(1, ShaftsOccluder{});
  // 001 eq. 6 tables: the intervals and march methods evaluate g exactly.
  const bool tables = !exact && planes_;
  const int n = config.table_size;
  std::vector<float> f_table(tables ? n : 1), h_table(tables ? size_t(n) * n : 1);
  if (tables) shaftsTables(n, range_, scene.air.density, scene.air.density * scene.air.extinction, use_hg, scene.air.g,
                           f_table, h_table);

  const size_t pixels = static_cast<size_t>(width_) * static_cast<size_t>(height_);
  const size_t shadow_texels =
      has_objects_ && planes_ ? size_t(light_count_) * shadow_size_ * shadow_size_ : 1;
  auto upload = [&](const void* data, size_t bytes) {
    return cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, bytes, const_cast<void*>(data));
  };
  const float zero = 0.0f;
  const ShaftsObject no_object{};
  onDevice("shafts pass set-up", [&] {
    const BuiltProgram& built = device.program(plan.kernel_file, plan.defines);
    render_kernel_ = cl::Kernel(built.program, "shafts_render");
    shadow_kernel_ = cl::Kernel(built.program, "shafts_shadow_map");
    params_ = upload(&p, sizeof p);
    lights_ = upload(lights.data(), sizeof(ShaftsLight) * lights.size());
    objects_ = objects.empty() ? upload(&no_object, sizeof no_object)
                               : upload(objects.data(), sizeof(ShaftsObject) * objects.size());
    light_maps_ = maps.empty() ? upload(&zero, sizeof zero) : upload(maps.data(), sizeof(float) * maps.size());
    f_table_ = upload(f_table.data(), sizeof(float) * f_table.size());
    h_table_ = upload(h_table.data(), sizeof(float) * h_table.size());
    occluders_ = upload(occluders.data(), sizeof(ShaftsOccluder) * occluders.size());
    shadow_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * shadow_texels);
    // Read and written: the render kernel writes it, the NaN/Inf check kernel reads it.
    rgb_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * 3 * pixels);
    shadow_kernel_.setArg(0, params_);
    shadow_kernel_.setArg(1, lights_);
    shadow_kernel_.setArg(2, objects_);
    shadow_kernel_.setArg(3, shadow_);
    render_kernel_.setArg(0, params_);
    render_kernel_.setArg(1, lights_);
    render_kernel_.setArg(2, objects_);
    render_kernel_.setArg(3, shadow_);
    render_kernel_.setArg(4, light_maps_);
    render_kernel_.setArg(5, f_table_);
    render_kernel_.setArg(6, h_table_);
    render_kernel_.setArg(7, occluders_);
    render_kernel_.setArg(8, rgb_);
  });
}

double ShaftsPass::run() {
  const size_t local = 8;
  shadow_ms_ = 0;
  if (has_objects_ && light_count_ > 0 && planes_) {
    const size_t side = roundUp(static_cast<size_t>(shadow_size_), local);
    shadow_ms_ = runKernel(device_, "shadow_maps", shadow_kernel_, cl::NDRange(side, side, light_count_),
                           cl::NDRange(local, local, 1));
  }
  shafts_ms_ = runKernel2d(device_, "shafts", render_kernel_, width_, height_, local);
  return shadow_ms_ + shafts_ms_;
}

void ShaftsPass::readRgb(std::vector<float>& out) {
  out.resize(size_t(3) * width_ * height_);
  onDevice("shafts pass: reading the frame back", [&] {
    device_.queue().enqueueReadBuffer(rgb_, CL_TRUE, 0, sizeof(float) * out.size(), out.data());
  });
}

}  // namespace seasim
