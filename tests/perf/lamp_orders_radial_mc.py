#!/usr/bin/env python3
"""lamp_orders_radial_mc.py — the lamps' orders model's radial weight W_n(s) = s² φ_n (per unit intensity)
against the exact one of an isotropic point source in an infinite HG medium, by Monte Carlo.

In optical units (σ_t = 1) order n's fluence is ω^n times that of a medium without absorption, so one walk
per g serves every water: photons leave the source isotropically, fly Exp(1) between collisions and turn by
HG(g); the (n+1)-th collision's radius, histogrammed in log-spaced bins and divided by the photon count and
the bin width, is the bin's mean of s² φ_n (collision estimator; σ_t = 1 makes collision density and
fluence equal). A cone lamp's sphere-averaged order-n fluence equals the isotropic source's of the same
power (the medium is rotation-invariant), so this checks W_n apart from the landing profile P_n.
The model (kernels/common/underwater_lamps_ms.h, uw_ms_weight): W_n = st e^{-ℓ} ℓ^n / n!, ℓ = τ st,
st = q_n^{-κ}, κ = quality.lamps_ms_kappa (0.6).
Usage: tests/perf/lamp_orders_radial_mc.py [photons, default 1000000]  (about 10 s per g per million)
Prints model / exact at τ = 0.1, 0.3, 1, 3 for orders 1–4 and g 0.5, 0.7, 0.9, 0.95.
"""
import math
import sys

import numpy as np

TAUS = [0.1, 0.3, 1.0, 3.0]
ORDERS = 4
EDGES = np.concatenate([[0.0], np.geomspace(1e-3, 400.0, 200)])


def exact_weights(g, photons, rng):
    """Bin means of s² φ_n for n = 0..ORDERS (rows) over EDGES (columns)."""
    table = np.zeros((ORDERS + 1, len(EDGES) - 1))
    chunk = 500000
    for start in range(0, photons, chunk):
        n = min(chunk, photons - start)
        pos = np.zeros((n, 3))
        d = rng.normal(size=(n, 3))
        d /= np.linalg.norm(d, axis=1, keepdims=True)
        for k in range(ORDERS + 1):
            pos += rng.exponential(1.0, n)[:, None] * d
            table[k] += np.histogram(np.sqrt(np.einsum("ij,ij->i", pos, pos)), bins=EDGES)[0]
            # Turn by HG(g) about d (its inverse CDF), uniform in azimuth.
            s = (1 - g * g) / (1 - g + 2 * g * rng.random(n))
            mu = np.clip((1 + g * g - s * s) / (2 * g), -1.0, 1.0)
            phi = 2 * np.pi * rng.random(n)
            axis = np.zeros_like(d)
            near_z = np.abs(d[:, 2]) < 0.9
            axis[near_z, 2] = 1.0
            axis[~near_z, 0] = 1.0
            t1 = np.cross(d, axis)
            t1 /= np.linalg.norm(t1, axis=1, keepdims=True)
            t2 = np.cross(d, t1)
            st = np.sqrt(np.maximum(0.0, 1 - mu * mu))
            d = mu[:, None] * d + (st * np.cos(phi))[:, None] * t1 + (st * np.sin(phi))[:, None] * t2
            d /= np.linalg.norm(d, axis=1, keepdims=True)
    return table / (photons * np.diff(EDGES)[None, :])


def model_weight(g, n, tau, kappa=0.6):
    q = sum(max(g, 0.0) ** k for k in range(n + 1)) / (n + 1)
    stretch = q ** (-kappa)
    path = tau * stretch
    return stretch * math.exp(-path) * path ** n / math.factorial(n)


def main():
    photons = int(sys.argv[1]) if len(sys.argv) > 1 else 1000000
    rng = np.random.default_rng(12345)
    centres = np.sqrt(EDGES[1:-1] * EDGES[2:])
    print("model / exact s² φ_n at τ = " + ", ".join(f"{t:g}" for t in TAUS) + f" ({photons} photons per g)")
    for g in [0.5, 0.7, 0.9, 0.95]:
        table = exact_weights(g, photons, rng)[:, 1:]
        cells = []
        for n in range(1, ORDERS + 1):
            ratios = [model_weight(g, n, t) / np.interp(math.log(t), np.log(centres), table[n]) for t in TAUS]
            cells.append(f"n {n}: " + " ".join(f"{r:.2f}" for r in ratios))
        print(f"g {g}: " + " | ".join(cells), flush=True)


if __name__ == "__main__":
    main()
