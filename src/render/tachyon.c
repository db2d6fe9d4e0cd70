/* tachyon.c: the `Tachyon` device: the scene in Tachyon's scene language as VMD writes it
 * (Debian's tachyon 0.99b6 renders it). Tachyon is left-handed, so z is negated; spheres and
 * cylinders are native (a bond as VMD's two half cylinders), triangle meshes and tessellated cones go out as VertexArray/TriMesh,
 * lines and points as thin cylinders and spheres, text as stroked cylinders. Every object
 * carries its own texture block, as VMD's files do. A list cut by clip planes is written
 * between Start_ClipGroup and End_ClipGroup, VMD's per-object clip groups. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef struct writer {
    FILE *f;
    const ms_scene_item *it;
    float rgb[3];                /* colour of the current stroke object */
    float last[3];               /* end of the previous text stroke */
    int have_last;
    float radius;
    /* triangles gathered for one VertexArray (tessellated cones) */
    float *p, *n, *c;
    size_t ntri, cap;
    int oom;
    char cached[2][512];         /* texture text of the current list: unlit, lit */
    const ms_scene_item *cached_for[2];
} writer;

static void put_g(FILE *f, float v)
{
    char b[32];
    fwrite(b, 1, (size_t)ms_fmt_g(b, v), f);
}

/* pre x y z post, with z negated when flip (Tachyon is left-handed) */
static void put_vec(FILE *f, const char *pre, const float v[3], int flip, const char *post)
{
    fputs(pre, f);
    put_g(f, v[0]);
    fputc(' ', f);
    put_g(f, v[1]);
    fputc(' ', f);
    put_g(f, flip ? 0.0f - v[2] : v[2]);
    fputs(post, f);
}

/* The material part of a texture block, as VMD writes it. */
static void material_text(const ms_material *m, int lit, float op, char *buf, size_t size)
{
    int n = lit ? snprintf(buf, size, "Texture\n  Ambient %g Diffuse %g Specular %g Opacity %g\n",
                           m->ambient, m->diffuse, m->mirror, op)
                : snprintf(buf, size, "Texture\n  Ambient %g Diffuse %g Specular %g Opacity %g\n",
                           1.0, 0.0, 0.0, op);
    if (m->transmode != 0) n += snprintf(buf + n, size - (size_t)n, "  TransMode R3D ");
    if (m->outline > 0)
        n += snprintf(buf + n, size - (size_t)n, "  Outline %g Outline_Width %g ", m->outline,
                      m->outlinewidth);
    snprintf(buf + n, size - (size_t)n, "  Phong Plastic %g Phong_size %g ", m->specular,
             m->shininess);
}

static void texture(writer *w, int lit, const float rgb[3], float alpha)
{
    const ms_material *m = &w->it->mat;
    char buf[512];
    if (alpha == 1.0f) {
        /* the same for every opaque primitive of the list: made once per list */
        if (w->cached_for[lit] != w->it) {
            material_text(m, lit, m->opacity, w->cached[lit], sizeof w->cached[lit]);
            w->cached_for[lit] = w->it;
        }
        fputs(w->cached[lit], w->f);
    } else {
        material_text(m, lit, m->opacity * alpha, buf, sizeof buf);
        fputs(buf, w->f);
    }
    put_vec(w->f, "Color ", rgb, 0, " TexFunc 0\n\n");
}

static void texture8(writer *w, int lit, ms_rgba8 c)
{
    float rgb[3];
    ms_rgba8_to_float(c, rgb);
    texture(w, lit, rgb, c.a / 255.0f);
}

static void sphere(writer *w, const float c[3], float r)
{
    put_vec(w->f, "Sphere \n  Center ", c, 1, " \n  Rad ");
    put_g(w->f, r);
    fputs(" \n", w->f);
}

static void fcylinder(writer *w, const float a[3], const float b[3], float r)
{
    put_vec(w->f, "FCylinder\n  Base ", a, 1, "\n");
    put_vec(w->f, "  Apex ", b, 1, "\n  Rad ");
    put_g(w->f, r);
    fputc('\n', w->f);
}

static void ring(writer *w, const float c[3], const float n[3], float r, int lit, ms_rgba8 col)
{
    fprintf(w->f, "Ring\nCenter %g %g %g \nNormal %g %g %g \nInner 0.0  Outer %g \n", c[0], c[1],
            0.0f - c[2], n[0], n[1], 0.0f - n[2], r);
    texture8(w, lit, col);
}

/* ---------------------------------------------------------------- primitives */

static void spheres(writer *w, const ms_displaylist *dl, float scale)
{
    const ms_dl_spheres *s = &dl->spheres;
    for (size_t i = 0; i < s->n; i++) {
        float c[3];
        ms_mat4_point(w->it->xform, s->xyz + 3 * i, c);
        sphere(w, c, s->radius[i] * scale);
        texture8(w, dl->lit, s->color[i]);
    }
}

static void cylinders(writer *w, const ms_displaylist *dl, float scale)
{
    ms_dl_pieces it = ms_dl_pieces_of(&dl->cylinders);
    ms_dl_piece p;
    while (ms_dl_pieces_next(&it, &p)) {
        float a[3], b[3], r = p.radius * scale;
        ms_mat4_point(w->it->xform, p.a, a);
        ms_mat4_point(w->it->xform, p.b, b);
        fcylinder(w, a, b, r);
        texture8(w, dl->lit, p.color);
        if (!p.caps) continue;
        float n[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
        float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (l <= 0) continue;
        for (int k = 0; k < 3; k++) n[k] /= l;
        float m[3] = {-n[0], 0.0f - n[1], 0.0f - n[2]};
        if (p.caps & MS_CAP_BASE) ring(w, a, n, r, dl->lit, p.color);
        if (p.caps & MS_CAP_APEX) ring(w, b, m, r, dl->lit, p.color);
    }
}

static void stroke(void *ud, const float a[3], const float b[3])
{
    writer *w = ud;
    if (!w->have_last || memcmp(w->last, a, sizeof w->last)) {
        sphere(w, a, w->radius);
        texture(w, 0, w->rgb, 1.0f);
    }
    fcylinder(w, a, b, w->radius);
    texture(w, 0, w->rgb, 1.0f);
    sphere(w, b, w->radius);
    texture(w, 0, w->rgb, 1.0f);
    memcpy(w->last, b, sizeof w->last);
    w->have_last = 1;
}

static void dash(void *ud, const float a[3], const float b[3])
{
    writer *w = ud;
    fcylinder(w, a, b, w->radius);
    texture(w, 0, w->rgb, 1.0f);
}

static void lines(writer *w, const ms_displaylist *dl)
{
    const ms_dl_lines *s = &dl->lines;
    for (size_t i = 0; i < s->n; i++) {
        float a[3], b[3];
        ms_mat4_point(w->it->xform, s->a + 3 * i, a);
        ms_mat4_point(w->it->xform, s->b + 3 * i, b);
        w->radius = s->width[i] * MS_EXPORT_LINE_RADIUS;
        ms_rgba8_to_float(s->color[i], w->rgb);
        if (s->style[i] == MS_LINE_DASHED) {
            ms_export_dashes(a, b, dash, w);
        } else {
            fcylinder(w, a, b, w->radius);
            texture8(w, 0, s->color[i]);
        }
    }
}

static void points(writer *w, const ms_displaylist *dl)
{
    const ms_dl_points *s = &dl->points;
    for (size_t i = 0; i < s->n; i++) {
        float c[3];
        ms_mat4_point(w->it->xform, s->xyz + 3 * i, c);
        sphere(w, c, s->size[i] * MS_EXPORT_LINE_RADIUS);
        texture8(w, 0, s->color[i]);
    }
}

static void texts(writer *w, const ms_displaylist *dl)
{
    const ms_dl_texts *s = &dl->texts;
    for (size_t i = 0; i < s->n; i++) {
        float c[3];
        ms_mat4_point(w->it->xform, s->xyz + 3 * i, c);
        w->radius = s->thickness[i] * MS_EXPORT_LINE_RADIUS;
        ms_rgba8_to_float(s->color[i], w->rgb);
        w->have_last = 0;
        ms_export_text(s->chars + s->start[i], c, s->size[i], stroke, w);
    }
}

/* ---------------------------------------------------------------- meshes */

/* "%.3f %.3f %.3f\n" */
static void put_f3(FILE *f, const float v[3])
{
    char b[100];
    int n = 0;
    for (int k = 0; k < 3; k++) {
        n += ms_fmt_f3(b + n, v[k]);
        b[n++] = k < 2 ? ' ' : '\n';
    }
    fwrite(b, 1, (size_t)n, f);
}

static void vertex_array_header(writer *w, size_t nverts)
{
    fprintf(w->f, "VertexArray  Numverts %zu\n\nCoords\n", nverts);
}

static void mesh(writer *w, const ms_displaylist *dl)
{
    const ms_dl_mesh *m = &dl->mesh;
    if (!m->ntris || !m->nverts) return;
    FILE *f = w->f;
    vertex_array_header(w, m->nverts);
    for (size_t i = 0; i < m->nverts; i++) {
        float p[3];
        ms_mat4_point(w->it->xform, m->xyz + 3 * i, p);
        put_vec(f, "", p, 1, "\n");
    }
    fputs("\nNormals\n", f);
    for (size_t i = 0; i < m->nverts; i++) {
        float n[3], q[3];
        for (int k = 0; k < 3; k++) n[k] = ms_normal_dequantize(m->normal[3 * i + k]);
        ms_mat4_normal(w->it->xform, n, q);
        /* VMD's sign convention for Tachyon normals; Tachyon faces them to the viewer */
        float v[3] = {0.0f - q[0], 0.0f - q[1], q[2]};
        put_f3(f, v);
    }
    fputs("\nColors\n", f);
    for (size_t i = 0; i < m->nverts; i++) {
        float c[3];
        ms_rgba8_to_float(m->color[i], c);
        put_f3(f, c);
    }
    fputs("\n", f);
    texture8(w, dl->lit, m->color[0]);
    fprintf(f, "TriMesh %zu\n", m->ntris);
    for (size_t t = 0; t < m->ntris; t++) {
        char b[48];
        int n = 0;
        for (int k = 0; k < 3; k++) {
            n += snprintf(b + n, sizeof b - (size_t)n, "%u", m->tri[3 * t + k]);
            b[n++] = k < 2 ? ' ' : '\n';
        }
        fwrite(b, 1, (size_t)n, f);
    }
    fputs("\nEnd_VertexArray\n", f);
}

static void gather(void *ud, const float p[9], const float n[9])
{
    writer *w = ud;
    if (w->oom) return;
    if (w->ntri == w->cap) {
        size_t cap = w->cap ? 2 * w->cap : 256;
        float *np = realloc(w->p, cap * 9 * sizeof(float));
        if (np) w->p = np;
        float *nn = realloc(w->n, cap * 9 * sizeof(float));
        if (nn) w->n = nn;
        float *nc = realloc(w->c, cap * 9 * sizeof(float));
        if (nc) w->c = nc;
        if (!np || !nn || !nc) {
            w->oom = 1;
            return;
        }
        w->cap = cap;
    }
    memcpy(w->p + 9 * w->ntri, p, 9 * sizeof(float));
    memcpy(w->n + 9 * w->ntri, n, 9 * sizeof(float));
    for (int k = 0; k < 9; k++) w->c[9 * w->ntri + k] = w->rgb[k % 3];
    w->ntri++;
}

/* Cones, tessellated in world space into one vertex array per list. */
static void cones(writer *w, const ms_displaylist *dl, float scale)
{
    const ms_dl_cones *s = &dl->cones;
    if (!s->n) return;
    w->ntri = 0;
    for (size_t i = 0; i < s->n; i++) {
        float a[3], b[3];
        ms_mat4_point(w->it->xform, s->base + 3 * i, a);
        ms_mat4_point(w->it->xform, s->apex + 3 * i, b);
        ms_rgba8_to_float(s->color[i], w->rgb);
        int res = s->res[i] < 12 ? 12 : s->res[i];
        ms_tess_cone(a, b, s->rbase[i] * scale, s->rapex[i] * scale, res, MS_CAP_BASE, gather, w);
    }
    if (!w->ntri || w->oom) return;
    FILE *f = w->f;
    vertex_array_header(w, 3 * w->ntri);
    for (size_t i = 0; i < 3 * w->ntri; i++)
        fprintf(f, "%g %g %g\n", w->p[3 * i], w->p[3 * i + 1], 0.0f - w->p[3 * i + 2]);
    fputs("\nNormals\n", f);
    for (size_t i = 0; i < 3 * w->ntri; i++)
        fprintf(f, "%.3f %.3f %.3f\n", 0.0f - w->n[3 * i], 0.0f - w->n[3 * i + 1], w->n[3 * i + 2]);
    fputs("\nColors\n", f);
    for (size_t i = 0; i < 3 * w->ntri; i++)
        fprintf(f, "%.3f %.3f %.3f\n", w->c[3 * i], w->c[3 * i + 1], w->c[3 * i + 2]);
    fputs("\n", f);
    texture(w, dl->lit, w->c, 1.0f);
    fprintf(f, "TriMesh %zu\n", w->ntri);
    for (size_t t = 0; t < w->ntri; t++) fprintf(f, "%zu %zu %zu\n", 3 * t, 3 * t + 1, 3 * t + 2);
    fputs("\nEnd_VertexArray\n", f);
}

/* ---------------------------------------------------------------- scene settings */

static void header(FILE *f, const ms_scene *s)
{
    fprintf(f, "# \n# Molecular graphics exported from molscope %s\n# \n", PACKAGE_VERSION);
    fputs("# Requires Tachyon version 0.99.0 or newer\n# \n", f);
    fputs("# Default tachyon rendering command for this scene:\n", f);
    fprintf(f, "#   tachyon  -aasamples %d %%s -format TARGA -o %%s.tga\n# \n", s->aa_samples);
    fputs("Begin_Scene\n", f);
    fprintf(f, "Resolution %d %d\n", s->width, s->height);
    fprintf(f, "Shader_Mode %s\n  Trans_VMD\n  Fog_VMD\n", s->settings.shadows || s->settings.ao ? "Full" : "Medium");
    if (s->settings.ao)
        fprintf(f, "  Ambient_Occlusion\n    Ambient_Color %g %g %g\n    Rescale_Direct %g\n"
                   "    Samples %d\n", s->settings.ao_ambient, s->settings.ao_ambient, s->settings.ao_ambient, s->settings.ao_direct,
                s->ao_samples);
    fputs("End_Shader_Mode\n", f);
}

static void camera(FILE *f, const ms_scene *s)
{
    const ms_camera *c = &s->settings.cam;
    fputs("Camera\n", f);
    if (c->projection == MS_PROJ_ORTHOGRAPHIC) {
        fputs("  Projection Orthographic\n", f);
        fprintf(f, "  Zoom %g\n", 1.0 / (c->height / 2.0));
    } else {
        /* Tachyon 0.99b6 (Debian's) takes the focal distance as FocalLength (newer versions
         * say FocalDist) and the aperture as a radius in world units, not VMD's f-number:
         * radius = focal distance / (2 f-number), the thin-lens aperture */
        if (c->dof)
            fprintf(f, "  Projection Perspective_DoF\n  FocalLength %g\n  Aperture %g\n",
                    c->dof_focaldist, c->dof_focaldist / (2.0f * c->dof_fnumber));
        fprintf(f, "  Zoom %g\n", (c->eye[2] - c->distance) / c->height);
    }
    fprintf(f, "  Aspectratio %g\n  Antialiasing %d\n  Raydepth %d\n", 1.0, s->aa_samples, 50);
    fprintf(f, "  Center  %g %g %g\n", c->eye[0], c->eye[1], 0.0f - c->eye[2]);
    fprintf(f, "  Viewdir %g %g %g\n", c->dir[0], c->dir[1], 0.0f - c->dir[2]);
    fprintf(f, "  Updir   %g %g %g\nEnd_Camera\n", c->up[0], c->up[1], 0.0f - c->up[2]);
}

static void lights_and_background(FILE *f, const ms_scene *s)
{
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        const ms_light *l = &s->settings.lights[i];
        if (!l->on) continue;
        fprintf(f, "Directional_Light Direction %g %g %g Color %g %g %g\n", 0.0f - l->pos[0],
                0.0f - l->pos[1], l->pos[2], l->color[0], l->color[1], l->color[2]);
    }
    const float *bg = s->background;
    fprintf(f, "\nBackground %g %g %g\n", bg[0], bg[1], bg[2]);
    if (s->settings.bg_gradient) {
        int ortho = s->settings.cam.projection == MS_PROJ_ORTHOGRAPHIC;
        float mag = ortho ? s->settings.cam.height / 4.0f
                          : MS_MIN(1.0f, (s->settings.cam.height / 2.0f) / (s->settings.cam.eye[2] - s->settings.cam.distance));
        fprintf(f, "Background_Gradient %s\n  UpDir %g %g %g\n  TopVal %g\n  BottomVal %g\n",
                ortho ? "Sky_Ortho_Plane" : "Sky_Sphere", 0.0, 1.0, 0.0, mag, -mag);
        fprintf(f, "  TopColor %g %g %g\n  BottomColor %g %g %g\n", s->bg_top[0], s->bg_top[1],
                s->bg_top[2], s->bg_bottom[0], s->bg_bottom[1], s->bg_bottom[2]);
    }
    if (!s->settings.depthcue) return;
    if (s->settings.cuemode == MS_CUE_LINEAR)
        fprintf(f, "Fog Linear Start %g End %g Density %g Color %g %g %g\n", s->settings.cue_start,
                s->settings.cue_end, 1.0, bg[0], bg[1], bg[2]);
    else
        fprintf(f, "Fog %s Start %g End %g Density %g Color %g %g %g\n",
                s->settings.cuemode == MS_CUE_EXP ? "Exp" : "Exp2", 0.0, s->settings.cue_end, s->settings.cue_density,
                bg[0], bg[1], bg[2]);
}

/* Tachyon's clip group: a point p (its coordinates) is cut when n . p > d. */
static void clip_group(FILE *f, const ms_scene_item *it)
{
    fprintf(f, "Start_ClipGroup\n  NumPlanes %d\n", it->nclip);
    for (int i = 0; i < it->nclip; i++) {
        const float *e = it->clip[i].eq;
        fprintf(f, "  %g %g %g %g\n", 0.0f - e[0], 0.0f - e[1], e[2], e[3]);
    }
}

static int write_tachyon(const ms_scene *s, const char *path, ms_error *err)
{
    ms_ofile *out;
    FILE *f = ms_ofile_open_stream(path, &out, err);
    if (!f) return -1;
    writer w;
    memset(&w, 0, sizeof w);
    w.f = f;
    header(f, s);
    camera(f, s);
    lights_and_background(f, s);
    for (size_t i = 0; i < s->nitems && !w.oom; i++) {
        w.it = &s->items[i];
        const ms_displaylist *dl = w.it->dl;
        float scale = ms_item_scale(w.it);
        if (w.it->nclip) clip_group(f, w.it);
        spheres(&w, dl, scale);
        cylinders(&w, dl, scale);
        cones(&w, dl, scale);
        mesh(&w, dl);
        lines(&w, dl);
        points(&w, dl);
        texts(&w, dl);
        if (w.it->nclip) fputs("End_ClipGroup\n", f);
    }
    fputs("End_Scene \n", f);
    free(w.p);
    free(w.n);
    free(w.c);
    if (w.oom) ms_error_set(err, "%s: out of memory", path);
    return ms_ofile_finish(out, !w.oom, err);
}

/* VMD's image formats for the tachyon command, and tachyon's names and file extensions. */
static const char *const formats[] = {"BMP", "PPM", "PPM48", "PSD48", "RGB", "TGA", NULL};

static void tachyon_cmd(int format, int aasamples, char *buf, size_t size)
{
    static const char *const flag[] = {"BMP", "PPM", "PPM48", "PSD48", "RGB", "TARGA"};
    static const char *const ext[] = {"bmp", "ppm", "ppm", "psd", "rgb", "tga"};
    const char *bin = getenv("TACHYON_BIN");
    snprintf(buf, size, "%s -aasamples %d %%s -format %s -o %%s.%s", bin && *bin ? bin : "tachyon",
             aasamples, flag[format], ext[format]);
}

const ms_render_device ms_render_tachyon = {
    .name = "Tachyon",
    .description = "Tachyon scene file (.dat)",
    .default_cmd = "tachyon -aasamples 12 %s -format TARGA -o %s.tga",
    .has_aa = 1, .aasamples = 12, .aosamples = 12,
    .write = write_tachyon,
    .formats = formats, .default_format = 5, .cmd_for = tachyon_cmd};
