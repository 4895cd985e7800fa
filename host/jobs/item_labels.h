// item_labels.h — labels.json of a dataset item (a job's [sample] items, jobs/job_sampling.h): the
// values drawn for it and what the scene resolved them to, so a training set needs no second
// parser of scene files. Written beside the item's images by the job runner, atomically, and
// listed with its checksum in the manifest like the images (resume and `farm merge` check it).
//
//   format           "seasim-labels-1"
//   item, seed, index, scene
//   sampled          {dotted key: drawn value (number, string, array)}
//   water            present, jerlov (or null), ior, bands_nm (band centres), band_width_nm, and per band
//                    a, b, c = a + b, kd (1/m): spectral/jerlov.h resolveWater on the render's grid,
//                    with the refracted sun's cosine the underwater model uses for a K_d it derives
//                    (kd_sun_cosine); phase {name: "henyey_greenstein", g}
//   sun              enabled, zenith_deg, azimuth_deg, irradiance, direction_air, direction_water
//                    (unit vectors towards the sun; in water after refraction)
//   camera           position, look_at, up, direction (unit), depth_m (below y = 0; 0 above it),
//                    fov_y_deg, fov_x_deg, width, height, exposure_ev, sensor, sensor_file (the
//                    camera curve CSV, null for cie1931/identity), white_balance
//   bottom           type ("none", "flat", "heightfield"), depth_m
//   underwater_model "thesis" or "discrete_ordinates"
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "jobs/job.h"
#include "scene/scene.h"

namespace seasim {

nlohmann::json itemLabels(const Scene& scene, const RenderItem& item);

// labels.json's "sampled": the item's drawn keys and values.
nlohmann::json sampledJson(const RenderItem& item);
// True when <dir>/labels.json exists and records other draws than `item` has now (the job's
// [sample] table was edited since): `--resume` renders such an item again, even where the keys
// changed are ones report.json's settings do not record (bottom.depth, objects, water.g ...).
bool labelsRecordOtherDraws(const RenderItem& item, const std::string& dir);

// Writes itemLabels as <dir>/labels.json (atomically) and returns the file's name in `dir`.
std::string writeItemLabels(const Scene& scene, const RenderItem& item, const std::string& dir);

}  // namespace seasim
