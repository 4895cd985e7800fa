// water_phase.h — the [water] table's phase keys (phase, phase_file, bb_ratio; scenes/README.md), and the
// phase function a scene's water describes.
#pragma once
#include <string>

#include "radiometry/phase_function.h"
#include "scene/scene.h"

namespace seasim {

class TableReader;

// Reads phase, phase_file and bb_ratio into w (a file resolved against scene_file and loaded once to check
// it), and with a phase other than "hg" sets w.g to the phase's own asymmetry (what the closed-form models
// take); g given beside such a phase is an error at its key. InputError naming file, line and key.
void readWaterPhase(TableReader& r, const std::string& scene_file, WaterDesc& w);

// The phase function of a parsed scene's water (RuntimeError if its table has become unreadable).
PhaseFunction waterPhase(const WaterDesc& w);

}  // namespace seasim
