#!/usr/bin/env python3
"""underwater_sun_aureole.py — the radiance around the refracted sun, path tracer against the fast models, from
`seasim underwater-regions --views sun --dump DIR` (tests/perf/underwater_sun_aureole.sh): every pixel binned by
its angle to the sun (the dump's cos_sun) in 2.5° steps, the bin's mean reference and fast renders.

Usage: tests/perf/underwater_sun_aureole.py OUT.csv OUT.svg DUMP.csv [DUMP.csv ...]
Writes one CSV row per case and bin (case, angle_deg, pixels, reference, reference_se, fast_<model>..., and
each model's ratio) and one SVG: radiance against angle, log scale, a panel per case. Plain SVG, no plotting
library (none is in the project's dependencies).
"""
import csv
import math
import os
import sys

STEP = 2.5
COLOURS = {"reference": "black", "fast_improved": "#1f77b4", "fast_thesis": "#d62728"}
W, H, L, R, T, B = 420, 300, 70, 20, 40, 50


def bins_of(path):
    rows = list(csv.DictReader(open(path)))
    models = [k for k in rows[0] if k.startswith("fast_")]
    bins = {}
    for r in rows:
        angle = math.degrees(math.acos(max(-1.0, min(1.0, float(r["cos_sun"])))))
        b = bins.setdefault(int(angle // STEP), {"n": 0, "reference": 0.0, "se2": 0.0, **{m: 0.0 for m in models}})
        b["n"] += 1
        b["reference"] += float(r["reference"])
        b["se2"] += float(r["reference_se"]) ** 2
        for m in models:
            b[m] += float(r[m])
    return models, bins


def panel(out, x0, title, models, bins):
    keys = sorted(bins)
    a_max = (keys[-1] + 1) * STEP
    vals = [bins[k][s] / bins[k]["n"] for k in keys for s in ["reference"] + models if bins[k][s] > 0]
    y0 = 10 ** math.floor(math.log10(min(vals)))
    y1 = 10 ** math.ceil(math.log10(max(vals)))

    def px(a):
        return x0 + L + a / a_max * (W - L - R)

    def py(v):
        return H - B - (math.log10(v) - math.log10(y0)) / (math.log10(y1) - math.log10(y0)) * (H - T - B)

    out.append(f'<text x="{x0 + W / 2}" y="24" text-anchor="middle" font-size="13">{title}</text>')
    d = y0
    while d <= y1 * 1.001:
        out.append(f'<line x1="{x0 + L}" y1="{py(d):.1f}" x2="{x0 + W - R}" y2="{py(d):.1f}" stroke="#ddd"/>')
        out.append(f'<text x="{x0 + L - 6}" y="{py(d) + 4:.1f}" text-anchor="end">{d:g}</text>')
        d *= 10
    a = 0.0
    while a <= a_max + 1e-9:
        out.append(f'<text x="{px(a):.1f}" y="{H - B + 16}" text-anchor="middle">{a:g}</text>')
        a += 10
    out.append(f'<rect x="{x0 + L}" y="{T}" width="{W - L - R}" height="{H - T - B}" fill="none" stroke="black"/>')
    out.append(f'<text x="{x0 + (L + W - R) / 2}" y="{H - 16}" text-anchor="middle">angle to the refracted sun (°)</text>')
    out.append(f'<text x="{x0 + 14}" y="{(T + H - B) / 2}" text-anchor="middle" '
               f'transform="rotate(-90 {x0 + 14} {(T + H - B) / 2})">radiance (R + G + B)</text>')
    for s in ["reference"] + models:
        pts = [(px((k + 0.5) * STEP), py(bins[k][s] / bins[k]["n"])) for k in keys if bins[k][s] > 0]
        dash = ' stroke-dasharray="5,3"' if s == "reference" else ""
        out.append(f'<polyline fill="none" stroke="{COLOURS.get(s, "gray")}" stroke-width="1.6"{dash} points="'
                   + " ".join(f"{x:.1f},{y:.1f}" for x, y in pts) + '"/>')


def main():
    out_csv, out_svg, dumps = sys.argv[1], sys.argv[2], sys.argv[3:]
    cases = [(os.path.basename(p)[:-4], *bins_of(p)) for p in dumps]
    models = cases[0][1]
    with open(out_csv + ".tmp", "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["case", "angle_deg", "pixels", "reference", "reference_se"] + models +
                   [m.replace("fast_", "ratio_") for m in models])
        for name, _, bins in cases:
            for k in sorted(bins):
                b = bins[k]
                n = b["n"]
                w.writerow([name, (k + 0.5) * STEP, n, f'{b["reference"] / n:.6g}', f'{math.sqrt(b["se2"]) / n:.3g}'] +
                           [f"{b[m] / n:.6g}" for m in models] + [f'{b[m] / b["reference"]:.4f}' for m in models])
    os.replace(out_csv + ".tmp", out_csv)
    total_w = W * len(cases)
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{total_w}" height="{H + 30}" font-family="sans-serif" '
           'font-size="11">', f'<rect width="{total_w}" height="{H + 30}" fill="white"/>']
    for i, (name, ms, bins) in enumerate(cases):
        panel(svg, i * W, name, ms, bins)
    x = 10
    for s in ["reference"] + models:
        dash = ' stroke-dasharray="5,3"' if s == "reference" else ""
        svg.append(f'<line x1="{x}" y1="{H + 18}" x2="{x + 24}" y2="{H + 18}" stroke="{COLOURS.get(s, "gray")}" '
                   f'stroke-width="2"{dash}/>')
        svg.append(f'<text x="{x + 30}" y="{H + 22}">{s.replace("fast_", "") + (" (path tracer)" if s == "reference" else "")}</text>')
        x += 170
    svg.append("</svg>")
    with open(out_svg + ".tmp", "w") as f:
        f.write("\n".join(svg) + "\n")
    os.replace(out_svg + ".tmp", out_svg)


if __name__ == "__main__":
    main()
