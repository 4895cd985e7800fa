#include "plan/memory_budget.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "plan/memory_limits.h"
#include "plan/pass_descriptor.h"
#include "util/error.h"

namespace seasim {

namespace {

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
  // 8-bit tone-mapped and encoded PNG bytes.
  out.push_back({"frame", "RGB image", 3 * 4 * w * h, wh, {w, h}});
  out.push_back({"frame", "RGB image read back to the host", 3 * 4 * w * h, wh, {w, h}, true});
  out.push_back({"frame", "8-bit PNG bytes (tone-mapped and encoded)", 2 * 3 * w * h, wh, {w, h}, true});
  if (s.spectral.spectral_exr)
    out.push_back({"frame", "spectral image (spectral.spectral_exr)", 4 * nb * w * h,
                   {"camera.width", "camera.height", "spectral.count"}, {w, h, nb}});
  // Each pass's own buffers, from its descriptor (plan/pass_descriptor.h).
  for (const PassPlan& p : plan.passes) {
    const PassDescriptor* d = descriptorOf(p);
    if (!d || !d->buffers) continue;
    for (BufferEstimate& b : d->buffers(s, p)) out.push_back(std::move(b));
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

namespace {

bool bySize(const BufferEstimate& a, const BufferEstimate& b) { return a.bytes < b.bytes; }

// The largest device buffer against the device's one-allocation limit (max_alloc_bytes; 0: none).
void checkLargestAllocation(const std::vector<BufferEstimate>& buffers, unsigned long long max_alloc_bytes,
                            const std::string& device_label) {
  std::vector<BufferEstimate> device_only;
  for (const auto& b : buffers)
    if (!b.host) device_only.push_back(b);
  const auto largest = std::max_element(device_only.begin(), device_only.end(), bySize);
  if (largest == device_only.end() || max_alloc_bytes == 0 || largest->bytes <= static_cast<double>(max_alloc_bytes))
    return;
  throw RuntimeError("not enough device memory: the " + largest->pass + " pass's " + largest->what + " need " +
                     mib(largest->bytes) + " in one buffer, more than the device's largest allocation (" +
                     mib(static_cast<double>(max_alloc_bytes)) + ", CL_DEVICE_MAX_MEM_ALLOC_SIZE of " + device_label +
                     ")" + whatFits(*largest, static_cast<double>(max_alloc_bytes)) + "; nothing was allocated");
}

// The buffers that depend on every setting of `largest` (all the per-pixel images with the camera
// size), summed into one estimate: shrinking those settings shrinks all of them, so what fits is
// computed over their sum.
BufferEstimate scalingWith(const std::vector<BufferEstimate>& buffers, const BufferEstimate& largest) {
  BufferEstimate scaling = largest;
  scaling.bytes = 0;
  for (const auto& b : buffers) {
    bool depends = true;
    for (const auto& key : largest.settings)
      depends = depends && std::find(b.settings.begin(), b.settings.end(), key) != b.settings.end();
    if (depends) scaling.bytes += b.bytes;
  }
  return scaling;
}

}  // namespace

void checkMemoryBudget(const std::vector<BufferEstimate>& all, unsigned long long global_mem_bytes,
                       unsigned long long max_alloc_bytes, const std::string& device_label,
                       bool host_shares_memory, const std::string& total_limit_name) {
  std::vector<BufferEstimate> buffers;
  for (const auto& b : all)
    if (!b.host || host_shares_memory) buffers.push_back(b);
  if (buffers.empty()) return;
  // One allocation limit applies to device buffers only.
  checkLargestAllocation(buffers, max_alloc_bytes, device_label);
  double total = 0;
  for (const auto& b : buffers) total += b.bytes;
  // A tenth kept for the small buffers, kernels and the driver's own use.
  const double usable = 0.9 * static_cast<double>(global_mem_bytes);
  if (global_mem_bytes == 0 || total <= usable) return;
  std::string list;
  for (const auto& b : buffers) list += "\n  " + b.pass + ": " + b.what + " " + mib(b.bytes);
  const BufferEstimate& largest = *std::max_element(buffers.begin(), buffers.end(), bySize);
  const BufferEstimate scaling = scalingWith(buffers, largest);
  throw RuntimeError("not enough device memory: this render needs about " + mib(total) + ", more than 90% of " +
                     device_label + "'s " + mib(static_cast<double>(global_mem_bytes)) + " (" + total_limit_name +
                     "). The largest is the " + largest.pass + " pass's " + largest.what +
                     whatFits(scaling, usable - (total - scaling.bytes)) + "; nothing was allocated. Buffers:" + list);
}

}  // namespace seasim
