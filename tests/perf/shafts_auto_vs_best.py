#!/usr/bin/env python3
"""shafts_auto_vs_best.py — the summary of tests/perf/shafts_auto_vs_best.sh: for each "auto" row, the
fastest fixed setting of the grid at equal or lower error (the issue's criterion: "auto" at most 1.1x
its time) and the fastest whose full-size error is within the budget.

Usage: tests/perf/shafts_auto_vs_best.py OUT.csv [OUT.csv ...] [--svg PLOT.svg]
  Prints a Markdown table; with --svg also one panel per CSV: every fixed setting's kernel ms against its
  RMS error (log-log, a colour per method) and "auto"'s choice at each budget ringed and labelled.
Equal error allows 0.005 levels: the grid's errors are single frames against one reference.
Plain SVG, no plotting library (none is in the project's dependencies).
"""
import csv
import math
import sys

TOLERANCE = 0.005


COLOURS = {"intervals": "#1f77b4", "planes": "#2ca02c", "march": "#9467bd"}
PW, PH, L, T, B = 360, 300, 60, 40, 50


def panel(rows, scene, x_off):
    """One scene's scatter as SVG elements, its left edge at x_off."""
    pts = [(float(r["kernel_ms"]), float(r["rmse_8bit"]), r) for r in rows]
    x0 = 10 ** math.floor(math.log10(min(p[0] for p in pts)))
    x1 = 10 ** math.ceil(math.log10(max(p[0] for p in pts)))
    y0 = 10 ** math.floor(math.log10(min(p[1] for p in pts)))
    y1 = 10 ** math.ceil(math.log10(max(p[1] for p in pts)))

    def px(v):
        return x_off + L + (math.log10(v) - math.log10(x0)) / (math.log10(x1) - math.log10(x0)) * (PW - L - 10)

    def py(v):
        return PH - B - (math.log10(v) - math.log10(y0)) / (math.log10(y1) - math.log10(y0)) * (PH - T - B)

    out = [f'<text x="{x_off + PW / 2}" y="24" text-anchor="middle" font-size="13">{scene}</text>',
           f'<rect x="{x_off + L}" y="{T}" width="{PW - L - 10}" height="{PH - T - B}" fill="none" stroke="#999"/>']
    d = x0
    while d <= x1 * 1.001:
        out.append(f'<text x="{px(d):.1f}" y="{PH - B + 14}" text-anchor="middle" font-size="10">{d:g}</text>')
        d *= 10
    d = y0
    while d <= y1 * 1.001:
        out.append(f'<text x="{x_off + L - 4}" y="{py(d) + 3:.1f}" text-anchor="end" font-size="10">{d:g}</text>')
        d *= 10
    out.append(f'<text x="{x_off + L + (PW - L) / 2}" y="{PH - 12}" text-anchor="middle" font-size="11">kernel ms per frame</text>')
    for ms, err, r in pts:
        name = r["setting"]
        if name.startswith("auto"):
            continue
        colour = COLOURS.get(name.split()[0], "#333")
        out.append(f'<circle cx="{px(ms):.1f}" cy="{py(err):.1f}" r="3.5" fill="{colour}"><title>{name}</title></circle>')
    for ms, err, r in pts:
        if r["setting"].startswith("auto"):
            budget = r["setting"].split()[1]
            out.append(f'<circle cx="{px(ms):.1f}" cy="{py(err):.1f}" r="7" fill="none" stroke="#d62728" stroke-width="1.5"/>')
            out.append(f'<text x="{px(ms) + 9:.1f}" y="{py(err) - 4:.1f}" font-size="9" fill="#d62728">auto {budget}</text>')
    return out


def write_svg(paths, svg):
    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{PW * len(paths)}" height="{PH + 20}" '
           'font-family="sans-serif">', f'<rect width="{PW * len(paths)}" height="{PH + 20}" fill="white"/>']
    for i, path in enumerate(paths):
        rows = list(csv.DictReader(open(path)))
        out += panel(rows, scene_name(path), i * PW)
    x = 10
    for name, colour in COLOURS.items():
        out.append(f'<circle cx="{x}" cy="{PH + 10}" r="4" fill="{colour}"/><text x="{x + 8}" y="{PH + 14}" '
                   f'font-size="11">{name}</text>')
        x += 90
    out.append(f'<circle cx="{x}" cy="{PH + 10}" r="6" fill="none" stroke="#d62728"/><text x="{x + 10}" '
               f'y="{PH + 14}" font-size="11">"auto" at its budget (levels); y: RMS 8-bit levels</text>')
    out.append("</svg>")
    open(svg, "w").write("\n".join(out) + "\n")


def scene_name(path):
    return path.rsplit("/", 1)[-1].removeprefix("auto_vs_best_").removesuffix(".csv")


def main():
    args = sys.argv[1:]
    svg = None
    if "--svg" in args:
        i = args.index("--svg")
        svg = args[i + 1]
        args = args[:i] + args[i + 2:]
    if svg:
        write_svg(args, svg)
    print("| scene | budget | auto's choice | ms | RMS | fastest at equal error | ms | ratio "
          "| fastest within the budget (full size) | ms | ratio |")
    print("|---|---:|---|---:|---:|---|---:|---:|---|---:|---:|")
    worst = 0.0
    for path in args:
        rows = list(csv.DictReader(open(path)))
        grid = [r for r in rows if not r["setting"].startswith("auto")]
        scene = scene_name(path)
        for a in (r for r in rows if r["setting"].startswith("auto")):
            budget = float(a["setting"].split()[1])
            ms, err = float(a["kernel_ms"]), float(a["rmse_8bit"])
            equal = [g for g in grid if float(g["rmse_8bit"]) <= err + TOLERANCE]
            within = [g for g in grid if float(g["rmse_8bit"]) <= budget]
            e = min(equal, key=lambda g: float(g["kernel_ms"])) if equal else None
            w = min(within, key=lambda g: float(g["kernel_ms"])) if within else None
            re = ms / float(e["kernel_ms"]) if e else float("nan")
            rw = ms / float(w["kernel_ms"]) if w else float("nan")
            if e:
                worst = max(worst, re)
            print(f"| {scene} | {budget:g} | {a['chosen']} | {ms:.1f} | {err:.3f} | "
                  f"{e['setting'] if e else '-'} | {float(e['kernel_ms']) if e else float('nan'):.1f} | {re:.2f} | "
                  f"{w['setting'] if w else '-'} | {float(w['kernel_ms']) if w else float('nan'):.1f} | {rw:.2f} |")
    print(f"\nworst ratio at equal error: {worst:.2f}")


if __name__ == "__main__":
    main()
