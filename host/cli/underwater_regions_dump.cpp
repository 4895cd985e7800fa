#include "cli/underwater_regions_dump.h"

#include <cstdio>

#include "io/csv.h"
#include "util/error.h"

namespace seasim {

namespace {

const char* const kTermColumns[] = {"inscatter_modes", "inscatter_beam",  "inscatter_tms",       "aureole", "froxel_ss",
                                    "window",          "reflected_inscatter", "reflected_bottom", "reflected_froxel_ss",
                                    "reflected_object", "lambert",        "model_total",         "forward"};

double sum3(const Image& im, size_t i) {
  return double(im.pixels[3 * i]) + im.pixels[3 * i + 1] + im.pixels[3 * i + 2];
}

}  // namespace

std::vector<std::string> underwaterRegionsDumpHeader(const std::vector<std::string>& models, bool with_terms) {
  std::vector<std::string> h = {"x", "y", "region", "d_y", "cos_sun", "reference", "reference_se"};
  for (const std::string& m : models) h.push_back("fast_" + m);
  if (with_terms)
    for (const char* c : kTermColumns) h.push_back(c);
  return h;
}

void writeUnderwaterRegionsDump(const std::string& path, const UnderwaterRegionsDump& d) {
  const size_t n = d.regions.size();
  const bool terms = !d.ordinates_terms.empty();
  bool sizes_agree = d.dir_y.size() == n && d.cos_sun.size() == n && d.reference.pixelCount() == n && d.reference_se.pixelCount() == n &&
                     (!terms || d.ordinates_terms.size() == n) && d.reference.channels == 3 &&
                     d.reference_se.channels == 3;
  for (const auto& [name, im] : d.fast) sizes_agree = sizes_agree && im.pixelCount() == n && im.channels == 3;
  if (!sizes_agree) throw RuntimeError("underwater-regions --dump: the images and the region map disagree in size");
  std::vector<std::string> models;
  for (const auto& f : d.fast) models.push_back(f.first);
  CsvWriter csv(underwaterRegionsDumpHeader(models, terms));
  const int width = d.reference.width;
  for (size_t i = 0; i < n; ++i) {
    std::vector<CsvCell> row = {int(i % width), int(i / width), std::string(uwRegionName(d.regions[i])), d.dir_y[i], d.cos_sun[i],
                                sum3(d.reference, i), sum3(d.reference_se, i)};
    for (const auto& f : d.fast) row.push_back(sum3(f.second, i));
    if (terms) {
      const UwiPixelTerms& t = d.ordinates_terms[i];
      for (double v : {t.inscatter_modes, t.inscatter_beam, t.inscatter_tms, t.aureole, t.froxel_ss, t.window,
                       t.reflected_inscatter, t.reflected_bottom, t.reflected_froxel_ss, t.reflected_object, t.lambert,
                       t.total, t.forward})
        row.push_back(v);
    }
    csv.addRow(row);
  }
  csv.write(path);
}

std::string underwaterRegionsDumpName(double a, double b, double g, double depth, const std::string& view) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "a%.4g_b%.4g_g%.4g_d%.4g_%s.csv", a, b, g, depth, view.c_str());
  return buf;
}

}  // namespace seasim
