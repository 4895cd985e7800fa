#!/usr/bin/env python3
"""expected_error_table.py — the measured cases that `seasim plan` and report.json look a scene's expected
error up in (host/quality/expected_error.h), built from the study tables in results/:

  results/sea_allorders/table.csv           sea.model = "paper" (+ second order) against all orders
  results/sea_allorders/table_multiple.csv  sea.model = "multiple" against all orders
  results/underwater/regions.csv            underwater "thesis" and "discrete_ordinates" (the study's
                                            "improved", the model's earlier name), training grid
  results/underwater/regions_heldout.csv    the same, held-out grid
  results/sea_allorders/table_*_preetham.csv, results/underwater/regions_sky_*.csv
                                            the same models under Preetham's sky and a sky image
  results/sea_allorders/widened*/, results/underwater/widened/
                                            one axis at a time beyond those grids (sun, g, view; sun
                                            azimuth, sky level, bottom albedo)
  results/underwater/lamp_orders_{fit,heldout,near,fresh}.csv
                                            the lamps under water (quality.lamps_model "single",
                                            "delta_m", "orders") against all orders, one lamp, no daylight

One file per model, data/expected_error/<view>_<model>.csv (numeric, data/README.md's format), one row
per measured case: the case's water (a, b at 550 nm, g), bottom depth (-1: none),
sun zenith in air, the sky (common/sky.h's SEASIM_SKY_*: 0 uniform, 2 image, 3 Preetham), for a lamp its
cone's half angle and its distance along its axis to the bottom (0 and -1 for the daylight views), and the error against the all-orders path tracer: max |ratio - 1| over the case's
judged image regions (the sea: its near and far halves; under water: regions with >= 40 pixels and a
reference noise <= 2 %), the worst ratio, the reference's noise, the judged regions, and `source`: the index of the table it came
from in SOURCES below (also listed in data/expected_error/README.md).

  python3 tests/perf/expected_error_table.py data/expected_error
"""
import csv
import os
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..")


def read(path):
    with open(os.path.join(ROOT, path), newline="") as f:
        return list(csv.DictReader(f))


def at550(path, jerlov):
    rows = read(path)
    for r in rows:
        if float(r["wavelength_nm"]) == 550.0:
            return float(r[jerlov])
    raise SystemExit(f"{path}: no 550 nm row")


# Per view and model, its tables in order (a row's `source` is the index; written beside the cases as
# <view>_<model>.tables, one path per line, which host/quality/expected_error.cpp reads), each with the
# sun's zenith and the sky its cases were measured under, and for the sea its g (the under-water tables
# carry theirs). The widened tables vary an axis the regime's distance does not see (the sun's azimuth,
# the sky's level, the bottom's albedo, the view's tilt): their cases sit at the distance of the case
# they vary, and the lookup takes the largest error among equally near cases.
WIDENED = "results/underwater/widened/"
UNDERWATER = [("results/underwater/regions.csv", 30, 0), ("results/underwater/regions_heldout.csv", 30, 0),
              ("results/underwater/regions_sky_preetham_sun30.csv", 30, 3),
              ("results/underwater/regions_sky_preetham_sun60.csv", 60, 3),
              ("results/underwater/regions_sky_image_sun30.csv", 30, 2),
              ("results/underwater/regions_sky_image_sun60.csv", 60, 2),
              (WIDENED + "sun_facing.csv", 30, 0), (WIDENED + "sun_side.csv", 30, 0),
              (WIDENED + "sun_low.csv", 75, 0), (WIDENED + "sky_bright.csv", 30, 0),
              (WIDENED + "sky_dim.csv", 30, 0), (WIDENED + "bottom_dark.csv", 30, 0),
              (WIDENED + "bottom_bright.csv", 30, 0), (WIDENED + "camera_shallow.csv", 30, 0),
              (WIDENED + "camera_deep.csv", 30, 0)]


def sea_tables(model):
    own = "results/sea_allorders/table.csv" if model == "paper" else "results/sea_allorders/table_multiple.csv"
    widened = "results/sea_allorders/widened" + ("_paper/" if model == "paper" else "/")
    return [(own, 40, 0, 0.9), (f"results/sea_allorders/table_{model}_preetham.csv", 40, 3, 0.9),
            (widened + "sun_high.csv", 20, 0, 0.9), (widened + "sun_low.csv", 65, 0, 0.9),
            (widened + "g_080.csv", 40, 0, 0.8), (widened + "g_095.csv", 40, 0, 0.95),
            (widened + "view_steep.csv", 40, 0, 0.9), (widened + "view_grazing.csv", 40, 0, 0.9)]


# Shipped scenes measured as they are (tests/perf/scene_vs_pathtracer.sh: whole image and halves), each
# with the `scene` column's value its rows have (None: every row) and its regime: Jerlov type, g, bottom
# depth (a height field's mean; -1: none), sun zenith, sky, floor (1: height field), surface (1: FFT
# waves). The wave scenes whose sun's glitter is in view come from the longer run (more paths, fewer
# pixels: tests/perf/sea_waves_vs_pathtracer.sh's note).
WAVES = "results/sea_allorders/waves_vs_pathtracer.csv"
GLITTER = "results/sea_allorders/waves_vs_pathtracer_glitter.csv"
UNDERWATER_SCENES = [("results/underwater/snells_window_vs_pathtracer.csv", None, "IB", 0.9, 8.0, 40, 3, 0, 0)]
SEA_SCENES = [("results/sea_allorders/seashore_vs_pathtracer.csv", None, "1C", 0.9, 20.5, 40, 0, 1, 0),
              (GLITTER, "wavy_sea", "IB", 0.9, -1, 50, 0, 0, 1),
              (WAVES, "wavy_sea_sun_side", "IB", 0.9, -1, 50, 0, 0, 1),
              (WAVES, "wavy_sea_sun_behind", "IB", 0.9, -1, 50, 0, 0, 1),
              (GLITTER, "wavy_sea_image_sky", "IB", 0.9, -1, 50, 2, 0, 1),
              (GLITTER, "ocean_noon", "IB", 0.9, -1, 35, 3, 0, 1),
              (GLITTER, "ocean_sunset", "IB", 0.9, -1, 85, 3, 0, 1),
              (WAVES, "stormy_sea", "3C", 0.9, -1, 70, 0, 0, 1),
              (WAVES, "tropical_lagoon", "I", 0.9, 4.0, 20, 3, 0, 1)]

SOURCES = {
    ("sea", "paper"): sea_tables("paper") + SEA_SCENES,
    ("sea", "multiple"): sea_tables("multiple") + SEA_SCENES,
    ("underwater", "thesis"): UNDERWATER + UNDERWATER_SCENES,
    ("underwater", "discrete_ordinates"): UNDERWATER + UNDERWATER_SCENES,
}
# The lamps under water: tests/perf/lamp_orders_sweep.sh's cases on tests/perf/lamp_glow.toml (one hard-edged
# lamp, no sun or sky), by quality.lamps_model. A region is judged with >= 20 pixels and a reference noise
# <= 10 % (the strongly forward-scattering cases' references are noisier than the daylight ones').
LAMPS = ["results/underwater/lamp_orders_fit.csv", "results/underwater/lamp_orders_heldout.csv",
         "results/underwater/lamp_orders_near.csv", "results/underwater/lamp_orders_fresh.csv"]
LAMP_MODELS = ["single", "delta_m", "orders"]
SOURCES.update({("lamps", m): [(t,) for t in LAMPS] for m in LAMP_MODELS})
# The shipped lamp scene measured as it is (tests/perf/rov_lights_tiles.sh: its lamps alone, the whole image and
# 3 x 3 tiles), with its Jerlov type and g; its lamp's cone and axis come from the scene file, and it has
# objects (rocks) in the lamps' light.
LAMP_SCENES = [("results/underwater/rov_lights_lamps_tiles.csv", "rov_lights", "1C", 0.9)]
SOURCES.update({("lamps", m): [(t,) for t in LAMPS] + [(t, scene) for t, scene, _, _ in LAMP_SCENES]
                for m in LAMP_MODELS})
HEADER = ["a", "b", "g", "bottom_m", "sun_zenith_deg", "sky", "floor", "surface", "objects", "cone_deg",
          "lamp_bottom_m", "max_abs_error", "worst_ratio", "reference_rel_se", "regions", "source"]


def lamp_glow_axis_slope():
    """The lamp's downward share of its axis in tests/perf/lamp_glow.toml: its axis meets the bottom at
    height / slope (the sweep's `height` is the lamp's height above the bottom)."""
    import tomllib
    with open(os.path.join(ROOT, "tests/perf/lamp_glow.toml"), "rb") as f:
        d = tomllib.load(f)["spotlights"][0]["direction"]
    return -d[1] / (d[0] ** 2 + d[1] ** 2 + d[2] ** 2) ** 0.5


def label(source):
    """A source's line in the .tables file: its path, and for a scene's rows of a shared table the scene."""
    if len(source) in (2, 9) and source[1] is not None:
        return f"{source[0]} ({source[1]})"
    return source[0]


def main():
    out_dir = sys.argv[1] if len(sys.argv) > 1 else "data/expected_error"
    rows = {k: [] for k in SOURCES}
    # The sea seen from above: flat_sea at 96x54, sun 40°, g 0.9 (results/sea_allorders/README.md).
    for model in ("paper", "multiple"):
        for source, (table, sun, sky, g) in enumerate(sea_tables(model)):
            for r in read(table):
                ratios = [float(r["ratio_near"]), float(r["ratio_far"])]
                worst = max(ratios, key=lambda x: abs(x - 1))
                se = max(float(r["ratio_near_se"]), float(r["ratio_far_se"]))
                bottom = -1 if r["bottom_m"] == "deep" else float(r["bottom_m"])
                rows[("sea", model)].append([round(at550("data/jerlov_a.csv", r["jerlov"]), 5),
                                             round(at550("data/jerlov_b.csv", r["jerlov"]), 5), g, bottom, sun, sky, 0, 0,
                                             0, 0, -1, round(abs(worst - 1), 4), round(worst, 4), round(se, 4), 2, source])
    # Under water: tests/perf/underwater_regions.toml, camera 3.8 m down, one band.
    regions = ["bottom_near", "bottom_far", "water_up", "water_down", "objects"]
    for source, (table, sun, sky) in enumerate(UNDERWATER):
        for r in read(table):
            judged = []
            for g in regions:
                pix, ratio, se = r[g + "_pixels"], r[g + "_ratio"], r[g + "_ref_rel_se"]
                if pix and ratio and se and int(pix) >= 40 and float(se) <= 0.02:
                    judged.append((float(ratio), float(se)))
            if not judged:
                continue
            worst = max(judged, key=lambda x: abs(x[0] - 1))
            bottom = -1 if r["depth_m"] in ("0", "none", "") or float(r["depth_m"]) == 0 else float(r["depth_m"])
            # The study's tables name the discrete-ordinates model by its earlier name.
            model = "discrete_ordinates" if r["model"] == "improved" else r["model"]
            rows[("underwater", model)].append([float(r["a"]), float(r["b"]), float(r["g"]), bottom, sun, sky, 0, 0, 0, 0, -1,
                                                round(abs(worst[0] - 1), 4), round(worst[0], 4),
                                                round(max(s for _, s in judged), 4), len(judged), source])
    for view, scenes, first in (("underwater", UNDERWATER_SCENES, len(UNDERWATER)),
                                ("sea", SEA_SCENES, len(sea_tables("multiple")))):
        for i, (table, scene, jerlov, g, bottom, sun, sky, floor, surface) in enumerate(scenes):
            by_model = {}
            for r in read(table):
                if scene is None or r["scene"] == scene:
                    by_model.setdefault(r["model"], []).append((float(r["ratio"]), float(r["ratio_se"])))
            for model, judged in by_model.items():
                worst = max(judged, key=lambda x: abs(x[0] - 1))
                rows[(view, model)].append([round(at550("data/jerlov_a.csv", jerlov), 5),
                                            round(at550("data/jerlov_b.csv", jerlov), 5), g, bottom, sun, sky, floor, surface,
                                            0, 0, -1, round(abs(worst[0] - 1), 4), round(worst[0], 4),
                                            round(max(e for _, e in judged), 4), len(judged), first + i])
    slope = lamp_glow_axis_slope()
    for source, table in enumerate(LAMPS):
        for r in read(table):
            judged = []
            for g in ("whole", "lit_bottom", "beam", "outside"):
                pix, ratio, se = r[g + "_pixels"], r[g + "_ratio"], r[g + "_ref_rel_se"]
                if pix and ratio and se and int(pix) >= 20 and float(se) <= 0.10:
                    judged.append((float(ratio), float(se)))
            worst = max(judged, key=lambda x: abs(x[0] - 1))
            # No bottom depth or sun: the lamp's layer is measured in the dark; its geometry is the cone and
            # the distance along the axis to the bottom.
            rows[("lamps", r["model"])].append([float(r["a"]), float(r["b"]), float(r["g"]), -1, 0, 0, 0, 0, 0,
                                                float(r["cone_deg"]), round(float(r["height_m"]) / slope, 4),
                                                round(abs(worst[0] - 1), 4), round(worst[0], 4),
                                                round(max(s for _, s in judged), 4), len(judged), source])
    for i, (table, scene, jerlov, g) in enumerate(LAMP_SCENES):
        import tomllib
        with open(os.path.join(ROOT, "scenes", scene + ".toml"), "rb") as f:
            spec = tomllib.load(f)
        lamp = spec["spotlights"][0]
        d = lamp["direction"]
        down = -d[1] / (d[0] ** 2 + d[1] ** 2 + d[2] ** 2) ** 0.5
        axis = (lamp["position"][1] + spec["bottom"]["depth"]) / down
        regions = read(table)
        for model in LAMP_MODELS:
            judged = [(float(r[model]), float(r["reference_rel_se"])) for r in regions]
            worst = max(judged, key=lambda x: abs(x[0] - 1))
            rows[("lamps", model)].append([round(at550("data/jerlov_a.csv", jerlov), 5),
                                           round(at550("data/jerlov_b.csv", jerlov), 5), g, -1, 0, 0, 0, 0, 1,
                                           float(lamp["cone_deg"]), round(axis, 4), round(abs(worst[0] - 1), 4),
                                           round(worst[0], 4), round(max(s for _, s in judged), 4), len(judged),
                                           len(LAMPS) + i])
    for (view, model), table in rows.items():
        with open(os.path.join(out_dir, f"{view}_{model}.csv"), "w", newline="") as f:
            w = csv.writer(f, lineterminator="\n")
            w.writerow(HEADER)
            w.writerows(table)
        with open(os.path.join(out_dir, f"{view}_{model}.tables"), "w") as f:
            f.write("".join(label(t) + "\n" for t in SOURCES[(view, model)]))


if __name__ == "__main__":
    main()
