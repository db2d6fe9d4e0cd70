/* rt_common.h: what TachyonInternal shares with the OpenCL tracer (src/oclrt), free of
 * Embree so that both build without the other: Tachyon's texture terms, transforms, the
 * camera, the shader settings, strokes as cylinders and spheres, the option checks
 * (common.c, camera.c, strokes.c); vectors and matrices are vecmath/vecf.h's. */
#ifndef MS_RT_COMMON_H
#define MS_RT_COMMON_H

#include "rt/rt.h"
#include "scene/displaylist.h"
#include "scene/material.h"
#include "scene/scene.h"
#include "vecmath/vecf.h"

/* Tachyon's smallest contribution worth computing (1/512). */
#define RT_MINCONTRIB 0.001953125f

/* The Tachyon texture terms of a display list, as render/tachyon.c writes them. */
typedef struct rt_material {
    float ambient, diffuse, mirror;   /* mirror: Tachyon's "Specular" (reflection) */
    float phong, phongexp;            /* Blinn-Phong highlight: VMD's specular, shininess */
    float opacity;                    /* multiplied by each primitive's alpha */
    float outline, outlinewidth;
    int r3d;                          /* angle-modulated (Raster3D) transparency */
} rt_material;

/* Tachyon's texture terms of a material as render/tachyon.c writes them (lit: the list is
 * shaded; unlit lists are ambient only). */
void rt_material_terms(const ms_material *m, int lit, rt_material *t);

/* A placed list's transform: list to world (3x4 row-major), world to list, the normal
 * matrix (inverse transpose of the 3x3), the scale of radii (the cube root of the
 * determinant's magnitude: VMD's transforms are rotations, translations and uniform
 * scales) and the determinant's sign (-1: a mirror image, which turns a mesh's winding). */
typedef struct rt_xform {
    float xf[12], inv[12], nm[9];
    float scale, sign;
} rt_xform;
/* The transform of a 4x4 row-major matrix; -1 when it is singular (nothing to see). */
int rt_xform_make(rt_xform *t, const float x[16]);
/* The secondary-ray offset of a scene, from its size. */
float rt_world_eps(const ms_scene *s);
/* The lines, points and text of a placed list as world-space cylinders and spheres appended
 * to out (strokes.c). 0, or -1 when memory runs out. */
int rt_strokes(const ms_scene_item *it, ms_displaylist *out);
/* The discs that close a list's cylinder ends and cone bases (the exporter closes cone
 * bases), in the list's coordinates: closed base ends, closed apex ends, then cone bases.
 * normal is the axis (apex - base, not unit); inner radii are 0. alpha: some colour is
 * translucent. */
typedef struct rt_discs {
    size_t n;
    float *centre, *normal, *outer, *inner;
    ms_rgba8 *color;
    int alpha;
} rt_discs;
/* One list to trace: a scene item's list with its transform, texture terms and cap discs, or
 * the world-space list made of an item's lines, points and text (identity transform). */
typedef struct rt_source {
    const ms_displaylist *dl;
    const float *xform;
    rt_material mat;
    rt_discs discs;
    const ms_scene_item *item;  /* the scene item it comes from (its clip planes) */
} rt_source;
/* What both tracers trace, derived once from a scene: the sources, and the stroke lists and
 * discs made for them (owned here). */
typedef struct rt_sources {
    rt_source *src;
    size_t n;
    ms_displaylist **lists;
    size_t nlists, caplists;
} rt_sources;
/* The sources of a scene: 0, or -1 with err set when memory runs out (set then empty). */
int rt_sources_make(rt_sources *set, const ms_scene *s, ms_error *err);
void rt_sources_free(rt_sources *set);
/* The limits of the samples and the image size: 0, or -1 with err saying which is wrong. */
int rt_check_options(const ms_scene *s, const ms_rt_options *o, ms_error *err);

/* ---------------------------------------------------------------- camera (camera.c) */

typedef struct rt_camera {
    int ortho, width, height;
    float eye[3], dir[3], up[3], right[3];
    float half_w, half_h;       /* perspective: at unit distance; orthographic: world units */
    int dof;
    float focal, lens_radius;
} rt_camera;

void rt_camera_init(rt_camera *c, const ms_scene *s);
/* The ray through image point (px, py) (pixels from the top left corner); lens: a point of
 * the unit disc for depth of field, or NULL for the pinhole ray. dir is unit length. */
void rt_camera_ray(const rt_camera *c, float px, float py, const float lens[2], float org[3],
                   float dir[3]);

/* ---------------------------------------------------------------- shader settings */

typedef enum rt_bg_mode { RT_BG_SOLID, RT_BG_SKY_SPHERE, RT_BG_SKY_PLANE } rt_bg_mode;

typedef struct rt_shader {
    const struct rt_world *w;   /* TachyonInternal's world (NULL for the OpenCL tracer) */
    rt_camera cam;
    int nlights;
    float ldir[MS_SCENE_LIGHTS][3], lcol[MS_SCENE_LIGHTS][3];
    float light_scale;          /* AO's aodirect, else 1 */
    int full;                   /* Tachyon's Full shader: shadows (and AO) */
    int ao_samples;
    float ao_col[3];
    rt_bg_mode bg_mode;
    float bg[3], bg_top[3], bg_bot[3], grad_top, grad_bot;
    int fog;
    ms_cuemode cuemode;
    float fog_start, fog_end, fog_density;
} rt_shader;

/* The settings of shade.c's shading for a scene (common.c). */
void rt_shader_init(rt_shader *sh, const ms_scene *s, const struct rt_world *w, int aosamples);

/* ---------------------------------------------------------------- small vectors */

/* out = m (3x3 row-major) applied to vector v (points: ms_mat4_point of vecmath/vecf.h). */
/* A direction by a 3x4 transform's linear part (not normalised). */
void rt_xf_dir(const float m[12], const float v[3], float out[3]);
void rt_m3_vec(const float m[9], const float v[3], float out[3]);

#endif
