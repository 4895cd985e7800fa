/* shafts_params.h — the parameter blocks of kernels/shafts.cl, shared with host/passes/shafts_pass.cpp
 * (which static_asserts their layout). No float3 inside (16 bytes in OpenCL C): vectors are float[4].
 * Included as plain C on both sides (not through kernel_math.h: it holds no math). */

/* Object types (ShaftsObject.type). */
#define SHAFTS_SPHERE 0
#define SHAFTS_BOX 1
#define SHAFTS_PLANE 2

typedef struct {
  float cam_pos[4];      /* m, world */
  float cam_right[4];    /* worldFromCamera basis, unit */
  float cam_up[4];
  float cam_forward[4];
  float tan_half_fov_y;
  float aspect;          /* width / height */
  float rho;             /* ρ, particle density: the scattering coefficient of 001 eq. 3, 1/m */
  float sigma_t;         /* ρκ, extinction coefficient, 1/m (001 eq. 1, 3) */
  float pad2;            /* (the sampling planes' range is per pixel and per lamp: shafts.cl) */
  float pad3;
  float hg_g;            /* Henyey–Greenstein asymmetry (SEASIM_SHAFTS_HG) */
  float s_min;           /* m, smallest light distance used in 1/s² (the lamp's radius) */
  float table_s_max;     /* m, range of the h(s,t) table over s (table mode): every plane's s */
  float table_t_max;     /* m, range over t: every plane's t (the far field does not use the table) */
  float pad0, pad1;
  int width;
  int height;
  int light_count;
  int object_count;
  int planes;            /* n sampling planes (001 eq. 5) */
  int subplanes;         /* m sub-sample planes per interval (001 eq. 7–9) */
  int shadow_map_size;   /* texels per side, per light */
  int table_size;        /* F table entries; the h table is table_size x table_size */
} ShaftsParams;

typedef struct {
  float position[4];     /* m, lamp position */
  float direction[4];    /* unit beam axis: the light frame's +z */
  float right[4];        /* unit, light frame +x (light-map u) */
  float up[4];           /* unit, light frame +y (light-map v) */
  float color[4];        /* W/sr on the axis, per R,G,B: intensity x colour tint */
  float cos_cone;        /* cos of the cone half angle */
  float cos_inner;       /* cos(cone - falloff): full intensity inside */
  float tan_cone;        /* the shadow map and light map span [-tan_cone, tan_cone]^2 in x/z, y/z */
  int light_map_offset;  /* first float of this light's RGB light map in the light-map buffer; -1: none */
  int light_map_width;
  int light_map_height;
  int shadow_offset;     /* first texel of this light's shadow map */
  int pad;
} ShaftsLight;

typedef struct {
  float a[4];            /* sphere: centre (xyz), radius (w); box: min; plane: point */
  float b[4];            /* box: max; plane: unit normal */
  float albedo[4];       /* Lambertian reflectance per R,G,B */
  int type;              /* SHAFTS_SPHERE, SHAFTS_BOX, SHAFTS_PLANE */
  int pad[3];
} ShaftsObject;
