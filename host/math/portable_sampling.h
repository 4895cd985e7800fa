// portable_sampling.h — random draws that are bit-identical on every machine, for dataset jobs
// (jobs/job_sampling.h): "the same seed gives the same items on any machine and any shard split".
//
// Why not <random>: std::mt19937_64 is specified bit for bit, but the distributions on top of it
// (uniform_real_distribution, normal_distribution) are not, and libstdc++, libc++ and MSVC give
// different values. Nor std::exp/std::log/std::erfc: libms differ in the last bits. So:
//   - the generator is a counter-based hash: every draw is splitmix64's output function (Steele,
//     Lea & Flood, "Fast splittable pseudorandom number generators", OOPSLA 2014; the finaliser of
//     Java's SplittableRandom) applied to a key made of (seed, item index, key name, component), so
//     a draw depends on nothing drawn before it: an item's values do not depend on which shard
//     renders it, or on how many keys the job samples;
//   - a draw becomes a double in (0, 1) as (k + 1/2) 2^-53 from its top 53 bits (never 0 or 1);
//   - the maths after it (exp, log, the normal CDF and its inverse) is written here with + - * /
//     and sqrt only, each correctly rounded by IEEE 754, in a file compiled with
//     -ffp-contract=off (CMakeLists.txt) so no compiler fuses a*b+c differently on another CPU.
//     frexp/ldexp are exact. Accuracy (tests/unit/portable_sampling_test.cpp, against libm in
//     long double): exp, log within 2e-16 relative (exp: normal results; subnormal ones within
//     two steps); normalCdf within 6e-14 relative for x in [-37, 0] (series for |x| < 2.5, the
//     Laplace continued fraction beyond) and 5e-16 absolute above; normalQuantile within 1e-13
//     relative in p for p >= 1e-100 and 3e-13 below (Acklam's rational start, two Halley steps).
#pragma once
#include <cstddef>
#include <cstdint>
#include <string_view>
#include <vector>

namespace seasim {

// splitmix64's output function: a bijection of 64-bit words that mixes every bit into every bit.
std::uint64_t splitmix64(std::uint64_t x);
// A key name as a 64-bit word: FNV-1a 64 (offset basis 14695981039346656037). Its own copy, not
// util/hash.h's checksum hash, so that no change there can change a dataset's draws.
std::uint64_t nameHash(std::string_view name);
// The draw for (seed, item, key, component): a chain of splitmix64 over the four words.
std::uint64_t drawBits(std::uint64_t seed, std::uint64_t item, std::uint64_t key, std::uint64_t component);
// The top 53 bits as a double in (0, 1): (k + 0.5) / 2^53.
double unitOpen(std::uint64_t bits);

// exp and natural log from + - * / only (see above). portableExp: 0 below -745.2, +inf above 709.8.
// portableLog: x > 0 and finite (else NaN; callers check first).
double portableExp(double x);
double portableLog(double x);

// The standard normal CDF Φ(x) and its inverse Φ⁻¹(p), p in (0, 1).
double normalCdf(double x);
double normalQuantile(double p);

// A draw of the standard normal truncated to [lo, hi] (lo < hi; either may be infinite, but the
// nearer bound must lie within 30 of 0, else the interval holds no representable mass) from u in
// (0, 1) by the inverse CDF: Φ⁻¹(Φ(lo) + u (Φ(hi) − Φ(lo))). An interval on the positive side is
// mirrored to the negative one first, where Φ keeps its relative precision. Clamped to [lo, hi].
double truncatedNormal(double u, double lo, double hi);

// The distributions of a dataset job, each from one u in (0, 1) by its inverse CDF, the result
// clamped to its bounds (a rounding can never step outside them):
double uniformIn(double u, double lo, double hi);     // lo + u (hi − lo)
double logUniformIn(double u, double lo, double hi);  // exp(ln lo + u (ln hi − ln lo)); 0 < lo
// mean + sd · truncatedNormal(u, (lo − mean)/sd, (hi − mean)/sd); sd > 0, infinite bounds allowed.
double normalIn(double u, double mean, double sd, double lo, double hi);
long long integerIn(double u, long long lo, long long hi);  // each of lo..hi with probability 1/(hi − lo + 1)
// The index i with cumulative[i−1] <= u · total < cumulative[i] (cumulative: running sums of
// positive weights, total = the last one).
std::size_t weightedIndex(double u, const std::vector<double>& cumulative);

}  // namespace seasim
