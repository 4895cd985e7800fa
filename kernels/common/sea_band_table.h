/* sea_band_table.h — the layout of sea_single.cl's band table: SeaBand's per-band values and eq. 5's
 * LUT, one row per quantity with the bands contiguous, so that the band lanes (common/sea_bands.h) read
 * SEA_BAND_LANES_MAX bands with one vector load. Built once per pass by the host
 * (host/passes/sea_band_table.cpp). Plain C on both sides, included once.
 *
 * Row r holds one value for every band: table[r * stride + band], stride = SEA_BAND_STRIDE(band_count).
 * The padding bands have sensor weight 0 and copy the last band's other values (finite, so the lanes
 * they fill cost nothing and add nothing). After the SEA_ROWS rows of SeaBand's fields come the
 * lut_size rows of eq. 5's LUT (SEASIM_SEA_LUT): row SEA_ROW_LUT + j holds entry j of every band's
 * table (the host's per-band LUT transposed; the angle, hence j, is the same for every band of a pixel).
 * sea.model "multiple" has no LUT; its rows from SEA_ROW_ORDINATES hold κ, one row per node.
 */
#ifndef SEASIM_SEA_BAND_TABLE_H
#define SEASIM_SEA_BAND_TABLE_H

#define SEA_BAND_LANES_MAX 16
#define SEA_BAND_STRIDE(n) ((((n) + SEA_BAND_LANES_MAX - 1) / SEA_BAND_LANES_MAX) * SEA_BAND_LANES_MAX)

#define SEA_ROW_SUN 0            /* SeaBand.sun_irradiance, normal to the sun */
#define SEA_ROW_SKY 1            /* SeaBand.sky_radiance, the uniform level */
#define SEA_ROW_A 2              /* absorption, 1/m */
#define SEA_ROW_B 3              /* scattering, 1/m */
#define SEA_ROW_C 4              /* attenuation, 1/m */
#define SEA_ROW_BOTTOM_ALBEDO 5
#define SEA_ROW_W_R 6            /* sensor weights (002 eq. 4.8); 0 for padding bands */
#define SEA_ROW_W_G 7
#define SEA_ROW_W_B 8
#define SEA_ROW_SKY_W_R 9        /* the band's share of the sky shape's R, G, B (common/sky.h) */
#define SEA_ROW_SKY_W_G 10
#define SEA_ROW_SKY_W_B 11
#define SEA_ROWS 12
#define SEA_ROW_LUT SEA_ROWS     /* + j: eq. 5's LUT entry j (SEASIM_SEA_LUT; lut_size rows) */
#define SEA_ROW_ORDINATES SEA_ROWS /* + node: sea.model "multiple"'s factor κ at node SEA_ORD_ROW (common/
                                    * sea_ordinates.h; SEA_ORD_LAYER rows, SEA_ORD_NODES over a height field;
                                    * in place of the LUT it never has) */

#endif /* SEASIM_SEA_BAND_TABLE_H */
