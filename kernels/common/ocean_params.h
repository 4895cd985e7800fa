/* ocean_params.h — the parameter blocks of kernels/ocean.cl and kernels/caustics.cl, shared with
 * host/passes/ocean_pass.cpp and host/passes/caustics_pass.cpp (which static_assert the layout).
 * No float3 inside (16 bytes in OpenCL C); explicit padding. */
typedef struct {
  float patch_size;           /* L, m: side of the periodic patch (004 §3.3) */
  float wind_speed;           /* V, m/s (004 eq. 23) */
  float wind_dir_x;           /* unit wind direction ŵ, x component */
  float wind_dir_z;           /* ŵ, z component */
  float phillips_a;           /* A (004 eq. 23), our normalisation: see ocean_spectrum.h */
  float directional_exponent; /* p in |k̂·ŵ|^p (2 in eq. 23, 6 in Figure 8) */
  float small_wave;           /* ℓ, m: suppression exp(-k²ℓ²) (004 eq. 24) */
  float depth;                /* D, m: finite-depth dispersion (004 eq. 15); 0 = deep water */
  float loop_period;          /* T, s: quantised frequencies (004 eq. 18); 0 = no loop */
  float time;                 /* t, s (used when loop_period == 0) */
  float loop_phase;           /* fmod(t, T) / T computed on the host in double (loop_period > 0) */
  float choppiness;           /* λ (004 eq. 29) */
  float gravity;              /* g, m/s² */
  unsigned int seed;          /* RNG key: same seed -> same ocean on every device */
  int n;                      /* N, grid points per side (power of two, 16..2048) */
  int pad0;
} OceanParams;

typedef struct {
  float sun_dir[4];      /* unit vector towards the sun (y up), [3] unused */
  float patch_size;      /* L, m (the caustic map covers the same periodic patch) */
  float plane_depth;     /* d, m below the mean surface y = 0 */
  float ior;             /* water relative to air */
  float attenuation;     /* c, 1/m: Beer–Lambert along the refracted path */
  float choppiness;      /* λ, as the ocean pass used it */
  int n;                 /* surface grid N */
  int map_size;          /* caustic map M x M texels over the patch */
  int supersample;       /* s: s x s refracted rays per surface cell */
} CausticsParams;
