// fourflow_reference.cpp — multiple-shooting solve of the four-flow ODEs (see the header).
#include "reference/fourflow_reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace seasim {
namespace {

using Vec4 = std::array<double, 4>;
using Mat4 = std::array<Vec4, 4>;  // row-major

// 003 eq. 4 as y' = M y, y = (G+, G-, F+, F-).
Mat4 odeMatrix(const FourFlowBvp& p) {
  const double l = p.k + p.S1 + p.S2;
  Mat4 M{};
  M[0] = {-l, 0, 0, 0};
  M[1] = {0, l, 0, 0};
  M[2] = {p.S1, p.S2, -(p.k + p.S), p.S};
  M[3] = {-p.S2, -p.S1, -p.S, p.k + p.S};
  return M;
}

Vec4 apply(const Mat4& M, const Vec4& y) {
  Vec4 r{};
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) r[i] += M[i][j] * y[j];
  return r;
}

// Φ = the RK4 propagator over length L (columns: the images of the unit vectors).
Mat4 propagator(const Mat4& M, double L, int steps) {
  const double h = L / steps;
  Mat4 phi{};
  for (int c = 0; c < 4; ++c) {
    Vec4 y{};
    y[c] = 1;
    for (int s = 0; s < steps; ++s) {
      Vec4 k1 = apply(M, y), y2{}, y3{}, y4{};
      for (int i = 0; i < 4; ++i) y2[i] = y[i] + 0.5 * h * k1[i];
      Vec4 k2 = apply(M, y2);
      for (int i = 0; i < 4; ++i) y3[i] = y[i] + 0.5 * h * k2[i];
      Vec4 k3 = apply(M, y3);
      for (int i = 0; i < 4; ++i) y4[i] = y[i] + h * k3[i];
      Vec4 k4 = apply(M, y4);
      for (int i = 0; i < 4; ++i) y[i] += h / 6 * (k1[i] + 2 * k2[i] + 2 * k3[i] + k4[i]);
    }
    for (int r = 0; r < 4; ++r) phi[r][c] = y[r];
  }
  return phi;
}

// A square banded system (lower bandwidth kl, upper ku) solved by Gaussian elimination with partial
// pivoting; row swaps widen U to kl + ku, so each row stores columns r - kl … r + kl + ku.
class BandedSystem {
 public:
  BandedSystem(int n, int kl, int ku) : n_(n), kl_(kl), ku_(ku), width_(2 * kl + ku + 1), a_(size_t(n) * width_), b_(n) {}
  double& at(int r, int c) {
    if (c < r - kl_ || c > r + kl_ + ku_) throw std::logic_error("fourflow reference: entry outside the band");
    return a_[size_t(r) * width_ + (c - r + kl_)];
  }
  double& rhs(int r) { return b_[r]; }

  std::vector<double> solve() {
    for (int j = 0; j < n_; ++j) {
      const int last = std::min(n_ - 1, j + kl_);
      int piv = j;
      for (int r = j + 1; r <= last; ++r)
        if (std::fabs(at(r, j)) > std::fabs(at(piv, j))) piv = r;
      if (at(piv, j) == 0) throw std::runtime_error("fourflow reference: singular boundary-value system");
      const int cmax = std::min(n_ - 1, j + kl_ + ku_);
      if (piv != j) {
        for (int c = j; c <= cmax; ++c) std::swap(at(j, c), at(piv, c));
        std::swap(b_[j], b_[piv]);
      }
      for (int r = j + 1; r <= last; ++r) {
        const double f = at(r, j) / at(j, j);
        if (f == 0) continue;
        for (int c = j; c <= cmax; ++c) at(r, c) -= f * at(j, c);
        b_[r] -= f * b_[j];
      }
    }
    std::vector<double> x(n_);
    for (int r = n_ - 1; r >= 0; --r) {
      double s = b_[r];
      const int cmax = std::min(n_ - 1, r + kl_ + ku_);
      for (int c = r + 1; c <= cmax; ++c) s -= at(r, c) * x[c];
      x[r] = s / at(r, r);
    }
    return x;
  }

 private:
  int n_, kl_, ku_, width_;
  std::vector<double> a_, b_;
};

}  // namespace

FourFlowProfile solveFourFlowBvp(const FourFlowBvp& p, double max_segment, int rk4_steps) {
  if (!(p.tau0 >= 0) || !(max_segment > 0) || rk4_steps < 1) throw std::invalid_argument("fourflow reference: bad arguments");
  const int m = std::max(1, int(std::ceil(p.tau0 / max_segment)));
  const double L = p.tau0 / m;
  const Mat4 phi = propagator(odeMatrix(p), L, rk4_steps);

  // Unknown 4i + j is component j of y at node i. Rows: 2 surface rows, 4 rows per segment, 2 bottom
  // rows, so row r touches columns r - 5 … r + 5.
  const int n = 4 * (m + 1);
  BandedSystem sys(n, 5, 5);
  enum { GP = 0, GM = 1, FP = 2, FM = 3 };
  // 003 eq. 7, surface: G+(0) - R~dd G-(0) = T_dd E_sun; F+(0) - R~df G-(0) - R~ff F-(0) = T_df E_sun + T_ff E_sky.
  sys.at(0, GP) = 1;
  sys.at(0, GM) = -p.Rw_dd;
  sys.rhs(0) = p.T_dd * p.e_sun;
  sys.at(1, FP) = 1;
  sys.at(1, GM) = -p.Rw_df;
  sys.at(1, FM) = -p.Rw_ff;
  sys.rhs(1) = p.T_df * p.e_sun + p.T_ff * p.e_sky;
  for (int i = 0; i < m; ++i) {
    for (int j = 0; j < 4; ++j) {
      const int r = 2 + 4 * i + j;
      sys.at(r, 4 * (i + 1) + j) = 1;
      for (int c = 0; c < 4; ++c) sys.at(r, 4 * i + c) = -phi[j][c];
    }
  }
  // 003 eq. 7, bottom: G-(τ0) - R^dd G+(τ0) = 0; F-(τ0) - R^df G+(τ0) - R^ff F+(τ0) = 0.
  const int b = 4 * m, r0 = n - 2;
  sys.at(r0, b + GM) = 1;
  sys.at(r0, b + GP) = -p.Rb_dd;
  sys.at(r0 + 1, b + FM) = 1;
  sys.at(r0 + 1, b + GP) = -p.Rb_df;
  sys.at(r0 + 1, b + FP) = -p.Rb_ff;

  const std::vector<double> x = sys.solve();
  FourFlowProfile out;
  out.tau.resize(m + 1);
  out.flow.resize(m + 1);
  for (int i = 0; i <= m; ++i) {
    out.tau[i] = (i == m) ? p.tau0 : i * L;
    for (int j = 0; j < 4; ++j) out.flow[i][j] = x[4 * i + j];
  }
  return out;
}

}  // namespace seasim
