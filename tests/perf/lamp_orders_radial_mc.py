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
Then where the light lands: a pencil beam's order-n collisions binned by radius and by the angle ψ from
its axis give the landing density per unit solid angle at a distance, against the model's HG(h_n),
h_n = 1 - β (1 - g^n), β = quality.lamps_ms_spread (0.6), which does not depend on the distance.
Last, the in-scatter's angular factor at a point: the mean of p_g(d · e) over the pencil's photons there (d
their directions) for e towards the lamp (-r̂) and towards the axis (-ê_ψ), against the model's HG(g^{n+1})
about r̂ (order 1 outside the cone takes the edge line in the model instead).
Usage: tests/perf/lamp_orders_radial_mc.py [photons, default 1000000]  (about 10 s per g per million)
Prints model / exact W_n at τ = 0.1, 0.3, 1, 3 for orders 1–4 and g 0.5, 0.7, 0.9, 0.95, then the landing
densities at ψ = 30°, 60°, 90°, 135° for orders 1–3 at τ 0.2–0.4, 0.8–1.25 and 2.5–3.5, g 0.5 and 0.9.
"""
import math
import sys

import numpy as np

TAUS = [0.1, 0.3, 1.0, 3.0]
ORDERS = 4
EDGES = np.concatenate([[0.0], np.geomspace(1e-3, 400.0, 200)])


def turn(d, g, rng):
    """Each direction in d turned by HG(g) (its inverse CDF), uniform in azimuth."""
    n = len(d)
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
    return d / np.linalg.norm(d, axis=1, keepdims=True)


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
            d = turn(d, g, rng)
    return table / (photons * np.diff(EDGES)[None, :])


LANDING_TAUS = [0.2, 0.4, 0.8, 1.25, 2.5, 3.5]  # three shells: [0.2, 0.4), [0.8, 1.25), [2.5, 3.5)
LANDING_MU = np.linspace(-1.0, 1.0, 41)


def landing(g, photons, rng):
    """A pencil beam along +z: per order 1..3 and shell, the landing density per unit solid angle over ψ."""
    counts = np.zeros((4, len(LANDING_TAUS) - 1, len(LANDING_MU) - 1))
    pos = np.zeros((photons, 3))
    d = np.tile([0.0, 0.0, 1.0], (photons, 1))
    for k in range(4):
        pos += rng.exponential(1.0, photons)[:, None] * d
        r = np.linalg.norm(pos, axis=1)
        counts[k] += np.histogram2d(r, pos[:, 2] / np.maximum(r, 1e-12), bins=[LANDING_TAUS, LANDING_MU])[0]
        d = turn(d, g, rng)
    return counts / np.maximum(counts.sum(axis=2, keepdims=True), 1) / (2 * np.pi * np.diff(LANDING_MU))


def hg(g, mu):
    return (1 - g * g) / (4 * np.pi * (1 + g * g - 2 * g * mu) ** 1.5)


FACTOR_SHELLS = [(0.2, 0.4), (0.8, 1.25), (2.5, 3.5)]
FACTOR_CONES = [(40.0, 50.0), (85.0, 95.0)]


def angular_factor(g, photons, rng):
    """Per order 1..4, shell and cone of ψ: the photons' mean p_g(d · e) for e = -r̂ and e = -ê_ψ, and their count."""
    sums = np.zeros((5, len(FACTOR_SHELLS), len(FACTOR_CONES), 2))
    counts = np.zeros((5, len(FACTOR_SHELLS), len(FACTOR_CONES)))
    pos = np.zeros((photons, 3))
    d = np.tile([0.0, 0.0, 1.0], (photons, 1))
    for k in range(5):
        pos += rng.exponential(1.0, photons)[:, None] * d
        r = np.sqrt(np.einsum("ij,ij->i", pos, pos))
        r_hat = pos / np.maximum(r, 1e-12)[:, None]
        cos_psi = np.clip(r_hat[:, 2], -1.0, 1.0)
        sin_psi = np.sqrt(np.maximum(1 - cos_psi * cos_psi, 1e-12))
        e_psi = (r_hat * cos_psi[:, None] - np.array([0.0, 0.0, 1.0])) / sin_psi[:, None]
        psi = np.degrees(np.arccos(cos_psi))
        back = hg(g, -np.einsum("ij,ij->i", d, r_hat))
        side = hg(g, -np.einsum("ij,ij->i", d, e_psi))
        for a, (lo, hi) in enumerate(FACTOR_SHELLS):
            for b, (p0, p1) in enumerate(FACTOR_CONES):
                sel = (r >= lo) & (r < hi) & (psi >= p0) & (psi < p1)
                counts[k, a, b] += sel.sum()
                sums[k, a, b, 0] += back[sel].sum()
                sums[k, a, b, 1] += side[sel].sum()
        d = turn(d, g, rng)
    return sums / np.maximum(counts, 1)[..., None], counts


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
            exact = [np.interp(math.log(t), np.log(centres), table[n]) for t in TAUS]
            # No collision in reach (a high order near the source at too few photons): no ratio.
            cells.append(f"n {n}: " + " ".join(f"{model_weight(g, n, t) / e:.2f}" if e > 0 else "-"
                                               for t, e in zip(TAUS, exact)))
        print(f"g {g}: " + " | ".join(cells), flush=True)
    centres = 0.5 * (LANDING_MU[1:] + LANDING_MU[:-1])
    angles = [30, 60, 90, 135]
    picks = [int(np.argmin(abs(centres - math.cos(math.radians(a))))) for a in angles]
    print("landing density per sr at ψ = " + ", ".join(f"{a}°" for a in angles) + ": exact by shell, then HG(h_n), β = 0.6")
    for g in [0.5, 0.9]:
        dens = landing(g, photons, rng)
        for n in range(1, 4):
            h = 1 - 0.6 * (1 - g ** n)
            shells = [" ".join(f"{dens[n, j, p]:.3f}" for p in picks) for j in (0, 2, 4)]
            print(f"g {g} n {n}: τ 0.2–0.4 {shells[0]} | 0.8–1.25 {shells[1]} | 2.5–3.5 {shells[2]} | model "
                  + " ".join(f"{hg(h, centres[p]):.3f}" for p in picks), flush=True)
    print("model / exact angular factor towards the lamp | towards the axis, ψ 40–50° then 85–95°, by shell")
    for g in [0.5, 0.9]:
        factor, counts = angular_factor(g, photons, rng)
        for n in range(1, 5):
            model = (hg(g ** (n + 1), -1.0), hg(g ** (n + 1), 0.0))
            cells = []
            for a, (lo, hi) in enumerate(FACTOR_SHELLS):
                pair = [f"{model[0] / factor[n, a, b, 0]:.2f}|{model[1] / factor[n, a, b, 1]:.2f}"
                        if counts[n, a, b] >= 500 else "-|-" for b in range(len(FACTOR_CONES))]
                cells.append(f"τ {lo}–{hi}: " + " ".join(pair))
            print(f"g {g} n {n}: " + "  ".join(cells), flush=True)


if __name__ == "__main__":
    main()
