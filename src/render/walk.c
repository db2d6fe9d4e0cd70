/* walk.c: every primitive of a scene in world coordinates, for the exporters that write one
 * record per primitive (STL, Raster3D, VRML-2, X3D, RenderMan): spheres, cylinders and cones
 * reach the format's own callback or are tessellated into triangles when it has none; mesh
 * triangles come one by one with their vertex normals and colours; lines (dashes drawn) and
 * text strokes come as segments, points as points. A list cut by clip planes has its solids
 * tessellated and every triangle and segment cut (render/clip.c), since none of these
 * formats has clip planes. ms_export_file writes such a file through base/safewrite. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

typedef struct walker {
    const ms_export_visitor *v;
    void *ud;
    const ms_scene_item *it;
    ms_rgba8 color;             /* of the solid being tessellated, the segment drawn */
    ms_rgba8 tri_colors[3];     /* of the mesh triangle being cut */
} walker;

static void kept_tri(void *ud, const float p[9], const float n[9])
{
    walker *w = ud;
    ms_rgba8 c[3] = {w->color, w->color, w->color};
    w->v->triangle(w->ud, p, n, c);
}

/* A triangle of a tessellated solid, cut when the item has planes. */
static void solid_tri(void *ud, const float p[9], const float n[9])
{
    walker *w = ud;
    ms_export_clip_tri(w->it, p, n, kept_tri, w);
}

static void spheres(walker *w, const ms_displaylist *dl, const float *m, float scale)
{
    int own = w->v->sphere && !w->it->nclip;
    for (size_t i = 0; i < dl->spheres.n; i++) {
        float c[3], r = dl->spheres.radius[i] * scale;
        ms_mat4_point(m, dl->spheres.xyz + 3 * i, c);
        w->color = dl->spheres.color[i];
        if (own) w->v->sphere(w->ud, c, r, w->color, dl->spheres.res[i]);
        else ms_tess_sphere(c, r, dl->spheres.res[i], solid_tri, w);
    }
}

/* Cylinders as VMD's pieces: a bond is its two halves, each in its own colour. */
static void cylinders(walker *w, const ms_displaylist *dl, const float *m, float scale)
{
    int own = w->v->cylinder && !w->it->nclip;
    ms_dl_pieces it = ms_dl_pieces_of(&dl->cylinders);
    ms_dl_piece p;
    while (ms_dl_pieces_next(&it, &p)) {
        float a[3], b[3], r = p.radius * scale;
        ms_mat4_point(m, p.a, a);
        ms_mat4_point(m, p.b, b);
        w->color = p.color;
        if (own) w->v->cylinder(w->ud, a, b, r, w->color, p.caps, p.res);
        else ms_tess_cone(a, b, r, r, p.res, p.caps, solid_tri, w);
    }
}

static void cones(walker *w, const ms_displaylist *dl, const float *m, float scale)
{
    const ms_dl_cones *co = &dl->cones;
    int own = w->v->cone && !w->it->nclip;
    for (size_t i = 0; i < co->n; i++) {
        float a[3], b[3], rb = co->rbase[i] * scale, ra = co->rapex[i] * scale;
        ms_mat4_point(m, co->base + 3 * i, a);
        ms_mat4_point(m, co->apex + 3 * i, b);
        w->color = co->color[i];
        if (own) w->v->cone(w->ud, a, b, rb, ra, w->color, co->res[i]);
        else ms_tess_cone(a, b, rb, ra, co->res[i], MS_CAP_BASE, solid_tri, w);
    }
}

static void mesh_tri(void *ud, const float p[9], const float n[9])
{
    walker *w = ud;
    w->v->triangle(w->ud, p, n, w->tri_colors);
}

void ms_export_mesh_tri(const ms_dl_mesh *ms, size_t t, const float *m, float p[9], float n[9])
{
    const uint32_t *v = ms->tri + 3 * t;
    for (int k = 0; k < 3; k++) {
        float q[3];
        ms_mat4_point(m, ms->xyz + 3 * v[k], p + 3 * k);
        for (int j = 0; j < 3; j++) q[j] = ms_normal_dequantize(ms->normal[3 * v[k] + j]);
        ms_mat4_normal(m, q, n + 3 * k);
    }
}

static void mesh(walker *w, const ms_displaylist *dl, const float *m)
{
    const ms_dl_mesh *ms = &dl->mesh;
    for (size_t t = 0; t < ms->ntris; t++) {
        const uint32_t *v = ms->tri + 3 * t;
        float p[9], n[9];
        ms_export_mesh_tri(ms, t, m, p, n);
        for (int k = 0; k < 3; k++) w->tri_colors[k] = ms->color[v[k]];
        ms_export_clip_tri(w->it, p, n, mesh_tri, w);
    }
}

static void seg(void *ud, const float a0[3], const float b0[3])
{
    walker *w = ud;
    float a[3] = {a0[0], a0[1], a0[2]}, b[3] = {b0[0], b0[1], b0[2]};
    if (ms_export_clip_seg(w->it, a, b)) w->v->line(w->ud, a, b, w->color);
}

static void thin(walker *w, const ms_displaylist *dl, const float *m)
{
    for (size_t i = 0; w->v->line && i < dl->lines.n; i++) {
        float a[3], b[3];
        ms_mat4_point(m, dl->lines.a + 3 * i, a);
        ms_mat4_point(m, dl->lines.b + 3 * i, b);
        w->color = dl->lines.color[i];
        if (dl->lines.style[i] == MS_LINE_DASHED) ms_export_dashes(a, b, seg, w);
        else seg(w, a, b);
    }
    for (size_t i = 0; w->v->point && i < dl->points.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->points.xyz + 3 * i, c);
        if (!ms_scene_clipped(w->it, c)) w->v->point(w->ud, c, dl->points.color[i]);
    }
    for (size_t i = 0; w->v->line && i < dl->texts.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->texts.xyz + 3 * i, c);
        w->color = dl->texts.color[i];
        ms_export_text(dl->texts.chars + dl->texts.start[i], c, dl->texts.size[i], seg, w);
    }
}

void ms_export_walk(const ms_scene *s, const ms_export_visitor *v, void *ud)
{
    walker w = {.v = v, .ud = ud};
    for (size_t i = 0; i < s->nitems; i++) {
        w.it = &s->items[i];
        const ms_displaylist *dl = w.it->dl;
        const float *m = w.it->xform;
        float scale = ms_item_scale(w.it);
        if (v->item) v->item(ud, w.it);
        spheres(&w, dl, m, scale);
        cylinders(&w, dl, m, scale);
        cones(&w, dl, m, scale);
        mesh(&w, dl, m);
        thin(&w, dl, m);
        if (v->item_end) v->item_end(ud, w.it);
    }
}

int ms_export_file(const ms_scene *s, const char *path, ms_export_body_fn body, void *user,
                   ms_error *err)
{
    ms_ofile *out;
    FILE *f = ms_ofile_open_stream(path, &out, err);
    if (!f) return -1;
    int ok = body(s, f, user, err) == 0;
    return ms_ofile_finish(out, ok, err);
}
