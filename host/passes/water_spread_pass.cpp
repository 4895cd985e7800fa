#include "passes/water_spread_pass.h"

#include <tuple>

#include "device/enqueue.h"
#include "util/error.h"

namespace seasim {

WaterSpreadPass::Channels WaterSpreadPass::makeChannels(int channels) {
  const size_t cells = static_cast<size_t>(spread_.params.low_width) * static_cast<size_t>(spread_.params.low_height);
  UwsParams params = spread_.params;
  params.channels = channels;
  Channels ch;
  ch.params = cl::Buffer(device_.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(UwsParams), &params);
  ch.layers = cl::Buffer(device_.context(), CL_MEM_READ_WRITE, sizeof(float) * cells * UWS_LAYERS * size_t(channels));
  ch.rows = cl::Buffer(device_.context(), CL_MEM_READ_WRITE, sizeof(float) * cells * UWS_LAYERS * size_t(channels));
  ch.blurred = cl::Buffer(device_.context(), CL_MEM_READ_WRITE, sizeof(float) * cells * size_t(channels));
  return ch;
}

WaterSpreadPass::WaterSpreadPass(Device& device, const PassPlan& plan, const WaterSpread& spread, int band_count)
    : device_(device), spread_(spread), band_count_(band_count) {
  const size_t cells = static_cast<size_t>(spread.params.low_width) * static_cast<size_t>(spread.params.low_height);
  onDevice("water spread pass set-up", [&] {
    const cl::Program& program = device.program(plan.kernel_file, plan.defines).program;
    reduce_ = cl::Kernel(program, "spread_reduce");
    rows_ = cl::Kernel(program, "spread_rows");
    columns_ = cl::Kernel(program, "spread_columns");
    expand_ = cl::Kernel(program, "spread_expand");
    taps_ = cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, sizeof(float) * spread.taps.size(),
                       const_cast<float*>(spread.taps.data()));
    cell_s_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * cells);
    cell_d_ = cl::Buffer(device.context(), CL_MEM_READ_WRITE, sizeof(float) * cells);
    rgb_ = makeChannels(3);
    if (band_count > 0) spectral_ = makeChannels(band_count);
  });
}

double WaterSpreadPass::blur(Channels& ch, const cl::Buffer& geom, const cl::Buffer& depth, const cl::Buffer& forward,
                             cl::Buffer& frame) {
  const size_t local = 8;
  auto range = [&](int w, int h) {
    return cl::NDRange(roundUp(static_cast<size_t>(w), local), roundUp(static_cast<size_t>(h), local));
  };
  const cl::NDRange cells = range(spread_.params.low_width, spread_.params.low_height);
  const cl::NDRange pixels = range(spread_.params.width, spread_.params.height);
  cl::Event done[4];
  onDevice("water spread pass", [&] {
    reduce_.setArg(0, ch.params);
    reduce_.setArg(1, geom);
    reduce_.setArg(2, depth);
    reduce_.setArg(3, forward);
    reduce_.setArg(4, ch.layers);
    reduce_.setArg(5, cell_s_);
    reduce_.setArg(6, cell_d_);
    for (auto [kernel, in, out] :
         {std::tuple{&rows_, &ch.layers, &ch.rows}, std::tuple{&columns_, &ch.rows, &ch.blurred}}) {
      kernel->setArg(0, ch.params);
      kernel->setArg(1, taps_);
      kernel->setArg(2, cell_s_);
      kernel->setArg(3, cell_d_);
      kernel->setArg(4, *in);
      kernel->setArg(5, *out);
    }
    expand_.setArg(0, ch.params);
    expand_.setArg(1, ch.blurred);
    expand_.setArg(2, frame);
    cl::CommandQueue& q = device_.queue();
    const cl::NDRange group(local, local);
    q.enqueueNDRangeKernel(reduce_, cl::NullRange, cells, workGroupFor(device_, reduce_, group), nullptr, &done[0]);
    q.enqueueNDRangeKernel(rows_, cl::NullRange, cells, workGroupFor(device_, rows_, group), nullptr, &done[1]);
    q.enqueueNDRangeKernel(columns_, cl::NullRange, cells, workGroupFor(device_, columns_, group), nullptr, &done[2]);
    q.enqueueNDRangeKernel(expand_, cl::NullRange, pixels, workGroupFor(device_, expand_, group), nullptr, &done[3]);
    done[3].wait();
  });
  double ms = 0;
  for (const cl::Event& e : done) ms += eventMs(e);
  return ms;
}

double WaterSpreadPass::addRgbInto(cl::Buffer& frame) { return expandInto(rgb_, frame); }

double WaterSpreadPass::addBandsInto(cl::Buffer& frame) {
  if (band_count_ <= 0) throw RuntimeError("water spread: the forward layer per band needs the pass set up with bands");
  return expandInto(spectral_, frame);
}

double WaterSpreadPass::expandInto(Channels& ch, cl::Buffer& frame) {
  const size_t local = 8;
  const cl::NDRange pixels(roundUp(static_cast<size_t>(spread_.params.width), local),
                           roundUp(static_cast<size_t>(spread_.params.height), local));
  cl::Event done;
  onDevice("water spread pass (forward layer)", [&] {
    expand_.setArg(0, ch.params);
    expand_.setArg(1, ch.blurred);
    expand_.setArg(2, frame);
    device_.queue().enqueueNDRangeKernel(expand_, cl::NullRange, pixels,
                                         workGroupFor(device_, expand_, cl::NDRange(local, local)), nullptr, &done);
    done.wait();
  });
  return eventMs(done);
}

double WaterSpreadPass::run(const cl::Buffer& geom, const cl::Buffer& depth, const cl::Buffer& forward_rgb,
                            cl::Buffer& rgb, const cl::Buffer* forward_spectral, cl::Buffer* spectral) {
  double ms = blur(rgb_, geom, depth, forward_rgb, rgb);
  if (band_count_ > 0 && forward_spectral && spectral) ms += blur(spectral_, geom, depth, *forward_spectral, *spectral);
  return ms;
}

}  // namespace seasim
