// sea_band_table.h — sea_single.cl's band table (kernels/common/sea_band_table.h): SeaBand's per-band
// values and eq. 5's LUT, one row per quantity with the bands contiguous, so that the kernel's band
// lanes read several bands with one vector load.
#pragma once
#include <vector>

extern "C" {
#include "common/sea_band_table.h"
#include "common/sea_params.h"
}

namespace seasim {

// (SEA_ROWS + lut_size) rows of SEA_BAND_STRIDE(bands) floats (lut_size 1: no LUT, SEA_ROWS + 1 rows with
// a zero last row). lut: band-major, lut[band * lut_size + j], bands.size() * lut_size entries when
// lut_size > 1. Padding bands weigh 0 and repeat the last band's other values and LUT. No bands: one
// padded band of zeros. ordinates: sea.model "multiple"'s κ (passes/sea_ordinates_table.h, node-major,
// SEA_ORD_NODES or SEA_ORD_LAYER nodes x bands), written from row SEA_ROW_ORDINATES in place of the LUT (then
// lut_size must be 1); empty: none.
std::vector<float> seaBandTable(const std::vector<SeaBand>& bands, const std::vector<float>& lut, int lut_size,
                                const std::vector<double>& ordinates = {});

}  // namespace seasim
