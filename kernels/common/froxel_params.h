/* froxel_params.h — the parameter block of the froxel single-scattering pass (kernels/froxel.cl,
 * 002 §5) and of its per-pixel read in kd_multiple.cl (common/froxel.h froxel_lookup), shared with
 * host/passes/froxel_pass.cpp (which static_asserts the layout). No float3 inside (16 bytes in OpenCL
 * C): vectors are float[4]. Plain C on both sides, included before host/math/kernel_math.h's
 * namespaces (it holds no math). The camera, sun and water come from UwParams/UwBand
 * (underwater_params.h); this block holds only what the froxel grid adds.
 *
 * Grid (common/froxel.h): nx × ny columns uniform over the screen, each along the view ray through
 * its centre; nz slices along that ray (distance along the ray, not camera depth), slice k ending at
 * z_{k+1} = z_near (z_far/z_near)^{(k+1)/nz}, slice 0 starting at 0.
 * Volume (froxel.cl output): 4 floats per froxel at ((k ny + j) nx + i): R, G, B single scattering
 * integrated from the camera to the END of slice k (sensor RGB, 002 eq. 4.8), and the column's
 * vertical direction d_y (froxel_lookup's in-slice fraction needs where the column leaves the water and
 * its rate 1 - d_y/μ_w).
 */

#ifndef SEASIM_FROXEL_PARAMS_H /* also included by host/math/kernel_math.h */
#define SEASIM_FROXEL_PARAMS_H

/* FroxelParams.injection (froxel.cl follows its define SEASIM_SPECTRAL_INJECTION; this copy is for
 * reports and the CPU evaluation). */
#define FROXEL_INJECTION_SPECTRAL 0 /* inject and integrate per wavelength band, accumulate RGB */
#define FROXEL_INJECTION_RGB 1      /* three pseudo-bands with sensor-weighted coefficients (002 eq. 5.3–5.4) */

typedef struct {
  float shadow_origin[4];  /* m, world: centre of the sun shadow map's plane, above every bounded object */
  float shadow_right[4];   /* unit, ⊥ sun_dir_water: texel x */
  float shadow_up[4];      /* unit, ⊥ sun_dir_water and shadow_right: texel y */
  float sigma_t_rgb[4];    /* 1/m, R,G,B pseudo-band extinction: RGB injection, and the in-slice
                              weighting of froxel_lookup in both modes (times the rate 1 - d_y/μ_w) */
  float sigma_s_rgb[4];    /* 1/m, R,G,B pseudo-band scattering; with e_beam_rgb for reports only: */
  float e_beam_rgb[4];     /* sensor R,G,B of the beam just below the surface; froxel_integrate reads
                              the pseudo-bands from its band buffer (froxelRgbPseudoBands) */
  float z_near;            /* m, end of the first slice is z_near (z_far/z_near)^{1/nz} */
  float z_far;             /* m, end of the last slice; pixels farther read the value at z_far */
  float log_far_near;      /* log(z_far / z_near), computed once in double: host and device slice alike */
  float shadow_half_extent;/* m, the map covers [-h, h]² around shadow_origin in (right, up) */
  float shadow_bias;       /* m, a point is shadowed when it lies this far beyond the occluder */
  float mu_w;              /* the refracted sun's cosine to the vertical, >= 1e-4 (froxel_integrate_column's) */
  float cam_depth;         /* m, the camera's depth below the surface (-cam_pos.y): where a column leaves the water */
  float pad2;
  int nx, ny, nz;          /* froxel grid */
  int shadow_size;         /* texels per side of the shadow map; 0: no bounded objects (no map) */
  int injection;           /* FROXEL_INJECTION_* */
  int pad3, pad4, pad5;
} FroxelParams;

#endif /* SEASIM_FROXEL_PARAMS_H */
