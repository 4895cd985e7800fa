// shafts_geometry_k.h — shafts_geometry.h in the kernels' double vectors (kmath_d::real3), for the
// .cpp files that run the kernels' math on the host (the shafts geometry and its reference).
// Include it after any TBB header: kernel_math.h defines the kernels' R(x) macro.
#pragma once
#include "geometry/shafts_geometry.h"
#include "math/kernel_math.h"

namespace seasim {

inline kmath_d::real3 toReal3(Vec3 v) { return kmath_d::real3{v.x, v.y, v.z}; }
inline Vec3 toVec3(kmath_d::real3 v) { return Vec3{v.x, v.y, v.z}; }

struct ShaftsHitK {
  double t = -1;
  kmath_d::real3 normal{0, 1, 0};  // faces the ray
  int index = -1;                  // scene.objects index; -1 for no hit
};
// shaftsSceneHit in double vectors.
ShaftsHitK shaftsSceneHitK(const Scene& scene, kmath_d::real3 o, kmath_d::real3 d, double t_min, double t_max);

}  // namespace seasim
