#include "plan/memory_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "plan/memory_limits.h"
#include "util/error.h"

namespace seasim {

namespace {

double knob(const Scene& s, const char* name, double fallback) {
  auto it = s.quality.find(name);
  return it == s.quality.end() ? fallback : it->second.value;
}

std::string mib(double bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f MiB", bytes / (1024.0 * 1024.0));
  return buf;
}

std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.0f", v);
  return buf;
}

// " (camera.width = 16384, camera.height = 16384); to fit, at most camera.width = 8192 or
// camera.height = 8192 (one at a time), or 11585 x 11585 together" for a buffer that must shrink
// to `limit` bytes. Each distinct setting enters the size to the power of its repeats.
std::string whatFits(const BufferEstimate& b, double limit) {
  std::vector<std::string> keys;
  std::vector<double> values;
  std::vector<int> powers;
  for (size_t i = 0; i < b.settings.size(); ++i) {
    auto it = std::find(keys.begin(), keys.end(), b.settings[i]);
    if (it == keys.end()) {
      keys.push_back(b.settings[i]);
      values.push_back(b.values[i]);
      powers.push_back(1);
    } else {
      ++powers[static_cast<size_t>(it - keys.begin())];
    }
  }
  if (keys.empty() || limit <= 0 || b.bytes <= 0) return "";
  const double ratio = limit / b.bytes;
  std::string now, fits;
  for (size_t i = 0; i < keys.size(); ++i) {
    now += (i ? ", " : "") + keys[i] + " = " + num(values[i]);
    const double max = std::floor(values[i] * std::pow(ratio, 1.0 / powers[i]));
    if (max >= 1) fits += (fits.empty() ? "" : " or ") + keys[i] + " = " + num(max);
  }
  std::string out = " (" + now + ")";
  if (fits.empty()) return out + "; no single one of them can shrink enough";
  out += "; to fit, at most " + fits + (keys.size() > 1 ? " (one at a time, the others as they are)" : "");
  // An image shrinks most naturally at its aspect ratio.
  if (keys.size() == 2 && keys[0] == "camera.width" && keys[1] == "camera.height") {
    const double f = std::sqrt(ratio);
    out += ", or " + num(std::floor(values[0] * f)) + " x " + num(std::floor(values[1] * f)) + " at this aspect ratio";
  }
  return out;
}

}  // namespace

std::vector<BufferEstimate> estimateBuffers(const Scene& s, const Plan& plan) {
  std::vector<BufferEstimate> out;
  const double w = s.camera.width, h = s.camera.height;
  const double nb = s.spectral.count;
  const std::vector<std::string> wh = {"camera.width", "camera.height"};
  // The frame's RGB image on the device and its host copies: the float read-back and the
  // 8-bit tone-mapped and encoded PNG bytes. The pass-specific per-pixel buffers are added below.
  out.push_back({"frame", "RGB image", 3 * 4 * w * h, wh, {w, h}});
  out.push_back({"frame", "RGB image read back to the host", 3 * 4 * w * h, wh, {w, h}, true});
  out.push_back({"frame", "8-bit PNG bytes (tone-mapped and encoded)", 2 * 3 * w * h, wh, {w, h}, true});
  if (s.spectral.spectral_exr)
    out.push_back({"frame", "spectral image (spectral.spectral_exr)", 4 * nb * w * h,
                   {"camera.width", "camera.height", "spectral.count"}, {w, h, nb}});
  const double n_z = knob(s, "sea_nz", 12), n_d = knob(s, "sea_nd", 128), M = knob(s, "sea_map_size", 32);
  const double lights = static_cast<double>(s.spotlights.size());
  for (const PassPlan& p : plan.passes) {
    if (p.name == "raycast" && p.kernel_file == "raycast.cl") {
      // G-buffer (002 §4.3.2): float4 hit and normal; int material and float sun visibility.
      out.push_back({p.name, "G-buffer hits", 16 * w * h, wh, {w, h}});
      out.push_back({p.name, "G-buffer materials", 4 * w * h, wh, {w, h}});
      out.push_back({p.name, "G-buffer sun visibility", 4 * w * h, wh, {w, h}});
    } else if (p.name == "sea_second") {
      out.push_back({p.name, "scattering maps", 4 * n_z * M * M * nb,
                     {"quality.sea_nz", "quality.sea_map_size", "quality.sea_map_size", "spectral.count"},
                     {n_z, M, M, nb}});
      out.push_back({p.name, "radiance maps", 4 * n_z * n_d * nb,
                     {"quality.sea_nz", "quality.sea_nd", "spectral.count"}, {n_z, n_d, nb}});
      if (s.bottom.type == BottomDesc::Type::HeightField)
        out.push_back({p.name, "height-field depth table", 4 * (n_z + 1) * M * M * n_d,
                       {"quality.sea_nz", "quality.sea_map_size", "quality.sea_map_size", "quality.sea_nd"},
                       {n_z + 1, M, M, n_d}});
    } else if (p.name == "shadow_maps") {
      const double S = knob(s, "shadow_map_size", 512);
      out.push_back({p.name, "shadow maps (one per spotlight)", 4 * lights * S * S,
                     {"spotlights (count)", "quality.shadow_map_size", "quality.shadow_map_size"}, {lights, S, S}});
    } else if (p.name == "shafts") {
      const double n = knob(s, "shafts_table_size", 256);
      // Built on the host in float and uploaded (an oversized one threw bad_alloc on the host).
      out.push_back({p.name, "shafts integral table", 4 * n * n,
                     {"quality.shafts_table_size", "quality.shafts_table_size"}, {n, n}});
    } else if (p.name == "froxel") {
      const double fx = knob(s, "froxel_x", 160), fy = knob(s, "froxel_y", 90), fz = knob(s, "froxel_z", 64);
      out.push_back({p.name, "froxel volume", 20 * fx * fy * fz,
                     {"quality.froxel_x", "quality.froxel_y", "quality.froxel_z"}, {fx, fy, fz}});
      // The sun's shadow map over the spheres and boxes (froxel_setup.cpp), one float per texel.
      const bool bounded = std::any_of(s.objects.begin(), s.objects.end(), [](const ObjectDesc& o) {
        return o.type == ObjectDesc::Type::Sphere || o.type == ObjectDesc::Type::Box;
      });
      if (bounded) {
        const double S = knob(s, "shadow_map_size", 512);
        out.push_back({p.name, "sun shadow map over the objects", 4 * S * S,
                       {"quality.shadow_map_size", "quality.shadow_map_size"}, {S, S}});
      }
      const double C = knob(s, "caustic_map_size", 256), L = knob(s, "caustic_layers", 8);
      out.push_back({p.name, "caustic maps", 4 * L * C * C,
                     {"quality.caustic_layers", "quality.caustic_map_size", "quality.caustic_map_size"}, {L, C, C}});
    } else if (p.name == "caustics") {
      const double C = knob(s, "caustic_map_size", 256);
      out.push_back({p.name, "caustic maps", 2 * 4 * C * C,
                     {"quality.caustic_map_size", "quality.caustic_map_size"}, {C, C}});
    } else if (p.name == "kd_multiple" &&
               std::find(p.defines.begin(), p.defines.end(), "SEASIM_UWI_SPREAD=1") != p.defines.end()) {
      // The forward light's moments the point spread blurs (underwater_pass.cpp): F and F E per
      // channel, F D and F per pixel, and per band with spectral output.
      out.push_back({p.name, "forward light moments (underwater.point_spread)", 4 * 8 * w * h, wh, {w, h}});
      if (s.spectral.spectral_exr)
        out.push_back({p.name, "forward light moments per band", 4 * 2 * nb * w * h,
                       {"camera.width", "camera.height", "spectral.count"}, {w, h, nb}});
    } else if (p.name == "underwater_lamps") {
      // Its own copies of the underwater parameter blocks are per band, not per pixel: only the spectra.
      out.push_back({p.name, "lamp spectra (one per spotlight and band)", 4 * lights * nb,
                     {"spotlights (count)", "spectral.count"}, {lights, nb}});
    } else if (p.name == "ocean_fft") {
      const double N = s.surface.grid;
      // h0, spectra, height, slope, displacement, normal, Jacobian, folding, FFT scratch (ocean_pass).
      out.push_back({p.name, "ocean maps", 4 * 28 * N * N, {"surface.grid", "surface.grid"}, {N, N}});
    }
  }
  return out;
}

void applyMemoryCap(unsigned long long& global_mem_bytes, unsigned long long& max_alloc_bytes) {
  const char* env = std::getenv("SEASIM_DEVICE_MEMORY_MB");
  if (!env || !*env) return;
  char* end = nullptr;
  const unsigned long long mb = std::strtoull(env, &end, 10);
  if (*end != '\0' || mb == 0 || mb > (1ull << 30))
    throw RuntimeError(std::string("SEASIM_DEVICE_MEMORY_MB must be a positive number of MiB, got '") + env + "'");
  const unsigned long long cap = mb << 20;
  global_mem_bytes = global_mem_bytes ? std::min(global_mem_bytes, cap) : cap;
  max_alloc_bytes = max_alloc_bytes ? std::min(max_alloc_bytes, cap) : cap;
}

void checkRenderMemory(const std::vector<BufferEstimate>& buffers, unsigned long long global_mem_bytes,
                       unsigned long long max_alloc_bytes, const std::string& device_label, bool host_shares_memory) {
  const unsigned long long device_global = global_mem_bytes, device_alloc = max_alloc_bytes;
  applyMemoryCap(global_mem_bytes, max_alloc_bytes);
  const bool capped = global_mem_bytes != device_global || max_alloc_bytes != device_alloc;
  const std::string label = device_label + (capped ? " capped by SEASIM_DEVICE_MEMORY_MB" : "");
  const ProcessMemoryLimit process = processMemoryLimit();
  if (process.available_bytes == 0) {
    checkMemoryBudget(buffers, global_mem_bytes, max_alloc_bytes, label, host_shares_memory);
    return;
  }
  if (host_shares_memory) {
    if (global_mem_bytes == 0 || process.available_bytes < global_mem_bytes) {
      // 0.9 of the total is usable in checkMemoryBudget: the same margin below the process's limit.
      checkMemoryBudget(buffers, process.available_bytes, std::min(max_alloc_bytes, process.available_bytes),
                        label + " within " + process.source, true, "what is left to this process");
      return;
    }
    checkMemoryBudget(buffers, global_mem_bytes, max_alloc_bytes, label, true);
    return;
  }
  checkMemoryBudget(buffers, global_mem_bytes, max_alloc_bytes, label, false);
  std::vector<BufferEstimate> host;
  for (BufferEstimate b : buffers)
    if (b.host) host.push_back(b);
  checkMemoryBudget(host, process.available_bytes, 0, "the host side of this process", true, process.source);
}

void checkMemoryBudget(const std::vector<BufferEstimate>& all, unsigned long long global_mem_bytes,
                       unsigned long long max_alloc_bytes, const std::string& device_label,
                       bool host_shares_memory, const std::string& total_limit_name) {
  std::vector<BufferEstimate> buffers;
  for (const auto& b : all)
    if (!b.host || host_shares_memory) buffers.push_back(b);
  if (buffers.empty()) return;
  // One allocation limit applies to device buffers only.
  std::vector<BufferEstimate> device_only;
  for (const auto& b : buffers)
    if (!b.host) device_only.push_back(b);
  const auto by_size = [](const BufferEstimate& a, const BufferEstimate& b) { return a.bytes < b.bytes; };
  const auto largest_device = std::max_element(device_only.begin(), device_only.end(), by_size);
  if (largest_device != device_only.end() && max_alloc_bytes > 0 &&
      largest_device->bytes > static_cast<double>(max_alloc_bytes)) {
    const BufferEstimate* largest = &*largest_device;
    throw RuntimeError("not enough device memory: the " + largest->pass + " pass's " + largest->what + " need " +
                       mib(largest->bytes) + " in one buffer, more than the device's largest allocation (" +
                       mib(static_cast<double>(max_alloc_bytes)) + ", CL_DEVICE_MAX_MEM_ALLOC_SIZE of " +
                       device_label + ")" + whatFits(*largest, static_cast<double>(max_alloc_bytes)) +
                       "; nothing was allocated");
  }
  const auto largest = std::max_element(buffers.begin(), buffers.end(), by_size);
  double total = 0;
  for (const auto& b : buffers) total += b.bytes;
  // A tenth kept for the small buffers, kernels and the driver's own use.
  const double usable = 0.9 * static_cast<double>(global_mem_bytes);
  if (global_mem_bytes > 0 && total > usable) {
    std::string list;
    for (const auto& b : buffers) list += "\n  " + b.pass + ": " + b.what + " " + mib(b.bytes);
    // Shrinking the largest buffer's settings shrinks every buffer that depends on all of them
    // (all the per-pixel images with the camera size): what fits is computed over their sum.
    BufferEstimate scaling = *largest;
    scaling.bytes = 0;
    for (const auto& b : buffers) {
      bool depends = true;
      for (const auto& key : largest->settings)
        depends = depends && std::find(b.settings.begin(), b.settings.end(), key) != b.settings.end();
      if (depends) scaling.bytes += b.bytes;
    }
    throw RuntimeError("not enough device memory: this render needs about " + mib(total) + ", more than 90% of " +
                       device_label + "'s " + mib(static_cast<double>(global_mem_bytes)) +
                       " (" + total_limit_name + "). The largest is the " + largest->pass + " pass's " +
                       largest->what + whatFits(scaling, usable - (total - scaling.bytes)) +
                       "; nothing was allocated. Buffers:" + list);
  }
}

}  // namespace seasim
