/* export.h: what the file exporters share: VMD's sizes for lines, points and text, world
 * transforms of scene items, tessellation for formats without spheres, cylinders or cones,
 * dashed lines, and the stroke font text is drawn with. */
#ifndef MS_EXPORT_H
#define MS_EXPORT_H

#include <stdio.h>

#include "vecmath/vecf.h"
#include "scene/scene.h"

#define MS_EXPORT_LINE_RADIUS 0.002f    /* VMD: width 1 lines and size 1 points */
#define MS_EXPORT_DASH 0.02f            /* VMD's dash length */
#define MS_EXPORT_TEXT_HEIGHT 0.1f      /* capital height of size-1 text, world units */

/* Triangles with per-vertex unit normals, in the coordinates given. */
typedef void (*ms_tri_cb)(void *ud, const float p[9], const float n[9]);
/* A UV sphere: max(res, 2) stacks of 2 * max(res, 2) slices (2 * slices * (stacks - 1)
 * triangles). */
void ms_tess_sphere(const float c[3], float r, int res, ms_tri_cb cb, void *ud);
/* A truncated cone (a cylinder when rb == ra) of max(res, 3) sides, with the ends named in
 * caps (MS_CAP_BASE, MS_CAP_APEX) closed by triangle fans. */
void ms_tess_cone(const float base[3], const float apex[3], float rb, float ra, int res,
                  int caps, ms_tri_cb cb, void *ud);

/* A triangle cut by the item's clip planes: the kept part, as triangles, to cb. */
void ms_export_clip_tri(const ms_scene_item *it, const float p[9], const float n[9],
                        ms_tri_cb cb, void *ud);

/* Triangle t of a mesh moved by the 4x4 transform m (walk.c): its corners in p, their
 * normals (dequantized) in n. */
void ms_export_mesh_tri(const ms_dl_mesh *ms, size_t t, const float *m, float p[9], float n[9]);

/* Segments. */
typedef void (*ms_seg_cb)(void *ud, const float a[3], const float b[3]);
/* VMD's dashed line: dashes of MS_EXPORT_DASH with gaps of the same length. */
/* Shorten the segment a-b to the part the item's clip planes keep; 0 when nothing is. */
int ms_export_clip_seg(const ms_scene_item *it, float a[3], float b[3]);
void ms_export_dashes(const float a[3], const float b[3], ms_seg_cb cb, void *ud);
/* Strokes of a string written from anchor along +x with +y up (screen-aligned in VMD's
 * default view), capital height size * MS_EXPORT_TEXT_HEIGHT. */
void ms_export_text(const char *s, const float anchor[3], float size, ms_seg_cb cb, void *ud);

/* Every primitive of a scene in world coordinates (walk.c). A solid whose callback is NULL,
 * and every solid of a list cut by clip planes, is tessellated into triangles; triangles and
 * segments are cut by the list's planes; lines, points or text with a NULL callback are left
 * out (text is drawn as segments). item and item_end, when set, open and close each list. */
typedef struct ms_export_visitor {
    void (*item)(void *ud, const ms_scene_item *it);
    void (*item_end)(void *ud, const ms_scene_item *it);
    void (*sphere)(void *ud, const float c[3], float r, ms_rgba8 col, int res);
    void (*cylinder)(void *ud, const float a[3], const float b[3], float r, ms_rgba8 col,
                     int caps, int res);
    void (*cone)(void *ud, const float base[3], const float apex[3], float rbase, float rapex,
                 ms_rgba8 col, int res);
    void (*triangle)(void *ud, const float p[9], const float n[9], const ms_rgba8 c[3]);
    void (*line)(void *ud, const float a[3], const float b[3], ms_rgba8 col);
    void (*point)(void *ud, const float c[3], ms_rgba8 col);
} ms_export_visitor;
void ms_export_walk(const ms_scene *s, const ms_export_visitor *v, void *ud);

/* Write a scene file: open path through base/safewrite, call body (with user), and put the
 * file in place when body returned 0 and every write succeeded. 0, or -1 with err set,
 * nothing left. */
typedef int (*ms_export_body_fn)(const ms_scene *s, FILE *f, void *user, ms_error *err);
int ms_export_file(const ms_scene *s, const char *path, ms_export_body_fn body, void *user,
                   ms_error *err);

/* Number text as printf's "%g" and "%.3f" give it, written faster (numfmt.c). out needs 32
 * bytes; the length is returned. */
int ms_fmt_g(char *out, float v);
int ms_fmt_f3(char *out, float v);

/* World-space helpers for scene items. */
static inline float ms_item_scale(const ms_scene_item *it)
{
    return ms_mat4_scale_factor(it->xform);
}

#endif
