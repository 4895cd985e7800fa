// sea_ordinates_table.h — κ of kernels/common/sea_ordinates.h: sea.model = "multiple"'s water-leaving
// radiance held to the discrete-ordinates solution of the same flat layer, per band, bottom depth and
// direction. Built by the sea pass (its band table's rows from SEA_ROW_ORDINATES) and by the double
// reference the kernel is tested against.
#pragma once
#include <vector>

#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

// What every band shares: the sun's entry through the flat mean surface, the water's phase, and the
// bottom depths the pixels can see.
struct SeaOrdinatesLight {
  double ior = 1.34;
  double g = 0.9;                // HG asymmetry of the water
  double sun_up = 0;             // the sun's vertical direction component (E on the horizontal per unit
                                 // normal irradiance); 0: no sun
  double t_in = 0;               // the sun's Fresnel transmittance into the flat sea
  double cos_io = 1;             // the refracted sun's cosine with the downward vertical
  double sky_fresnel_mean = 0;   // r̄, the uniform sky's mean Fresnel reflectance (SeaParams)
  bool column = true;            // sea.single_scattering: the water's own light is drawn (else κ = 1)
  bool bottom = false;           // some pixels see a bottom, at depths depth_min..depth_max (m)
  double depth_min = 0, depth_max = 0;
  bool deep = true;              // some pixels see no bottom
  bool depth_grid = false;       // a height field: κ on the depth grid; else one layer at the one depth
};

struct SeaOrdinatesBand {
  double a = 0, b = 0;   // 1/m
  double e_sun = 0;      // the sun's irradiance normal to it, W m^-2 nm^-1
  double e_sky = 0;      // the sky's diffuse irradiance just below the surface, π L (1 - r̄)
  double albedo = 0;     // the bottom's
};

// The scene's: sun (unit, towards it; below the horizon: no sun), the water's index and g, the bottom's
// depths (flat: its depth; height field: bottom.min_depth..max_depth; none: no bottom). column:
// sea.single_scattering; bottom: the bottom is drawn (else every pixel sees none).
SeaOrdinatesLight seaOrdinatesLight(const Scene& scene, const Vec3& sun, double sky_fresnel_mean, bool column,
                                    bool bottom);

// κ per node and band, node-major: kappa[node * bands.size() + band] (SEA_ORD_ROW). With depth_grid over
// SEA_ORD_NODES nodes, 1 at depth nodes no pixel reads (only the nodes around the scene's depths are
// solved); else over the SEA_ORD_LAYER nodes of one layer at the scene's one depth (depth_min, or none).
// 1 where κ has no meaning: no light, no scattering, or the column not drawn.
std::vector<double> seaOrdinatesTable(const SeaOrdinatesLight& light, const std::vector<SeaOrdinatesBand>& bands);

// The closed form's radiance just below the surface towards the eye (column, bottom and surface return as
// the kernel adds them; no T_o) at bottom depth H (< 0: none), along the refracted view of cosine cos_ji with
// the vertical, the sun's beam scattered into it with the HG phase `phase`. The double reference's sum.
double seaClosedFormBelowAlong(const SeaOrdinatesLight& light, const SeaOrdinatesBand& band, double H, double cos_ji,
                               double phase);

// The same for upwelling light at cosine cos_up with the zenith and azimuth cosine cos_phi from the
// refracted sun's travel (the phase from the flat surface's geometry).
double seaClosedFormBelow(const SeaOrdinatesLight& light, const SeaOrdinatesBand& band, double H, double cos_up,
                          double cos_phi);

// κ at one pixel's depth and direction from a table of seaOrdinatesTable (band `band` of `bands`; a depth
// grid when it has SEA_ORD_NODES nodes), as the kernel reads it (sea_ord_taps).
double seaOrdinatesFactor(const std::vector<double>& kappa, int bands, int band, double H, double cos_up,
                          double cos_phi);

}  // namespace seasim
