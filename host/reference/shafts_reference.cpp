#include "reference/shafts_reference.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "geometry/shafts_geometry_k.h"
#include "io/image_io.h"
#include "io/tonemap.h"
#include "math/kernel_math.h"
#include "spectral/lamp_spectrum.h"
#include "util/error.h"

namespace seasim {

namespace k = kmath_d;

namespace {

k::real3 r3(Vec3 v) { return toReal3(v); }

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
    lamp.color = r3(shaftsLampRgb(l, scene.spectral, scene.files.get()));  // spectral/lamp_spectrum.h
    lamp.cos_cone = std::cos(l.cone);
    lamp.cos_inner = std::cos(std::max(0.0, l.cone - l.falloff));
    lamp.tan_cone = std::tan(l.cone);
    if (!l.light_map.empty()) {
      lamp.map = loadLightMap(l.light_map, scene.files.get());
      lamp.has_map = true;
    }
    lamps.push_back(std::move(lamp));
  }
  return lamps;
}

}  // namespace

Image renderShaftsReference(const Scene& scene, int steps) {
  if (!scene.air.present) throw RuntimeError("the shafts reference needs an [air] table");
  if (steps < 1) throw RuntimeError("--steps must be at least 1");
  requireShaftsSupported(scene);
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
      const k::real3 d = r3(f.ray(x + 0.5, y + 0.5, cam.width, cam.height));
      k::real3 result{0, 0, 0};
      double t_end = std::numeric_limits<double>::infinity();
      const ShaftsHitK hit = shaftsSceneHitK(scene, eye, d, 0.0, 1e30);
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
          if (shaftsSceneHitK(scene, P + eps * hit.normal, wl, 0.0, s - 2 * eps).index >= 0) continue;
          const double sc = std::max(s, kShaftsLampRadius);
          Io = Io + e * (cos_n * std::exp(-sigma_t * s) / (sc * sc));
        }
        result = Io * albedo[hit.index] * (std::exp(-sigma_t * hit.t) / M_PI);  // 001 eq. 1
        t_end = std::min(t_end, hit.t);
      }
      // 001 eq. 2, lamp by lamp, over the cone's part of [0, t_end]: t = a + r tan φ maps it to a finite
      // φ interval (t = ∞ is φ = π/2) with dt = r sec²φ dφ, and the integrand g dt/dφ is bounded
      // (g ~ 1/s² = 1/(r² sec²φ) when h >= r). Midpoint steps in φ never sample t = ∞.
      for (const Lamp& L : lamps) {
        double ta = 0, tb = 0;
        if (!k::shafts_cone_interval(eye, d, L.pos, L.dir, L.cos_cone, &ta, &tb)) continue;
        if (tb >= SHAFTS_T_INF) tb = std::numeric_limits<double>::infinity();
        tb = std::min(tb, t_end);
        if (!(tb > ta)) continue;
        double a = 0, h = 0;
        k::shafts_closest_approach(eye, d, L.pos, &a, &h);
        const double r = std::max(h, kShaftsLampRadius);
        const double phi_a = std::atan((ta - a) / r);
        const double phi_b = std::isinf(tb) ? M_PI / 2 : std::atan((tb - a) / r);
        const double dphi = (phi_b - phi_a) / steps;
        for (int i = 0; i < steps; ++i) {
          const double phi = phi_a + (i + 0.5) * dphi;
          const double tan_phi = std::tan(phi);
          const double t = a + r * tan_phi;
          const k::real3 P = eye + t * d;
          const k::real3 e = L.emission(P);
          if (e.x + e.y + e.z <= 0) continue;
          const k::real3 w = P - L.pos;
          const double s = k::length(w);
          if (s > 0 && !scene.objects.empty() && shaftsSceneHitK(scene, P, -(w / s), 0.0, s).index >= 0) continue;  // H = 0
          const double cos_alpha = s > 0 ? k::dot(w, -d) / s : 1.0;
          const double g = k::shafts_phase_fn(cos_alpha, use_hg, hg_g) *
                           k::shafts_h(s, t, rho, sigma_t, kShaftsLampRadius);  // 001 eq. 3
          result = result + e * (g * r * (1 + tan_phi * tan_phi) * dphi);
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
