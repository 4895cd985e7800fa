#include "reference/shafts_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

#include "io/image_io.h"
#include "io/tonemap.h"
#include "math/kernel_math.h"
#include "util/error.h"

namespace seasim {

namespace k = kmath_d;

namespace {

k::real3 r3(Vec3 v) { return k::real3{v.x, v.y, v.z}; }

struct Hit {
  double t = -1;
  k::real3 normal{0, 1, 0};
  int index = -1;
};

// "FILE:LINE: key 'objects[i].type': ..." like the parser's errors, before anything is rendered.
void requireSupported(const Scene& scene) {
  for (size_t i = 0; i < scene.objects.size(); ++i) {
    const ObjectDesc& o = scene.objects[i];
    if (o.type == ObjectDesc::Type::HeightField) {
      throw InputError(o.loc.file, o.loc.line, "objects[" + std::to_string(i) + "].type",
                       "\"heightfield\" objects are not supported with [[spotlights]] (the shafts ray caster "
                       "handles spheres, boxes and planes); remove the spotlights or use those object types");
    }
  }
}

// First hit in (t_min, t_max) among the analytic objects; the normal faces the ray.
Hit sceneHit(const Scene& scene, k::real3 o, k::real3 d, double t_min, double t_max) {
  Hit hit;
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

struct CameraFrame {
  Vec3 eye, fwd, right, up;
  double tan_half, aspect;
  k::real3 ray(double x, double y, int w, int h) const {  // x, y in pixels (centre = +0.5)
    const double u = (2.0 * x / w - 1.0) * tan_half * aspect;
    const double v = (1.0 - 2.0 * y / h) * tan_half;
    return r3(normalize(fwd + right * u + up * v));
  }
};

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

// A lamp in double: its frame, light map and cone, evaluated as kernels/shafts.cl does.
struct Lamp {
  k::real3 pos, dir, right, up, color;
  double cos_cone, cos_inner, tan_cone;
  LightMap map;
  bool has_map = false;

  k::real3 emission(k::real3 p) const {
    const k::real3 w = p - pos;
    const double s = k::length(w);
    const double qz = k::dot(w, dir);
    if (qz <= 0 || s <= 0) return k::real3{0, 0, 0};
    const double profile = k::shafts_cone_profile(qz / s, cos_cone, cos_inner);
    if (profile <= 0) return k::real3{0, 0, 0};
    k::real3 e = color * profile;
    if (has_map) {
      const double inv = 1.0 / (qz * tan_cone);
      const double fu = 0.5 * (k::dot(w, right) * inv + 1.0) * map.width - 0.5;
      const double fv = 0.5 * (1.0 - k::dot(w, up) * inv) * map.height - 0.5;
      const double cu = std::clamp(fu, 0.0, double(map.width - 1)), cv = std::clamp(fv, 0.0, double(map.height - 1));
      const int x0 = std::min(int(cu), map.width - 1), y0 = std::min(int(cv), map.height - 1);
      const int x1 = std::min(x0 + 1, map.width - 1), y1 = std::min(y0 + 1, map.height - 1);
      const double ax = cu - x0, ay = cv - y0;
      auto tex = [&](int x, int y, int c) { return double(map.rgb[3 * (size_t(y) * map.width + x) + c]); };
      double m[3];
      for (int c = 0; c < 3; ++c) {
        const double top = tex(x0, y0, c) * (1 - ax) + tex(x1, y0, c) * ax;
        const double bot = tex(x0, y1, c) * (1 - ax) + tex(x1, y1, c) * ax;
        m[c] = top * (1 - ay) + bot * ay;
      }
      e = e * k::real3{m[0], m[1], m[2]};
    }
    return e;
  }
};

std::vector<Lamp> makeLamps(const Scene& scene) {
  std::vector<Lamp> lamps;
  for (const auto& l : scene.spotlights) {
    Lamp lamp;
    Vec3 right, up;
    shaftsLightBasis(l, right, up);
    lamp.pos = r3(l.position);
    lamp.dir = r3(normalize(l.direction));
    lamp.right = r3(right);
    lamp.up = r3(up);
    lamp.color = r3(l.color) * l.intensity;
    lamp.cos_cone = std::cos(l.cone);
    lamp.cos_inner = std::cos(std::max(0.0, l.cone - l.falloff));
    lamp.tan_cone = std::tan(l.cone);
    if (!l.light_map.empty()) {
      lamp.map = loadLightMap(l.light_map);
      lamp.has_map = true;
    }
    lamps.push_back(std::move(lamp));
  }
  return lamps;
}

}  // namespace

void shaftsLightBasis(const SpotlightDesc& light, Vec3& right, Vec3& up) {
  const Vec3 dir = normalize(light.direction);
  // Any reference not parallel to the axis; world up unless the beam is (nearly) vertical.
  const Vec3 ref = std::fabs(dir.y) < 0.99 ? Vec3{0, 1, 0} : Vec3{0, 0, -1};
  right = normalize(cross(dir, ref));
  up = cross(right, dir);
}

LightMap loadLightMap(const std::string& path) {
  const Image img = readImage(path);
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

ShaftsRange shaftsRange(const Scene& scene) {
  requireSupported(scene);
  const CameraDesc& cam = scene.camera;
  const CameraFrame f = cameraFrame(cam);
  // The scene's finite extent seen from the eye: lamps and bounded objects.
  double extent = 1.0;
  for (const auto& l : scene.spotlights) extent = std::max(extent, length(l.position - cam.position));
  for (const auto& o : scene.objects) {
    if (o.type == ObjectDesc::Type::Sphere) extent = std::max(extent, length(o.center - cam.position) + o.radius);
    if (o.type == ObjectDesc::Type::Box) {
      for (int c = 0; c < 8; ++c) {
        const Vec3 p{(c & 1) ? o.box_max.x : o.box_min.x, (c & 2) ? o.box_max.y : o.box_min.y,
                     (c & 4) ? o.box_max.z : o.box_min.z};
        extent = std::max(extent, length(p - cam.position));
      }
    }
  }
  // Far plane: the deepest visible surface over a coarse grid of rays (2 % margin); a ray that
  // sees nothing (or a surface beyond 2 x extent) extends it to 2 x the finite extent.
  const double cap = 2.0 * extent;
  double z_far = 0;
  const int gx = 96, gy = 64;
  for (int j = 0; j <= gy; ++j)
    for (int i = 0; i <= gx; ++i) {
      const k::real3 d = f.ray(double(i) / gx * cam.width, double(j) / gy * cam.height, cam.width, cam.height);
      const double cos_t = k::dot(d, r3(f.fwd));
      const Hit h = sceneHit(scene, r3(cam.position), d, 0.0, 1e30);
      const double z = h.t > 0 ? std::min(h.t * cos_t * 1.02, cap) : cap;
      z_far = std::max(z_far, z);
    }
  ShaftsRange r;
  r.z_far = std::max(z_far, 2 * r.z_near);
  const k::real3 corner = f.ray(0, 0, cam.width, cam.height);
  r.t_max = r.z_far / k::dot(corner, r3(f.fwd));
  r.s_max = 0;
  for (const auto& l : scene.spotlights) r.s_max = std::max(r.s_max, length(l.position - cam.position) + r.t_max);
  return r;
}

namespace {

// A half-space n·x <= d (world coordinates).
struct HalfSpace {
  Vec3 n;
  double d;
};

// Distance S beyond which the airlight a view ray can collect from a lamp's beam is below eps:
// along any line, ∫ dt / s² over the part with s >= S is at most π / S, so the radiance from there
// is at most ρ I F_max π exp(-ρκ S) / S (001 eq. 2–3 with H = 1), decreasing in S. Capped at 1e6 m.
double beamLength(double rho, double sigma_t, double intensity, double f_max, double eps) {
  auto bound = [&](double S) { return rho * intensity * f_max * M_PI * std::exp(-sigma_t * S) / S; };
  double lo = 1e-3, hi = 1e6;
  if (bound(hi) > eps) return hi;
  if (bound(lo) <= eps) return lo;
  for (int i = 0; i < 100; ++i) {  // bisection in log S
    const double mid = std::sqrt(lo * hi);
    (bound(mid) > eps ? lo : hi) = mid;
  }
  return hi;
}

// Extremes of f·x over the polytope {x : n_i·x <= d_i} (bounded here by the frustum's near and far
// planes), by enumerating the vertices: every triple of planes whose intersection point satisfies all
// constraints. 15 planes: 455 triples, negligible per frame. Returns false when the polytope is empty.
bool depthExtremes(const std::vector<HalfSpace>& hs, Vec3 f, double& lo, double& hi) {
  bool any = false;
  const size_t n = hs.size();
  for (size_t i = 0; i < n; ++i)
    for (size_t j = i + 1; j < n; ++j)
      for (size_t k = j + 1; k < n; ++k) {
        const Vec3 a = hs[i].n, b = hs[j].n, c = hs[k].n;
        const Vec3 bc = cross(b, c);
        const double det = dot(a, bc);
        if (std::fabs(det) < 1e-12) continue;  // two planes (nearly) parallel: no single vertex
        const Vec3 x = (bc * hs[i].d + cross(c, a) * hs[j].d + cross(a, b) * hs[k].d) * (1.0 / det);  // Cramer
        bool inside = true;
        for (size_t m = 0; m < n && inside; ++m) {
          const double tol = 1e-9 * std::max({1.0, std::fabs(hs[m].d), length(x)});
          inside = dot(hs[m].n, x) <= hs[m].d + tol;
        }
        if (!inside) continue;
        const double z = dot(f, x);
        lo = any ? std::min(lo, z) : z;
        hi = any ? std::max(hi, z) : z;
        any = true;
      }
  return any;
}

}  // namespace

ShaftsRange shaftsClipToCones(const Scene& scene, const ShaftsRange& range) {
  const CameraDesc& cam = scene.camera;
  const CameraFrame f = cameraFrame(cam);
  // The view frustum in camera depth z = fwd·(x - eye): z_near <= z <= z_far, |right·q| <= tx z,
  // |up·q| <= ty z (q = x - eye), as half-spaces n·x <= d.
  const double ty = f.tan_half, tx = f.tan_half * f.aspect;
  const double e_f = dot(f.fwd, f.eye);
  std::vector<HalfSpace> frustum = {
      {f.fwd * -1.0, -(range.z_near + e_f)},
      {f.fwd, range.z_far + e_f},
      {f.right - f.fwd * tx, dot(f.right - f.fwd * tx, f.eye)},
      {f.right * -1.0 - f.fwd * tx, dot(f.right * -1.0 - f.fwd * tx, f.eye)},
      {f.up - f.fwd * ty, dot(f.up - f.fwd * ty, f.eye)},
      {f.up * -1.0 - f.fwd * ty, dot(f.up * -1.0 - f.fwd * ty, f.eye)},
  };
  const double rho = scene.air.density, sigma_t = scene.air.density * scene.air.extinction;
  const int use_hg = scene.air.phase == AirDesc::Phase::HenyeyGreenstein;
  const double f_max = std::max(k::shafts_phase_fn(1.0, use_hg, scene.air.g), k::shafts_phase_fn(-1.0, use_hg, scene.air.g));
  // 0.01 of an 8-bit level at the dark end of the tone map (io/tonemap.h: slope 12.92 · 2^EV there).
  const double eps = 0.01 / (255.0 * 12.92 * std::exp2(cam.exposure_ev));

  bool any = false;
  double z_lo = 0, z_hi = 0;
  constexpr int kSides = 8;
  for (const SpotlightDesc& l : scene.spotlights) {
    Vec3 lr, lu;
    shaftsLightBasis(l, lr, lu);
    const Vec3 a = normalize(l.direction);
    const double i_max = l.intensity * std::max({l.color.x, l.color.y, l.color.z});
    if (!(i_max > 0)) continue;  // a dark lamp lights nothing
    const double L = beamLength(rho, sigma_t, i_max, f_max, eps);
    std::vector<HalfSpace> hs = frustum;
    // Circumscribed pyramid: the plane tangent to the cone along lateral direction w has outward
    // normal cos θ w - sin θ a; 8 of them contain the cone (θ < 90°, checked by the parser).
    const double c = std::cos(l.cone), s = std::sin(l.cone);
    for (int side = 0; side < kSides; ++side) {
      const double phi = 2 * M_PI * side / kSides;
      const Vec3 w = lr * std::cos(phi) + lu * std::sin(phi);
      const Vec3 n = w * c - a * s;
      hs.push_back({n, dot(n, l.position)});
    }
    hs.push_back({a, L + dot(a, l.position)});  // cap: axial distance <= L bounds the sector of radius L
    double lo = 0, hi = 0;
    if (!depthExtremes(hs, f.fwd, lo, hi)) continue;  // this cone is outside the frustum
    lo -= e_f;
    hi -= e_f;
    z_lo = any ? std::min(z_lo, lo) : lo;
    z_hi = any ? std::max(z_hi, hi) : hi;
    any = true;
  }
  ShaftsRange r = range;
  if (!any) {
    r.z_far = r.z_near;  // empty: no plane carries light
  } else {
    r.z_near = std::max(range.z_near, z_lo);
    r.z_far = std::min(range.z_far, std::max(z_hi, r.z_near));
  }
  // Tighter table ranges for the clipped planes (t <= z_far / cos θ_corner; s <= |lamp - eye| + t).
  const k::real3 corner = f.ray(0, 0, cam.width, cam.height);
  r.t_max = std::max(r.z_far, 2 * range.z_near) / k::dot(corner, r3(f.fwd));
  r.s_max = r.t_max;
  for (const auto& l : scene.spotlights) r.s_max = std::max(r.s_max, length(l.position - cam.position) + r.t_max);
  return r;
}

Image renderShaftsReference(const Scene& scene, int steps, const ShaftsRange* range_in) {
  if (!scene.air.present) throw RuntimeError("the shafts reference needs an [air] table");
  if (steps < 1) throw RuntimeError("--steps must be at least 1");
  requireSupported(scene);
  const ShaftsRange range = range_in ? *range_in : shaftsRange(scene);
  const CameraDesc& cam = scene.camera;
  const CameraFrame f = cameraFrame(cam);
  const std::vector<Lamp> lamps = makeLamps(scene);
  const double rho = scene.air.density, sigma_t = scene.air.density * scene.air.extinction;
  const int use_hg = scene.air.phase == AirDesc::Phase::HenyeyGreenstein;
  const double hg_g = scene.air.g;
  std::vector<k::real3> albedo;
  for (const auto& o : scene.objects) albedo.push_back(r3(objectAlbedoRgb(o)));

  Image img;
  img.resize(cam.width, cam.height, 3);
  img.channel_names = {"R", "G", "B"};
  const k::real3 eye = r3(cam.position);
  tbb::parallel_for(0, cam.height, [&](int y) {
    for (int x = 0; x < cam.width; ++x) {
      const k::real3 d = f.ray(x + 0.5, y + 0.5, cam.width, cam.height);
      const double cos_t = k::dot(d, r3(f.fwd));
      k::real3 result{0, 0, 0};
      double t_end = range.z_far / cos_t;
      const Hit hit = sceneHit(scene, eye, d, 0.0, 1e30);
      if (hit.index >= 0) {
        const k::real3 P = eye + hit.t * d;
        k::real3 Io{0, 0, 0};
        for (const Lamp& L : lamps) {
          const k::real3 to_lamp = L.pos - P;
          const double s = k::length(to_lamp);
          const k::real3 wl = to_lamp / std::max(s, 1e-300);
          const double cos_n = k::dot(hit.normal, wl);
          if (cos_n <= 0) continue;
          const k::real3 e = L.emission(P);
          if (e.x + e.y + e.z <= 0) continue;
          const double eps = 1e-7 * std::max(1.0, hit.t);
          if (sceneHit(scene, P + eps * hit.normal, wl, 0.0, s - 2 * eps).index >= 0) continue;
          const double sc = std::max(s, kShaftsLampRadius);
          Io = Io + e * (cos_n * std::exp(-sigma_t * s) / (sc * sc));
        }
        result = Io * albedo[hit.index] * (std::exp(-sigma_t * hit.t) / M_PI);  // 001 eq. 1
        t_end = std::min(t_end, hit.t);
      }
      // 001 eq. 2 by midpoint steps over the same depth range the planes cover.
      const double t0 = range.z_near / cos_t;
      if (t_end > t0) {
        const double dt = (t_end - t0) / steps;
        for (int i = 0; i < steps; ++i) {
          const double t = t0 + (i + 0.5) * dt;
          const k::real3 P = eye + t * d;
          for (const Lamp& L : lamps) {
            const k::real3 e = L.emission(P);
            if (e.x + e.y + e.z <= 0) continue;
            const k::real3 w = P - L.pos;
            const double s = k::length(w);
            if (!scene.objects.empty() && sceneHit(scene, P, -(w / s), 0.0, s).index >= 0) continue;  // H = 0
            const double cos_alpha = s > 0 ? k::dot(w, -d) / s : 1.0;
            const double g = k::shafts_phase_fn(cos_alpha, use_hg, hg_g) *
                             k::shafts_h(s, t, rho, sigma_t, kShaftsLampRadius);  // 001 eq. 3
            result = result + e * (g * dt);
          }
        }
      }
      img.at(x, y, 0) = static_cast<float>(result.x);
      img.at(x, y, 1) = static_cast<float>(result.y);
      img.at(x, y, 2) = static_cast<float>(result.z);
    }
  });
  return img;
}

namespace {

// Adaptive Simpson on [a, b] to relative tolerance (double).
template <class Fn>
double adaptiveSimpson(Fn f, double a, double b, double fa, double fm, double fb, double whole, double tol, int depth) {
  const double m = 0.5 * (a + b), lm = 0.5 * (a + m), rm = 0.5 * (m + b);
  const double flm = f(lm), frm = f(rm);
  const double left = (m - a) / 6 * (fa + 4 * flm + fm), right = (b - m) / 6 * (fm + 4 * frm + fb);
  const double delta = left + right - whole;
  if (depth <= 0 || std::fabs(delta) <= 15 * tol) return left + right + delta / 15;
  return adaptiveSimpson(f, a, m, fa, flm, fm, left, tol / 2, depth - 1) +
         adaptiveSimpson(f, m, b, fm, frm, fb, right, tol / 2, depth - 1);
}

}  // namespace

namespace {

// ∫_a^b f by adaptive Simpson to ~1e-13 relative of the integral's magnitude.
template <class Fn>
double integrate(Fn f, double a, double b) {
  if (b <= a) return 0;
  double coarse = 0;  // magnitude estimate for the tolerance (64-panel midpoint rule)
  for (int i = 0; i < 64; ++i) coarse += std::fabs(f(a + (i + 0.5) * (b - a) / 64)) * (b - a) / 64;
  const double fa = f(a), fb = f(b), fm = f(0.5 * (a + b));
  const double whole = (b - a) / 6 * (fa + 4 * fm + fb);
  return adaptiveSimpson(f, a, b, fa, fm, fb, whole, 1e-13 * std::max(coarse, 1e-300), 50);
}

}  // namespace

double sunF(double u, double v) {
  // exp(-u tan ξ) -> 0 as ξ -> π/2 (u > 0); for u = 0 the integrand is 1.
  auto f = [u](double xi) { return xi >= M_PI / 2 ? (u > 0 ? 0.0 : 1.0) : std::exp(-u * std::tan(xi)); };
  return integrate(f, 0, v);
}

double sunAirlight(double sigma_s, double sigma_t, double I0, double D, double gamma, double T) {
  const double sg = std::sin(gamma), cg = std::cos(gamma);
  const double A1 = sigma_t * D * sg;
  const double v1 = M_PI / 4 + 0.5 * std::atan((T - D * cg) / (D * sg));
  // A0 [F(A1, v1) - F(A1, γ/2)] as one integral over [γ/2, v1] with exp(-σt D cos γ) inside: the
  // difference of two F's cancels, and exp(-σt D cos γ) overflows for a light behind the eye.
  const double c = -sigma_t * D * cg;
  auto f = [&](double xi) { return xi >= M_PI / 2 ? (A1 > 0 ? 0.0 : std::exp(c)) : std::exp(c - A1 * std::tan(xi)); };
  return sigma_s * I0 / (2 * M_PI * D * sg) * integrate(f, gamma / 2, v1);
}

}  // namespace seasim
