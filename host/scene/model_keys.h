// model_keys.h — scene keys that a model declares in its own pass descriptor
// (PassDescriptor::scene_keys, host/plan/pass_descriptor.h) rather than in the parser: "surface.whitecaps"
// belongs to the model that reads it. The parser reads every declared key of a table it parses (with
// the key's type, range and default; errors name file:line:key like any other key), stores the value
// in Scene::model_keys, and reports a key nobody declared as unknown, as before. A model with keys of
// its own therefore adds no line to host/scene.
#pragma once
#include <string>
#include <string_view>
#include <vector>

#include "scene/scene.h"

namespace seasim {

struct ModelKey {
  enum class Type { Boolean, Number, Integer };
  std::string table;  // the top-level table it lives in ("surface")
  std::string name;   // the key inside it ("whitecaps")
  Type type = Type::Boolean;
  double default_value = 0.0;  // Boolean: 0 or 1
  double min = 0.0, max = 0.0;  // Number, Integer: the accepted range, closed unless min_open
  std::string unit;             // Number: printed after the range in messages ("m/s"); may be empty
  bool min_open = false;        // Number: min itself is refused, (min, max]

  std::string dotted() const { return table + "." + name; }
};

// A [quality] knob a pass reads (PassDescriptor::knobs): a count (a positive integer, or "auto" where
// the method picks its cheapest setting under its error budget), or a switch, which the parser reads
// itself as a boolean stored as 0 or 1.
struct KnobDefault {
  const char* name;  // without "quality."
  double value;
  bool is_switch = false;
  bool automatic = false;  // "auto" unless the scene gives a number: the pass sizes it from the scene
                           // (value is then only a placeholder)
};

// Every pass's count knobs, each once, in plan order: the descriptors' knobs that are not switches
// (defined beside passDescriptors(); two descriptors sharing a knob must agree on its default).
const std::vector<KnobDefault>& qualityCountKnobs();

// Every model's declared scene keys: the descriptors' scene_keys, in plan order (defined beside
// passDescriptors(), host/plan/pass_descriptor.cpp).
const std::vector<ModelKey>& modelSceneKeys();

// The declared key `dotted` ("surface.whitecaps") in `scene`: its parsed value, else its default (a scene
// built in code has no parsed values). Throws RuntimeError when no model declares the key.
double modelKey(const Scene& scene, std::string_view dotted);

}  // namespace seasim
