// plan.h — the planner: scene -> ordered passes with their kernel file and typed features
// (DESIGN.md "Leave out what a scene does not need"). Each model's rule lives in its descriptor
// (plan/pass_descriptor.h); makePlan asks them in order. `seasim plan SCENE` prints toText().
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "plan/features.h"
#include "scene/scene.h"

namespace seasim {

struct PassPlan {
  std::string name;                  // its descriptor's name (plan/pass_descriptor.h)
  std::string kernel_file;           // relative to kernels/, e.g. "sea_single.cl"
  std::vector<std::string> defines;  // "SEASIM_HAS_BOTTOM=1"
  std::vector<std::string> reads;    // resources the pass reads ("scene", "gbuffer", ...)
  std::vector<std::string> writes;   // resources it writes ("rgb", ...)
  std::string why;                   // the scene content that made the planner add it
  bool implemented = true;           // false: planned but the model is not built yet
  std::string missing;               // for !implemented: what is missing and what to do instead
  // The pass's optional kernel features (null: it has none); `defines` is generated from them.
  std::shared_ptr<const PassFeatures> features;

  // The features as the pass's own struct; RuntimeError naming the entry when it carries another.
  template <class T>
  const T& featuresAs() const {
    if (const T* f = dynamic_cast<const T*>(features.get())) return *f;
    missingFeatures();
  }
  [[noreturn]] void missingFeatures() const;
};

struct Plan {
  std::vector<PassPlan> passes;
  bool hasPass(const std::string& name) const;
  const PassPlan* find(const std::string& name) const;
  bool produces(const std::string& resource) const;          // some pass writes it ("caustic_map")
  const PassPlan* writerOf(const std::string& resource) const;  // the first pass that writes it, or null
  std::vector<std::string> kernelFiles() const;  // distinct, in pass order
  std::string toText() const;                    // one pass per line
};

Plan makePlan(const Scene& scene);

// Whether the scene's kernels are built with -cl-fast-relaxed-math: quality.fast_math when it is
// true or false; with "auto" (the default), on unless the sea is seen from above with FFT waves, the
// one kind of shipped scene whose fast-maths image moved by more than 0.05 of an 8-bit level (max
// |Δ| 0.13 and 0.28 levels on wavy_sea and wavy_sea_image_sky; every other shipped scene <= 0.0002;
// results/BENCHMARKS.md).
bool fastMathFor(const Scene& scene);

}  // namespace seasim
