#include "scene/water_phase.h"

#include <cstdio>
#include <stdexcept>

#include "scene/toml_reader.h"
#include "util/error.h"
#include "util/paths.h"

namespace seasim {

void readWaterPhase(TableReader& r, const std::string& scene_file, WaterDesc& w) {
  const bool g_given = r.has("g");
  w.phase = r.choice("phase", "hg", {"hg", "petzold", "fournier_forand", "rayleigh_like", "table"});
  if (w.phase != "fournier_forand" && r.has("bb_ratio"))
    r.fail("bb_ratio", "is read only with phase = \"fournier_forand\"");
  if (w.phase != "table" && r.has("phase_file")) r.fail("phase_file", "is read only with phase = \"table\"");
  if (w.phase == "hg") return;
  if (g_given) r.fail("g", "g is the phase's own first moment with phase = \"" + w.phase + "\"; leave it out");
  if (w.phase == "fournier_forand") {
    w.bb_ratio = r.number("bb_ratio", w.bb_ratio);
    if (!(w.bb_ratio >= 0.001 && w.bb_ratio <= 0.5)) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "must be in [0.001, 0.5], got %g", w.bb_ratio);
      r.fail("bb_ratio", buf);
    }
  }
  if (w.phase == "table") {
    if (!r.has("phase_file")) r.fail("phase", "phase = \"table\" needs phase_file (a CSV of angle_deg, phase_per_sr)");
    const std::string p = r.string("phase_file", "");
    r.check(!p.empty(), "phase_file", "must not be empty");
    w.phase_file = resolveRelativeTo(scene_file, p);
    const std::string problem = inputFileProblem(w.phase_file);
    r.check(problem.empty(), "phase_file", problem);
  }
  try {
    w.g = waterPhase(w).asymmetry();
  } catch (const std::exception& e) {
    r.fail(w.phase == "table" ? "phase_file" : "phase", e.what());
  }
}

PhaseFunction waterPhase(const WaterDesc& w) {
  if (w.phase == "petzold") return PhaseFunction::petzold();
  if (w.phase == "fournier_forand") return PhaseFunction::fournierForand(w.bb_ratio);
  if (w.phase == "rayleigh_like") return PhaseFunction::rayleighLike();
  if (w.phase == "table") return PhaseFunction::loadTable(w.phase_file);
  return PhaseFunction::henyeyGreenstein(w.g);
}

}  // namespace seasim
