// render_item.h — one render from scene to files: plan, render, NaN check, outputs (atomic), report.json.
// Shared by `seasim render` and the job runner.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "device/device.h"
#include "plan/plan.h"
#include "render/renderer.h"
#include "scene/scene.h"

namespace seasim {

struct ItemOutputs {
  std::vector<std::string> formats = {"exr", "png"};  // "exr", "png", "spectral_exr", "npy"
  std::string reference;                              // optional EXR to report error against
};

// Renders `scene` into folder `dir` (created): image.exr / image.png / spectral.exr / image.npy as
// asked, and report.json last (its presence means the item is complete). Returns the report.
// Throws RuntimeError (NaN/Inf found, unimplemented pass, I/O) or DeviceError; files already
// written for this item stay complete (each is atomic) but report.json is not written.
nlohmann::json renderItem(Device& device, const Scene& scene, const ItemOutputs& outputs, const std::string& dir);
// Before any buffer exists: throws RuntimeError naming the settings when the plan's buffers would not
// fit the device (plan/memory_budget.h; SEASIM_DEVICE_MEMORY_MB caps the device's limits).
void checkRenderFitsDevice(Device& device, const Scene& scene, const Plan& plan);
// Throws RuntimeError, before anything renders or is written, when `formats` asks for an output the
// scene cannot give: spectral_exr without spectral.spectral_exr, or from a plan with no spectral pass.
void checkOutputsPossible(const Scene& scene, const Plan& plan, const std::vector<std::string>& formats);
// report.json's description of one frame (seasim version, scene, device, plan, per-pass ms, kernel
// build ms, wall ms, settings, NaN/Inf count) without the files: renderItem adds "outputs" and
// "error"; the Python package hands it back with the image.
nlohmann::json frameReport(const Device& device, const Scene& scene, const Plan& plan, const FrameResult& frame);
// The same with a renderer the caller keeps (a job's items on one scene file: only what changed
// since the previous item runs again); renders its current scene.
nlohmann::json renderItem(Device& device, Renderer& renderer, const ItemOutputs& outputs, const std::string& dir);

}  // namespace seasim
