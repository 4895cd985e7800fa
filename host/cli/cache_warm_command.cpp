// cache_warm_command.cpp — `seasim cache warm` (cache_warm_command.h).
//
// Why a frame and not only Device::program: PoCL compiles a kernel's work-group function lazily, at
// its first enqueue, for that local size (and caches it under $POCL_CACHE_DIR); the seasim program
// cache only holds the OpenCL program. Running each distinct plan once at its real size is the one
// way to hit every (kernel, defines, local size) the renders will, including the passes' own extra
// defines (sea_single's LUT switch, the froxel pass's) and the `auto` quality searches, which cache
// their choice too (the shafts' measured method before the plan is made, as the Renderer does). Renders that differ only in time, sun, camera pose or other values that change no
// kernel build share one warm-up.
#include "cli/cache_warm_command.h"

#include <stdlib.h>

#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>

#include "cli/commands.h"
#include "device/device.h"
#include "device/kernel_cache.h"
#include "device/kernel_store.h"
#include "jobs/job.h"
#include "quality/render_frame.h"
#include "quality/shafts_method_auto.h"
#include "plan/plan.h"
#include "scene/scene_parser.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {

namespace {

// What decides the kernel builds and work-group sizes of a render: the plan (passes, kernel files,
// defines), the image size, the band count, the quality knobs (grid and map sizes) and the FFT ocean's
// grid, which VkFFT's generated programs are built for (the plan's text does not show it).
std::string buildKey(const Scene& scene, const Plan& plan) {
  std::ostringstream key;
  key << plan.toText() << scene.camera.width << "x" << scene.camera.height << " n=" << scene.spectral.count;
  if (scene.surface.type == SurfaceDesc::Type::Fft) key << " fft=" << scene.surface.grid;
  for (const auto& [name, knob] : scene.quality) key << " " << name << "=" << (knob.automatic ? -1.0 : knob.value);
  return key.str();
}

// With --store, the warm-up compiles into fresh private caches (no store read), so that after it they
// hold exactly what these renders need: returns their folder, removed again by the caller.
std::string usePrivateCaches() {
  const std::string dir = makeTempFolder("seasim-store");
  if (dir.empty())
    throw RuntimeError(std::string("cannot create a folder for the kernel store's caches: ") + std::strerror(errno));
  ::setenv("SEASIM_CACHE_DIR", dir.c_str(), 1);
  ::setenv("POCL_CACHE_DIR", (dir + "/pocl").c_str(), 1);
  ::setenv("SEASIM_KERNEL_STORE", "", 1);
  return dir;
}

// The kernel store (device/kernel_store.h) from the private caches the warm-up filled: the programs'
// binaries, every PoCL entry (seasim's programs, which a load from their binaries finds under the same
// name, with their specialised work-group functions; VkFFT's programs) and the depth tables.
void writeKernelStore(Device& device, const std::string& store) {
  const int programs = device.writeCompiledKernels(store);
  int pocl_entries = 0;
  if (const std::string pocl = poclCacheDir(); device.info().is_pocl && !pocl.empty())
    pocl_entries = storePoclEntries(pocl, store, device.deviceId());
  const int tables = storeDepthTables(cacheDir("sea_depth_tables"), store);
  std::printf("kernel store %s: %d program(s), %d of PoCL's entries and %d depth table(s) for %s\n", store.c_str(),
              programs, pocl_entries, tables, device.info().label().c_str());
}

}  // namespace

int cmdCacheWarm(const CacheWarmCmd& cmd) {
  // Parse and validate everything first: a typo fails before any compile.
  struct Item {
    std::string label;
    Scene scene;
  };
  std::vector<Item> items;
  const std::vector<Override> extra = [&] {
    std::vector<Override> o;
    for (const auto& s : cmd.sets) o.push_back(parseSetOption(s));
    return o;
  }();
  for (const std::string& file : cmd.files) {
    if (isJobFile(file)) {
      const Job job = loadJob(file);
      for (const RenderItem& r : job.items) {
        std::vector<Override> o = r.overrides;
        o.insert(o.end(), extra.begin(), extra.end());
        items.push_back({job.name + "/" + r.name, loadScene(r.scene_file, o)});
      }
    } else {
      items.push_back({file, loadScene(file, extra)});
    }
  }

  if (!cmd.store.empty())  // before any compile
    if (const std::string problem = outputDirProblem(cmd.store); !problem.empty())
      throw RuntimeError("cache warm --store '" + cmd.store + "': " + problem);
  struct RemovedAtExit {
    std::string dir;
    ~RemovedAtExit() {
      std::error_code ec;
      if (!dir.empty()) std::filesystem::remove_all(dir, ec);
    }
  } const private_caches{cmd.store.empty() ? "" : usePrivateCaches()};  // before PoCL loads
  Device device(chooseDevice(cmd.device));
  std::printf("device: %s\n", device.info().label().c_str());
  std::set<std::string> done;
  int warmed = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (const Item& item : items) {
    // The plan a render will make: with quality.shafts_method = "auto" measured first (which also caches
    // the choice, so the node's renders search nothing).
    const Scene scene = sceneWithMeasuredShaftsMethod(device, item.scene).value_or(item.scene);
    const Plan plan = makePlan(scene);
    if (!done.insert(buildKey(scene, plan)).second) continue;  // same builds as one already warmed
    const double build_before = device.totalBuildMs();
    const FrameResult frame = renderFrame(device, scene, plan);
    ++warmed;
    std::printf("warm %-40s %4zu passes  frame %9.1f ms  (program builds/cache loads %8.1f ms)\n",
                item.label.c_str(), plan.passes.size(), frame.wall_ms, device.totalBuildMs() - build_before);
  }
  if (!cmd.store.empty()) writeKernelStore(device, cmd.store);
  const double total_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  std::printf("cache warm: %d distinct plan(s) of %zu render(s) in %.1f s\n", warmed, items.size(), total_ms * 1e-3);
  return 0;
}

}  // namespace seasim
