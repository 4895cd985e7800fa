"""Matching water scenes for seasim and Mitsuba 3 (make validate): one scene description,
written as a seasim TOML and built as a Mitsuba scene, and the comparison by image regions. Used by
mitsuba_underwater.py (camera under water) and mitsuba_sea.py (the sea seen from above).

Mapping of conventions (seasim -> Mitsuba 3, variant scalar_rgb; docs/radiometry.md):
  one band, grey          [spectral] count = 1, range_nm = [559.5, 560.5], sensor = "identity": the band
                          centre is 560 nm, where the D65 scale of sun and sky is exactly 1, so
                          sun.irradiance and sky.radiance are the values themselves. Mitsuba renders
                          grey RGB (R = G = B) and channel R is compared. `seasim render` writes the raw
                          band; `seasim reference` writes the band's CIE Y (D65 -> 1) in grey, which for a
                          1 nm band at 560 nm is the raw band to 2e-5 (D65 and ȳ bend at 560).
  [water] a, b, g, ior    homogeneous medium, sigma_t = a + b, albedo = b / (a + b), hg phase with g;
                          a rectangle at y = 0 (normal +y, half-size 1 km) with a smooth `dielectric`
                          (int_ior = ior, ext_ior = 1) and the water as its interior; Mitsuba's
                          dielectric scales transmitted radiance by 1/eta², so radiance/n² is conserved
                          across it as in seasim.
  [bottom] depth, albedo  a rectangle at y = -depth (normal +y) with a `diffuse` bsdf (albedo/π), the
                          water as its exterior; no bottom: nothing (the water is 1 km deep).
  [sky] uniform, L        `constant` emitter of radiance L (the sky below the horizon is never reached:
                          the water is absorbing and 1 km wide).
  [sun] zenith, azimuth,  seasim's sun is a delta light under water: a beam refracted at the flat
        irradiance E⊥     surface, of irradiance E⊥ cos θ_z (1 - R(θ_z)) / cos θ_w normal to the
                          refracted beam (docs/radiometry.md "The sun"), reached only by next-event
                          estimation. A unidirectional path tracer cannot see a delta light through a
                          smooth dielectric, so Mitsuba renders the sun as a separate image: a
                          `directional` emitter along the refracted beam with that irradiance, and the
                          surface as the same dielectric for paths but transparent to shadow rays
                          (SunPassDielectric below: eval_null_transmission = 1). The sky image uses the
                          plain dielectric. The two images add (light is linear). Neither draws the
                          sun's disk or glint (seasim does not under water; the sea scenes keep the
                          glint out of view).
  camera fov_deg          perspective, fov_axis = "y" (seasim's fov is vertical); the sensor's medium is
                          the water when the camera is under the surface.
  pixel filter            seasim's path tracer jitters each path over the pixel, as Mitsuba's box
                          filter; `seasim render` samples pixel centres, so it is rendered at SS x SS
                          the resolution and block-averaged.
  all orders              volpathmis, max_depth = 1000 (Russian roulette from depth 5; volpath's
                          spectral MIS, right where the extinction differs between channels: prbvolpath
                          is not, Mitsuba issue 1846); seasim's path tracer: 1000 vertices and roulette
                          from the 3rd.
Noise: Mitsuba's from the spread of its seeds (spaced by SEED_STRIDE: consecutive seeds are correlated),
seasim's path tracer's from its standard-error image;
a ratio's ± is twice the standard error of both together.
"""
import math
import os
import subprocess

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_rgb")

SS = 4  # supersampling per axis of `seasim render` (pixel centres) to match Mitsuba's box filter
# Mitsuba 3.9's scalar sampler behaves as if pixel i were seeded with seed + i (measured, not read in
# its source): seed 1's image is largely seed 0's shifted by one pixel (957 pixel values equal to the
# other seed's neighbour, against 30-110 at other shifts), so consecutive seeds are not independent and
# their spread understates the noise of a region's mean. Seeds k x 1000003 show no such excess.
SEED_STRIDE = 1000003


class SunPassDielectric(mi.BSDF):
    """A smooth dielectric for paths, transparent to shadow rays: lets volpathmis's next-event estimation
    reach the sun's refracted beam, a directional emitter in the water, as seasim's path tracer does."""

    def __init__(self, props):
        mi.BSDF.__init__(self, props)
        self.inner = mi.load_dict({"type": "dielectric", "int_ior": props.get("int_ior", 1.333), "ext_ior": 1.0})
        self.m_flags = self.inner.flags()
        self.m_components = [self.inner.flags(0), self.inner.flags(1)]

    def sample(self, ctx, si, sample1, sample2, active=True):
        return self.inner.sample(ctx, si, sample1, sample2, active)

    def eval(self, ctx, si, wo, active=True):
        return mi.Spectrum(0.0)  # delta lobes only

    def pdf(self, ctx, si, wo, active=True):
        return 0.0

    def eval_pdf(self, ctx, si, wo, active=True):
        return mi.Spectrum(0.0), 0.0

    def eval_null_transmission(self, si, active=True):
        return mi.Spectrum(1.0)

    def to_string(self):
        return "SunPassDielectric"


mi.register_bsdf("sunpass_dielectric", lambda props: SunPassDielectric(props))


def fresnel(cos_i, n):
    """Unpolarised Fresnel reflectance from air (1) into n at incidence cosine cos_i."""
    sin_t2 = (1.0 - cos_i * cos_i) / (n * n)
    cos_t = math.sqrt(1.0 - sin_t2)
    rs = (cos_i - n * cos_t) / (cos_i + n * cos_t)
    rp = (n * cos_i - cos_t) / (n * cos_i + cos_t)
    return 0.5 * (rs * rs + rp * rp)


def sun_in_water(s):
    """The refracted sun: unit vector towards it in the water, and its irradiance normal to the beam."""
    n, th, ph = s["ior"], math.radians(s["sun_zenith"]), math.radians(s["sun_azimuth"])
    sin_w = math.sin(th) / n
    cos_w = math.sqrt(1.0 - sin_w * sin_w)
    to_sun = [sin_w * math.cos(ph), cos_w, sin_w * math.sin(ph)]  # azimuth from +x towards +z
    e_beam = s["sun_irradiance"] * math.cos(th) * (1.0 - fresnel(math.cos(th), n)) / cos_w
    return to_sun, e_beam


def scene_toml(s, scale=1):
    bottom = f"""[bottom]
type = "flat"
depth = {s['bottom_depth']}
albedo = {s['bottom_albedo']}
""" if s["bottom_depth"] else ""
    extra = "".join(f"{line}\n" for line in s.get("toml_extra", []))
    return f"""[scene]
name = "{s['name']}"
[camera]
position = {list(s['camera'])}
look_at = {list(s['look_at'])}
up = [0.0, 1.0, 0.0]
fov_deg = {s['fov']}
width = {s['width'] * scale}
height = {s['height'] * scale}
[sun]
zenith_deg = {s['sun_zenith']}
azimuth_deg = {s['sun_azimuth']}
irradiance = {s['sun_irradiance']}
[sky]
model = "uniform"
radiance = {s['sky_radiance']}
[water]
wavelengths_nm = [560.0]
a = [{s['a']}]
b = [{s['b']}]
g = {s['g']}
ior = {s['ior']}
[surface]
type = "flat"
{bottom}[spectral]
count = 1
range_nm = [559.5, 560.5]
sensor = "identity"
{extra}"""


def mitsuba_scene(s, part, seed, spp):
    """part = "sky" (the uniform sky, plain dielectric) or "sun" (the refracted beam, SunPassDielectric)."""
    T = mi.ScalarTransform4f
    c = s["a"] + s["b"]
    water = {"type": "homogeneous", "sigma_t": c, "albedo": s["b"] / c,
             "phase": {"type": "hg", "g": s["g"]} if s["g"] != 0 else {"type": "isotropic"}}
    surface_bsdf = ({"type": "sunpass_dielectric", "int_ior": s["ior"]} if part == "sun" else
                    {"type": "dielectric", "int_ior": s["ior"], "ext_ior": 1.0})
    sensor = {"type": "perspective", "fov": s["fov"], "fov_axis": "y",
              "to_world": T().look_at(origin=list(s["camera"]), target=list(s["look_at"]), up=[0, 1, 0]),
              "film": {"type": "hdrfilm", "width": s["width"], "height": s["height"], "rfilter": {"type": "box"},
                       "pixel_format": "rgb"},
              "sampler": {"type": "independent", "sample_count": spp, "seed": seed}}
    if s["camera"][1] < 0:
        sensor["medium"] = {"type": "ref", "id": "water"}
    d = {"type": "scene", "integrator": {"type": "volpathmis", "max_depth": 1000}, "water": water, "sensor": sensor,
         "surface": {"type": "rectangle", "to_world": T().rotate([1, 0, 0], -90).scale([1000, 1000, 1]),
                     "bsdf": surface_bsdf, "interior": {"type": "ref", "id": "water"}}}
    if s["bottom_depth"]:
        d["bottom"] = {"type": "rectangle",
                       "to_world": T().translate([0, -s["bottom_depth"], 0]).rotate([1, 0, 0], -90).scale([1000, 1000, 1]),
                       "bsdf": {"type": "diffuse", "reflectance": s["bottom_albedo"]},
                       "exterior": {"type": "ref", "id": "water"}}
    if part == "sun":
        to_sun, e_beam = sun_in_water(s)
        d["sun"] = {"type": "directional", "direction": [-x for x in to_sun], "irradiance": e_beam}
    else:
        d["sky"] = {"type": "constant", "radiance": s["sky_radiance"]}
    return mi.load_dict(d)


def render_mitsuba(s, seeds, spp):
    """One image (channel R) per seed: sky and sun rendered separately and added."""
    runs = []
    for seed in range(seeds):
        img = sum(np.array(mi.render(mitsuba_scene(s, part, (seed + 1) * SEED_STRIDE, spp)), dtype=np.float64)[:, :, 0]
                  for part in ("sky", "sun"))
        runs.append(img)
    return runs


def read_band(path, scale=1):
    """The one band of a seasim EXR (render: the raw band; reference: its grey RGB), box-averaged."""
    img = np.array(mi.Bitmap(path), dtype=np.float64)
    if img.ndim == 3:
        img = img[:, :, 0]
    h, w = img.shape[0] // scale, img.shape[1] // scale
    return img.reshape(h, scale, w, scale).mean(axis=(1, 3))


def seasim(binary, args, env_dir):
    env = dict(os.environ)
    env.setdefault("POCL_CACHE_DIR", os.path.join(env_dir, "pocl-cache"))
    env.setdefault("SEASIM_CACHE_DIR", os.path.join(env_dir, "seasim-cache"))
    subprocess.run([binary] + args, check=True, stdout=subprocess.DEVNULL, env=env)


def pixel_rays(s):
    """Unit view directions through the pixel centres, as seasim's pinhole camera (H x W x 3)."""
    eye, target = np.array(s["camera"], float), np.array(s["look_at"], float)
    f = (target - eye) / np.linalg.norm(target - eye)
    r = np.cross(f, [0.0, 1.0, 0.0])
    r /= np.linalg.norm(r)
    u = np.cross(r, f)
    t = math.tan(math.radians(s["fov"]) / 2)
    W, H = s["width"], s["height"]
    px = (2 * (np.arange(W) + 0.5) / W - 1) * t * W / H
    py = (1 - 2 * (np.arange(H) + 0.5) / H) * t
    d = f[None, None, :] + px[None, :, None] * r[None, None, :] + py[:, None, None] * u[None, None, :]
    return d / np.linalg.norm(d, axis=2, keepdims=True)


def region_row(label, mask, runs, ref, ref_se, others):
    """Ratios of region means to Mitsuba's: seasim's path tracer with ± 2 combined standard errors,
    then each fast model's ratio (Mitsuba's ± 2 se only: the fast models are deterministic)."""
    per_run = np.array([r[mask].mean() for r in runs])
    m = per_run.mean()
    se_m = per_run.std(ddof=1) / math.sqrt(len(runs))
    a = ref[mask].mean()
    se_a = math.sqrt((ref_se[mask] ** 2).sum()) / mask.sum()
    ratio = a / m
    se_ratio = ratio * math.sqrt((se_a / a) ** 2 + (se_m / m) ** 2)
    cells = [f"{label} ({mask.sum()} px)", f"{m:.5g}", f"{ratio:.4f} ± {2 * se_ratio:.4f}",
             f"{(ratio - 1) / se_ratio:+.1f}"]
    cells += [f"{o[mask].mean() / m:.3f} ± {2 * o[mask].mean() / m * se_m / m:.3f}" for o in others]
    return "| " + " | ".join(cells) + " |"


def pixel_z_rms(runs, ref, ref_se):
    """RMS over pixels of (seasim path tracer - Mitsuba) / combined standard error: about 1 if the
    two agree within noise."""
    m = np.mean(runs, axis=0)
    se_m = np.std(runs, axis=0, ddof=1) / math.sqrt(len(runs))
    z = (ref - m) / np.sqrt(se_m ** 2 + ref_se ** 2 + 1e-30)
    return float(np.sqrt(np.mean(z ** 2)))
