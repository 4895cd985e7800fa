#!/usr/bin/env python3
"""lamp_order1_point_source.py — the lamps' orders model's radial weight of order 1 against the exact
single-scattered fluence of an isotropic point source in an infinite HG medium (pure Python, no device).

The exact order-1 fluence at distance r, in prolate spheroidal coordinates about the source and the point
(x = (r1 + r2)/r, y = (r1 - r2)/r; the scattering angle's cosine (2 - x² - y²)/(x² - y²)):
    4π r² φ1(r) / (σs r) = F(τ, g) = 4π ∫_1^∞ ∫_-1^1 p_HG(cos θ; g) e^{-τ x} / (x² - y²) dy dx,   τ = σt r
(F(0, 0) = π²/4). The model's (kernels/common/underwater_lamps_ms.h, W_1 with ℓ = r q_1^{-κ}):
    F_model = s² e^{-τ s},   s = q_1^{-κ},   q_1 = (1 + g)/2.
Usage: tests/perf/lamp_order1_point_source.py [kappa]   (default 0.6, the model's; about a minute)
"""
import math
import sys


def hg(c, g):
    return (1 - g * g) / (4 * math.pi * (1 + g * g - 2 * g * c) ** 1.5)


def exact(tau, g, nu=1500, nv=600):
    # x = 1 + u² and y = sin(π v / 2): nodes gather where the integrand's log singularities and HG's peak are.
    top = math.sqrt(60.0 / tau)
    du, dv = top / nu, 2.0 / nv
    ys = []
    for j in range(nv):
        v = -1 + (j + 0.5) * dv
        ys.append((math.sin(math.pi / 2 * v), math.pi / 2 * math.cos(math.pi / 2 * v) * dv))
    total = 0.0
    for i in range(nu):
        u = (i + 0.5) * du
        x = 1 + u * u
        e = math.exp(-tau * x)
        if e < 1e-14:
            break
        inner = sum(hg((2 - x * x - y * y) / (x * x - y * y), g) / (x * x - y * y) * w for y, w in ys)
        total += inner * e * 2 * u * du
    return 4 * math.pi * total


def main():
    kappa = float(sys.argv[1]) if len(sys.argv) > 1 else 0.6
    print(f"| g | τ = σt r: exact F / model F (model / exact), κ = {kappa} |")
    print("|---|---|")
    for g in (0.0, 0.5, 0.7, 0.9):
        s = ((1 + g) / 2) ** -kappa
        cells = []
        for tau in (0.1, 0.3, 1.0, 3.0):
            e, m = exact(tau, g), s * s * math.exp(-tau * s)
            cells.append(f"{tau}: {e:.3f} / {m:.3f} ({m / e:.2f})")
        print(f"| {g} | " + "; ".join(cells) + " |", flush=True)


if __name__ == "__main__":
    main()
