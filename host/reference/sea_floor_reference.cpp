#include "reference/sea_floor_reference.h"

#include <algorithm>
#include <cmath>

namespace seasim {

namespace {

// Node (i, j) clamped into the grid; the cell (i0, j0) and local (u, v) holding world (x, z).
struct Cell {
  int i0, j0;
  double u, v;
};

Cell cellAt(const HeightField& f, double x, double z) {
  const SeaHeightField& p = f.params;
  const double gx = std::clamp((x / p.extent + 0.5) * (p.nx - 1), 0.0, double(p.nx - 1));
  const double gz = std::clamp((z / p.extent + 0.5) * (p.ny - 1), 0.0, double(p.ny - 1));
  const int i0 = std::min(static_cast<int>(gx), p.nx - 2), j0 = std::min(static_cast<int>(gz), p.ny - 2);
  return {i0, j0, gx - i0, gz - j0};
}

double node(const HeightField& f, int i, int j) { return f.depth[static_cast<size_t>(j) * f.params.nx + i]; }

}  // namespace

double floorDepthAt(const HeightField& f, double x, double z) {
  const Cell c = cellAt(f, x, z);
  return (1 - c.u) * (1 - c.v) * node(f, c.i0, c.j0) + c.u * (1 - c.v) * node(f, c.i0 + 1, c.j0) +
         (1 - c.u) * c.v * node(f, c.i0, c.j0 + 1) + c.u * c.v * node(f, c.i0 + 1, c.j0 + 1);
}

void floorNormalAt(const HeightField& f, double x, double z, double normal[3]) {
  const SeaHeightField& p = f.params;
  const Cell c = cellAt(f, x, z);
  const double h00 = node(f, c.i0, c.j0), h10 = node(f, c.i0 + 1, c.j0);
  const double h01 = node(f, c.i0, c.j0 + 1), h11 = node(f, c.i0 + 1, c.j0 + 1);
  // Outside the square the border extends outwards: no slope across it.
  const double gx = (x / p.extent + 0.5) * (p.nx - 1), gz = (z / p.extent + 0.5) * (p.ny - 1);
  const bool in_x = gx >= 0 && gx <= p.nx - 1, in_z = gz >= 0 && gz <= p.ny - 1;
  const double dhdx = in_x ? ((1 - c.v) * (h10 - h00) + c.v * (h11 - h01)) * (p.nx - 1) / p.extent : 0.0;
  const double dhdz = in_z ? ((1 - c.u) * (h01 - h00) + c.u * (h11 - h10)) * (p.ny - 1) / p.extent : 0.0;
  const double len = std::sqrt(dhdx * dhdx + 1 + dhdz * dhdz);
  normal[0] = dhdx / len;
  normal[1] = 1 / len;
  normal[2] = dhdz / len;
}

double fineMarchFloor(const HeightField& f, const double o[3], const double dir[3], double t_max, double step) {
  auto above = [&](double t) { return floorDepthAt(f, o[0] + t * dir[0], o[2] + t * dir[2]) + (o[1] + t * dir[1]); };
  if (above(0) <= 0) return 0;
  // Going down, the ray is under every node once it passes the deepest one.
  if (dir[1] < 0) t_max = std::min(t_max, (f.params.max_depth + o[1]) / -dir[1] + step);
  double prev = 0;
  for (long n = 1; n < 100000000; ++n) {
    const double t = std::min(n * step, t_max);
    if (above(t) <= 0) {
      double lo = prev, hi = t;
      for (int k = 0; k < 60; ++k) {
        const double mid = 0.5 * (lo + hi);
        (above(mid) > 0 ? lo : hi) = mid;
      }
      return hi;
    }
    if (t >= t_max) return -1;
    prev = t;
  }
  return -1;  // a ray that neither ends nor goes down: never under the floor within 1e8 steps
}

}  // namespace seasim
