/* underwater_band_table.h — the layout of kd_multiple.cl's band table: every per-band value the band
 * loop reads that does not depend on the pixel, computed once per frame on the host
 * (host/underwater/underwater_band_table.cpp) and read UW_BAND_LANES_MAX bands at a time with vector loads
 * (common/band_lanes.h). Plain C on both sides, included once (like underwater_params.h).
 *
 * Row r of the table holds one value for every band: table[r * stride + band], stride =
 * UW_BAND_STRIDE(band_count). The padding bands have sensor weight 0 and copy the last band's other
 * values (finite, so the lanes they fill cost nothing and add nothing). After the UW_ROWS rows of the
 * water and light, one row of albedo per object (UW_ROWS + object index).
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

#endif /* SEASIM_UNDERWATER_BAND_TABLE_H */
