#!/usr/bin/env python3
"""plane_parallel_dom.py — an independent plane-parallel reference for the discrete-ordinates underwater model's
diffuse field: discrete ordinates for a homogeneous water layer under a flat Fresnel
surface, written apart from host/underwater/discrete_ordinates.cpp and sharing none of its shortcuts:

  - the exact Henyey-Greenstein phase averaged over azimuth numerically (no Legendre series, no delta-M),
    its quadrature mass error put on the diagonal (the forward peak);
  - Gauss-Legendre cosines per hemisphere (default 100), numpy's general eigen-solver on the 2N x 2N
    system (no symmetric reduction);
  - the unscattered beam exact (attenuated by c = a + b), the sun's beam and a uniform sky through Snell's
    window, the surface's Fresnel reflection (total internal reflection outside the window), a
    Lambertian bottom or none.

tests/unit/discrete_ordinates_test.cpp holds the C++ solver (16 streams, delta-M) to its numbers.
Needs numpy (the validation venv has it: make validate, or pip install numpy).

Usage: plane_parallel_dom.py A B G [--bottom H] [--albedo RHO] [--streams N] [--depths 0,5,10]
prints depth, E_d (with the beam), E_u and E_0 (scalar irradiance, with the beam) for the study's light:
sun 30 deg from the zenith refracted at n = 1.34, e_sun0 = 0.85 (horizontal, below the surface), a uniform
sky of radiance 0.05 above the surface.
"""
import argparse

import numpy as np
from numpy.polynomial.legendre import leggauss

IOR = 1.34


def fresnel(mu_w, n=IOR):
    """Unpolarised reflectance seen from the water at cosine mu_w; 1 under total internal reflection."""
    s_a = n * np.sqrt(np.maximum(1 - mu_w**2, 0))
    out = np.ones_like(mu_w)
    ok = s_a < 1
    ca, cw = np.sqrt(1 - s_a[ok] ** 2), mu_w[ok]
    rs = ((n * cw - ca) / (n * cw + ca)) ** 2
    rp = ((cw - n * ca) / (cw + n * ca)) ** 2
    out[ok] = 0.5 * (rs + rp)
    return out


def hg(cos_t, g):
    return (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * cos_t) ** 1.5)


def azimuth_average(mu_a, mu_b, g, n_phi=8192):
    """(1/2π) ∫ p_HG(μ μ' + √(1-μ²)√(1-μ'²) cos φ) dφ by the periodic trapezoid rule."""
    cphi = np.cos((np.arange(n_phi) + 0.5) * 2 * np.pi / n_phi)
    sb = np.sqrt(1 - mu_b**2)
    out = np.empty((len(mu_a), len(mu_b)))
    for i, m in enumerate(mu_a):
        ct = m * mu_b[:, None] + np.sqrt(1 - m * m) * sb[:, None] * cphi[None, :]
        out[i] = hg(np.clip(ct, -1, 1), g).mean(axis=1)
    return out


class Layer:
    def __init__(self, a, b, g, bottom, mu0, e_sun0, sky_radiance, albedo=0.35, streams=100):
        x, w = leggauss(streams)
        mu, w = 0.5 * (x + 1), 0.5 * w
        n = streams
        self.mu = np.concatenate([mu, -mu])
        self.w = np.concatenate([w, w])
        self.n, self.c, self.bottom, self.mu0 = n, a + b, bottom, mu0
        self.m = self.c / mu0
        p = azimuth_average(self.mu, self.mu, g)
        mass = (p * 2 * np.pi * self.w[None, :]).sum(1)
        p[np.arange(2 * n), np.arange(2 * n)] += (1 - mass) / (2 * np.pi * self.w)
        pb = azimuth_average(self.mu, np.array([mu0]), g)[:, 0]
        pb /= (pb * 2 * np.pi * self.w).sum()
        self.f0 = e_sun0 / mu0
        source = b * pb * self.f0
        B = -self.c * np.eye(2 * n) + b * p * (2 * np.pi * self.w)[None, :]
        lam, V = np.linalg.eig(B / self.mu[:, None])
        self.lam, self.V = lam.real, V.real
        self.zp = np.linalg.solve(B + self.m * np.diag(self.mu), -source)
        dn, up = np.arange(n), np.arange(n, 2 * n)
        R = fresnel(mu)
        T = np.where(R < 1, (1 - R) * IOR**2 * sky_radiance, 0.0)
        self.decay = self.lam < 0
        Vd = self.V
        if bottom > 0:
            e0 = np.where(self.decay, 1.0, np.exp(-np.abs(self.lam) * bottom))
            eH = np.where(self.decay, np.exp(-np.abs(self.lam) * bottom), 1.0)
            M = np.zeros((2 * n, 2 * n))
            r = np.zeros(2 * n)
            M[:n] = Vd[dn] * e0 - R[:, None] * Vd[up] * e0
            r[:n] = T - (self.zp[dn] - R * self.zp[up])
            flux = (2 * np.pi * w * mu)[None, :] @ (Vd[dn] * eH)
            M[n:] = Vd[up] * eH - albedo / np.pi * np.repeat(flux, n, 0)
            em = np.exp(-self.m * bottom)
            r[n:] = -(self.zp[up] * em - albedo / np.pi * ((2 * np.pi * w * mu) @ self.zp[dn] * em + mu0 * self.f0 * em))
            self.C = np.linalg.solve(M, r)
        else:
            Vn = Vd[:, self.decay]
            M = Vn[dn] - R[:, None] * Vn[up]
            self.C = np.zeros(2 * n)
            self.C[self.decay] = np.linalg.solve(M, T - (self.zp[dn] - R * self.zp[up]))

    def radiance(self, y):
        if self.bottom > 0:
            with np.errstate(over="ignore"):  # np.where evaluates the branch it does not take
                e = np.where(self.decay, np.exp(self.lam * y), np.exp(self.lam * (y - self.bottom)))
        else:
            e = np.where(self.decay, np.exp(np.minimum(self.lam * y, 0)), 0.0)
        return self.V @ (self.C * e) + self.zp * np.exp(-self.m * y)

    def irradiance(self, y):
        L = self.radiance(y)
        n = self.n
        fw = 2 * np.pi * self.w[:n] * self.mu[:n]
        beam = self.f0 * np.exp(-self.c * y / self.mu0)
        return fw @ L[:n] + self.mu0 * beam, fw @ L[n:], (2 * np.pi * self.w) @ L + beam

    def asymptotic_k(self):
        return -self.lam[self.decay].max()


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("a", type=float)
    ap.add_argument("b", type=float)
    ap.add_argument("g", type=float)
    ap.add_argument("--bottom", type=float, default=0.0)
    ap.add_argument("--albedo", type=float, default=0.35)
    ap.add_argument("--streams", type=int, default=100)
    ap.add_argument("--depths", default="0,5,10,20")
    args = ap.parse_args()
    mu0 = np.cos(np.arcsin(np.sin(np.radians(30)) / IOR))
    layer = Layer(args.a, args.b, args.g, args.bottom, mu0, 0.85, 0.05, args.albedo, args.streams)
    print(f"# a {args.a} b {args.b} g {args.g} bottom {args.bottom} m, K_inf {layer.asymptotic_k():.5f} 1/m")
    print("depth_m,E_d,E_u,E_0")
    for y in (float(v) for v in args.depths.split(",")):
        e_d, e_u, e_0 = layer.irradiance(y)
        print(f"{y:g},{e_d:.6g},{e_u:.6g},{e_0:.6g}")


if __name__ == "__main__":
    main()
