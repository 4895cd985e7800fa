#include "radiometry/canonical_problems.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <sstream>
#include <tuple>

#include "radiometry/light_profile_mc.h"
#include "util/error.h"

namespace seasim {
namespace {
constexpr double kPi = 3.14159265358979323846;
}

std::vector<CanonicalValue> loadCanonicalValues(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw RuntimeError(path + ": cannot open the canonical problems' values");
  std::vector<CanonicalValue> out;
  std::string line;
  int n = 0;
  while (std::getline(in, line)) {
    ++n;
    if (n == 1 || line.empty()) continue;  // header
    std::stringstream ss(line);
    std::string cell[6];
    for (std::string& c : cell) std::getline(ss, c, ',');
    CanonicalValue v;
    try {
      v.problem = std::stoi(cell[0]);
      v.albedo = std::stod(cell[1]);
      v.optical_depth = std::stod(cell[2]);
      v.quantity = cell[3];
      v.mean = std::stod(cell[4]);
      v.cv = std::stod(cell[5]);
    } catch (const std::exception&) {
      throw RuntimeError(path + ":" + std::to_string(n) + ": expected problem,albedo,optical_depth,quantity,mean,cv");
    }
    if (v.quantity != "Ed" && v.quantity != "E0u" && v.quantity != "Lu")
      throw RuntimeError(path + ":" + std::to_string(n) + ": quantity must be Ed, E0u or Lu, got '" + v.quantity + "'");
    out.push_back(v);
  }
  return out;
}

PlaneParallelWater canonicalWater(int problem, double albedo) {
  PlaneParallelWater w;
  w.a = 1 - albedo;
  w.b = albedo;
  w.ior = 1.34;
  w.sun_zenith = 60 * kPi / 180;
  w.sun_irradiance = 1;
  w.sky_irradiance = 0;
  if (problem == 6) {
    w.bottom_depth = 5;
    w.bottom_albedo = 0.5;
  }
  return w;
}

PhaseFunction canonicalPhase(int problem) {
  return problem == 1 ? PhaseFunction::rayleighLike() : PhaseFunction::petzold();
}

double canonicalTolerance(const CanonicalValue& v) { return std::max(v.cv, v.quantity == "Lu" ? 0.10 : 0.02); }

std::vector<CanonicalResult> solveCanonicalProblems(const std::vector<CanonicalValue>& published, int streams,
                                                    double* seconds) {
  // One solve per (problem, albedo) at all its depths.
  std::map<std::pair<int, double>, std::vector<double>> depths;
  for (const CanonicalValue& v : published) depths[{v.problem, v.albedo}].push_back(v.optical_depth);
  const PhaseFunction rayleigh = PhaseFunction::rayleighLike(), petzold = PhaseFunction::petzold();
  std::map<std::pair<int, double>, LightProfile> solved;
  const auto t0 = std::chrono::steady_clock::now();
  for (auto& [key, zs] : depths) {
    std::sort(zs.begin(), zs.end());
    zs.erase(std::unique(zs.begin(), zs.end()), zs.end());
    solved[key] = solveLightProfile(canonicalWater(key.first, key.second), key.first == 1 ? rayleigh : petzold, zs,
                                    streams);
  }
  if (seconds) *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::vector<CanonicalResult> out;
  for (const CanonicalValue& v : published) {
    const LightProfile& p = solved.at({v.problem, v.albedo});
    const auto row = std::find_if(p.rows.begin(), p.rows.end(), [&](const LightAtDepth& r) { return r.depth == v.optical_depth; });
    CanonicalResult r;
    r.published = v;
    r.computed = v.quantity == "Ed" ? row->e_d : v.quantity == "E0u" ? row->e_0u : row->l_u;
    r.relative_error = r.computed / v.mean - 1;
    r.pass = std::abs(r.relative_error) <= canonicalTolerance(v);
    out.push_back(r);
  }
  return out;
}

std::vector<CanonicalResult> monteCarloCanonicalProblems(const std::vector<CanonicalValue>& published,
                                                         long long photons, double* seconds) {
  std::map<std::pair<int, double>, std::vector<double>> depths;
  for (const CanonicalValue& v : published) depths[{v.problem, v.albedo}].push_back(v.optical_depth);
  const PhaseFunction rayleigh = PhaseFunction::rayleighLike(), petzold = PhaseFunction::petzold();
  std::map<std::pair<int, double>, LightProfileMc> solved;
  double total = 0;
  for (auto& [key, zs] : depths) {
    std::sort(zs.begin(), zs.end());
    zs.erase(std::unique(zs.begin(), zs.end()), zs.end());
    MonteCarloSettings s;
    s.photons = photons;
    solved[key] = solveLightProfileMonteCarlo(canonicalWater(key.first, key.second), key.first == 1 ? rayleigh : petzold,
                                              zs, s);
    total += solved[key].seconds;
  }
  if (seconds) *seconds = total;
  std::vector<CanonicalResult> out;
  for (const CanonicalValue& v : published) {
    const LightProfileMc& p = solved.at({v.problem, v.albedo});
    size_t k = 0;
    while (p.mean.rows[k].depth != v.optical_depth) ++k;
    const LightAtDepth &m = p.mean.rows[k], &e = p.standard_error[k];
    CanonicalResult r;
    r.published = v;
    r.computed = v.quantity == "Ed" ? m.e_d : v.quantity == "E0u" ? m.e_0u : m.l_u;
    r.standard_error = v.quantity == "Ed" ? e.e_d : v.quantity == "E0u" ? e.e_0u : e.l_u;
    r.relative_error = r.computed / v.mean - 1;
    r.resolved = r.standard_error <= canonicalTolerance(v) * v.mean;
    r.pass = r.resolved && std::abs(r.computed - v.mean) <= canonicalTolerance(v) * v.mean + 3 * r.standard_error;
    out.push_back(r);
  }
  return out;
}

std::string canonicalTableMarkdown(const std::vector<CanonicalResult>& results, const std::string& solver,
                                   double seconds) {
  std::string s;
  char buf[320];
  int passed = 0, judged = 0;
  bool mc = false;
  for (const CanonicalResult& r : results) {
    passed += r.pass;
    judged += r.resolved;
    mc = mc || r.standard_error > 0;
  }
  std::snprintf(buf, sizeof buf, "%s (all problems: %.3f s). %d of %d values within the rule", solver.c_str(), seconds,
                passed, judged);
  s += buf;
  if (judged < static_cast<int>(results.size()))
    s += " (" + std::to_string(results.size() - judged) + " not judged: standard error above the tolerance, n/r)";
  s += ".\n\n";
  s += std::string("| problem | albedo | c z | quantity | published mean | codes' cv | seasim |") +
       (mc ? " standard error |" : "") + " seasim/mean - 1 | tolerance | pass |\n";
  s += std::string("|---|---|---|---|---|---|---|") + (mc ? "---|" : "") + "---|---|---|\n";
  for (const CanonicalResult& r : results) {
    const CanonicalValue& v = r.published;
    std::string se;
    if (mc) {
      std::snprintf(buf, sizeof buf, " %.1f %% |", r.computed > 0 ? 100 * r.standard_error / r.computed : 100.0);
      se = buf;
    }
    std::snprintf(buf, sizeof buf, "| %d | %g | %g | %s | %.4g | %.1f %% | %.4g |%s %+.1f %% | %.0f %% | %s |\n",
                  v.problem, v.albedo, v.optical_depth, v.quantity.c_str(), v.mean, 100 * v.cv, r.computed, se.c_str(),
                  100 * r.relative_error, 100 * canonicalTolerance(v), !r.resolved ? "n/r" : r.pass ? "yes" : "**no**");
    s += buf;
  }
  return s;
}

}  // namespace seasim
