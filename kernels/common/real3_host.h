/* real3_host.h — C++ only: the OpenCL vector built-ins for the host's real3, so shared math reads the
 * same in both languages. Included by host/math/kernel_math.h inside each kmath namespace, after
 * `typedef <float|double> real;`. Never included by kernels (OpenCL has these natively). */
struct real3 {
  real x, y, z;
};
SEASIM_FN real3 operator+(real3 a, real3 b) { return real3{a.x + b.x, a.y + b.y, a.z + b.z}; }
SEASIM_FN real3 operator-(real3 a, real3 b) { return real3{a.x - b.x, a.y - b.y, a.z - b.z}; }
SEASIM_FN real3 operator-(real3 a) { return real3{-a.x, -a.y, -a.z}; }
SEASIM_FN real3 operator*(real3 a, real s) { return real3{a.x * s, a.y * s, a.z * s}; }
SEASIM_FN real3 operator*(real s, real3 a) { return real3{a.x * s, a.y * s, a.z * s}; }
SEASIM_FN real3 operator*(real3 a, real3 b) { return real3{a.x * b.x, a.y * b.y, a.z * b.z}; }
SEASIM_FN real3 operator/(real3 a, real s) { return real3{a.x / s, a.y / s, a.z / s}; }
SEASIM_FN real dot(real3 a, real3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
SEASIM_FN real3 cross(real3 a, real3 b) {
  return real3{a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
SEASIM_FN real length(real3 a) { return std::sqrt(dot(a, a)); }
SEASIM_FN real3 normalize(real3 a) { return a / length(a); }
SEASIM_FN real clamp(real x, real lo, real hi) { return x < lo ? lo : (x > hi ? hi : x); }
SEASIM_FN real mix(real a, real b, real t) { return a + (b - a) * t; }
SEASIM_FN real3 mix(real3 a, real3 b, real t) { return a + (b - a) * t; }
SEASIM_FN real3 exp(real3 a) { return real3{std::exp(a.x), std::exp(a.y), std::exp(a.z)}; }
using std::acos;
using std::atan2;
using std::cos;
using std::exp;
using std::expm1;
using std::fabs;
using std::fmax;
using std::fmin;
using std::log;
using std::log1p;
using std::pow;
using std::sin;
using std::sqrt;
