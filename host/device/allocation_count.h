// allocation_count.h — the bytes of device memory seasim has allocated, counted where every buffer
// is made: the link wraps clCreateBuffer (CMakeLists.txt: --wrap=clCreateBuffer), so the passes'
// cl::Buffer objects, VkFFT's buffers and the renderer's own are all counted without a call site
// knowing. A buffer's bytes are subtracted when the driver frees it (its destructor callback), so
// `live` is what is held now and `peak` the most held at once since resetPeak(). The memory-budget
// test compares them with the plan's estimate (plan/memory_budget.h).
#pragma once
#include <cstdint>

namespace seasim {

struct DeviceAllocations {
  static uint64_t live();    // bytes in buffers not yet freed by the driver
  static uint64_t peak();    // the largest `live` since the last resetPeak()
  static uint64_t count();   // buffers made since the start
  static void resetPeak();   // peak = live
};

}  // namespace seasim
