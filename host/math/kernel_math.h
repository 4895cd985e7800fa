// kernel_math.h — the kernels' shared math (kernels/common/*.h) compiled for the host twice:
// seasim::kmath_f with real = float and seasim::kmath_d with real = double (compat.h explains why).
// Add a new common header here, in dependency order, when you add it to kernels/common/.
#pragma once
#include "common/compat.h"
#include "common/underwater_params.h"  // plain C structs, used by underwater.h
#include "common/underwater_ordinates_params.h"  // plain C struct, used by underwater_ordinates.h
#include "common/froxel_params.h"      // plain C struct, used by froxel.h
#include "common/sea_bottom_params.h"  // plain C struct, used by sea_bottom.h
#include "common/fourflow_params.h"    // plain C structs, used by fourflow.h
#include "common/underwater_lamps_params.h"  // plain C structs of underwater_lamps.cl
#include "common/sky_params.h"             // plain C struct, used by sky_view.h
#include "common/underwater_band_table.h"  // plain C layout, used by underwater_bands.h
#include "common/sea_band_table.h"         // plain C layout, used by sea_bands.h
#include "common/sea_params.h"             // plain C structs, used by sea_view.h
#include "common/shafts_params.h"          // plain C structs, used by shafts_render.h
#include "common/water_spread_params.h"    // UWS_LAYERS, used by water_spread.h


namespace seasim::kmath_f {
typedef float real;
#include "common/real3_host.h"
#include "common/optics.h"
#include "common/phase.h"
#include "common/shafts.h"
#include "common/shafts_intervals.h"
#include "common/shafts_render.h"
#include "common/sea_surface.h"
#include "common/sea_waves.h"
#include "common/gauss_legendre.h"
#include "common/sea_lean.h"
#include "common/polynomial_trig.h"
#include "common/sky.h"
#include "common/sky_view.h"
#include "common/sky_table.h"
#include "common/sea_second.h"
#include "common/sea_bottom.h"
#include "common/sea_multiple.h"
#include "common/ocean_spectrum.h"
#include "common/underwater.h"
#include "common/output_layers.h"
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/sky_view_lanes.h"
#include "common/sea_bottom_lanes.h"
#include "common/underwater_bands.h"
#include "common/underwater_hit_lanes.h"
#include "common/sea_bands.h"
#include "common/sea_multiple_bands.h"
#include "common/underwater_ordinates.h"
#include "common/underwater_ordinates_lanes.h"
#include "common/underwater_ordinates_bands.h"
#include "common/water_spread.h"
#include "common/underwater_lamps.h"
#include "common/path_tracer.h"
#include "common/underwater_lamps_ms.h"
#include "common/caustic_texture.h"
#include "common/caustic_texture_lanes.h"
#include "common/caustic_map.h"
#include "common/sea_ordinates.h"
#include "common/sea_view.h"
#include "common/sea_band_terms.h"
#include "common/froxel.h"
#include "common/path_tracer_lamps.h"
#include "common/fourflow.h"
#include "common/fourflow_waves.h"
}  // namespace seasim::kmath_f

namespace seasim::kmath_d {
typedef double real;
#include "common/real3_host.h"
#include "common/optics.h"
#include "common/phase.h"
#include "common/shafts.h"
#include "common/shafts_intervals.h"
#include "common/shafts_render.h"
#include "common/sea_surface.h"
#include "common/sea_waves.h"
#include "common/gauss_legendre.h"
#include "common/sea_lean.h"
#include "common/polynomial_trig.h"
#include "common/sky.h"
#include "common/sky_view.h"
#include "common/sky_table.h"
#include "common/sea_second.h"
#include "common/sea_bottom.h"
#include "common/sea_multiple.h"
#include "common/ocean_spectrum.h"
#include "common/underwater.h"
#include "common/output_layers.h"
#include "common/band_lanes.h"
#include "common/band_lanes_math.h"
#include "common/sky_view_lanes.h"
#include "common/sea_bottom_lanes.h"
#include "common/underwater_bands.h"
#include "common/underwater_hit_lanes.h"
#include "common/sea_bands.h"
#include "common/sea_multiple_bands.h"
#include "common/underwater_ordinates.h"
#include "common/underwater_ordinates_lanes.h"
#include "common/underwater_ordinates_bands.h"
#include "common/water_spread.h"
#include "common/underwater_lamps.h"
#include "common/path_tracer.h"
#include "common/underwater_lamps_ms.h"
#include "common/caustic_texture.h"
#include "common/caustic_texture_lanes.h"
#include "common/caustic_map.h"
#include "common/sea_ordinates.h"
#include "common/sea_view.h"
#include "common/sea_band_terms.h"
#include "common/froxel.h"
#include "common/path_tracer_lamps.h"
#include "common/fourflow.h"
#include "common/fourflow_waves.h"
}  // namespace seasim::kmath_d
