/* sea_second_params.h — the parameter block of kernels/sea_second.cl, shared with
 * host/passes/sea_second_pass.cpp (which static_asserts its layout). Bands use SeaBand of
 * sea_params.h. No float3 inside (16 bytes in OpenCL C): vectors are float[4]. */
typedef struct {
  float cam_pos[4];      /* m, world */
  float cam_right[4];    /* worldFromCamera basis, unit */
  float cam_up[4];
  float cam_forward[4];
  float sun_in_water[4]; /* unit travel direction of the refracted sunlight (y < 0) */
  float tan_half_fov_y;
  float aspect;          /* width / height */
  float ior;             /* water relative to air */
  float g;               /* HG asymmetry of the water's volume scattering function */
  float bottom_depth;    /* m, flat bottom (SEASIM_HAS_BOTTOM) */
  float cos_io;          /* cosine of the refracted sun to the downward vertical, > 0 */
  float sun_beam;        /* E_h T_i / cos_io per unit band sun irradiance (0: sun below the horizon) */
  float table_c;         /* 1/m, reference attenuation of the depth-table nodes (SEASIM_BOTTOM_HEIGHTFIELD;
                            bottom_depth is then the deepest node of the floor) */
  int width;             /* image, px */
  int height;
  int band_count;
  int n_z;               /* sampling planes */
  int n_theta;           /* sampling directions n_d = n_theta * n_phi */
  int n_phi;
  int map_size;          /* scattering-map sampling points per side (map_size^2 per plane) */
  int vsf_size;          /* entries of the volume-scattering-function map */
} SeaSecondParams;

/* Rows of bands (the scattering maps, the planes' weights, the bands themselves) and of sampling
 * directions (the height field's depth tables and the direction table) are padded to a multiple of the
 * widest band lanes (common/band_lanes.h), so that a lane loop reads every band or direction in whole
 * vector steps. A padded band is zero (the host pads the bands: c = 0, no sensor weight; the kernels
 * write 0 into the maps' and the weights' padding), a padded direction has weight 0 and distance 0, so
 * each adds exactly 0. */
#define SEA_SECOND_LANES_MAX 16
#define SEA_SECOND_STRIDE(n) ((((n) + SEA_SECOND_LANES_MAX - 1) / SEA_SECOND_LANES_MAX) * SEA_SECOND_LANES_MAX)
