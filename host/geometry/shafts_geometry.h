// shafts_geometry.h — the geometry of the spotlight shafts (paper 001) that the fast pass
// (passes/shafts_pass) and its references (reference/shafts_reference) share, so both integrate the
// same problem without either holding the other's parts: the camera frame, ray–object hits, light
// frames and light maps, object albedo, and the ranges of the 001 eq. 6 table.
#pragma once
#include <string>
#include <vector>

#include "math/vec3.h"
#include "scene/scene.h"

namespace seasim {

// The first hit of a ray among the scene's analytic objects (spheres, boxes, planes).
// (Vec3 here, so this header stays free of kernel_math.h and its macros.)
struct ShaftsHit {
  double t = -1;
  Vec3 normal{0, 1, 0};  // faces the ray
  int index = -1;        // scene.objects index; -1 for no hit
};
// First hit in (t_min, t_max).
ShaftsHit shaftsSceneHit(const Scene& scene, Vec3 o, Vec3 d, double t_min, double t_max);

// InputError "FILE:LINE: key 'objects[i].type': ..." for objects the shafts ray caster does not handle.
void requireShaftsSupported(const Scene& scene);

// The pinhole camera's frame; ray(x, y) is the unit direction through pixel position (x, y)
// (pixel centres at +0.5).
struct CameraFrame {
  Vec3 eye, fwd, right, up;
  double tan_half, aspect;
  Vec3 ray(double x, double y, int w, int h) const;
};
CameraFrame cameraFrame(const CameraDesc& cam);

// The ranges of the 001 eq. 6 table ĥ(s, t) (table mode): the largest t and s at which any pixel's
// sampling planes evaluate g. shafts.cl integrates each lamp over the part of the view ray inside its
// cone, up to the first surface, with planes up to SHAFTS_TAIL_K r past the closest approach (the far
// field beyond does not read the table); this walks the same geometry in double at every pixel
// centre, plus 1 % for float rounding. At least 1 mm each, so an unlit scene still has a table.
struct ShaftsRange {
  double t_max = 0.0;  // m, longest view-ray distance of any plane
  double s_max = 0.0;  // m, largest lamp distance of any plane
};
ShaftsRange shaftsTableRange(const Scene& scene);

// Light frame: +z = direction, right/up across the beam (the light map's u and v).
void shaftsLightBasis(const SpotlightDesc& light, Vec3& right, Vec3& up);

// A lamp's light map as linear RGB (sRGB-decoded from the file), top row first.
struct LightMap {
  int width = 0, height = 0;
  std::vector<float> rgb;  // 3 per texel
};
// files: read the image through it (io/data_files.h), or directly when null.
LightMap loadLightMap(const std::string& path, DataFiles* files = nullptr);

// Lambertian albedo of an object as linear R,G,B (its spectrum at 610, 550, 465 nm).
Vec3 objectAlbedoRgb(const ObjectDesc& object);

// The lamp's radius: 1/s² is clamped at this distance (common/shafts.h).
constexpr double kShaftsLampRadius = 1e-3;  // m

}  // namespace seasim
