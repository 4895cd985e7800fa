#include "device/allocation_count.h"

#include <CL/cl.h>

#include <atomic>

namespace {

std::atomic<uint64_t> g_live{0};
std::atomic<uint64_t> g_peak{0};
std::atomic<uint64_t> g_count{0};

void CL_CALLBACK released(cl_mem, void* bytes) {
  g_live.fetch_sub(reinterpret_cast<uintptr_t>(bytes), std::memory_order_relaxed);
}

}  // namespace

// The linker sends every clCreateBuffer of seasim's objects here (--wrap), and __real_clCreateBuffer
// to the OpenCL loader's.
extern "C" cl_mem __real_clCreateBuffer(cl_context context, cl_mem_flags flags, size_t size, void* host_ptr,
                                        cl_int* errcode_ret);

extern "C" cl_mem __wrap_clCreateBuffer(cl_context context, cl_mem_flags flags, size_t size, void* host_ptr,
                                        cl_int* errcode_ret) {
  cl_mem mem = __real_clCreateBuffer(context, flags, size, host_ptr, errcode_ret);
  if (!mem) return mem;
  g_count.fetch_add(1, std::memory_order_relaxed);
  const uint64_t now = g_live.fetch_add(size, std::memory_order_relaxed) + size;
  uint64_t peak = g_peak.load(std::memory_order_relaxed);
  while (now > peak && !g_peak.compare_exchange_weak(peak, now, std::memory_order_relaxed)) {
  }
  // Without the callback the bytes would stay counted after the buffer is gone: count them out
  // again here rather than report a false figure.
  if (clSetMemObjectDestructorCallback(mem, released, reinterpret_cast<void*>(static_cast<uintptr_t>(size))) !=
      CL_SUCCESS)
    g_live.fetch_sub(size, std::memory_order_relaxed);
  return mem;
}

namespace seasim {

uint64_t DeviceAllocations::live() { return g_live.load(); }
uint64_t DeviceAllocations::peak() { return g_peak.load(); }
uint64_t DeviceAllocations::count() { return g_count.load(); }
void DeviceAllocations::resetPeak() { g_peak.store(g_live.load()); }

}  // namespace seasim
