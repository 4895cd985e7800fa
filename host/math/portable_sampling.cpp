// portable_sampling.cpp — compiled with -ffp-contract=off (CMakeLists.txt): see the header for why
// every operation here is one IEEE-754 basic operation, frexp or ldexp.
#include "math/portable_sampling.h"

#include <cmath>
#include <limits>

namespace seasim {

namespace {

// ln 2 split so that k · kLn2Hi is exact for |k| < 2^11 (its low 21 bits are zero; fdlibm's split).
constexpr double kLn2Hi = 6.93147180369123816490e-01;
constexpr double kLn2Lo = 1.90821492927058770002e-10;
constexpr double kLog2E = 1.44269504088896338700e+00;
constexpr double kInvSqrt2Pi = 0.398942280401432677940;  // 1/sqrt(2π)
constexpr double kInf = std::numeric_limits<double>::infinity();

double normalPdf(double x) { return kInvSqrt2Pi * portableExp(-0.5 * x * x); }

// Q(t) = 1 − Φ(t) for t >= 2.5 by Laplace's continued fraction
//   Q(t) = φ(t) / (t + 1/(t + 2/(t + 3/(t + …)))),
// evaluated backwards from 120 levels: at t = 2.5 the truncation error is below 1e-15 relative
// (checked against erfc in long double), and it shrinks as t grows.
double upperTail(double t) {
  double f = t;
  for (int k = 120; k >= 1; --k) f = t + static_cast<double>(k) / f;
  return normalPdf(t) / f;
}

}  // namespace

std::uint64_t splitmix64(std::uint64_t x) {
  x += 0x9e3779b97f4a7c15ULL;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ULL;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebULL;
  return x ^ (x >> 31);
}

std::uint64_t nameHash(std::string_view name) {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  for (unsigned char c : name) {
    h ^= c;
    h *= 0x100000001b3ULL;
  }
  return h;
}

std::uint64_t drawBits(std::uint64_t seed, std::uint64_t item, std::uint64_t key, std::uint64_t component) {
  // Each word is mixed in after the previous ones have been spread over all 64 bits, so nearby
  // (seed, item) pairs give unrelated draws (seed 1 item 2 is not seed 2 item 1).
  std::uint64_t h = splitmix64(seed);
  h = splitmix64(h ^ item);
  h = splitmix64(h ^ key);
  return splitmix64(h ^ component);
}

double unitOpen(std::uint64_t bits) {
  return (static_cast<double>(bits >> 11) + 0.5) * 0x1.0p-53;
}

double portableExp(double x) {
  if (std::isnan(x)) return x;
  if (x > 709.8) return kInf;
  if (x < -745.2) return 0.0;
  // x = k ln2 + r, |r| <= ln2/2; e^x = 2^k e^r with e^r by its Taylor series (Horner, 20 terms:
  // the first omitted one is below 1e-25 for |r| <= 0.35).
  const double k = std::floor(x * kLog2E + 0.5);
  const double r = (x - k * kLn2Hi) - k * kLn2Lo;
  double sum = 1.0;
  for (int n = 20; n >= 1; --n) sum = 1.0 + r * sum / static_cast<double>(n);
  return std::ldexp(sum, static_cast<int>(k));
}

double portableLog(double x) {
  if (!(x > 0.0) || std::isinf(x)) return std::numeric_limits<double>::quiet_NaN();
  // x = m 2^e with m in [1/√2, √2); ln m = 2 atanh(s), s = (m − 1)/(m + 1), |s| <= 0.172, whose
  // odd series (13 terms) ends below 1e-19 relative. m − 1 is exact (Sterbenz).
  int e = 0;
  double m = std::frexp(x, &e);
  if (m < 0.70710678118654752440) {
    m *= 2.0;
    e -= 1;
  }
  const double f = m - 1.0;
  const double s = f / (2.0 + f);
  const double s2 = s * s;
  double series = 0.0;  // Σ_{n>=1} s^{2n} / (2n + 1)
  for (int n = 13; n >= 1; --n) series = s2 * (1.0 / static_cast<double>(2 * n + 1) + series);
  const double ln_m = 2.0 * s + 2.0 * s * series;
  const double de = static_cast<double>(e);
  return de * kLn2Hi + (ln_m + de * kLn2Lo);
}

double normalCdf(double x) {
  if (std::isnan(x)) return x;
  if (x <= -2.5) return upperTail(-x);
  if (x >= 2.5) return 1.0 - upperTail(x);
  // Φ(x) = 1/2 + φ(x) Σ_{n>=0} x^{2n+1} / (1·3·5···(2n+1)); all terms positive for x > 0, and the
  // cancellation for x > -2.5 costs under 3 digits.
  double term = x, sum = x;
  const double x2 = x * x;
  for (int n = 1; n < 200; ++n) {
    term *= x2 / static_cast<double>(2 * n + 1);
    sum += term;
    if (std::fabs(term) < 1e-17 * std::fabs(sum)) break;
  }
  return 0.5 + normalPdf(x) * sum;
}

double normalQuantile(double p) {
  if (!(p > 0.0)) return -kInf;
  if (!(p < 1.0)) return kInf;
  // Start: P. J. Acklam's rational approximation (relative error 1.15e-9), central and tail pieces.
  static constexpr double a[] = {-3.969683028665376e+01, 2.209460984245205e+02, -2.759285104469687e+02,
                                 1.383577518672690e+02,  -3.066479806614716e+01, 2.506628277459239e+00};
  static constexpr double b[] = {-5.447609879822406e+01, 1.615858368580409e+02, -1.556989798598866e+02,
                                 6.680131188771972e+01,  -1.328068155288572e+01};
  static constexpr double c[] = {-7.784894002430293e-03, -3.223964580411365e-01, -2.400758277161838e+00,
                                 -2.549732539343734e+00, 4.374664141464968e+00,  2.938163982698783e+00};
  static constexpr double d[] = {7.784695709041462e-03, 3.224671290700398e-01, 2.445134137142996e+00,
                                 3.754408661907416e+00};
  constexpr double kLow = 0.02425;
  double x;
  if (p < kLow || p > 1.0 - kLow) {
    const double q = std::sqrt(-2.0 * portableLog(p < kLow ? p : 1.0 - p));
    x = (((((c[0] * q + c[1]) * q + c[2]) * q + c[3]) * q + c[4]) * q + c[5]) /
        ((((d[0] * q + d[1]) * q + d[2]) * q + d[3]) * q + 1.0);
    if (p >= kLow) x = -x;
  } else {
    const double q = p - 0.5;
    const double r = q * q;
    x = (((((a[0] * r + a[1]) * r + a[2]) * r + a[3]) * r + a[4]) * r + a[5]) * q /
        (((((b[0] * r + b[1]) * r + b[2]) * r + b[3]) * r + b[4]) * r + 1.0);
  }
  // Two Halley steps on Φ(x) − p = 0 (cubic convergence: 1e-9 -> below rounding).
  for (int step = 0; step < 2; ++step) {
    const double pdf = normalPdf(x);
    if (!(pdf > 0.0)) break;
    const double u = (normalCdf(x) - p) / pdf;
    x = x - u / (1.0 + 0.5 * x * u);
  }
  return x;
}

double truncatedNormal(double u, double lo, double hi) {
  if (lo > 0.0) return -truncatedNormal(u, -hi, -lo);  // mirror into the lower tail
  const double pa = std::isinf(lo) ? 0.0 : normalCdf(lo);
  const double pb = std::isinf(hi) ? 1.0 : normalCdf(hi);
  const double x = normalQuantile(pa + u * (pb - pa));
  return x < lo ? lo : (x > hi ? hi : x);
}

double uniformIn(double u, double lo, double hi) {
  const double x = lo + u * (hi - lo);
  return x < lo ? lo : (x > hi ? hi : x);
}

double logUniformIn(double u, double lo, double hi) {
  const double a = portableLog(lo), b = portableLog(hi);
  const double x = portableExp(a + u * (b - a));
  return x < lo ? lo : (x > hi ? hi : x);
}

double normalIn(double u, double mean, double sd, double lo, double hi) {
  const double z = truncatedNormal(u, (lo - mean) / sd, (hi - mean) / sd);
  const double x = mean + sd * z;
  return x < lo ? lo : (x > hi ? hi : x);
}

long long integerIn(double u, long long lo, long long hi) {
  // hi − lo + 1 <= 2^53 (callers' bounds): the count and u · count are exact or correctly rounded.
  const double count = static_cast<double>(hi - lo) + 1.0;
  const long long k = static_cast<long long>(std::floor(u * count));
  return k > hi - lo ? hi : lo + k;
}

std::size_t weightedIndex(double u, const std::vector<double>& cumulative) {
  const double target = u * cumulative.back();
  for (std::size_t i = 0; i < cumulative.size(); ++i)
    if (target < cumulative[i]) return i;
  return cumulative.size() - 1;
}

}  // namespace seasim
