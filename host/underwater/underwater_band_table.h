// underwater_band_table.h — kd_multiple.cl's band table (kernels/common/underwater_band_table.h): the
// per-band values of a set-up that do not depend on the pixel, one row per quantity so that the kernel
// reads several bands with one vector load.
#pragma once
#include <vector>

#include "underwater/underwater_setup.h"

extern "C" {
#include "common/underwater_band_table.h"
}

namespace seasim {

// (UW_ROWS + objects) rows of UW_BAND_STRIDE(bands) floats, and UWI_ROWS more when setup.ordinates is
// filled (underwater.model = "discrete_ordinates"); padding bands weigh 0 and repeat the last band's other values.
// Empty set-up (no bands): one padded band of zeros.
std::vector<float> underwaterBandTable(const UnderwaterSetup& setup);

}  // namespace seasim
