/* underwater_band_table.h — the layout of kd_multiple.cl's band table: every per-band value the band
 * loop reads that does not depend on the pixel, computed once per frame on the host
 * (host/underwater/underwater_band_table.cpp) and read UW_BAND_LANES_MAX bands at a time with vector loads
 * (common/band_lanes.h). Plain C on both sides, included once (like underwater_params.h).
 *
 * Row r of the table holds one value for every band: table[r * stride + band], stride =
 * UW_BAND_STRIDE(band_count). The padding bands have sensor weight 0 and copy the last band's other
 * values (finite, so the lanes they fill cost nothing and add nothing). After the UW_ROWS rows of the
 * water and light, one row of albedo per object (UW_ROWS + object index); with underwater.model =
 * "discrete_ordinates", UWI_ROWS more after those (row UW_ROWS + object count + UWI_ROW_*), read by
 * common/underwater_ordinates_bands.h.
 */
#ifndef SEASIM_UNDERWATER_BAND_TABLE_H
#define SEASIM_UNDERWATER_BAND_TABLE_H

#define UW_BAND_LANES_MAX 16
#define UW_BAND_STRIDE(n) ((((n) + UW_BAND_LANES_MAX - 1) / UW_BAND_LANES_MAX) * UW_BAND_LANES_MAX)

#define UW_ROW_C 0             /* σ_t, 1/m */
#define UW_ROW_KD 1            /* K_d, 1/m */
#define UW_ROW_K_BEAM 2        /* σ_t / max(μ_w, 1e-4): the sun beam's attenuation per metre of depth */
#define UW_ROW_MS_TOTAL 3      /* σ_s/(4π) (e_sky0 + e_sun0): 002 eq. 4.7's factor for the whole E(y) */
#define UW_ROW_MS_DIRECT 4     /* σ_s/(4π) e_sun0: the same for the direct beam's part */
#define UW_ROW_E_TOTAL 5       /* e_sky0 + e_sun0 */
#define UW_ROW_E_SUN 6         /* e_sun0 */
#define UW_ROW_E_BEAM 7        /* e_beam0 */
#define UW_ROW_SKY 8           /* the sky's uniform radiance in air */
#define UW_ROW_SKY_W_R 9       /* the band's share of the sky shape's R, G, B (common/sky_view.h) */
#define UW_ROW_SKY_W_G 10
#define UW_ROW_SKY_W_B 11
#define UW_ROW_W_R 12          /* sensor weights (002 eq. 4.8); 0 for padding bands */
#define UW_ROW_W_G 13
#define UW_ROW_W_B 14
#define UW_ROW_BOTTOM_ALBEDO 15
#define UW_ROWS 16

/* underwater.model = "discrete_ordinates" (common/underwater_ordinates_bands.h): UwiBand's values
 * (common/underwater_ordinates_params.h) and what the model makes of them without the pixel. */
#define UWI_ROW_C_DM 0         /* delta-M extinction c', 1/m: view rays */
#define UWI_ROW_K 1            /* the diffuse field's attenuation k, 1/m */
#define UWI_ROW_M 2            /* the delta-M beam's attenuation with depth c'/μ_w, 1/m */
#define UWI_ROW_B_E_BEAM 3     /* b e_beam0 (times p_HG: the beam scattered once) */
#define UWI_ROW_D1 4           /* E_d's coefficients of e^{-k y}, e^{-k (H - y)}, e^{-m y}: the bottom's light */
#define UWI_ROW_D2 5
#define UWI_ROW_DP 6
#define UWI_ROW_BOTTOM_L 7     /* the bottom's sunlit, unshadowed radiance (uwi_lambert at y = H, n up) */
/* The start factors of the camera's integrals (UwiStart, common/underwater_ordinates_bands.h): every primary
 * ray starts at the camera's depth o_d = -cam_pos[1], the same for the whole frame. */
#define UWI_ROW_EXP_K_OD 8     /* e^{-k o_d} */
#define UWI_ROW_EXP_M_OD 9     /* e^{-m o_d} */
#define UWI_ROW_EXP_BEAM_OD 10 /* e^{-(σ_t/μ_w) o_d} (UW_ROW_K_BEAM's attenuation) */
#define UWI_ROW_EXP_K_HOD 11   /* e^{-k max(H - o_d, 0)}: the bottom's term, whose integral runs from the bottom */
#define UWI_ROW_EXP_K_H 12     /* e^{-k H}: the same for the surface's reflected ray (o_d = 0); 1 without a bottom */
/* The source's table (UwiBand.src): node j's term q in row UWI_ROW_SRC + j * UWI_SOURCE_TERMS + q
 * (common/underwater_ordinates_params.h); then the tilted plane's irradiance table (UwiBand.tilt) the same
 * way from UWI_ROW_TILT. */
#define UWI_ROW_SRC 13
#define UWI_ROW_TILT (UWI_ROW_SRC + UWI_SOURCE_NODES * UWI_SOURCE_TERMS)
#define UWI_ROW_TILT_BOTTOM (UWI_ROW_TILT + UWI_TILT_NODES * UWI_SOURCE_TERMS) /* UwiBand.tilt_bottom: node j's
                                                                            term q in row + j * 3 + q */
/* The forward peak (UwiBand.p_clip, aureole_single, aureole): the TMS term's phase ceiling (a
 * large float where UwiBand has none), the aureole's once-scattered part per unit of (p_HG - p_clip)+, its
 * table, node j in row UWI_ROW_AUREOLE + j, and its azimuth modes per source node that the source's table holds. */
#define UWI_ROW_P_CLIP (UWI_ROW_TILT_BOTTOM + UWI_TILT_NODES * 3)
#define UWI_ROW_AUREOLE_1 (UWI_ROW_P_CLIP + 1)
#define UWI_ROW_AUREOLE (UWI_ROW_AUREOLE_1 + 1)
#define UWI_ROW_AUREOLE_M (UWI_ROW_AUREOLE + UWI_AUREOLE_NODES) /* UwiBand.aureole_modes: source node j's mode m
                                                                   in row + j * 3 + m */
/* UwiBand.src_sand: source node j's term q in row UWI_ROW_SRC_SAND + j * 3 + q; then sand_beam, sand_diffuse. */
#define UWI_ROW_SRC_SAND (UWI_ROW_AUREOLE_M + UWI_SOURCE_NODES * 3)
#define UWI_ROW_SAND_BEAM (UWI_ROW_SRC_SAND + UWI_SOURCE_NODES * 3)
#define UWI_ROW_SAND_DIFFUSE (UWI_ROW_SAND_BEAM + 1)
#define UWI_ROWS (UWI_ROW_SAND_DIFFUSE + 1)

#endif /* SEASIM_UNDERWATER_BAND_TABLE_H */
