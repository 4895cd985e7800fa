#!/usr/bin/env python3
"""sea_orders_fit_g.py — fit sea.model = "multiple"'s higher-orders factor
(kernels/common/sea_multiple.h, sea_higher_orders) as one closed form of u = b_b/(a + b_b) and the HG g,
to the factor the uncapped path tracer needs (results/sea_allorders/orders_fit_g.csv, made by
tests/perf/sea_orders_fit.sh with G, U and MAXB). Plain python (no numpy on the build machine).

  tests/perf/sea_orders_fit_g.py [orders_fit_g.csv]

Points: per (g, u) the row with the largest cap max_bounces <= 2048 (2048 is uncapped there: 8192 gave the
same image at g 0.9, u 0.6; where only cap 64 was traced, g 0.5 and g 0.8 at u <= 0.1, the bounce-cap study found 2048
the same within 0.3 % or no path near the cap). The form, with h = 2 c_f - 1 (c_f = hg_forward_fraction(g),
what the kernel already has per pixel; 0 at g = 0, -> 1 as g -> 1; g < 0 taken as g = 0):
    orders(u, g) = 1 + p0 u (1/2 + u) + p1 h u^2 / (u^2 + p2)
exactly 1 at u = 0, rising in u for h >= 0, no exp. A Nelder-Mead fit of the relative error's squares;
prints the numbers, then the worst and RMS relative error over the points for the numbers rounded as the
kernel writes them (ROUNDED), and each point.
"""
import csv
import math
import sys

ROUNDED = (0.52, 0.636, 0.0397)  # what sea_higher_orders uses


def forward_fraction(g):
    """hg_forward_fraction (kernels/common/optics.h): 1 - the HG back-scattered fraction."""
    if abs(g) < 1e-6:
        return 0.5
    back = (1 - g) / (2 * g) * ((1 + g) / math.sqrt(1 + g * g) - 1)
    return 1 - back


def orders(p, u, g):
    h = max(2 * forward_fraction(g) - 1, 0.0)
    return 1 + p[0] * u * (0.5 + u) + p[1] * h * u * u / (u * u + p[2])


def read_points(path):
    best = {}
    for r in csv.DictReader(open(path, newline="")):
        g, u, cap = float(r["g"]), round(float(r["u"]), 2), int(r["max_bounces"])
        if cap > 2048:
            continue
        if (g, u) not in best or cap > best[(g, u)][0]:
            best[(g, u)] = (cap, float(r["needed"]))
    return sorted((g, u, cap, needed) for (g, u), (cap, needed) in best.items())


def nelder_mead(f, x0, iterations=4000):
    n = len(x0)
    simplex = [list(x0)] + [[x0[j] * (1.1 if j == i else 1.0) for j in range(n)] for i in range(n)]
    values = [f(p) for p in simplex]
    for _ in range(iterations):
        order = sorted(range(n + 1), key=lambda i: values[i])
        simplex, values = [simplex[i] for i in order], [values[i] for i in order]
        centre = [sum(p[j] for p in simplex[:-1]) / n for j in range(n)]
        worst = simplex[-1]
        reflected = [2 * centre[j] - worst[j] for j in range(n)]
        fr = f(reflected)
        if fr < values[0]:
            expanded = [3 * centre[j] - 2 * worst[j] for j in range(n)]
            fe = f(expanded)
            simplex[-1], values[-1] = (expanded, fe) if fe < fr else (reflected, fr)
        elif fr < values[-2]:
            simplex[-1], values[-1] = reflected, fr
        else:
            contracted = [(centre[j] + worst[j]) / 2 for j in range(n)]
            fc = f(contracted)
            if fc < values[-1]:
                simplex[-1], values[-1] = contracted, fc
            else:
                simplex = [simplex[0]] + [[(simplex[0][j] + p[j]) / 2 for j in range(n)] for p in simplex[1:]]
                values = [values[0]] + [f(p) for p in simplex[1:]]
    i = min(range(n + 1), key=lambda k: values[k])
    return simplex[i]


def main():
    path = sys.argv[1] if len(sys.argv) > 1 else "results/sea_allorders/orders_fit_g.csv"
    points = read_points(path)

    def cost(p):
        return sum((orders(p, u, g) / needed - 1) ** 2 for g, u, _, needed in points)

    p = [0.5, 0.7, 0.04]
    for _ in range(3):
        p = nelder_mead(cost, p)
    print("fitted on %d points: p0 = %.4g, p1 = %.4g, p2 = %.4g" % (len(points), *p))
    for name, q in (("fitted", p), ("rounded", ROUNDED)):
        errors = [orders(q, u, g) / needed - 1 for g, u, _, needed in points]
        print("%s: worst %.4f, rms %.4f" % (name, max(abs(e) for e in errors),
                                            math.sqrt(sum(e * e for e in errors) / len(errors))))
    print("g,u,max_bounces,needed,orders,orders_over_needed")
    for g, u, cap, needed in points:
        o = orders(ROUNDED, u, g)
        print("%g,%g,%d,%.4f,%.4f,%.4f" % (g, u, cap, needed, o, o / needed))


if __name__ == "__main__":
    main()
