// pass.h — the one interface through which the renderer runs every model (DESIGN.md "The renderer's
// shape", after Filament's frame graph: set-up split from execution). A Pass wraps one plan entry:
// its name, reads and writes come from the plan; its keys say which scene settings it depends on.
//
//   prepare  — tables, kernels, buffers; called on the first frame, when a key in `rebuild_on`
//              changed, or when a resource it reads was replaced by a new object.
//   execute  — enqueue the kernels and append their times to ctx.timings; called when the pass was
//              prepared, when a key in `rerun_on` changed, or when a resource it reads was written.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "plan/pass_descriptor.h"  // PassKeys
#include "plan/plan.h"
#include "render/frame_context.h"
#include "render/resources.h"

namespace seasim {

// Scene keys as written in files and --set: "sun.zenith_deg", "objects[1].center". A pattern is a
// key ("surface.time") or a section with ".*" ("sun.*"; "objects.*" covers every objects[i] key).
bool keyMatches(const std::string& pattern, const std::string& key);
// Whether any of `keys` (FrameContext::changedKeys) matches `pattern`.
bool anyKeyMatches(const std::string& pattern, const std::vector<std::string>& keys);

class Pass {
 public:
  virtual ~Pass() = default;
  virtual PassKeys keys() const = 0;
  virtual void prepare(FrameContext& ctx, PassResources& res) = 0;
  virtual void execute(FrameContext& ctx, PassResources& res) = 0;
};

}  // namespace seasim
