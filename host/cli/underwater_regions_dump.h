// underwater_regions_dump.h — `seasim underwater-regions --dump DIR`: one case's images as a per-pixel
// CSV, to see where in the frame a region's miss sits and which of the fast model's terms it is in
// Columns: x, y (pixel, row 0 at the top), region, d_y (the centre ray's vertical direction,
// > 0 towards the surface), cos_sun (its cosine with the direction to the refracted sun), reference and reference_se (the path tracer and its standard error),
// fast_<model> per model rendered, and with the discrete-ordinates model its terms (reference/
// underwater_ordinates_terms.h): every radiance the sum of the three channels; reflected_object 0 or 1;
// forward, the part of the hit's light that delta-M counts as unscattered (not a part of model_total).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "io/image.h"
#include "reference/underwater_ordinates_terms.h"
#include "reference/underwater_regions.h"

namespace seasim {

struct UnderwaterRegionsDump {
  std::vector<UwRegion> regions;
  std::vector<double> dir_y, cos_sun;                  // per pixel
  Image reference, reference_se;
  std::vector<std::pair<std::string, Image>> fast;     // model name, its render
  std::vector<UwiPixelTerms> ordinates_terms;           // empty: no discrete-ordinates model in the case
};

// The CSV's header, in column order (the terms' columns only with_terms).
std::vector<std::string> underwaterRegionsDumpHeader(const std::vector<std::string>& models, bool with_terms);

// Writes the case to `path` atomically (RuntimeError when the images' sizes disagree).
void writeUnderwaterRegionsDump(const std::string& path, const UnderwaterRegionsDump& dump);

// The case's file name: a, b, g, depth, view, e.g. "a0.03_b0.05_g0.9_d2_level.csv".
std::string underwaterRegionsDumpName(double a, double b, double g, double depth, const std::string& view);

}  // namespace seasim
