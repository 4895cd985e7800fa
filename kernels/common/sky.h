/* sky.h — sky radiance models for the sea seen from above: a uniform
 * sky, an environment image and analytic skies. kernels/sea_single.cl picks one by
 * SEASIM_SKY_MODEL (set by host/plan): 0 uniform, 1 analytic, 2 image. Needs compat.h.
 *
 * Every model is a direction-dependent shape times the band's sky radiance L_sky(λ) (the scene's
 * [sky] radiance × the D65 shape, host/spectral): L(λ, d) = L_sky(λ) · scale · shape(d). The host
 * sets scale = 1 / (cosine-weighted mean of the shape over the upper hemisphere), so that
 *   (1/π) ∫_{d.y > 0} L(λ, d) cos θ dω = L_sky(λ):
 * every model gives the same sky irradiance π L_sky on a horizontal surface as the uniform sky of
 * the same `radiance` (the underwater model's E_sky0 assumes that), and only the distribution changes.
 *
 * Analytic (1): the CIE standard clear sky (CIE S 011/E:2003, ISO 15469:2004, sky type 12 "CIE
 * standard clear sky, low illuminance turbidity"): a luminance distribution relative to the zenith,
 *   shape(θ, χ) = φ(θ) f(χ),  φ(θ) = 1 + a exp(b / cos θ),  f(χ) = 1 + c (e^{dχ} − e^{dπ/2}) + e cos²χ,
 * θ the view's zenith angle, χ its angle to the sun, (a, b, c, d, e) = (−1, −0.32, 10, −3, 0.45).
 * The standard's division by φ(0) f(Z_sun) is a constant absorbed by our own scale. The shape is the
 * same at every wavelength (spectrally flat: a luminance distribution, not Preetham's chromaticity).
 * Positive everywhere (φ ∈ [0.274, 1], f ≥ 0.90), so the mean is never 0.
 *
 * Image (2): a latitude–longitude environment image, RGB linear, 4 reals per texel (R, G, B, unused),
 * row-major, top row first. Column u ∈ [0, 1) is the azimuth 2πu measured from +x towards +z (the
 * scene's sun azimuth convention), row v ∈ [0, 1] the zenith angle πv (top row: the zenith, middle:
 * the horizon). Bilinear between texel centres, wrapping in azimuth, clamped at the poles. Per band
 * the image's R, G, B are mixed by sky_image_band_weights (a partition of unity over wavelength), so a
 * grey image gives exactly L_sky(λ) × its normalised luminance, and scale = 1 / (cosine-weighted mean
 * luminance Y = 0.2126 R + 0.7152 G + 0.0722 B over the upper hemisphere).
 *
 * Preetham (3): Preetham, Shirley & Smits 1999, "A Practical Analytic Model for Daylight" (SIGGRAPH
 * 99), Appendix A.2: luminance Y and chromaticity x, y each follow Perez et al.'s distribution
 *   F(θ, γ) = (1 + A e^{B / cos θ}) (1 + C e^{D γ} + E cos²γ),   Y = Y_z F(θ, γ) / F(0, θ_s)
 * (and so for x, y), with A…E linear in the turbidity T (sky_preetham_coefficients) and the zenith
 * chromaticity x_z, y_z a cubic in θ_s times a quadratic in T. The zenith luminance Y_z is absorbed by
 * the scale, like every model's overall level. Spectral (sky_preetham_daylight): x, y → the CIE
 * daylight spectrum S0 + M1 S1 + M2 S2 (CIE 15:2004 §3.1, as Preetham 1999 §A.3 does) at luminance Y,
 * as three basis weights that each band mixes by S_k(λ) / D65(λ). (sky_preetham_rgb, x, y, Y → XYZ →
 * linear Rec. 709 RGB with negative primaries clamped to 0, is kept for the zenith chromaticity test
 * and the RGB view of the sky.) The host packs, per quantity (Y, x, y), A…E and zenith / F(0, θ_s)
 * into 18 reals, then the daylight basis's luminance weights n0, n1, n2 and the daylight-locus flag
 * (22 in all; the sky buffer). The
 * fit covers T ∈ [2, 10] and the sun above the horizon: the parser takes T ∈ [1.7, 10], and θ_s is
 * clamped to 90° (a sun below the horizon gives the sky of a sun at the horizon).
 *
 * Stiff cases: the horizon (cos θ → 0 in b / cos θ: clamped to 1e-4, where exp underflows to 0
 * and φ = 1, its limit); the zenith; the sun below the horizon (χ up to π: every term finite); the
 * view straight up (atan2(0, 0) = 0). Below the horizon the analytic shape holds its horizon value
 * (cos θ is clamped) and the image gives its lower half; sea_single.cl never asks there (a reflected
 * ray pointing down is clamped to the horizon first, sea_waves.h).
 */

#define SEASIM_SKY_UNIFORM 0
#define SEASIM_SKY_ANALYTIC 1
#define SEASIM_SKY_IMAGE 2
#define SEASIM_SKY_PREETHAM 3

/* CIE type 12 coefficients. */
#define SKY_CIE_A R(-1.0)
#define SKY_CIE_B R(-0.32)
#define SKY_CIE_C R(10.0)
#define SKY_CIE_D R(-3.0)
#define SKY_CIE_E R(0.45)

/* φ(θ) of the CIE clear sky from cos θ of the view (θ to the zenith). */
SEASIM_FN real sky_cie_gradation(real cos_theta) {
  const real c = fmax(cos_theta, R(1e-4)); /* horizon: b/c -> -inf, exp -> 0, φ -> 1 */
  return R(1.0) + SKY_CIE_A * exp(SKY_CIE_B / c);
}

/* f(χ) of the CIE clear sky from cos χ (χ the angle between the view and the sun). */
SEASIM_FN real sky_cie_indicatrix(real cos_chi) {
  const real cc = clamp(cos_chi, R(-1.0), R(1.0));
  const real chi = acos(cc);
  return R(1.0) + SKY_CIE_C * (exp(SKY_CIE_D * chi) - exp(SKY_CIE_D * R(0.5) * SEASIM_PI)) + SKY_CIE_E * cc * cc;
}

/* The CIE clear sky's relative luminance towards unit direction d, sun towards unit direction sun. */
SEASIM_FN real sky_cie_clear_shape(real3 d, real3 sun) {
  return sky_cie_gradation(d.y) * sky_cie_indicatrix(dot(d, sun));
}

/* (1/π) ∫_{upper hemisphere} shape cos θ dω by the midpoint rule. With s = cos²θ, cos θ dω = ½ ds dφ,
 * so the cosine-weighted mean is the plain mean of the shape over (s, φ) ∈ [0, 1] × [0, 2π): n_s × n_phi
 * midpoints. 128 × 256 is within 3e-4 of a 1024 × 2048 rule for any sun (tests/unit/sky_test.cpp). */
SEASIM_FN real sky_cie_clear_cosine_mean(real3 sun, int n_s, int n_phi) {
  real sum = R(0.0);
  for (int i = 0; i < n_s; ++i) {
    const real s = ((real)i + R(0.5)) / (real)n_s;
    const real ct = sqrt(s), st = sqrt(R(1.0) - s);
    real row = R(0.0);
    for (int k = 0; k < n_phi; ++k) {
      const real phi = R(2.0) * SEASIM_PI * ((real)k + R(0.5)) / (real)n_phi;
      row += sky_cie_clear_shape(MAKE_REAL3(st * cos(phi), ct, st * sin(phi)), sun);
    }
    sum += row;
  }
  return sum / ((real)n_s * (real)n_phi);
}

/* Bilinear RGB of a latitude–longitude image (layout above) towards unit direction d. In kernels the
 * angles come from polynomial_trig.h (within 2.2e-8 rad of the library's: 1e-4 of a texel of a
 * 4096-wide image), which needs no library call per read. */
SEASIM_FN real3 sky_latlong_rgb(const SEASIM_GLOBAL real* texels, int w, int h, real3 d) {
  real u = lookup_atan2(d.z, d.x) / (R(2.0) * SEASIM_PI); /* [-1/2, 1/2] */
  u = u - floor(u);                                  /* [0, 1]; 1 only by rounding, handled by the wrap */
  const real v = lookup_acos(clamp(d.y, R(-1.0), R(1.0))) / SEASIM_PI;
  const real fx = u * (real)w - R(0.5);
  const real fy = clamp(v * (real)h - R(0.5), R(0.0), (real)(h - 1));
  int x0 = (int)floor(fx);
  const real tx = fx - (real)x0;
  x0 = x0 < 0 ? x0 + w : (x0 >= w ? x0 - w : x0);
  const int x1 = x0 + 1 < w ? x0 + 1 : 0;
  int y0 = (int)floor(fy);
  y0 = y0 < 0 ? 0 : (y0 > h - 1 ? h - 1 : y0);
  const real ty = fy - (real)y0;
  const int y1 = y0 + 1 < h ? y0 + 1 : h - 1;
  const SEASIM_GLOBAL real* t00 = texels + 4 * (y0 * w + x0);
  const SEASIM_GLOBAL real* t10 = texels + 4 * (y0 * w + x1);
  const SEASIM_GLOBAL real* t01 = texels + 4 * (y1 * w + x0);
  const SEASIM_GLOBAL real* t11 = texels + 4 * (y1 * w + x1);
  real c[3];
  for (int k = 0; k < 3; ++k) {
    const real top = t00[k] + tx * (t10[k] - t00[k]);
    const real bottom = t01[k] + tx * (t11[k] - t01[k]);
    c[k] = top + ty * (bottom - top);
  }
  return MAKE_REAL3(c[0], c[1], c[2]);
}

/* Preetham's A…E for Y, x, y at turbidity t (1999, Appendix A.2), into c[15]: c[5 q + k], q = Y, x, y. */
SEASIM_FN void sky_preetham_coefficients(real t, real c[15]) {
  const real slope[15] = {R(0.1787), R(-0.3554), R(-0.0227), R(0.1206), R(-0.0670),
                          R(-0.0193), R(-0.0665), R(-0.0004), R(-0.0641), R(-0.0033),
                          R(-0.0167), R(-0.0950), R(-0.0079), R(-0.0441), R(-0.0109)};
  const real offset[15] = {R(-1.4630), R(0.4275), R(5.3251), R(-2.5771), R(0.3703),
                           R(-0.2592), R(0.0008), R(0.2125), R(-0.8989), R(0.0452),
                           R(-0.2608), R(0.0092), R(0.2102), R(-1.6537), R(0.0529)};
  for (int k = 0; k < 15; ++k) c[k] = slope[k] * t + offset[k];
}

/* Perez's F(θ, γ) from cos θ of the view (clamped at the horizon, as the CIE sky's), γ, the angle
 * between the view and the sun, and its cosine cos_gamma (which a caller that found γ by acos has:
 * PoCL's cos of γ, with its argument reduction, was a tenth of a filtered sea's frame); c: A…E. */
SEASIM_FN real sky_perez_cos(const real* c, real cos_theta, real gamma, real cos_gamma) {
  const real ct = fmax(cos_theta, R(1e-4));
  return (R(1.0) + c[0] * exp(c[1] / ct)) * (R(1.0) + c[2] * exp(c[3] * gamma) + c[4] * cos_gamma * cos_gamma);
}

/* sky_perez_cos with the cosine of γ computed here. */
SEASIM_FN real sky_perez(const real* c, real cos_theta, real gamma) {
  return sky_perez_cos(c, cos_theta, gamma, cos(gamma));
}

/* Zenith chromaticity x_z, y_z (1999, Appendix A.2) for sun zenith angle theta_s (radians) and
 * turbidity t. */
SEASIM_FN void sky_preetham_zenith_xy(real theta_s, real t, real* xz, real* yz) {
  const real th = theta_s, th2 = th * th, th3 = th2 * th, t2 = t * t;
  *xz = t2 * (R(0.00166) * th3 - R(0.00375) * th2 + R(0.00209) * th) +
        t * (R(-0.02903) * th3 + R(0.06377) * th2 - R(0.03202) * th + R(0.00394)) +
        (R(0.11693) * th3 - R(0.21196) * th2 + R(0.06052) * th + R(0.25886));
  *yz = t2 * (R(0.00275) * th3 - R(0.00610) * th2 + R(0.00317) * th) +
        t * (R(-0.04214) * th3 + R(0.08970) * th2 - R(0.04153) * th + R(0.00516)) +
        (R(0.15346) * th3 - R(0.26756) * th2 + R(0.06670) * th + R(0.26688));
}

/* The 18 reals of the Preetham sky (header): per quantity Y, x, y, A…E then zenith / F(0, θ_s),
 * with the zenith luminance taken as 1. */
SEASIM_FN void sky_preetham_pack(real3 sun, real t, real packed[18]) {
  real c[15];
  sky_preetham_coefficients(t, c);
  const real theta_s = acos(clamp(sun.y, R(0.0), R(1.0)));
  real xz, yz;
  sky_preetham_zenith_xy(theta_s, t, &xz, &yz);
  const real zenith[3] = {R(1.0), xz, yz};
  for (int q = 0; q < 3; ++q) {
    for (int k = 0; k < 5; ++k) packed[6 * q + k] = c[5 * q + k];
    packed[6 * q + 5] = zenith[q] / sky_perez(c + 5 * q, R(1.0), theta_s);
  }
}

/* The sun Preetham's model sees: held at the horizon when below it (the fit's range). */
SEASIM_FN real3 sky_preetham_sun(real3 sun) {
  if (sun.y >= R(0.0)) return sun;
  const real h = sqrt(sun.x * sun.x + sun.z * sun.z);
  return h > R(1e-12) ? MAKE_REAL3(sun.x / h, R(0.0), sun.z / h) : MAKE_REAL3(R(1.0), R(0.0), R(0.0));
}

/* Preetham's Y, x, y (v[0], v[1], v[2]) of a view at cos θ = cos_theta to the zenith and cos γ =
 * cos_gamma to sky_preetham_sun's sun: the model depends on the view through these two alone.
 * packed: the 18 reals of sky_preetham_pack. */
SEASIM_FN void sky_preetham_yxy_cos(const SEASIM_GLOBAL real* packed, real cos_theta, real cos_gamma, real* v) {
  cos_gamma = clamp(cos_gamma, R(-1.0), R(1.0));
  /* polynomial_trig.h's acos in kernels (2.2e-8 rad: 7e-8 relative in exp(D γ) for |D| <= 3): PoCL's
   * acosf was 9 % of a filtered sea's frame under this sky. */
  const real gamma = lookup_acos(cos_gamma);
#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
  /* sky_perez_cos for Y, x and y as the lanes of one real3: two vector exps for six scalar ones (the
   * sky was a third of a filtered sea's frame under Preetham's sky); the host's loop below checks it. */
#define SKY_PREETHAM_LANES(k) MAKE_REAL3(packed[(k)], packed[6 + (k)], packed[12 + (k)])
  const real ct = fmax(cos_theta, R(1e-4));
  const real3 f = (R(1.0) + SKY_PREETHAM_LANES(0) * exp(SKY_PREETHAM_LANES(1) / ct)) *
                  (R(1.0) + SKY_PREETHAM_LANES(2) * exp(SKY_PREETHAM_LANES(3) * gamma) +
                   SKY_PREETHAM_LANES(4) * (cos_gamma * cos_gamma));
  const real3 yxy = SKY_PREETHAM_LANES(5) * f;
#undef SKY_PREETHAM_LANES
  v[0] = yxy.x;
  v[1] = yxy.y;
  v[2] = yxy.z;
#else
  for (int q = 0; q < 3; ++q) {
    real c[5];
    for (int k = 0; k < 5; ++k) c[k] = packed[6 * q + k];
    v[q] = packed[6 * q + 5] * sky_perez_cos(c, cos_theta, gamma, cos_gamma);
  }
#endif
}

/* Preetham's Y, x, y towards unit d (v[0], v[1], v[2]); packed: the 18 reals of sky_preetham_pack;
 * sun: unit, towards the sun, held at the horizon when below it. */
SEASIM_FN void sky_preetham_yxy(const SEASIM_GLOBAL real* packed, real3 d, real3 sun, real* v) {
  sky_preetham_yxy_cos(packed, d.y, dot(d, sky_preetham_sun(sun)), v);
}

/* Linear Rec. 709 RGB (relative) of the Preetham sky towards unit d; sun: unit, towards the sun,
 * held at the horizon when below it. */
SEASIM_FN real3 sky_preetham_rgb(const SEASIM_GLOBAL real* packed, real3 d, real3 sun) {
  real v[3];
  sky_preetham_yxy(packed, d, sun, v);
  const real Y = fmax(v[0], R(0.0)), x = v[1], y = fmax(v[2], R(1e-4));
  const real X = x * Y / y, Z = (R(1.0) - x - y) * Y / y;
  const real r = R(3.2404542) * X - R(1.5371385) * Y - R(0.4985314) * Z;
  const real g = R(-0.9692660) * X + R(1.8760108) * Y + R(0.0415560) * Z;
  const real b = R(0.0556434) * X - R(0.2040259) * Y + R(1.0572252) * Z;
  return MAKE_REAL3(fmax(r, R(0.0)), fmax(g, R(0.0)), fmax(b, R(0.0)));
}

/* The CIE daylight basis weights M1, M2 of chromaticity x, y (CIE 15:2004 §3.1, eq. 3.5–3.6; the
 * daylight spectrum is S0 + M1 S1 + M2 S2): M = 0.0241 + 0.2562 x − 0.7341 y, negative for every
 * chromaticity near the daylight locus (about −0.12 there); held at −1e-3 so that a chromaticity far
 * off it (never met by Preetham's fit over its range) stays finite. Preetham 1999 §A.3 uses the same. */
SEASIM_FN void sky_daylight_m(real x, real y, real* m1, real* m2) {
  const real m = fmin(R(0.0241) + R(0.2562) * x - R(0.7341) * y, R(-1e-3));
  *m1 = (R(-1.3515) - R(1.7703) * x + R(5.9114) * y) / m;
  *m2 = (R(0.0300) - R(31.4424) * x + R(30.0717) * y) / m;
}

/* The CIE daylight locus, y_D = −3.000 x² + 2.870 x − 0.275 (CIE 15:2004 eq. 3.3; Judd, MacAdam &
 * Wyszecki 1964 fitted it to measured daylight and skylight spectra), stated for x in [0.250, 0.380]
 * (25000 K to 4000 K) and used as the same smooth quadratic past its ends. sky.chromaticity =
 * "daylight_locus" keeps Preetham's x (his correlated colour) and lifts a y below the locus onto it:
 * near the horizon Preetham's separate Perez fits for x and y put y 0.010–0.017 below the locus
 * (towards magenta: the pink band of docs/journal/noon_colour.md), which measured daylight does not
 * show, while overhead they sit on it (within 3e-3). A y above the locus (greener: the blue sky away
 * from the sun, +0.011 at x = 0.248, past the locus's stated range) is left as Preetham has it. */
SEASIM_FN real sky_daylight_locus_y(real x) { return R(-3.0) * x * x + R(2.870) * x - R(0.275); }

/* The spectral Preetham sky from Preetham's Y and x, y of a view (v[0], v[1], v[2]): from x, y the CIE
 * daylight spectrum S(λ) = S0 + M1 S1 + M2 S2 scaled to luminance Y. Returned as the three weights of
 * the basis, (Y, Y M1, Y M2) / N with N = n0 + M1 n1 + M2 n2 the spectrum's luminance, so that a band
 * takes dot(w_λ, shape) with w_λ = S_k(λ) / D65(λ) (host/passes/sea_sky.cpp): linear in the shape
 * like every model's, and the luminance of the band radiances is exactly Y times the uniform sky's.
 * packed: the 18 reals of sky_preetham_pack, then n0, n1, n2 = ∫ S_k ȳ dλ / ∫ D65 ȳ dλ (the host's,
 * from data/cie_daylight_components.csv), then packed[21]: 1 to hold the chromaticity no lower than
 * the daylight locus (sky_daylight_locus_y), 0 for Preetham's own y (22 reals in all). */
SEASIM_FN real3 sky_preetham_daylight_of_yxy(const SEASIM_GLOBAL real* packed, const real* v) {
  /* packed[21] = 1: sky.chromaticity = "daylight_locus", y no lower than the locus (sky_daylight_locus_y). */
  const real y = packed[21] > R(0.5) ? fmax(v[2], sky_daylight_locus_y(v[1])) : v[2];
  real m1, m2;
  sky_daylight_m(v[1], y, &m1, &m2);
  const real n = fmax(packed[18] + m1 * packed[19] + m2 * packed[20], R(1e-6));
  const real k = fmax(v[0], R(0.0)) / n;
  return MAKE_REAL3(k, k * m1, k * m2);
}

/* The same from the view's cos θ to the zenith and cos γ to sky_preetham_sun's sun. */
SEASIM_FN real3 sky_preetham_daylight_cos(const SEASIM_GLOBAL real* packed, real cos_theta, real cos_gamma) {
  real v[3];
  sky_preetham_yxy_cos(packed, cos_theta, cos_gamma, v);
  return sky_preetham_daylight_of_yxy(packed, v);
}

/* The same towards unit d, sun: unit, towards the sun (held at the horizon when below it). */
SEASIM_FN real3 sky_preetham_daylight(const SEASIM_GLOBAL real* packed, real3 d, real3 sun) {
  return sky_preetham_daylight_cos(packed, d.y, dot(d, sky_preetham_sun(sun)));
}

/* (1/π) ∫_{upper hemisphere} Y cos θ dω of the spectral Preetham sky (its luminance, Y of each view),
 * by the midpoint rule in (s = cos²θ, φ) as sky_cie_clear_cosine_mean. */
SEASIM_FN real sky_preetham_daylight_cosine_mean(const SEASIM_GLOBAL real* packed, real3 sun, int n_s, int n_phi) {
  real sum = R(0.0);
  for (int i = 0; i < n_s; ++i) {
    const real s = ((real)i + R(0.5)) / (real)n_s;
    const real ct = sqrt(s), st = sqrt(R(1.0) - s);
    for (int k = 0; k < n_phi; ++k) {
      const real phi = R(2.0) * SEASIM_PI * ((real)k + R(0.5)) / (real)n_phi;
      const real3 w = sky_preetham_daylight(packed, MAKE_REAL3(st * cos(phi), ct, st * sin(phi)), sun);
      sum += w.x * packed[18] + w.y * packed[19] + w.z * packed[20];
    }
  }
  return sum / ((real)n_s * (real)n_phi);
}

/* Luminance of linear Rec. 709 / sRGB primaries. */
SEASIM_FN real sky_luminance(real3 rgb) { return R(0.2126) * rgb.x + R(0.7152) * rgb.y + R(0.0722) * rgb.z; }

/* (1/π) ∫_{upper hemisphere} Y cos θ dω of the image taken as constant per texel: each texel row
 * [θ0, θ1] (clipped to θ ≤ π/2) spans ∫ cos θ sin θ dθ dφ = (sin²θ1 − sin²θ0)/2 · 2π/w per texel.
 * The bilinear reading differs from this by the interpolation only (< 1 % for smooth images;
 * tests/unit/sky_test.cpp). */
SEASIM_FN real sky_latlong_cosine_mean_luminance(const SEASIM_GLOBAL real* texels, int w, int h) {
  real sum = R(0.0);
  for (int y = 0; y < h; ++y) {
    const real th0 = SEASIM_PI * (real)y / (real)h;
    if (th0 >= R(0.5) * SEASIM_PI) break;
    const real th1 = fmin(SEASIM_PI * (real)(y + 1) / (real)h, R(0.5) * SEASIM_PI);
    const real s0 = sin(th0), s1 = sin(th1);
    const real weight = R(0.5) * (s1 * s1 - s0 * s0) * R(2.0) / (real)w; /* (1/π) · row band · 2π/w */
    real row = R(0.0);
    for (int x = 0; x < w; ++x) {
      const SEASIM_GLOBAL real* t = texels + 4 * (y * w + x);
      row += sky_luminance(MAKE_REAL3(t[0], t[1], t[2]));
    }
    sum += weight * row;
  }
  return sum;
}

/* How much of the image's R, G and B a band at lambda_nm takes: blue alone up to 450 nm, green
 * alone at 540 nm, red alone from 610 nm, linear in between; the three sum to 1 at every wavelength,
 * so a grey image is spectrally flat (times the D65 sky spectrum). A deliberately simple RGB -> band
 * spreading: the image carries three numbers per direction, not a spectrum. */
SEASIM_FN real3 sky_image_band_weights(real lambda_nm) {
  const real blue = clamp((R(540.0) - lambda_nm) / R(90.0), R(0.0), R(1.0));
  const real red = clamp((lambda_nm - R(540.0)) / R(70.0), R(0.0), R(1.0));
  return MAKE_REAL3(red, R(1.0) - blue - red, blue);
}

/* (1/π) ∫_{upper hemisphere} Y cos θ dω of the Preetham sky's RGB (its luminance), by the midpoint rule
 * in (s = cos²θ, φ) as sky_cie_clear_cosine_mean. */
SEASIM_FN real sky_preetham_cosine_mean(const SEASIM_GLOBAL real* packed, real3 sun, int n_s, int n_phi) {
  real sum = R(0.0);
  for (int i = 0; i < n_s; ++i) {
    const real s = ((real)i + R(0.5)) / (real)n_s;
    const real ct = sqrt(s), st = sqrt(R(1.0) - s);
    for (int k = 0; k < n_phi; ++k) {
      const real phi = R(2.0) * SEASIM_PI * ((real)k + R(0.5)) / (real)n_phi;
      sum += sky_luminance(sky_preetham_rgb(packed, MAKE_REAL3(st * cos(phi), ct, st * sin(phi)), sun));
    }
  }
  return sum / ((real)n_s * (real)n_phi);
}
