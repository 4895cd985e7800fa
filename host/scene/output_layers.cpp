#include "scene/output_layers.h"

#include <toml++/toml.h>

#include <algorithm>

#include "scene/toml_reader.h"
#include "util/error.h"

namespace seasim {

namespace {

std::vector<std::string> rgb(const std::string& layer) { return {layer + ".R", layer + ".G", layer + ".B"}; }
std::vector<std::string> masked(const std::string& layer) {
  std::vector<std::string> c = rgb(layer);
  c.push_back(layer + "_mask");
  return c;
}

std::vector<std::string> layerNames() {
  std::vector<std::string> names;
  for (const OutputLayer& l : outputLayers()) names.push_back(l.name);
  return names;
}

std::string validText() {
  std::string text;
  for (const auto& n : layerNames()) text += (text.empty() ? "" : ", ") + n;
  return text;
}

void add(OutputsDesc& out, const std::string& name) {
  if (!out.wants(name)) out.layers.push_back(name);
  // Catalogue order: image.exr's channels do not depend on the order the layers were asked in.
  const std::vector<std::string> order = layerNames();
  std::sort(out.layers.begin(), out.layers.end(), [&](const std::string& a, const std::string& b) {
    return std::find(order.begin(), order.end(), a) < std::find(order.begin(), order.end(), b);
  });
}

}  // namespace

const std::vector<OutputLayer>& outputLayers() {
  static const std::vector<OutputLayer> layers = {
      {"range", "metres along the camera ray to the first surface (+inf: open water)", {"range"}, false},
      {"depth", "camera z of the first surface, metres along the optical axis (+inf: open water)", {"depth"}, false},
      {"normal", "world-space unit normal of the first surface (0 for open water)",
       {"normal.X", "normal.Y", "normal.Z"}, false},
      {"object_id", "0 water (and the surface), 1 bottom, 2... objects in file order", {"object_id"}, false},
      {"albedo", "the first surface's albedo, the sensor's weighted mean over its bands", rgb("albedo"), true},
      {"clear", "radiance leaving the first surface toward the camera, no water between (J)", rgb("clear"), true},
      {"direct", "clear attenuated along the ray: J T", rgb("direct"), true},
      {"backscatter", "light the water scatters into the ray between camera and surface", rgb("backscatter"), true},
      {"forward", "what forward scattering (the point spread) adds to the signal", rgb("forward"), true},
      {"lamps", "the underwater lamps' light in the image", rgb("lamps"), true},
      {"lamps_single", "the lamps' light scattered at most once in the water: lit surfaces seen unscattered, the beam's single scattering (001)",
       rgb("lamps_single"), true},
      {"lamps_multiple", "the lamps' light scattered more than once, as the lamps model has it: lamps - lamps_single",
       rgb("lamps_multiple"), true},
      {"transmission", "T = exp(-c range) along the ray", rgb("transmission"), true},
      {"veiling", "B_inf: the radiance of an infinitely long water path in the pixel's direction", rgb("veiling"),
       true},
      {"beta_d", "-ln(direct/clear)/range where defined (else 0, mask 0)", masked("beta_d"), false},
      {"beta_b", "-ln(1 - backscatter/veiling)/range where defined (else 0, mask 0)", masked("beta_b"), false},
  };
  return layers;
}

const OutputLayer* findOutputLayer(const std::string& name) {
  for (const OutputLayer& l : outputLayers())
    if (name == l.name) return &l;
  return nullptr;
}

bool OutputsDesc::wants(const std::string& layer) const {
  return std::find(layers.begin(), layers.end(), layer) != layers.end();
}

bool OutputsDesc::wantsAny(const std::vector<std::string>& names) const {
  for (const auto& n : names)
    if (wants(n)) return true;
  return false;
}

void parseOutputs(TableReader& r, OutputsDesc& out) {
  if (const toml::node* n = r.get("layers")) {
    const toml::array* a = n->as_array();
    if (!a) r.fail("layers", "must be an array of layer names, got " + typeName(*n) + "; valid: " + validText());
    for (size_t i = 0; i < a->size(); ++i) {
      const toml::node& e = *a->get(i);
      const std::string key = r.path("layers") + "[" + std::to_string(i) + "]";
      const auto* s = e.as_string();
      if (!s) r.source().fail(&e, key, "must be a layer name (a string), got " + typeName(e));
      const std::string name = s->get();
      if (!findOutputLayer(name))
        r.source().fail(&e, key, "unknown layer '" + name + "'" + suggestion(name, layerNames(), 20));
      add(out, name);
    }
  }
  out.profile_depths = r.numbers("profile_depths");
  for (size_t i = 0; i < out.profile_depths.size(); ++i) {
    const double z = out.profile_depths[i];
    r.check(z >= 0, "profile_depths", "depths must be >= 0 m (0: just below the surface), got " + std::to_string(z));
    r.check(i == 0 || z > out.profile_depths[i - 1], "profile_depths", "depths must be ascending and distinct");
  }
  r.finish();
}

void addOutputLayers(OutputsDesc& out, const std::vector<std::string>& names, const std::string& where) {
  for (const auto& name : names) {
    if (!findOutputLayer(name))
      throw RuntimeError(where + ": unknown layer '" + name + "'; valid: " + validText());
    add(out, name);
  }
}

}  // namespace seasim
