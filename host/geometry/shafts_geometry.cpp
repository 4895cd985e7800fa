#include "geometry/shafts_geometry.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "geometry/shafts_geometry_k.h"
#include "io/data_files.h"
#include "io/image_io.h"
#include "io/tonemap.h"
#include "util/error.h"

namespace seasim {

namespace k = kmath_d;

namespace {

k::real3 r3(Vec3 v) { return toReal3(v); }

}  // namespace

// First hit in (t_min, t_max) among the analytic objects; the normal faces the ray.
ShaftsHitK shaftsSceneHitK(const Scene& scene, k::real3 o, k::real3 d, double t_min, double t_max) {
  ShaftsHitK hit;
  double best = t_max;
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectDesc& ob = scene.objects[i];
    double t = -1;
    int axis = 0;
    k::real3 n{0, 1, 0};
    if (ob.type == ObjectDesc::Type::Sphere) {
      t = k::ray_sphere(o, d, r3(ob.center), ob.radius, t_min, best);
      if (t > 0) n = k::normalize(o + t * d - r3(ob.center));
    } else if (ob.type == ObjectDesc::Type::Box) {
      t = k::ray_box(o, d, r3(ob.box_min), r3(ob.box_max), t_min, best, &axis);
      if (t > 0) n = k::box_normal(o + t * d, r3(ob.box_min), r3(ob.box_max), axis);
    } else if (ob.type == ObjectDesc::Type::Plane) {
      t = k::ray_plane(o, d, r3(ob.point), r3(ob.normal), t_min, best);
      if (t > 0) n = r3(ob.normal);
    }
    if (t > 0) {
      best = t;
      hit.t = t;
      hit.normal = n;
      hit.index = static_cast<int>(i);
    }
  }
  if (hit.index >= 0 && k::dot(hit.normal, d) > 0) hit.normal = -hit.normal;
  return hit;
}

// "FILE:LINE: key 'objects[i].type': ..." like the parser's errors, before anything is rendered.
void requireShaftsSupported(const Scene& scene) {
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectDesc& o = scene.objects[i];
    if (o.type == ObjectDesc::Type::HeightField) {
      throw InputError(o.loc.file, o.loc.line, "objects[" + std::to_string(i) + "].type",
                       "\"heightfield\" objects are not supported with [[spotlights]] (the shafts ray caster "
                       "handles spheres, boxes and planes); remove the spotlights or use those object types");
    }
  }
}

ShaftsHit shaftsSceneHit(const Scene& scene, Vec3 o, Vec3 d, double t_min, double t_max) {
  const ShaftsHitK h = shaftsSceneHitK(scene, toReal3(o), toReal3(d), t_min, t_max);
  return ShaftsHit{h.t, toVec3(h.normal), h.index};
}

Vec3 CameraFrame::ray(double x, double y, int w, int h) const {
  const double u = (2.0 * x / w - 1.0) * tan_half * aspect;
  const double v = (1.0 - 2.0 * y / h) * tan_half;
  return normalize(fwd + right * u + up * v);
}

CameraFrame cameraFrame(const CameraDesc& cam) {
  CameraFrame f;
  f.eye = cam.position;
  f.fwd = normalize(cam.look_at - cam.position);
  f.right = normalize(cross(f.fwd, cam.up));
  f.up = cross(f.right, f.fwd);
  f.tan_half = std::tan(cam.fov_y / 2);
  f.aspect = double(cam.width) / cam.height;
  return f;
}

void shaftsLightBasis(const SpotlightDesc& light, Vec3& right, Vec3& up) {
  const Vec3 dir = normalize(light.direction);
  // Any reference not parallel to the axis; world up unless the beam is (nearly) vertical.
  const Vec3 ref = std::fabs(dir.y) < 0.99 ? Vec3{0, 1, 0} : Vec3{0, 0, -1};
  right = normalize(cross(dir, ref));
  up = cross(right, dir);
}

LightMap loadLightMap(const std::string& path, DataFiles* files) {
  const Image img = readImageVia(files, path);
  if (img.width < 1 || img.height < 1 || img.channels < 1 || img.channels > 4) {
    throw RuntimeError("light map '" + path + "': expected a grey or RGB(A) image");
  }
  LightMap map;
  map.width = img.width;
  map.height = img.height;
  map.rgb.resize(size_t(img.width) * img.height * 3);
  for (int y = 0; y < img.height; ++y)
    for (int x = 0; x < img.width; ++x)
      for (int c = 0; c < 3; ++c) {
        const int src = img.channels >= 3 ? c : 0;
        map.rgb[3 * (size_t(y) * img.width + x) + c] = static_cast<float>(srgbDecode(img.at(x, y, src)));
      }
  return map;
}

Vec3 objectAlbedoRgb(const ObjectDesc& object) {
  return {object.albedo.at(610.0), object.albedo.at(550.0), object.albedo.at(465.0)};
}

ShaftsRange shaftsTableRange(const Scene& scene) {
  requireShaftsSupported(scene);
  const CameraDesc& cam = scene.camera;
  const CameraFrame f = cameraFrame(cam);
  const k::real3 eye = r3(cam.position);
  std::vector<ShaftsRange> rows(cam.height);
  tbb::parallel_for(0, cam.height, [&](int y) {
    ShaftsRange& row = rows[y];
    for (int x = 0; x < cam.width; ++x) {
      const k::real3 d = r3(f.ray(x + 0.5, y + 0.5, cam.width, cam.height));
      const ShaftsHitK hit = shaftsSceneHitK(scene, eye, d, 0.0, 1e30);
      for (const SpotlightDesc& l : scene.spotlights) {
        const k::real3 lamp = r3(l.position);
        double ta = 0, tb = 0;
        if (!k::shafts_cone_interval(eye, d, lamp, r3(normalize(l.direction)), std::cos(l.cone), &ta, &tb)) continue;
        if (hit.index >= 0) tb = std::min(tb, hit.t);
        if (!(tb > ta)) continue;
        double a = 0, h = 0;
        k::shafts_closest_approach(eye, d, lamp, &a, &h);
        const double tp = std::min(tb, std::max(ta, a + SHAFTS_TAIL_K * std::max(h, kShaftsLampRadius)));
        if (!(tp > ta)) continue;
        row.t_max = std::max(row.t_max, tp);
        // s is convex along the ray: its largest value on [ta, tp] is at an end.
        row.s_max = std::max({row.s_max, k::length(eye + ta * d - lamp), k::length(eye + tp * d - lamp)});
      }
    }
  });
  ShaftsRange r;
  for (const ShaftsRange& row : rows) {
    r.t_max = std::max(r.t_max, row.t_max);
    r.s_max = std::max(r.s_max, row.s_max);
  }
  r.t_max = std::max(1.01 * r.t_max, 1e-3);
  r.s_max = std::max(1.01 * r.s_max, 1e-3);
  return r;
}

}  // namespace seasim
