#!/usr/bin/env python3
"""regions_ratio_plot.py — one SVG of model / path tracer per judged region, one column per study table
(`seasim underwater-regions` CSVs, or tests/perf/sea_allorders.sh tables by their two halves), each
model in its own colour, with the ±5 % band. Standard library only.
Usage: tests/perf/regions_ratio_plot.py out.svg table.csv [more.csv ...]
"""
import csv
import os
import sys

REGIONS = ["bottom_near", "bottom_far", "water_up", "water_down", "objects"]
COLOURS = {"thesis": "#c0392b", "improved": "#1f6fb2", "discrete_ordinates": "#1f6fb2", "multiple": "#1f6fb2"}
LO, HI = 0.5, 1.5  # the axis; ratios outside are drawn at its edge as open marks


def points(path):
    """(model, ratio) of every judged region of a table."""
    out = []
    with open(path, newline="") as f:
        for r in csv.DictReader(f):
            if "ratio_near" in r:  # the sea's table: one model, two halves
                out += [("multiple", float(r["ratio_near"])), ("multiple", float(r["ratio_far"]))]
                continue
            for reg in REGIONS:
                pix, ratio, se = r[reg + "_pixels"], r[reg + "_ratio"], r[reg + "_ref_rel_se"]
                if pix and ratio and se and int(pix) >= 40 and float(se) <= 0.02:
                    out.append((r["model"], float(ratio)))
    return out


def main(out, tables):
    w, h, left, top, bottom = 110 * len(tables) + 90, 420, 70, 30, 80
    y = lambda v: top + (HI - min(max(v, LO), HI)) / (HI - LO) * (h - top - bottom)
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">',
           f'<rect x="{left}" y="{y(1.05):.1f}" width="{w - left - 10}" height="{y(0.95) - y(1.05):.1f}" fill="#e8f4e8"/>']
    for v in (0.5, 0.75, 0.95, 1.0, 1.05, 1.25, 1.5):
        svg.append(f'<line x1="{left}" x2="{w - 10}" y1="{y(v):.1f}" y2="{y(v):.1f}" stroke="#ccc"/>'
                   f'<text x="{left - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:g}</text>')
    svg.append(f'<text x="14" y="{top + (h - top - bottom) / 2:.0f}" transform="rotate(-90 14 {top + (h - top - bottom) / 2:.0f})"'
               ' text-anchor="middle">model / path tracer, per judged region</text>')
    for i, t in enumerate(tables):
        cx = left + 55 + 110 * i
        name = os.path.splitext(os.path.basename(t))[0]
        svg.append(f'<text x="{cx}" y="{h - bottom + 16}" text-anchor="end" transform="rotate(-35 {cx} {h - bottom + 16})">{name}</text>')
        for j, (model, ratio) in enumerate(points(t)):
            dx = (-18 if model == "thesis" else 18) + (j % 7 - 3) * 2.5
            colour = COLOURS.get(model, "#555")
            fill = colour if LO <= ratio <= HI else "none"
            svg.append(f'<circle cx="{cx + dx:.1f}" cy="{y(ratio):.1f}" r="2.6" fill="{fill}" stroke="{colour}" fill-opacity="0.6"/>')
    svg.append(f'<text x="{left}" y="16">blue: discrete ordinates / multiple (the defaults); red: thesis; '
               'green band: within 5 %; open marks: beyond the axis</text></svg>')
    with open(out, "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
