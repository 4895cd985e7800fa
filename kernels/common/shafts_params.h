/* shafts_params.h — the parameter blocks of kernels/shafts.cl, shared with host/passes/shafts_pass.cpp
 * (which static_asserts their layout). No float3 inside (16 bytes in OpenCL C): vectors are float[4].
 * Included as plain C on both sides; kernel_math.h includes it for common/shafts_render.h. */
#ifndef SEASIM_SHAFTS_PARAMS_H
#define SEASIM_SHAFTS_PARAMS_H

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
  float panel_rad;       /* intervals method: widest quadrature panel, radians of the lamp's angle */
  float map_panel_texels; /* intervals method: widest panel over a light map, in its texels */
  float hg_g;            /* Henyey–Greenstein asymmetry (SEASIM_SHAFTS_HG) */
  float s_min;           /* m, smallest light distance used in 1/s² (the lamp's radius) */
  float table_s_max;     /* m, range of the h(s,t) table over s (table mode): every plane's s */
  float table_t_max;     /* m, range over t: every plane's t (the far field does not use the table) */
  int march_steps;       /* march method: midpoint steps per ray and lamp, uniform in the lamp's angle */
  float pad1;
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

/* The shadow volume of one object from one lamp (intervals method, common/shafts_intervals.h's
 * ShaftsShadowVolume in float[4]s): inside every plane n.xyz . p <= n.w (the first plane_count), and
 * inside the cone of apex `apex`, axis xyz and cos w when has_cone. always: 1 every point is in
 * shadow (the lamp is inside the object), -1 none is. Indexed [light * object_count + object]. */
#define SHAFTS_OCCLUDER_PLANES 9
typedef struct {
  float planes[SHAFTS_OCCLUDER_PLANES][4];
  float apex[4];
  float axis[4];
  int plane_count;
  int has_cone;
  int always;
  int pad;
} ShaftsOccluder;

#endif /* SEASIM_SHAFTS_PARAMS_H */
