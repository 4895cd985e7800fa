#include "passes/underwater_lamps_pass.h"

#include <algorithm>
#include <cstring>

#include "device/enqueue.h"
#include "passes/underwater_features.h"
#include "underwater/lamps_bottom_glow.h"
#include "underwater/lamps_ms_table.h"
#include "underwater/lamps_ms_weights.h"
#include "underwater/lamps_setup.h"
#include "math/kernel_math.h"
#include "plan/pass_descriptor.h"
#include "plan/scene_facts.h"
#include "scene/model_keys.h"
#include "util/error.h"

namespace seasim {

UnderwaterLampsPass::Config UnderwaterLampsPass::configFromScene(const Scene& scene) {
  const PassDescriptor& d = descriptorFor(PassRole::UnderwaterLamps);
  Config c;
  c.planes = static_cast<int>(d.settledKnob(scene, "shafts_planes"));
  c.subplanes = static_cast<int>(d.settledKnob(scene, "shafts_subplanes"));
  const std::string model = underwaterLampsModel(scene);
  c.model = model == "orders" ? Model::Orders : model == "delta_m" ? Model::DeltaM : Model::Single;
  c.orders = static_cast<int>(modelKey(scene, "quality.lamps_orders"));
  c.ms_steps = static_cast<int>(modelKey(scene, "quality.lamps_ms_steps"));
  c.kappa = modelKey(scene, "quality.lamps_ms_kappa");
  c.beta = modelKey(scene, "quality.lamps_ms_spread");
  return c;
}

UnderwaterLampsPass::UnderwaterLampsPass(Device& device, const Scene& scene, const UnderwaterSetup& setup,
                                         const WavelengthGrid& grid, const PassPlan& plan, const Config& config)
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
  lamp_g_ = params.g;
  lamp_s_min_ = lamps.params.s_min;
  ms_table_host_ = config_.model == Model::Orders ? lampMsTable(lamp_list_, lamp_g_, config_.beta, config_.orders)
                                                  : std::vector<float>{0.0f};
  const std::vector<float> ms_glow = config_.model == Model::Orders ? bottomGlow(params, bands) : std::vector<float>{0.0f};
  const std::vector<float> ms_weights = config_.model == Model::Orders
                                            ? lampMsWeights(bands, params.g, config_.kappa, config_.orders)
                                            : std::vector<float>{0.0f};
  glow_bands_ = bands;
  glow_depth_ = params.bottom_depth;
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
    ms_table_ = cl::Buffer(device.context(), in, sizeof(float) * ms_table_host_.size(), ms_table_host_.data());
    ms_glow_ = cl::Buffer(device.context(), in, sizeof(float) * ms_glow.size(), const_cast<float*>(ms_glow.data()));
    ms_weights_ = cl::Buffer(device.context(), in, sizeof(float) * ms_weights.size(), const_cast<float*>(ms_weights.data()));
    plain_bands_ = single_apart_
                       ? cl::Buffer(device.context(), in, sizeof(UwBand) * setup.bands.size(),
                                    const_cast<UwBand*>(setup.bands.data()))
                       : bands_;
  });
  plain_g_ = setup.params.g;
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
  // The orders' table depends on g only: rebuilt when the water's g changed.
  if (config_.model == Model::Orders && params.g != lamp_g_) {
    lamp_g_ = params.g;
    ms_table_host_ = lampMsTable(lamp_list_, lamp_g_, config_.beta, config_.orders);
    onDevice("underwater_lamps pass update", [&] {
      device_.queue().enqueueWriteBuffer(ms_table_, CL_TRUE, 0, sizeof(float) * ms_table_host_.size(), ms_table_host_.data());
    });
    glow_bands_.clear();  // the glow follows the new profiles
  }
  // The bottom's glow depends on the water, the bottom and the profiles, the orders' weights on the water:
  // both rebuilt when those changed.
  const bool same_glow = glow_depth_ == params.bottom_depth && glow_bands_.size() == bands.size() &&
                         std::memcmp(glow_bands_.data(), bands.data(), sizeof(UwBand) * bands.size()) == 0;
  if (config_.model == Model::Orders && !same_glow) {
    const std::vector<float> ms_glow = bottomGlow(params, bands);
    const std::vector<float> ms_weights = lampMsWeights(bands, params.g, config_.kappa, config_.orders);
    onDevice("underwater_lamps pass update", [&] {
      device_.queue().enqueueWriteBuffer(ms_glow_, CL_TRUE, 0, sizeof(float) * ms_glow.size(), ms_glow.data());
      device_.queue().enqueueWriteBuffer(ms_weights_, CL_TRUE, 0, sizeof(float) * ms_weights.size(), ms_weights.data());
    });
    glow_bands_ = bands;
    glow_depth_ = params.bottom_depth;
  }
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

double UnderwaterLampsPass::run(cl::Buffer& geom, cl::Buffer& material, cl::Buffer& rgb, cl::Buffer* spectral,
                                cl::Buffer* lamps_layer, cl::Buffer* band_layers, const LampSplitLayers& split) {
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
  return runKernel2d(device_, "underwater_lamps", kernel_, width_, height_);
}

std::vector<float> UnderwaterLampsPass::bottomGlow(const UwParams& params, const std::vector<UwBand>& bands) const {
  LampGlowModel model;
  model.g = params.g;
  model.kappa = config_.kappa;
  model.orders = config_.orders;
  return lampBottomGlowTable(lamp_list_, params, bands, ms_table_host_, lamp_s_min_, model);
}

}  // namespace seasim
