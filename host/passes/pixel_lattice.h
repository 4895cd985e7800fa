// pixel_lattice.h — the lattices of every step-th pixel on which a pass evaluates what varies smoothly
// across the image (sand_share.cl's sand share, underwater_lamps.cl's orders of multiple scattering):
// the lattice pixel (i step, j step), clamped to the image's last row and column, for i < its size.
#pragma once

namespace seasim {

// The lattice's size along an image side of `pixels` pixels.
inline int pixelLatticeSize(int pixels, int step) { return (pixels + step - 1) / step; }

}  // namespace seasim
