/* pov3.c: the `POV3` device: the scene as a POV-Ray 3.7 scene file, in VMD's camera and
 * coordinates (POV-Ray is left-handed, so z is negated). Spheres, cylinders and cones are
 * native objects; a display list's triangle mesh becomes one mesh2 with per-vertex colours;
 * lines, points and text are thin unlit cylinders and spheres. Each display list's material
 * becomes a declared finish. A list cut by clip planes is a union clipped_by its planes. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <math.h>
#include <string.h>

typedef struct pov {
    FILE *f;
    const ms_scene *s;
    const ms_scene_item *it;
    size_t index;            /* of the item: names its finish */
    float radius, rgb[3];    /* current stroke */
} pov;

/* <x,y,-z>: POV-Ray is left-handed */
static void vec(FILE *f, const float p[3])
{
    char b[100];
    int n = 0;
    b[n++] = '<';
    n += ms_fmt_g(b + n, p[0]);
    b[n++] = ',';
    n += ms_fmt_g(b + n, p[1]);
    b[n++] = ',';
    n += ms_fmt_g(b + n, 0.0f - p[2]);
    b[n++] = '>';
    fwrite(b, 1, (size_t)n, f);
}

/* texture { pigment { rgbt } finish { MS_F<i> or MS_Unlit } } */
static void texture(pov *w, ms_rgba8 c, int lit)
{
    float rgb[3];
    ms_rgba8_to_float(c, rgb);
    float t = 1.0f - w->it->mat.opacity * (c.a / 255.0f);
    fprintf(w->f, " texture { pigment { rgbt <%.3f,%.3f,%.3f,%.3f> } finish { ", rgb[0], rgb[1],
            rgb[2], t);
    if (lit) fprintf(w->f, "MS_F%zu", w->index);
    else fputs("MS_Unlit", w->f);
    fprintf(w->f, " } }%s }\n", w->s->settings.shadows ? "" : " no_shadow");
}

static int degenerate(const float a[3], const float b[3])
{
    float d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    return d[0] * d[0] + d[1] * d[1] + d[2] * d[2] < 1e-20f;
}

static void cylinder(pov *w, const float a[3], const float b[3], float r, int open)
{
    fputs("cylinder { ", w->f);
    vec(w->f, a);
    fputs(", ", w->f);
    vec(w->f, b);
    fprintf(w->f, ", %g%s", r, open ? " open" : "");
}

static void sphere(pov *w, const float c[3], float r)
{
    fputs("sphere { ", w->f);
    vec(w->f, c);
    fprintf(w->f, ", %g", r);
}

static void stroke(void *ud, const float a[3], const float b[3])
{
    pov *w = ud;
    ms_rgba8 c = ms_rgba8_from_float(w->rgb, 1.0f);
    if (!degenerate(a, b)) {
        cylinder(w, a, b, w->radius, 0);
        texture(w, c, 0);
    }
    sphere(w, b, w->radius);
    texture(w, c, 0);
}

static void solids(pov *w, const ms_displaylist *dl, float scale)
{
    const float *m = w->it->xform;
    for (size_t i = 0; i < dl->spheres.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->spheres.xyz + 3 * i, c);
        sphere(w, c, dl->spheres.radius[i] * scale);
        texture(w, dl->spheres.color[i], dl->lit);
    }
    ms_dl_pieces it = ms_dl_pieces_of(&dl->cylinders);
    ms_dl_piece p;
    while (ms_dl_pieces_next(&it, &p)) {
        float a[3], b[3];
        ms_mat4_point(m, p.a, a);
        ms_mat4_point(m, p.b, b);
        if (degenerate(a, b)) continue;
        cylinder(w, a, b, p.radius * scale, p.caps == 0);
        texture(w, p.color, dl->lit);
    }
    const ms_dl_cones *co = &dl->cones;
    for (size_t i = 0; i < co->n; i++) {
        float a[3], b[3];
        ms_mat4_point(m, co->base + 3 * i, a);
        ms_mat4_point(m, co->apex + 3 * i, b);
        if (degenerate(a, b)) continue;
        fputs("cone { ", w->f);
        vec(w->f, a);
        fprintf(w->f, ", %g, ", co->rbase[i] * scale);
        vec(w->f, b);
        fprintf(w->f, ", %g", co->rapex[i] * scale);
        texture(w, co->color[i], dl->lit);
    }
}

static void thin(pov *w, const ms_displaylist *dl)
{
    const float *m = w->it->xform;
    const ms_dl_lines *l = &dl->lines;
    for (size_t i = 0; i < l->n; i++) {
        float a[3], b[3];
        ms_mat4_point(m, l->a + 3 * i, a);
        ms_mat4_point(m, l->b + 3 * i, b);
        w->radius = l->width[i] * MS_EXPORT_LINE_RADIUS;
        ms_rgba8_to_float(l->color[i], w->rgb);
        if (l->style[i] == MS_LINE_DASHED) {
            ms_export_dashes(a, b, stroke, w);
        } else if (!degenerate(a, b)) {
            cylinder(w, a, b, w->radius, 0);
            texture(w, l->color[i], 0);
        }
    }
    for (size_t i = 0; i < dl->points.n; i++) {
        float c[3];
        ms_mat4_point(m, dl->points.xyz + 3 * i, c);
        sphere(w, c, dl->points.size[i] * MS_EXPORT_LINE_RADIUS);
        texture(w, dl->points.color[i], 0);
    }
    const ms_dl_texts *t = &dl->texts;
    for (size_t i = 0; i < t->n; i++) {
        float c[3];
        ms_mat4_point(m, t->xyz + 3 * i, c);
        w->radius = t->thickness[i] * MS_EXPORT_LINE_RADIUS;
        ms_rgba8_to_float(t->color[i], w->rgb);
        ms_export_text(t->chars + t->start[i], c, t->size[i], stroke, w);
    }
}

static void mesh(pov *w, const ms_displaylist *dl)
{
    const ms_dl_mesh *ms = &dl->mesh;
    if (!ms->ntris || !ms->nverts) return;
    FILE *f = w->f;
    const float *m = w->it->xform;
    fprintf(f, "mesh2 {\n  vertex_vectors { %zu", ms->nverts);
    for (size_t i = 0; i < ms->nverts; i++) {
        float p[3];
        ms_mat4_point(m, ms->xyz + 3 * i, p);
        fputs(",\n    ", f);
        vec(f, p);
    }
    fprintf(f, " }\n  normal_vectors { %zu", ms->nverts);
    for (size_t i = 0; i < ms->nverts; i++) {
        float n[3], q[3];
        for (int k = 0; k < 3; k++) n[k] = ms_normal_dequantize(ms->normal[3 * i + k]);
        ms_mat4_normal(m, n, q);
        fprintf(f, ",\n    <%.4f,%.4f,%.4f>", q[0], q[1], 0.0f - q[2]);
    }
    fprintf(f, " }\n  texture_list { %zu", ms->nverts);
    float op = w->it->mat.opacity;
    for (size_t i = 0; i < ms->nverts; i++) {
        float c[3];
        ms_rgba8_to_float(ms->color[i], c);
        fprintf(f, ",\n    texture { pigment { rgbt <%.3f,%.3f,%.3f,%.3f> } finish { ", c[0],
                c[1], c[2], 1.0f - op * (ms->color[i].a / 255.0f));
        if (dl->lit) fprintf(f, "MS_F%zu } }", w->index);
        else fputs("MS_Unlit } }", f);
    }
    fprintf(f, " }\n  face_indices { %zu", ms->ntris);
    for (size_t t = 0; t < ms->ntris; t++) {
        const uint32_t *v = ms->tri + 3 * t;
        fprintf(f, ",\n    <%u,%u,%u>,%u,%u,%u", v[0], v[1], v[2], v[0], v[1], v[2]);
    }
    fprintf(f, " }\n%s}\n", w->s->settings.shadows ? "" : "  no_shadow\n");
}

/* ---------------------------------------------------------------- scene settings */

static void camera(FILE *f, const ms_scene *s)
{
    const ms_camera *c = &s->settings.cam;
    float aspect = (float)s->width / (float)s->height;
    fputs("camera {\n", f);
    if (c->projection == MS_PROJ_ORTHOGRAPHIC) {
        fprintf(f, "  orthographic\n  up <0, %g, 0>\n  right <%g, 0, 0>\n", c->height / 2.0f,
                aspect * c->height / 2.0f);
    } else {
        fprintf(f, "  up <0, %g, 0>\n  right <%g, 0, 0>\n", c->height, aspect * c->height);
        fprintf(f, "  direction <0, 0, %g>\n", c->eye[2] - c->distance);
    }
    fprintf(f, "  location <%g, %g, %g>\n", c->eye[0], c->eye[1], 0.0f - c->eye[2]);
    fprintf(f, "  look_at <%g, %g, %g>\n", c->eye[0] + c->dir[0], c->eye[1] + c->dir[1],
            -(c->eye[2] + c->dir[2]));
    if (c->dof && c->projection == MS_PROJ_PERSPECTIVE)
        fprintf(f, "  focal_point <%g, %g, %g>\n  aperture %g\n  blur_samples 100\n",
                c->eye[0] + c->dir[0] * c->dof_focaldist, c->eye[1] + c->dir[1] * c->dof_focaldist,
                -(c->eye[2] + c->dir[2] * c->dof_focaldist),
                c->height * 4.0f * c->dof_focaldist / c->dof_fnumber);
    fputs("}\n", f);
}

static void environment(FILE *f, const ms_scene *s)
{
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        const ms_light *l = &s->settings.lights[i];
        if (!l->on) continue;
        fprintf(f, "light_source { <%g, %g, %g> color rgb <%g, %g, %g> parallel "
                   "point_at <0, 0, 0> }\n", l->pos[0], l->pos[1], 0.0f - l->pos[2], l->color[0],
                l->color[1], l->color[2]);
    }
    const float *bg = s->background;
    fprintf(f, "background { color rgb <%.3f, %.3f, %.3f> }\n", bg[0], bg[1], bg[2]);
    if (s->settings.bg_gradient)
        fprintf(f, "sky_sphere { pigment { gradient y color_map { [0.0 color rgb <%.3f, %.3f, "
                   "%.3f>] [1.0 color rgb <%.3f, %.3f, %.3f>] } scale 2 translate -1 } }\n",
                s->bg_bottom[0], s->bg_bottom[1], s->bg_bottom[2], s->bg_top[0], s->bg_top[1],
                s->bg_top[2]);
    if (s->settings.depthcue && s->settings.cue_density > 1e-4f)
        fprintf(f, "fog { distance %g color rgb <%.3f, %.3f, %.3f> }\n",
                s->settings.cuemode == MS_CUE_LINEAR ? s->settings.cue_end : 1.0f / s->settings.cue_density, bg[0], bg[1],
                bg[2]);
}

static void finishes(FILE *f, const ms_scene *s)
{
    fputs("#declare MS_Unlit = finish { ambient 1 diffuse 0 specular 0 }\n", f);
    for (size_t i = 0; i < s->nitems; i++) {
        const ms_material *m = &s->items[i].mat;
        fprintf(f, "#declare MS_F%zu = finish { ambient %g diffuse %g phong %g phong_size %g "
                   "reflection %g }\n", i, m->ambient, m->diffuse, m->specular, m->shininess,
                m->mirror);
    }
}

/* The planes that keep what is not cut: POV-Ray keeps the inside of a plane, n . p < d. */
static void clipped_by(pov *w)
{
    fputs("  clipped_by {", w->f);
    for (int i = 0; i < w->it->nclip; i++) {
        const float *e = w->it->clip[i].eq;
        float n[3] = {0.0f - e[0], 0.0f - e[1], 0.0f - e[2]};
        fputs(" plane { ", w->f);
        vec(w->f, n);
        fprintf(w->f, ", %g }", e[3]);
    }
    fputs(" }\n}\n", w->f);
}

static int write_pov(const ms_scene *s, const char *path, ms_error *err)
{
    ms_ofile *out;
    FILE *f = ms_ofile_open_stream(path, &out, err);
    if (!f) return -1;
    fprintf(f, "// Molecular graphics exported from molscope %s\n", PACKAGE_VERSION);
    fprintf(f, "// Requires POV-Ray 3.7; try: povray +W%d +H%d -I%s -O%s.tga +X +A +FT\n",
            s->width, s->height, path, path);
    fputs("#version 3.7;\nglobal_settings { assumed_gamma 1.0 max_trace_level 10 }\n", f);
    camera(f, s);
    environment(f, s);
    finishes(f, s);
    pov w = {f, s, NULL, 0, 0, {0, 0, 0}};
    for (size_t i = 0; i < s->nitems; i++) {
        w.it = &s->items[i];
        w.index = i;
        int clip = w.it->nclip && ms_dl_count(w.it->dl);
        if (clip) fputs("union {\n", f);
        solids(&w, w.it->dl, ms_item_scale(w.it));
        mesh(&w, w.it->dl);
        thin(&w, w.it->dl);
        if (clip) clipped_by(&w);
    }
    return ms_ofile_commit(out, err);
}

const ms_render_device ms_render_pov3 = {
    .name = "POV3",
    .description = "POV-Ray 3.7 scene file (.pov)",
    .default_cmd = "povray +W%w +H%h -I%s -O%s.tga +D +X +A +FT",
    .has_aa = 1, .aasamples = 12, .aosamples = 12,
    .write = write_pov};
