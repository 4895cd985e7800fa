#include "passes/underwater_lamps_pass.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "device/enqueue.h"
#include "passes/pixel_lattice.h"
#include "passes/underwater_features.h"
#include "underwater/lamps_setup.h"
#include "math/kernel_math.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "scene/model_keys.h"
#include "util/error.h"

namespace seasim {

int lampsMsLatticeStep(const Scene& scene) {
  const double cell_deg = modelKey(scene, "quality.lamps_ms_cell_deg");
  const double pixel_deg = scene.camera.fov_y * 180.0 / std::numbers::pi / std::max(1, scene.camera.height);
  // 1e-6: a cell of a whole number of pixels stays whole against the rounding of the division.
  return std::max(1, static_cast<int>(std::floor(cell_deg / pixel_deg + 1e-6)));
}

size_t lampsMsLatticeFloats(int band_count, bool lamps_split) {
  return 2 * static_cast<size_t>(band_count) * (lamps_split ? 2 : 1);
}

UnderwaterLampsPass::Config UnderwaterLampsPass::configFromScene(const Scene& scene) {
  const PassDescriptor& d = descriptorFor(PassRole::UnderwaterLamps);
  Config c;
  c.planes = static_cast<int>(d.settledKnob(scene, "shafts_planes"));
  const auto m = scene.quality.find("shafts_subplanes");
  c.subplanes = m != scene.quality.end() && m->second.given && !m->second.automatic && m->second.value > 0
                    ? static_cast<int>(m->second.value)
                    : kSubplanesInWater;
  const std::string model = underwaterLampsModel(scene);
  c.model = model == "orders" ? Model::Orders : model == "delta_m" ? Model::DeltaM : Model::Single;
  c.orders = static_cast<int>(modelKey(scene, "quality.lamps_orders"));
  c.ms_steps = static_cast<int>(modelKey(scene, "quality.lamps_ms_steps"));
  c.kappa = modelKey(scene, "quality.lamps_ms_kappa");
  c.beta = modelKey(scene, "quality.lamps_ms_spread");
  c.ms_step = lampsMsLatticeStep(scene);
  return c;
}

UnderwaterLampsPass::UnderwaterLampsPass(Device& device, const Scene& scene, const UnderwaterSetup& setup,
                                         const WavelengthGrid& grid, const PassPlan& plan, const Config& config,
                                         LampsOrdersTables* tables)
    : device_(device),
      config_(config),
      width_(setup.params.width),
      height_(setup.params.height),
      band_count_(setup.bands.size()),
      object_count_(setup.objects.size()),
      albedo_count_(setup.albedo.size()),
      single_apart_(config.model == Model::DeltaM && plan.featuresAs<UnderwaterLampsFeatures>().lamps_split) {
  if (config.planes < 1 || config.subplanes < 1)
    throw RuntimeError("underwater_lamps: planes and sub-planes must be at least 1");
  if (config.orders < 1 || config.orders > UW_MS_MAX_ORDERS || config.ms_steps < 1 || config.ms_steps > UW_MS_MAX_STEPS)
    throw RuntimeError("underwater_lamps: orders must be in [1, 12] and quadrature steps in [1, 64]");
  UnderwaterLamps lamps = makeUnderwaterLamps(scene, grid);
  lamps.params.planes = config.planes;
  lamps.params.subplanes = config.subplanes;
  // The medium the lamps' light sees: the water, delta-M scaled in that model only.
  UwParams params = setup.params;
  std::vector<UwBand> bands = setup.bands;
  if (config_.model == Model::DeltaM) deltaMScale(params, bands);
  lamp_list_ = lamps.lamps;
  lamp_s_min_ = lamps.params.s_min;
  if (!tables) {
    own_tables_ = std::make_unique<LampsOrdersTables>();
    tables = own_tables_.get();
  }
  tables_ = tables;
  UwObject none{};  // OpenCL buffers cannot be empty
  const cl_mem_flags in = CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR;
  onDevice("underwater_lamps pass set-up", [&] {
    kernel_ = cl::Kernel(device.program(plan.kernel_file, plan.defines).program, "underwater_lamps");
    params_ = cl::Buffer(device.context(), in, sizeof(UwParams), &params);
    bands_ = cl::Buffer(device.context(), in, sizeof(UwBand) * bands.size(), bands.data());
    albedo_ = cl::Buffer(device.context(), in, sizeof(float) * setup.albedo.size(), const_cast<float*>(setup.albedo.data()));
    objects_ = cl::Buffer(device.context(), in, sizeof(UwObject) * std::max<size_t>(1, setup.objects.size()),
                          setup.objects.empty() ? &none : const_cast<UwObject*>(setup.objects.data()));
    lamp_params_ = cl::Buffer(device.context(), in, sizeof(UwLampParams), &lamps.params);
    lamps_ = cl::Buffer(device.context(), in, sizeof(UwLamp) * lamps.lamps.size(), lamps.lamps.data());
    spectra_ = cl::Buffer(device.context(), in, sizeof(float) * lamps.spectra.size(), lamps.spectra.data());
    plain_bands_ = single_apart_
                       ? cl::Buffer(device.context(), in, sizeof(UwBand) * setup.bands.size(),
                                    const_cast<UwBand*>(setup.bands.data()))
                       : bands_;
  });
  if (config_.model == Model::Orders) orderTables(params, bands, true);
  plain_g_ = setup.params.g;
  if (plan.featuresAs<UnderwaterLampsFeatures>().ms_lattice) {
    lattice_w_ = pixelLatticeSize(width_, config_.ms_step);
    lattice_h_ = pixelLatticeSize(height_, config_.ms_step);
    const size_t stride = lampsMsLatticeFloats(band_count_, plan.featuresAs<UnderwaterLampsFeatures>().lamps_split);
    onDevice("underwater_lamps lattice set-up", [&] {
      lattice_kernel_ = cl::Kernel(device.program(plan.kernel_file, plan.defines).program, "underwater_lamps_lattice");
      lattice_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE,
                            sizeof(float) * stride * static_cast<size_t>(lattice_w_) * static_cast<size_t>(lattice_h_));
    });
  }
}

void UnderwaterLampsPass::orderTables(const UwParams& params, const std::vector<UwBand>& bands, bool create) {
  const LampsOrdersTables::Table& profiles = tables_->profiles(lamp_list_, params.g, config_.beta, config_.orders);
  const LampsOrdersTables::Table& glow = tables_->glow(lamp_list_, params, bands, lamp_s_min_);
  const LampsOrdersTables::Table& weights = tables_->weights(bands, params.g, config_.kappa, config_.orders);
  onDevice("underwater_lamps pass tables", [&] {
    const auto upload = [&](cl::Buffer& buffer, const LampsOrdersTables::Table& t, int& on_device) {
      if (create)
        buffer = cl::Buffer(device_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * t.values.size(),
                            const_cast<float*>(t.values.data()));
      else if (t.generation != on_device)
        device_.queue().enqueueWriteBuffer(buffer, CL_TRUE, 0, sizeof(float) * t.values.size(), t.values.data());
      on_device = t.generation;
    };
    upload(ms_table_, profiles, profiles_on_device_);
    upload(ms_glow_, glow, glow_on_device_);
    upload(ms_weights_, weights, weights_on_device_);
  });
}

void UnderwaterLampsPass::update(const UnderwaterSetup& setup) {
  if (setup.bands.size() != band_count_ || setup.objects.size() != object_count_ ||
      setup.albedo.size() != albedo_count_ || setup.params.width != width_ || setup.params.height != height_) {
    throw RuntimeError("underwater_lamps pass: the new set-up has other sizes (bands, objects or image); make a new pass");
  }
  UwParams params = setup.params;
  std::vector<UwBand> bands = setup.bands;
  if (config_.model == Model::DeltaM) deltaMScale(params, bands);
  plain_g_ = setup.params.g;
  // The orders' tables follow the water (g, a and b per band) and the bottom: rebuilt and written where those changed.
  if (config_.model == Model::Orders) orderTables(params, bands, false);
  onDevice("underwater_lamps pass update", [&] {
    cl::CommandQueue& q = device_.queue();
    q.enqueueWriteBuffer(params_, CL_FALSE, 0, sizeof(UwParams), &params);
    q.enqueueWriteBuffer(bands_, CL_FALSE, 0, sizeof(UwBand) * band_count_, bands.data());
    if (object_count_ > 0)
      q.enqueueWriteBuffer(objects_, CL_FALSE, 0, sizeof(UwObject) * object_count_, setup.objects.data());
    q.enqueueWriteBuffer(albedo_, CL_FALSE, 0, sizeof(float) * albedo_count_, setup.albedo.data());
    if (single_apart_)
      q.enqueueWriteBuffer(plain_bands_, CL_FALSE, 0, sizeof(UwBand) * band_count_, setup.bands.data());
    q.finish();
  });
}

void UnderwaterLampsPass::run(std::vector<PassTiming>& timings, cl::Buffer& geom, cl::Buffer& material, cl::Buffer& rgb,
                              cl::Buffer* spectral, cl::Buffer* lamps_layer, cl::Buffer* band_layers,
                              const LampSplitLayers& split) {
  if (lattice_w_ > 0) {
    onDevice("underwater_lamps lattice", [&] {
      cl_uint arg = 0;
      for (cl::Buffer* b : {&params_, &bands_, &albedo_, &objects_, &geom, &material, &lamp_params_, &lamps_, &spectra_,
                            &ms_table_, &ms_glow_, &ms_weights_})
        lattice_kernel_.setArg(arg++, *b);
      lattice_kernel_.setArg(arg++, static_cast<cl_int>(config_.orders));
      lattice_kernel_.setArg(arg++, static_cast<cl_int>(config_.ms_steps));
      lattice_kernel_.setArg(arg++, static_cast<cl_int>(config_.ms_step));
      lattice_kernel_.setArg(arg++, static_cast<cl_int>(lattice_w_));
      lattice_kernel_.setArg(arg++, static_cast<cl_int>(lattice_h_));
      lattice_kernel_.setArg(arg++, lattice_);
    });
    timings.push_back({"underwater_lamps_lattice",
                       runKernel2d(device_, "underwater_lamps_lattice", lattice_kernel_, lattice_w_, lattice_h_)});
  }
  onDevice("underwater_lamps pass", [&] {
    cl_uint arg = 0;
    kernel_.setArg(arg++, params_);
    kernel_.setArg(arg++, bands_);
    kernel_.setArg(arg++, albedo_);
    kernel_.setArg(arg++, objects_);
    kernel_.setArg(arg++, geom);
    kernel_.setArg(arg++, material);
    kernel_.setArg(arg++, lamp_params_);
    kernel_.setArg(arg++, lamps_);
    kernel_.setArg(arg++, spectra_);
    if (config_.model == Model::Orders) {
      kernel_.setArg(arg++, ms_table_);
      kernel_.setArg(arg++, ms_glow_);
      kernel_.setArg(arg++, ms_weights_);
      kernel_.setArg(arg++, static_cast<cl_int>(config_.orders));
      kernel_.setArg(arg++, static_cast<cl_int>(config_.ms_steps));
    }
    if (lattice_w_ > 0) {
      kernel_.setArg(arg++, lattice_);
      kernel_.setArg(arg++, static_cast<cl_int>(config_.ms_step));
      kernel_.setArg(arg++, static_cast<cl_int>(lattice_w_));
      kernel_.setArg(arg++, static_cast<cl_int>(lattice_h_));
    }
    kernel_.setArg(arg++, rgb);
    if (spectral) kernel_.setArg(arg++, *spectral);
    if (lamps_layer) kernel_.setArg(arg++, *lamps_layer);
    if (band_layers) kernel_.setArg(arg++, *band_layers);
    if (split.buffer) {
      kernel_.setArg(arg++, *split.buffer);
      kernel_.setArg(arg++, static_cast<cl_int>(split.stride));
      kernel_.setArg(arg++, static_cast<cl_int>(split.single_at));
      kernel_.setArg(arg++, static_cast<cl_int>(split.multiple_at));
      kernel_.setArg(arg++, plain_bands_);
      kernel_.setArg(arg++, static_cast<cl_float>(plain_g_));
      kernel_.setArg(arg++, static_cast<cl_int>(single_apart_));
    }
  });
  timings.push_back({"underwater_lamps", runKernel2d(device_, "underwater_lamps", kernel_, width_, height_)});
}

}  // namespace seasim
