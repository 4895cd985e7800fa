#include "py_tools.h"

#include <nanobind/ndarray.h>
#include <nanobind/stl/function.h>
#include <nanobind/stl/string.h>

#include <CL/opencl.hpp>

#include "io/image_io.h"
#include "io/tonemap.h"
#include "jobs/runner.h"
#include "py_convert.h"
#include "py_scene.h"
#include "reference/compare.h"
#include "reference/reference_image.h"
#include "util/error.h"
#include "util/paths.h"
#include "util/version.h"

namespace nb = nanobind;

namespace seasim::py {

namespace {

using ImageArray = nb::ndarray<const float, nb::ndim<3>, nb::c_contig, nb::device::cpu>;

// An (H, W, C) float32 array as an Image (the Python side makes it contiguous float32 first).
Image toImage(const ImageArray& a) {
  Image img;
  img.width = static_cast<int>(a.shape(1));
  img.height = static_cast<int>(a.shape(0));
  img.channels = static_cast<int>(a.shape(2));
  img.pixels.assign(a.data(), a.data() + a.size());
  return img;
}

nb::ndarray<nb::numpy, float> toArray(Image&& img) {
  const size_t h = img.height, w = img.width, c = img.channels;
  return ownedArray(std::move(img.pixels), {h, w, c});
}

nb::dict compare(const ImageArray& test, const ImageArray& reference, double exposure_ev) {
  const CompareResult c = compareImages(toImage(test), toImage(reference), exposure_ev);
  nb::dict d;
  d["rmse_8bit"] = c.rmse_8bit;
  d["max_abs_8bit"] = c.max_abs_8bit;
  d["rel_l2"] = c.rel_l2;
  d["hue_sat_distance"] = c.hue_sat_distance;
  d["nonfinite"] = c.nonfinite;
  return d;
}

nb::dict reference(const PyScene& scene, int steps, long long seed, bool all_orders, int max_bounces,
                   const std::string& device, int sun_single_subpixels, nb::object progress) {
  ReferenceOptions options;
  options.device = device;
  options.steps = steps;
  options.seed = seed;
  options.all_orders = all_orders;
  options.max_bounces = max_bounces;
  options.sun_single_subpixels = sun_single_subpixels;
  if (!progress.is_none()) {
    options.progress = [progress](int done, int total) {
      nb::gil_scoped_acquire locked;
      progress(done, total);
    };
  }
  ReferenceImage r;
  {
    nb::gil_scoped_release unlocked;
    r = renderReference(scene.scene, options);
  }
  nb::dict d;
  d["method"] = r.method;
  d["steps"] = r.steps;
  d["ms"] = r.ms;
  if (r.method == "path tracer") {
    d["seed"] = r.seed;
    d["max_bounces"] = r.max_bounces;
    d["mean_std_error"] = r.mean_std_error;
    d["image_mean_std_error"] = r.image_mean_std_error;
    d["effective_samples"] = r.effective_samples;
    d["blocks"] = r.blocks;
    d["device"] = r.device_name;
    d["std_error"] = toArray(std::move(r.std_error));
    if (!r.direct.pixels.empty()) {
      d["direct"] = toArray(std::move(r.direct));
      d["direct_std_error"] = toArray(std::move(r.direct_std_error));
    }
  }
  d["rgb"] = toArray(std::move(r.rgb));
  return d;
}

nb::dict runJob(nb::handle job, int shard_index, int shard_count, bool resume, const std::string& device,
                const std::string& output_dir, nb::object on_item) {
  RunOptions options;
  options.device = device;
  options.shard_index = shard_index;
  options.shard_count = shard_count;
  options.resume = resume;
  options.output_dir = output_dir;
  if (!on_item.is_none()) {
    options.on_item = [on_item](int handled, int total, const std::string& item, const std::string& outcome) {
      nb::gil_scoped_acquire locked;
      on_item(handled, total, item, outcome);
    };
  }
  const std::string path = pathArg(job);
  RunSummary s;
  {
    nb::gil_scoped_release unlocked;
    s = seasim::runJob(path, options);
  }
  nb::list failed;
  for (const FailedItem& f : s.failed) {
    nb::dict item;
    item["name"] = f.name;
    item["error"] = f.error;
    failed.append(item);
  }
  nb::dict d;
  d["rendered"] = s.rendered;
  d["skipped"] = s.skipped;
  d["other_shards"] = s.other_shards;
  d["failed"] = failed;
  d["output_dir"] = s.output_dir;
  d["manifest"] = s.manifest;
  return d;
}

// Sets `name` from seasim.errors, with message and attributes, as the pending Python error (an
// exception translator sets it and returns).
void raise(const char* name, const std::string& message, nb::dict attrs = {}) {
  nb::object type = nb::module_::import_("seasim.errors").attr(name);
  nb::object error = type(message);
  for (auto [k, v] : attrs) nb::setattr(error, k, v);
  PyErr_SetObject(type.ptr(), error.ptr());
}

}  // namespace

void registerErrors() {
  nb::register_exception_translator([](const std::exception_ptr& p, void*) {
    try {
      std::rethrow_exception(p);
    } catch (const InputError& e) {
      // A dict or an override has no line to point at: its key (the dict path) says where.
      const bool no_line = e.file() == kDictFile || e.line() <= 0;
      std::string message = e.what();
      const std::string prefix = e.file() + ":" + std::to_string(e.line()) + ": ";
      if (no_line && message.rfind(prefix, 0) == 0) message = e.file() + ": " + message.substr(prefix.size());
      nb::dict attrs;
      attrs["file"] = no_line ? nb::none() : nb::object(nb::str(e.file().c_str()));
      attrs["line"] = no_line ? nb::none() : nb::object(nb::int_(e.line()));
      attrs["key"] = e.key().empty() ? nb::none() : nb::object(nb::str(e.key().c_str()));
      raise("SceneError", message, attrs);
    } catch (const DeviceError& e) {
      raise("DeviceError", e.what());
    } catch (const RuntimeError& e) {
      raise("RenderError", e.what());
    } catch (const cl::Error& e) {
      raise("DeviceError", std::string(e.what()) + " (OpenCL error " + std::to_string(e.err()) + ")");
    }
  });
}

void bindTools(nb::module_& m) {
  m.def("_compare", &compare, nb::arg("test"), nb::arg("reference"), nb::arg("exposure_ev") = 0.0);
  m.def("_read_image", [](nb::handle path) {
    const std::string p = pathArg(path);
    Image img;
    {
      nb::gil_scoped_release unlocked;
      img = readImage(p);
    }
    return toArray(std::move(img));
  }, nb::arg("path"));
  m.def("_reference", &reference, nb::arg("scene"), nb::arg("steps"), nb::arg("seed"), nb::arg("all_orders"),
        nb::arg("max_bounces"), nb::arg("device"), nb::arg("sun_single_subpixels"), nb::arg("progress").none());
  m.def("_run_job", &runJob, nb::arg("job"), nb::arg("shard_index"), nb::arg("shard_count"), nb::arg("resume"),
        nb::arg("device"), nb::arg("output_dir"), nb::arg("on_item").none());
  m.def("_display", [](const ImageArray& linear, double exposure_ev) {
    Image display;
    const long long nonfinite = toneMapImage(toImage(linear), exposure_ev, display);
    if (nonfinite) throw RuntimeError(std::to_string(nonfinite) + " NaN/Inf values in the image to display");
    return toArray(std::move(display));
  }, nb::arg("linear"), nb::arg("exposure_ev"));
  m.def("data_dir", &dataDir, "The data folder seasim reads spectra and cameras from.");
  m.def("version", [] { return std::string(version()) + " (" + gitCommit() + ")"; },
        "seasim's version and git commit, as `seasim --version` prints them.");
}

}  // namespace seasim::py
