// sea_sky.h — the [sky] of a scene made ready for kernels/common/sky.h: the model, the scale that
// makes every model's cosine-weighted mean radiance equal the uniform sky's, the environment image as
// linear RGB texels and each band's share of its R, G, B. Shared by host/passes/sea_single_pass.cpp
// (float upload) and host/reference/sea_reference.cpp (double), so both read the same sky.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "scene/scene.h"
#include "spectral/wavelength_grid.h"

namespace seasim {

struct SeaSky {
  int model = 0;                    // SEASIM_SKY_MODEL: 0 uniform, 1 analytic (CIE clear sky), 2 image, 3 Preetham
  double scale = 1.0;               // sky_scale: 1 / cosine-weighted mean of the shape (common/sky.h)
  int width = 1, height = 1;        // environment image texels (1 x 1 black placeholder otherwise)
  std::vector<double> texels;       // 4 per texel (R, G, B, 0), linear, top row = zenith; Preetham: its 21 reals
  // per band: share of R, G, B (sky_image_band_weights); Preetham: of the daylight basis (cie_daylight.h)
  std::vector<std::array<double, 3>> band_weights;
};

// SEASIM_SKY_MODEL of a scene's sky (the planner's define).
int skyModelDefine(const SkyDesc& sky);

// Reads the image for model = "image": EXR/HDR/PFM/NPY as linear values, other formats (PNG, JPEG)
// as sRGB-encoded and decoded to linear; grey images are used for R, G and B. sun: unit, towards the
// sun (the analytic sky's indicatrix). RuntimeError naming the file if it cannot be used.
// files: read the sky image through it (io/data_files.h), or directly when null.
SeaSky makeSeaSky(const SkyDesc& sky, const double sun_dir[3], const WavelengthGrid& grid, DataFiles* files = nullptr);

// The reflected sky's n x n table (common/sky_table.h: nodes in sqrt(cos theta) and gamma,
// SKY_TABLE_STRIDE reals each): the analytic sky's own quantities at each node (sky_table_shape turns a
// read into the scaled shape). RuntimeError for n < 2 or a sky that is not analytic (CIE clear or
// Preetham).
std::vector<double> seaSkyTable(const SeaSky& sky, int n);

}  // namespace seasim
