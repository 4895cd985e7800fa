#!/usr/bin/env python3
"""shafts_error_time_plot.py — one SVG of the error–time curves that tests/perf/shafts_error_time.sh
writes: RMS error in 8-bit levels against CPU ms per frame, log–log, one series per method (intervals,
planes, the device's march, the CPU ray march), points in increasing time, and the issue's 1-level budget as a dashed line.

Usage: tests/perf/shafts_error_time_plot.py OUT.csv OUT.svg "title"
Plain SVG, no plotting library (none is in the project's dependencies).
"""
import csv
import math
import sys

COLOURS = {"intervals": "#1f77b4", "planes": "#2ca02c", "march": "#9467bd", "ray march": "#d62728"}
W, H, L, R, T, B = 720, 460, 80, 170, 40, 60


def main():
    rows = list(csv.DictReader(open(sys.argv[1])))
    title = sys.argv[3] if len(sys.argv) > 3 else sys.argv[1]
    series = {}
    for r in rows:
        ms, err = float(r["cpu_ms_per_frame"]), float(r["rmse_8bit"])
        if ms <= 0 or err <= 0:
            continue  # a time lost in the machine's noise cannot go on a log axis
        series.setdefault(r["method"], []).append((ms, err, r["setting"]))
    pts = [p for s in series.values() for p in s]
    x0 = 10 ** math.floor(math.log10(min(p[0] for p in pts)))
    x1 = 10 ** math.ceil(math.log10(max(p[0] for p in pts)))
    y0 = 10 ** math.floor(math.log10(min(p[1] for p in pts)))
    y1 = 10 ** math.ceil(math.log10(max(max(p[1] for p in pts), 1.0) * 1.01))

    def px(v):
        return L + (math.log10(v) - math.log10(x0)) / (math.log10(x1) - math.log10(x0)) * (W - L - R)

    def py(v):
        return H - B - (math.log10(v) - math.log10(y0)) / (math.log10(y1) - math.log10(y0)) * (H - T - B)

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{W}" height="{H}" font-family="sans-serif" font-size="12">',
           f'<rect width="{W}" height="{H}" fill="white"/>',
           f'<text x="{W / 2}" y="22" text-anchor="middle" font-size="14">{title}</text>']
    d = x0
    while d <= x1 * 1.001:
        out.append(f'<line x1="{px(d):.1f}" y1="{T}" x2="{px(d):.1f}" y2="{H - B}" stroke="#ddd"/>')
        out.append(f'<text x="{px(d):.1f}" y="{H - B + 16}" text-anchor="middle">{d:g}</text>')
        d *= 10
    d = y0
    while d <= y1 * 1.001:
        out.append(f'<line x1="{L}" y1="{py(d):.1f}" x2="{W - R}" y2="{py(d):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{L - 6}" y="{py(d) + 4:.1f}" text-anchor="end">{d:g}</text>')
        d *= 10
    out.append(f'<rect x="{L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="black"/>')
    out.append(f'<line x1="{L}" y1="{py(1):.1f}" x2="{W - R}" y2="{py(1):.1f}" stroke="black" stroke-dasharray="5,4"/>')
    out.append(f'<text x="{W - R - 4}" y="{py(1) - 4:.1f}" text-anchor="end">budget: 1 level RMS</text>')
    out.append(f'<text x="{(L + W - R) / 2}" y="{H - 18}" text-anchor="middle">CPU ms per frame (user + system, 2-core VM)</text>')
    out.append(f'<text x="18" y="{(T + H - B) / 2}" text-anchor="middle" transform="rotate(-90 18 {(T + H - B) / 2})">'
               'RMS error vs converged ray march (8-bit levels)</text>')
    for k, (name, s) in enumerate(sorted(series.items())):
        s.sort()
        colour = COLOURS.get(name, "black")
        path = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y, _ in s)
        out.append(f'<polyline points="{path}" fill="none" stroke="{colour}" stroke-width="1.5"/>')
        for x, y, label in s:
            out.append(f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="3.5" fill="{colour}"><title>{name} {label}: '
                       f'{x:.0f} ms, {y:.4f} levels</title></circle>')
        out.append(f'<line x1="{W - R + 12}" y1="{T + 20 + 20 * k}" x2="{W - R + 32}" y2="{T + 20 + 20 * k}" '
                   f'stroke="{colour}" stroke-width="2"/>')
        out.append(f'<text x="{W - R + 38}" y="{T + 24 + 20 * k}">{name}</text>')
    out.append("</svg>")
    open(sys.argv[2], "w").write("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
