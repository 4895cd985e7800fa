#!/usr/bin/env python3
"""lamp_orders_plot.py — the lamps' models against the path tracer, error against time, from the
`seasim lamp-regions` CSVs of tests/perf/lamp_orders_sweep.sh. One SVG, two panels:
  left:  model / path tracer per region (whole image, lit bottom, beam, outside it) of every case, per
         model, with the ±5 % band;
  right: per case, the worst region's |ratio - 1| against the lamp pass's milliseconds (log axis), per
         model: the error-versus-time picture of the sweep.
Regions are judged as the sweep's table judges them: at least 20 pixels and a ratio. Standard library only.
Usage: tests/perf/lamp_orders_plot.py out.svg table.csv [more.csv ...]
"""
import csv
import math
import sys

REGIONS = ["whole", "lit_bottom", "beam", "outside"]
MODELS = ["single", "delta_m", "orders"]
COLOURS = {"single": "#c0392b", "delta_m": "#8e6bbf", "orders": "#1f6fb2"}
LO, HI = 0.0, 1.5  # the ratio axis


def rows(paths):
    out = []
    for path in paths:
        with open(path, newline="") as f:
            out += list(csv.DictReader(f))
    return out


def judged(r):
    """The (region, ratio) pairs of a row the sweep's table judges."""
    out = []
    for reg in REGIONS:
        pix, ratio = r[reg + "_pixels"], r[reg + "_ratio"]
        if pix and ratio and int(pix) >= 20:
            out.append((reg, float(ratio)))
    return out


def main(out, tables):
    data = rows(tables)
    w, h, top, bottom = 900, 440, 34, 60
    pl, pr = 70, 420           # left panel: x from pl to pr
    ql, qr = 500, 880          # right panel
    ph = h - top - bottom
    y = lambda v: top + (HI - min(max(v, LO), HI)) / (HI - LO) * ph
    svg = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" font-family="sans-serif" font-size="11">']
    # Left: ratios by region and model.
    svg.append(f'<rect x="{pl}" y="{y(1.05):.1f}" width="{pr - pl}" height="{y(0.95) - y(1.05):.1f}" fill="#e8f4e8"/>')
    for v in (0.0, 0.5, 0.75, 0.95, 1.0, 1.05, 1.25, 1.5):
        svg.append(f'<line x1="{pl}" x2="{pr}" y1="{y(v):.1f}" y2="{y(v):.1f}" stroke="#ccc"/>'
                   f'<text x="{pl - 6}" y="{y(v) + 4:.1f}" text-anchor="end">{v:g}</text>')
    svg.append(f'<text x="14" y="{top + ph / 2:.0f}" transform="rotate(-90 14 {top + ph / 2:.0f})" '
               'text-anchor="middle">model / path tracer, per region</text>')
    col = (pr - pl) / len(REGIONS)
    for i, reg in enumerate(REGIONS):
        cx = pl + col * (i + 0.5)
        svg.append(f'<text x="{cx:.0f}" y="{h - bottom + 16}" text-anchor="middle">{reg.replace("_", " ")}</text>')
        for m, model in enumerate(MODELS):
            ratios = [v for r in data if r["model"] == model for g, v in judged(r) if g == reg]
            for j, v in enumerate(ratios):
                dx = (m - 1) * col / 3.5 + (j % 5 - 2) * 2.2
                fill = COLOURS[model] if LO <= v <= HI else "none"
                svg.append(f'<circle cx="{cx + dx:.1f}" cy="{y(v):.1f}" r="2.6" fill="{fill}" stroke="{COLOURS[model]}" '
                           'fill-opacity="0.6"/>')
    # Right: worst region's error against the lamp pass's time.
    times = [float(r["lamps_ms"]) for r in data if float(r["lamps_ms"]) > 0]
    t_lo, t_hi = math.log10(min(times)) - 0.1, math.log10(max(times)) + 0.1
    x = lambda t: ql + (math.log10(t) - t_lo) / (t_hi - t_lo) * (qr - ql)
    e_hi = 1.0
    ye = lambda e: top + (e_hi - min(e, e_hi)) / e_hi * ph
    svg.append(f'<rect x="{ql}" y="{ye(0.05):.1f}" width="{qr - ql}" height="{ye(0) - ye(0.05):.1f}" fill="#e8f4e8"/>')
    for e in (0.0, 0.05, 0.1, 0.25, 0.5, 0.75, 1.0):
        svg.append(f'<line x1="{ql}" x2="{qr}" y1="{ye(e):.1f}" y2="{ye(e):.1f}" stroke="#ccc"/>'
                   f'<text x="{ql - 6}" y="{ye(e) + 4:.1f}" text-anchor="end">{e:g}</text>')
    for k in range(math.floor(t_lo), math.ceil(t_hi) + 1):
        if t_lo <= k <= t_hi:
            svg.append(f'<line x1="{x(10 ** k):.1f}" x2="{x(10 ** k):.1f}" y1="{top}" y2="{top + ph}" stroke="#eee"/>'
                       f'<text x="{x(10 ** k):.1f}" y="{top + ph + 14}" text-anchor="middle">{10 ** k:g}</text>')
    svg.append(f'<text x="{(ql + qr) / 2:.0f}" y="{top + ph + 30}" text-anchor="middle">lamp pass, ms per frame (log)</text>')
    svg.append(f'<text x="{ql - 40}" y="{top + ph / 2:.0f}" transform="rotate(-90 {ql - 40} {top + ph / 2:.0f})" '
               'text-anchor="middle">worst region |ratio - 1|, per case</text>')
    for r in data:
        regions = judged(r)
        t = float(r["lamps_ms"])
        if not regions or t <= 0:
            continue
        e = max(abs(v - 1) for _, v in regions)
        svg.append(f'<circle cx="{x(t):.1f}" cy="{ye(e):.1f}" r="3" fill="{COLOURS.get(r["model"], "#555")}" '
                   'fill-opacity="0.6"/>')
    legend = "; ".join(f'<tspan fill="{COLOURS[m]}">{m}</tspan>' for m in MODELS)
    svg.append(f'<text x="{pl}" y="18">{legend}; green band: within 5 %; open marks: beyond the axis</text></svg>')
    with open(out, "w") as f:
        f.write("\n".join(svg) + "\n")


if __name__ == "__main__":
    if len(sys.argv) < 3:
        sys.exit(__doc__)
    main(sys.argv[1], sys.argv[2:])
