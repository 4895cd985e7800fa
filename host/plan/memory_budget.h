// memory_budget.h — the device memory a plan will allocate, known before any allocation. Large
// but allowed settings (16384^2 images, 4000 spotlights, a huge sea_map_size) used to abort
// inside the OpenCL driver or throw bad_alloc; now the estimate is compared with the device's
// CL_DEVICE_GLOBAL_MEM_SIZE and CL_DEVICE_MAX_MEM_ALLOC_SIZE first, and the message names the
// settings that drive the size and the largest values that would fit.
#pragma once
#include <string>
#include <vector>

#include "plan/plan.h"
#include "scene/scene.h"

namespace seasim {

// One buffer: bytes = the product of its settings' values times a constant. Each name in
// `settings` is one factor ("camera.width", "camera.height"; "shadow_map_size" twice for a square
// map), so scaling every listed setting by f scales the buffer by f^settings.size().
struct BufferEstimate {
  std::string pass;                   // the plan entry's name, or "frame" for the image
  std::string what;                   // "shadow maps"
  double bytes = 0;
  std::vector<std::string> settings;  // scene keys, e.g. "quality.shadow_map_size"
  std::vector<double> values;         // their values in this scene
  bool host = false;                  // a host-side copy: shares the device's memory on a CPU device
};

// The plan's big buffers (device and the host copies the frame needs). Small parameter blocks are
// left out; the check keeps a margin for them.
std::vector<BufferEstimate> estimateBuffers(const Scene& scene, const Plan& plan);

// Throws RuntimeError when one device buffer exceeds max_alloc_bytes or all of them exceed
// global_mem_bytes (less a margin), naming the buffer, its settings and the largest values that
// fit. Host copies count towards the total only when `host_shares_memory` (a CPU device such as
// PoCL allocates its "device" buffers in the same RAM). A zero limit is not checked.
// `total_limit_name` says where global_mem_bytes came from in the message.
void checkMemoryBudget(const std::vector<BufferEstimate>& buffers, unsigned long long global_mem_bytes,
                       unsigned long long max_alloc_bytes, const std::string& device_label,
                       bool host_shares_memory = false,
                       const std::string& total_limit_name = "CL_DEVICE_GLOBAL_MEM_SIZE");

// The whole check a render makes before allocating: the device's limits (capped by
// SEASIM_DEVICE_MEMORY_MB) and the process's own (plan/memory_limits.h: address space, cgroup).
// On a CPU device every buffer, device or host copy, is this process's memory and the smaller
// limit applies to all; on a GPU the host copies are checked against the process's limit.
void checkRenderMemory(const std::vector<BufferEstimate>& buffers, unsigned long long global_mem_bytes,
                       unsigned long long max_alloc_bytes, const std::string& device_label, bool host_shares_memory);

// The limits a render plans with: the device's, capped by $SEASIM_DEVICE_MEMORY_MB when set (a
// farm node whose GPU is shared with other jobs). Throws RuntimeError for a malformed value.
void applyMemoryCap(unsigned long long& global_mem_bytes, unsigned long long& max_alloc_bytes);

// Most spotlights and objects a scene may hold (each light has its own shadow map and shaft
// planes; objects are tested per pixel per light). The scene parser enforces them.
constexpr int kMaxSpotlights = 64;
constexpr int kMaxObjects = 256;

}  // namespace seasim
