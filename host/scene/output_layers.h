// output_layers.h — the per-pixel ground-truth layers a render can write beside its image
// (outputs.layers in a scene file, `--output LAYER` on render and run): their names, their channels
// in image.exr, and which of them split the image physically. The passes that compute them are
// host/passes/nodes/layers_*_node.cpp; docs/layers.md states what each channel means.
//
// Channel names (the contract scripts rely on): an RGB layer is "<layer>.R/.G/.B", a scalar layer
// one channel named as the layer ("range", "depth", "object_id"), the normal "normal.X/.Y/.Z", a
// layer's mask of undefined pixels "<layer>_mask". In spectral.exr a per-band layer is
// "<layer>." + the band's channel name (io/spectral_layout.h): "direct.S0.550,000000nm".
#pragma once
#include <string>
#include <vector>

namespace seasim {

class TableReader;

struct OutputLayer {
  const char* name;
  const char* meaning;                // one line, for errors and docs
  std::vector<std::string> channels;  // image.exr channel names, in order
  bool per_band;                      // also one channel per band in spectral.exr
};

// Every layer seasim can write, in the order image.exr holds them.
const std::vector<OutputLayer>& outputLayers();
// The layer of that name, or null.
const OutputLayer* findOutputLayer(const std::string& name);

// outputs.layers as written (validated, duplicates removed, catalogue order).
struct OutputsDesc {
  std::vector<std::string> layers;
  bool wants(const std::string& layer) const;
  bool wantsAny(const std::vector<std::string>& layers) const;
};

// Reads [outputs] (the caller's TableReader of that table): `layers`, an array of layer names.
// An unknown name fails at its element's line with the valid names.
void parseOutputs(TableReader& r, OutputsDesc& out);

// Adds layers named outside the scene file (the CLI's --output) to `out`; RuntimeError naming
// `where` and the valid names for an unknown one.
void addOutputLayers(OutputsDesc& out, const std::vector<std::string>& names, const std::string& where);

}  // namespace seasim
