/* output_layers.h — the per-pixel ground-truth layers' maths (host/scene/output_layers.h names them):
 * what the G-buffer's hit becomes in the geometry layers, and the image-formation model's effective
 * coefficients of Akkaynak & Treibitz ("A revised underwater image formation model", CVPR 2018;
 * "Sea-thru", CVPR 2019), I = J e^{-β_D z} + B∞ (1 - e^{-β_B z}), solved per pixel for
 *   β_D = -ln(direct / clear) / z          (direct = J T: the surface's light that arrives unscattered)
 *   β_B = -ln(1 - backscatter / B∞) / z     (backscatter: the water's in-scattered light over z)
 * with z the range. Both are 0/0 as z → 0 (direct → clear, backscatter → 0) and undefined where the
 * light is 0 (black objects, no veiling light) or z is infinite (open water): -log1p of the small
 * difference keeps the z → 0 ratio exact down to the float's resolution (the log of the ratio itself
 * where it is far from 1), and every undefined case returns 0 with *defined = 0 instead of NaN/Inf (docs/layers.md, docs/stiff_cases.md).
 * Plain C, compiled as OpenCL C and as C++ in float and double (host/math/kernel_math.h); after
 * underwater.h (UW_INFINITE). Its kernels are built without -cl-fast-relaxed-math: the finiteness
 * tests below must not be folded away.
 */

/* |x| below the largest float: false for Inf and NaN (NaN compares false). */
SEASIM_FN int layer_finite(real x) { return fabs(x) < R(3.0e38); }
/* object_id: 0 water (rays into open water and to the surface), 1 the bottom, 2 + object index. */
SEASIM_FN int layer_object_id(int mat) { return mat >= 0 ? mat + 2 : (mat == UW_MAT_BOTTOM ? 1 : 0); }

/* Whether a G-buffer distance is a hit (raycast.cl writes >= UW_INFINITE for open water). */
SEASIM_FN int layer_hit(real S) { return S < R(0.5) * UW_INFINITE; }

/* depth: the hit's camera z, S d·forward (the camera looks along +forward). */
SEASIM_FN real layer_depth(real S, real3 d, real3 forward) { return S * dot(d, forward); }

/* The sensor's weighted mean of a per-band value over one channel's weights: Σ a w / Σ w (0 when the
 * channel's weights are all 0). */
SEASIM_FN real layer_weighted_mean(real sum_aw, real sum_w) { return sum_w > R(0.0) ? sum_aw / sum_w : R(0.0); }

/* β_D = -ln(direct / clear) / z. Defined for z in (0, ∞) with clear > 0 and direct > 0; the log of a
 * ratio near 1 as log1p((direct - clear) / clear), exact as z → 0. Beyond those: 0, *defined = 0. */
SEASIM_FN real layer_beta_d(real direct, real clear, real z, int* defined) {
  const int ok = z > R(0.0) && layer_hit(z) && clear > R(0.0) && direct > R(0.0);
  *defined = ok;
  if (!ok) return R(0.0);
  /* Near 1 the ratio's difference from 1 carries the value (log1p); far from it the ratio itself does
   * (direct/clear - 1 would round to -1 once the ratio is below the float's epsilon). */
  const real ratio = direct / clear;
  const real beta = -(fabs(ratio - R(1.0)) < R(0.5) ? log1p((direct - clear) / clear) : log(ratio)) / z;
  /* z below the float's resolution of the ratio (z ~ 1e-38): the quotient itself may overflow. */
  *defined = layer_finite(beta);
  return layer_finite(beta) ? beta : R(0.0);
}

/* β_B = -ln(1 - backscatter / B∞) / z. Defined for z in (0, ∞) with B∞ > 0 and 0 <= backscatter < B∞
 * (at backscatter = B∞ the path is saturated and β_B is infinite). 0 backscatter gives 0. */
SEASIM_FN real layer_beta_b(real backscatter, real veiling, real z, int* defined) {
  const int ok = z > R(0.0) && layer_hit(z) && veiling > R(0.0) && backscatter >= R(0.0) && backscatter < veiling;
  *defined = ok;
  if (!ok) return R(0.0);
  /* The same two forms: log1p(-q) for a small share q, the log of the rest (veiling - backscatter, exact
   * by Sterbenz when close) for a share near 1. */
  const real rest = (veiling - backscatter) / veiling;
  const real beta = -(rest > R(0.5) ? log1p(-backscatter / veiling) : log(rest)) / z;
  *defined = layer_finite(beta);
  return layer_finite(beta) ? beta : R(0.0);
}
