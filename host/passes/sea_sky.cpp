#include "passes/sea_sky.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <string>

#include <tbb/parallel_for.h>

#include "io/data_files.h"
#include "io/image_io.h"
#include "io/tonemap.h"
#include "math/kernel_math.h"
#include "spectral/cie_daylight.h"
#include "util/error.h"

namespace seasim {

namespace kd = kmath_d;

int skyModelDefine(const SkyDesc& sky) {
  switch (sky.model) {
    case SkyDesc::Model::Analytic: return 1;
    case SkyDesc::Model::Image: return 2;
    case SkyDesc::Model::Preetham: return 3;
    case SkyDesc::Model::Uniform: break;
  }
  return 0;
}

namespace {

bool linearFormat(const std::string& path) {
  std::string ext = path.substr(path.find_last_of('.') == std::string::npos ? path.size() : path.find_last_of('.'));
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return ext == ".exr" || ext == ".hdr" || ext == ".pfm" || ext == ".npy";
}

}  // namespace

SeaSky makeSeaSky(const SkyDesc& desc, const double sun_dir[3], const WavelengthGrid& grid, DataFiles* files) {
  SeaSky sky;
  sky.model = skyModelDefine(desc);
  sky.texels.assign(4, 0.0);
  for (double lambda : grid.centers_nm) {
    const kd::real3 w = kd::sky_image_band_weights(lambda);
    sky.band_weights.push_back({w.x, w.y, w.z});
  }
  if (sky.model == 1) {
    // 128 x 256 midpoints: within 3e-4 of a 1024 x 2048 rule (tests/unit/sky_test.cpp).
    const kd::real3 sun{sun_dir[0], sun_dir[1], sun_dir[2]};
    sky.scale = 1.0 / kd::sky_cie_clear_cosine_mean(sun, 128, 256);
  } else if (sky.model == 3) {
    // Preetham: the 18 packed reals in place of texels (common/sky.h), and the scale from its mean
    // luminance (256 x 512 midpoints: the circumsolar peak is sharper than the CIE sky's, and 128 x 256
    // was 0.3 % off; tests/unit/sky_preetham_test.cpp).
    // Spectral: the 18 reals, then the daylight basis's luminance weights; each band takes
    // the basis S0, S1, S2 over D65 (sky_preetham_daylight), not R, G, B.
    const kd::real3 sun{sun_dir[0], sun_dir[1], sun_dir[2]};
    sky.texels.assign(22, 0.0);
    kd::sky_preetham_pack(sun, desc.turbidity, sky.texels.data());
    const std::array<double, 3> n = daylightLuminanceWeights();
    for (int k = 0; k < 3; ++k) sky.texels[static_cast<size_t>(18 + k)] = n[static_cast<size_t>(k)];
    sky.texels[21] = desc.chromaticity_on_daylight_locus ? 1.0 : 0.0;  // sky.chromaticity (common/sky.h)
    for (size_t i = 0; i < grid.centers_nm.size(); ++i) sky.band_weights[i] = daylightBandWeights(grid.centers_nm[i]);
    const double mean = kd::sky_preetham_daylight_cosine_mean(sky.texels.data(), sun, 256, 512);
    sky.scale = mean > 0 ? 1.0 / mean : 0.0;
  } else if (sky.model == 2) {
    const Image img = readImageVia(files, desc.image);
    if (img.width < 2 || img.height < 2 || img.channels < 1) {
      throw RuntimeError("sky image '" + desc.image + "': expected a latitude-longitude image of at least 2 x 2 texels");
    }
    const bool linear = linearFormat(desc.image);
    sky.width = img.width;
    sky.height = img.height;
    sky.texels.assign(4 * img.pixelCount(), 0.0);
    for (int y = 0; y < img.height; ++y)
      for (int x = 0; x < img.width; ++x)
        for (int c = 0; c < 3; ++c) {
          const double v = img.at(x, y, img.channels >= 3 ? c : 0);
          if (!std::isfinite(v) || v < 0) {
            throw RuntimeError("sky image '" + desc.image + "': texel (" + std::to_string(x) + ", " + std::to_string(y) +
                               ") is negative or not finite; an environment image holds radiances >= 0");
          }
          sky.texels[4 * (static_cast<size_t>(y) * img.width + x) + c] = linear ? v : srgbDecode(v);
        }
    const double mean = kd::sky_latlong_cosine_mean_luminance(sky.texels.data(), sky.width, sky.height);
    // A sky black above the horizon stays black (scale 0) rather than dividing by zero.
    sky.scale = mean > 0 ? 1.0 / mean : 0.0;
  }
  return sky;
}

std::vector<double> seaSkyTable(const SeaSky& sky, int n) {
  if (n < 2) throw RuntimeError("sea sky table: needs at least 2 x 2 nodes, got " + std::to_string(n));
  if (sky.model != SEASIM_SKY_ANALYTIC && sky.model != SEASIM_SKY_PREETHAM)
    throw RuntimeError("sea sky table: only the analytic skies (CIE clear, Preetham) depend on the view through "
                       "cos theta and cos gamma alone");
  std::vector<double> table(static_cast<size_t>(SKY_TABLE_STRIDE) * n * n, 0.0);
  // 65,536 evaluations of Preetham's model at the default 256: rows on threads.
  tbb::parallel_for(0, n, [&](int i) {
    for (int j = 0; j < n; ++j) {
      double ct, cg;
      kd::sky_table_node(i, j, n, &ct, &cg);
      double v[3];
      if (sky.model == SEASIM_SKY_ANALYTIC) {
        v[0] = v[1] = v[2] = kd::sky_cie_gradation(ct) * kd::sky_cie_indicatrix(cg);
      } else {
        kd::sky_preetham_yxy_cos(sky.texels.data(), ct, cg, v);
      }
      double* t = table.data() + static_cast<size_t>(SKY_TABLE_STRIDE) * (static_cast<size_t>(i) * n + j);
      for (int c = 0; c < 3; ++c) t[c] = v[c];
    }
  });
  return table;
}

}  // namespace seasim
