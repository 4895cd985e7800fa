// py_renderer.cpp — seasim.Renderer and its Frame: the persistent Renderer of host/render (the one
// the CLI, the job runner and the preview use), its device, and each frame's image, per-band values,
// per-pass times and report as NumPy arrays and dicts. Kernels run with the GIL released.
#include "py_renderer.h"

#include <nanobind/ndarray.h>
#include <nanobind/stl/string.h>
#include <nanobind/stl/vector.h>

#include <memory>

#include "jobs/layer_image.h"
#include "jobs/render_item.h"
#include "plan/plan.h"
#include "py_convert.h"
#include "py_device.h"
#include "py_scene.h"
#include "quality/auto_quality.h"
#include "render/renderer.h"
#include "util/error.h"

namespace nb = nanobind;

namespace seasim::py {

namespace {

struct PyFrame {
  FrameResult frame;
  nlohmann::json report;
  // R, G, B and the asked layers' channels, as image.exr holds them (jobs/layer_image.h); the image
  // alone when the scene asks for no layers.
  Image with_layers;
  // The asked layers per band for spectral.exr (bandLayersImage); no channels without them.
  Image band_layers;
};

// Per-band layers by name: (H, W, bands) for each, from "<layer>.S0.<nm>" channels in band order.
nb::dict bandLayerArrays(const Image& image, size_t bands) {
  nb::dict out;
  const size_t h = image.height, w = image.width, pixels = h * w;
  for (size_t first = 0; bands > 0 && first + bands <= static_cast<size_t>(image.channels); first += bands) {
    const std::string& channel = image.channel_names[first];
    std::vector<float> values(pixels * bands);
    for (size_t i = 0; i < pixels; ++i)
      for (size_t b = 0; b < bands; ++b) values[i * bands + b] = image.pixels[i * image.channels + first + b];
    out[channel.substr(0, channel.find('.')).c_str()] =
        nb::cast(ownedArray(std::move(values), {h, w, bands}), nb::rv_policy::automatic);
  }
  return out;
}

// The asked layers by name: one (H, W) array for a one-channel layer ("range", "object_id"), an
// (H, W, k) array for "<layer>.R/.G/.B" or "normal.X/.Y/.Z", and a mask channel ("beta_d_mask") under
// its own name. Copies: the arrays outlive the frame.
nb::dict layerArrays(const Image& image) {
  std::vector<std::pair<std::string, std::vector<int>>> groups;  // name -> channel indices, in file order
  for (int c = 3; c < image.channels; ++c) {
    const std::string& channel = image.channel_names[c];
    const size_t dot = channel.find('.');
    const std::string name = channel.substr(0, dot);
    if (groups.empty() || groups.back().first != name) groups.push_back({name, {}});
    groups.back().second.push_back(c);
  }
  const size_t h = image.height, w = image.width, pixels = h * w;
  nb::dict out;
  for (const auto& [name, channels] : groups) {
    const size_t k = channels.size();
    std::vector<float> values(pixels * k);
    for (size_t i = 0; i < pixels; ++i)
      for (size_t j = 0; j < k; ++j) values[i * k + j] = image.pixels[i * image.channels + channels[j]];
    const bool scalar = k == 1 && image.channel_names[channels[0]].find('.') == std::string::npos;
    out[name.c_str()] = scalar ? nb::cast(ownedArray(std::move(values), {h, w}), nb::rv_policy::automatic)
                               : nb::cast(ownedArray(std::move(values), {h, w, k}), nb::rv_policy::automatic);
  }
  return out;
}

struct PyRenderer {
  std::unique_ptr<Device> device;
  std::unique_ptr<Renderer> renderer;

  PyRenderer(const PyScene& scene, const std::string& selector) {
    nb::gil_scoped_release unlocked;  // device start-up and kernel builds
    device = std::make_unique<Device>(pickDevice(selector));
    // Before any buffer exists, as `seasim render` does: a render too big for the device fails here.
    checkRenderFitsDevice(*device, scene.scene, makePlan(scene.scene));
    renderer = std::make_unique<Renderer>(*device, scene.path, scene.text, scene.overrides, shippedPasses());
  }

  PyFrame render() {
    PyFrame out;
    {
      nb::gil_scoped_release unlocked;
      out.frame = renderer->render();
    }
    // As renderItem: an image with NaN/Inf is never handed back.
    if (out.frame.nonfinite != 0) {
      throw RuntimeError("scene '" + renderer->scene().name + "': the kernels produced " +
                         std::to_string(out.frame.nonfinite) + " NaN/Inf values. Check the scene for extreme values "
                         "(huge irradiance, scattering or intensity); if they are physical, please report it with the scene");
    }
    // As the job runner: a layer with NaN/Inf (but open water's +inf range) is never handed back.
    out.with_layers = imageWithLayers(out.frame, renderer->scene().outputs);
    out.band_layers = bandLayersImage(out.frame, renderer->scene().outputs);
    out.report = frameReport(*device, renderer->scene(), renderer->plan(), out.frame);
    return out;
  }

  // Python keyword names cannot hold dots: sun__zenith_deg stands for sun.zenith_deg.
  void update(nb::handle overrides, nb::kwargs kwargs) {
    std::vector<Override> all = overridesFrom(overrides);
    nb::dict renamed;
    for (auto [k, v] : kwargs) {
      std::string key = nb::cast<std::string>(k);
      for (size_t at; (at = key.find("__")) != std::string::npos;) key.replace(at, 2, ".");
      renamed[key.c_str()] = v;
    }
    for (Override& o : overridesFrom(renamed)) all.push_back(std::move(o));
    renderer->update(all);
  }
};

// The frame's image as an (H, W, C) view into the frame's memory, kept alive by the Python frame.
template <class T>
nb::ndarray<nb::numpy, T> view(const PyFrame& owner, T* data, size_t h, size_t w, size_t c) {
  return nb::ndarray<nb::numpy, T>(data, {h, w, c}, nb::find(&owner));
}

}  // namespace

void bindRenderer(nb::module_& m) {
  nb::class_<PyFrame>(m, "Frame", "One rendered frame (Renderer.render()).")
      .def_prop_ro(
          "rgb",
          [](PyFrame& f) {
            Image& rgb = f.frame.rgb;
            return view(f, rgb.pixels.data(), rgb.height, rgb.width, rgb.channels);
          },
          "Linear sensor RGB, float32 (height, width, 3): the values `seasim render` writes to image.exr. "
          "A view of the frame's memory, no copy.")
      .def_prop_ro(
          "spectral",
          [](PyFrame& f) -> nb::object {
            if (f.frame.spectral.empty()) return nb::none();
            const Image& rgb = f.frame.rgb;
            const size_t bands = f.frame.wavelengths_nm.size();
            return nb::cast(view(f, f.frame.spectral.data(), rgb.height, rgb.width, bands), nb::rv_policy::reference);
          },
          nb::for_getter(nb::sig("def spectral(self, /) -> NDArray[numpy.float32] | None")),
          "Per-band radiance, float32 (height, width, bands), when the scene sets spectral.spectral_exr = true; "
          "else None.")
      .def_prop_ro("layers", [](const PyFrame& f) { return layerArrays(f.with_layers); },
                   nb::for_getter(nb::sig("def layers(self, /) -> dict[str, NDArray[numpy.float32]]")),
                   "The ground-truth layers the scene asks for (outputs.layers; docs/layers.md), by name, float32: "
                   "(height, width) for range, depth and object_id and for each mask ('beta_d_mask'), "
                   "(height, width, 3) for the RGB layers and the normal; the same values as the channels of "
                   "image.exr. Empty when the scene asks for none. Copies, made on each read.")
      .def_prop_ro("band_layers",
                   [](const PyFrame& f) { return bandLayerArrays(f.band_layers, f.frame.wavelengths_nm.size()); },
                   nb::for_getter(nb::sig("def band_layers(self, /) -> dict[str, NDArray[numpy.float32]]")),
                   "The asked layers that have bands (albedo, clear, direct, backscatter, forward, lamps, transmission, veiling), "
                   "per band: (height, width, bands) float32 by name, as spectral.exr's '<layer>.S0.<nm>' channels. "
                   "Empty without spectral.spectral_exr or such layers. Copies, made on each read.")
      .def_prop_ro("wavelengths_nm", [](const PyFrame& f) {
        std::vector<double> nm = f.frame.wavelengths_nm;
        const size_t n = nm.size();
        return nb::cast(ownedArray(std::move(nm), {n}), nb::rv_policy::automatic);
      }, nb::for_getter(nb::sig("def wavelengths_nm(self, /) -> NDArray[numpy.float64]")), "The bands' centres in nm.")
      .def_prop_ro("timings", [](const PyFrame& f) {
        nb::dict d;  // a pass that ran twice adds up
        for (const PassTiming& t : f.frame.timings) {
          const double before = d.contains(t.name.c_str()) ? nb::cast<double>(d[t.name.c_str()]) : 0.0;
          d[t.name.c_str()] = before + t.ms;
        }
        return d;
      }, "Milliseconds of each pass that ran for this frame (OpenCL profiling), in plan order.")
      .def_prop_ro("report", [](const PyFrame& f) { return jsonToPython(f.report); },
                   nb::for_getter(nb::sig("def report(self, /) -> dict")),
                   "report.json's content for this frame (device, plan, pass_ms, settings, ...), without outputs.")
      .def_prop_ro("build_ms", [](const PyFrame& f) { return f.frame.build_ms; })
      .def_prop_ro("wall_ms", [](const PyFrame& f) { return f.frame.wall_ms; })
      .def("__repr__", [](const PyFrame& f) {
        return "<seasim.Frame " + std::to_string(f.frame.rgb.width) + "x" + std::to_string(f.frame.rgb.height) + ">";
      });

  nb::class_<PyRenderer>(m, "Renderer",
                         "The frame graph of one scene on one device, kept between frames: after update() only "
                         "the passes that read a changed key run again (as in `seasim preview`).")
      .def(nb::init<const PyScene&, const std::string&>(), nb::arg("scene"), nb::arg("device") = "",
           "Opens the device (a selector as --device takes; '' = first GPU, else PoCL) and plans the scene. "
           "Raises seasim.DeviceError when no device opens or the render does not fit it.")
      .def("render", &PyRenderer::render,
           "Renders a frame (the GIL is released while the kernels run). Raises seasim.RenderError when the "
           "kernels produce NaN/Inf.")
      .def("update", &PyRenderer::update, nb::arg("overrides") = nb::none(), nb::arg("kwargs"),
           "Applies overrides on top of those so far: update({'sun.zenith_deg': 30}) or update(sun__zenith_deg=30). "
           "The next render() reruns only the passes whose keys changed. A bad value raises seasim.SceneError "
           "and changes nothing.")
      .def("rerun_all", [](PyRenderer& r) { r.renderer->rerunAll(); },
           "Makes the next render() run every pass again (to time a whole frame).")
      .def_prop_ro("last_prepared", [](const PyRenderer& r) { return r.renderer->lastPrepared(); },
                   "Passes set up by the last render(), in plan order.")
      .def_prop_ro("last_executed", [](const PyRenderer& r) { return r.renderer->lastExecuted(); },
                   "Passes run by the last render(), in plan order.")
      .def_prop_ro("plan", [](const PyRenderer& r) { return r.renderer->plan().toText(); })
      .def_prop_ro("device", [](const PyRenderer& r) { return r.device->info(); })
      .def("__repr__", [](const PyRenderer& r) {
        return "<seasim.Renderer '" + r.renderer->scene().name + "' on " + r.device->info().label() + ">";
      });
}

}  // namespace seasim::py
