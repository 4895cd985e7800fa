#include "jobs/render_item.h"

#include <algorithm>
#include <filesystem>

#include "io/atomic_file.h"
#include "io/image_io.h"
#include "io/tonemap_eq18.h"
#include "jobs/layer_image.h"
#include "jobs/recorded_settings.h"
#include "jobs/test_hooks.h"
#include "plan/memory_budget.h"
#include "plan/plan.h"
#include "quality/auto_quality.h"
#include "quality/expected_error.h"
#include "reference/compare.h"
#include "util/error.h"
#include "util/paths.h"
#include "util/version.h"

namespace fs = std::filesystem;

namespace seasim {

namespace {

nlohmann::json planJson(const Plan& plan) {
  nlohmann::json passes = nlohmann::json::array();
  for (const auto& p : plan.passes) {
    passes.push_back({{"name", p.name}, {"kernel", p.kernel_file.empty() ? "" : "kernels/" + p.kernel_file}, {"defines", p.defines},
                      {"reads", p.reads}, {"writes", p.writes}});
  }
  return passes;
}

}  // namespace

nlohmann::json renderItem(Device& device, const Scene& scene, const ItemOutputs& outputs, const std::string& dir) {
  Renderer renderer(device, scene, shippedPasses());  // plans (and makes its measured choices); allocates nothing
  checkRenderFitsDevice(device, renderer.scene(), renderer.plan());
  return renderItem(device, renderer, outputs, dir);
}

void checkRenderFitsDevice(Device& device, const Scene& scene, const Plan& plan) {
  checkRenderMemory(estimateBuffers(scene, plan), device.info().global_mem_bytes, device.info().max_alloc_bytes,
                    device.info().label(), !device.info().is_gpu);
}

void checkOutputsPossible(const Scene& scene, const Plan& plan, const std::vector<std::string>& formats) {
  checkLayerOutputs(scene, formats);
  if (std::find(formats.begin(), formats.end(), "spectral_exr") == formats.end()) return;
  if (!scene.spectral.spectral_exr)
    throw RuntimeError("output 'spectral_exr' needs spectral.spectral_exr = true in the scene '" + scene.file +
                       "' (or --set spectral.spectral_exr=true); nothing written");
  // Only the passes built with SEASIM_SPECTRAL_OUTPUT keep per-band radiance; the air-only
  // models (shafts, raycast) render sensor RGB directly.
  std::string names;
  for (const PassPlan& p : plan.passes) {
    if (std::find(p.defines.begin(), p.defines.end(), "SEASIM_SPECTRAL_OUTPUT=1") != p.defines.end()) return;
    names += (names.empty() ? "" : ", ") + p.name;
  }
  throw RuntimeError("output 'spectral_exr': scene '" + scene.name + "' has no spectral image: its passes (" + names +
                     ") render RGB only, spectral output comes from the sea and underwater models; drop "
                     "spectral_exr from the outputs; nothing written");
}

nlohmann::json renderItem(Device& device, Renderer& renderer, const ItemOutputs& outputs, const std::string& dir) {
  const Scene& scene = renderer.scene();
  const Plan& plan = renderer.plan();
  checkOutputsPossible(scene, plan, outputs.formats);  // before the render and before any file
  FrameResult frame = renderer.render();
  if (frame.nonfinite != 0) {
    // Input images are checked for NaN/Inf before the render (scene/scene_inputs.h); still name them.
    std::string images;
    for (const ImageInputRef& image : scene.images) images += "\n  " + image.key + " = '" + image.path + "'";
    throw RuntimeError("scene '" + scene.name + "' (" + scene.file + "): the kernels produced " +
                       std::to_string(frame.nonfinite) +
                       " NaN/Inf values; nothing written for this render. Check the scene for extreme values "
                       "(huge irradiance, scattering or intensity)" +
                       (images.empty() ? "" : " and the images it reads:" + images + "\n") +
                       "; if they are physical, please report it with the scene");
  }
  // The reference is read and compared before any image is written, so a bad reference leaves
  // no images behind that look like a finished render.
  nlohmann::json error;
  if (!outputs.reference.empty()) {
    const Image reference = readImage(outputs.reference);
    if (reference.width != frame.rgb.width || reference.height != frame.rgb.height)
      throw RuntimeError("the reference '" + outputs.reference + "' is " + std::to_string(reference.width) + "x" +
                         std::to_string(reference.height) + " but the render is " + std::to_string(frame.rgb.width) +
                         "x" + std::to_string(frame.rgb.height) + "; nothing written");
    const CompareResult c = compareImages(frame.rgb, reference, scene.camera.exposure_ev);
    error = {{"reference", outputs.reference},
             {"rmse_8bit", c.rmse_8bit},
             {"max_abs_8bit", c.max_abs_8bit},
             {"rel_l2", c.rel_l2},
             {"hue_sat_distance", c.hue_sat_distance}};
  }
  const bool wants_spectral =
      std::find(outputs.formats.begin(), outputs.formats.end(), "spectral_exr") != outputs.formats.end();
  if (wants_spectral && frame.spectral.empty())  // the plan promised it (checkOutputsPossible): a bug
    throw RuntimeError("output 'spectral_exr': the render produced no spectral image; nothing written");
  const Image exr_image = imageWithLayers(frame, scene.outputs);  // R, G, B and the layers; before any file
  const Image band_layers = bandLayersImage(frame, scene.outputs);  // spectral.exr's layers per band
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw RuntimeError("cannot create the output folder '" + dir + "': " + ec.message());
  nlohmann::json files = nlohmann::json::array();
  holdItemIfAsked(fs::path(dir).filename().string());  // tests only (jobs/test_hooks.h)
  for (const auto& format : outputs.formats) {
    std::string path;  // what the writer really wrote (a .npy beside it in builds without OpenImageIO)
    if (format == "exr") {
      // sensor = "identity": the raw bands are the image (the spectral.exr layout).
      path = scene.spectral.sensor == "identity" && !frame.spectral.empty()
                 ? writeSpectralExr(dir + "/image.exr", frame.rgb.width, frame.rgb.height, frame.wavelengths_nm,
                                    frame.spectral)
                 : writeExr(dir + "/image.exr", exr_image);
    } else if (format == "png") {
      if (scene.display.tone_map == DisplayDesc::ToneMap::Eq18) {  // 003 eq. 18 (io/tonemap_eq18.h)
        std::vector<std::uint8_t> bytes;
        toneMapImage8Eq18(frame.rgb, scene.camera.exposure_ev, scene.display.eq18, bytes);
        path = writePngBytes(dir + "/image.png", frame.rgb.width, frame.rgb.height, frame.rgb.channels, bytes);
      } else {
        path = writePng(dir + "/image.png", frame.rgb, scene.camera.exposure_ev);
      }
    } else if (format == "npy") {
      path = dir + "/image.npy";
      writeNpy(path, frame.rgb);
    } else if (format == "spectral_exr") {
      path = writeSpectralExr(dir + "/spectral.exr", frame.rgb.width, frame.rgb.height, frame.wavelengths_nm,
                              frame.spectral, band_layers.channels > 0 ? &band_layers : nullptr);
    } else {
      throw RuntimeError("unknown output format '" + format + "'");
    }
    files.push_back(fs::path(path).filename().string());
    killMidItemIfAsked(fs::path(dir).filename().string());  // tests only (jobs/test_hooks.h)
  }
  for (const TextOutput& t : frame.texts) {  // the passes' text files (render/text_output.h)
    writeTextAtomic(dir + "/" + t.file_name, t.text);
    files.push_back(t.file_name);
  }

  nlohmann::json report = frameReport(device, scene, plan, frame);
  report["outputs"] = files;
  if (!error.is_null()) report["error"] = error;
  writeTextAtomic(dir + "/report.json", report.dump(2) + "\n");
  return report;
}

nlohmann::json frameReport(const Device& device, const Scene& scene, const Plan& plan, const FrameResult& frame) {
  nlohmann::json timings = nlohmann::json::object();
  double total = 0;
  for (const auto& t : frame.timings) {
    timings[t.name] = t.ms;
    total += t.ms;
  }
  return {{"seasim", {{"version", version()}, {"git_commit", gitCommit()}, {"data_dir", dataDir()}}},
          {"scene", scene.file},
          {"name", scene.name},
          {"device",
           {{"label", device.info().label()},
            {"platform", device.info().platform_name},
            {"name", device.info().name},
            {"driver", device.info().driver}}},
          {"plan", planJson(plan)},
          {"expected_error", expectedErrorJson(expectedErrors(scene))},
          {"pass_ms", timings},
          {"kernel_ms_total", total},
          {"kernel_build_ms", frame.build_ms},
          {"wall_ms", frame.wall_ms},
          {"settings", settingsJson(scene)},
          {"nonfinite", frame.nonfinite}};
}

}  // namespace seasim
