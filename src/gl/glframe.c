/* glframe.c: one frame of the renderer. The camera, lights, depth cue and background of
 * the scene become uniforms; every display list's arrays go into GL buffers as they are
 * (structure of arrays, no repacking); then the passes: background (colour or gradient),
 * opaque surfaces with depth, translucent surfaces into the weighted-blended targets, and the
 * composite of those over the opaque image. Text becomes line strokes of the stroke font in
 * world coordinates (render/export.h), as the file exporters draw it. */
#include "config.h"
#include "gl/glrender.h"
#include "render/export.h"
#include "vecmath/vecf.h"

#include <limits.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { K_SPHERES, K_CYLINDERS, K_CONES, K_MESH, K_LINES, K_POINTS, K_TEXT, K_N };
#define MAX_ARRAYS 7               /* per kind; attribute locations go to 7 */

/* One scene item in GL: its buffers per kind and what it needs. */
typedef struct glitem {
    const ms_scene_item *it;
    float mv[16];                  /* model to eye, row-major */
    float rscale;
    GLuint buf[K_N][MAX_ARRAYS];
    size_t count[K_N];             /* primitives (mesh: indices) to draw */
    int translucent[K_N];          /* some primitive has alpha < 1 */
    ms_displaylist *text;          /* strokes of its texts, world coordinates */
} glitem;

typedef struct frame {
    ms_gl *g;
    const ms_scene *s;
    float view[16], proj[16];
    float ray[3], nearfar[2];
    ms_glcam cam;
    ms_glcull *cull;
    int nlights;
    float ldir[12], lcol[12];
    int fog;
    float fogp[3], bg_top[3], bg_bot[3];
    glitem *items;
    size_t n;
} frame;

/* ---------------------------------------------------------------- camera */

/* World to eye: right = dir x up, up, -dir; the eye at the origin (as ms_scene_project). */
static void view_matrix(const ms_camera *c, float m[16])
{
    float d[3] = {c->dir[0], c->dir[1], c->dir[2]};
    ms_v3f_normalize(d);
    float r[3] = {d[1] * c->up[2] - d[2] * c->up[1], d[2] * c->up[0] - d[0] * c->up[2],
                  d[0] * c->up[1] - d[1] * c->up[0]};
    ms_v3f_normalize(r);
    float u[3] = {r[1] * d[2] - r[2] * d[1], r[2] * d[0] - r[0] * d[2], r[0] * d[1] - r[1] * d[0]};
    const float *rows[3] = {r, u, d};
    for (int i = 0; i < 3; i++) {
        float sg = i == 2 ? -1.0f : 1.0f;
        for (int k = 0; k < 3; k++) m[4 * i + k] = sg * rows[i][k];
        m[4 * i + 3] = -(m[4 * i] * c->eye[0] + m[4 * i + 1] * c->eye[1] +
                         m[4 * i + 2] * c->eye[2]);
    }
    m[12] = m[13] = m[14] = 0;
    m[15] = 1;
}

/* VMD's frustum: perspective through the screen plane (height tall, eye[2] - distance from
 * the eye); orthographic height / 2 tall. */
static void projection(frame *fr)
{
    const ms_camera *c = &fr->s->settings.cam;
    float n = c->near_clip, f = c->far_clip, aspect = (float)fr->s->width / (float)fr->s->height;
    float *p = fr->proj;
    memset(p, 0, 16 * sizeof *p);
    int ortho = c->projection == MS_PROJ_ORTHOGRAPHIC;
    float hy = ortho ? c->height / 4.0f : c->height / 2.0f / (c->eye[2] - c->distance);
    float hx = hy * aspect;
    p[0] = 1.0f / hx;
    p[5] = 1.0f / hy;
    if (ortho) {
        p[10] = -2.0f / (f - n);
        p[11] = -(f + n) / (f - n);
        p[15] = 1.0f;
    } else {
        p[10] = -(f + n) / (f - n);
        p[11] = -2.0f * f * n / (f - n);
        p[14] = -1.0f;
    }
    fr->ray[0] = hx;
    fr->ray[1] = hy;
    fr->ray[2] = (float)ortho;
    fr->nearfar[0] = n;
    fr->nearfar[1] = f;
    fr->cam = (ms_glcam){fr->s->width, fr->s->height, ortho, hx, hy, n, f};
}

static void lights_and_fog(frame *fr)
{
    const ms_scene *s = fr->s;
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        if (!s->settings.lights[i].on) continue;
        float *d = fr->ldir + 3 * fr->nlights;
        const float *l = s->settings.lights[i].pos;
        for (int k = 0; k < 3; k++)
            d[k] = fr->view[4 * k] * l[0] + fr->view[4 * k + 1] * l[1] + fr->view[4 * k + 2] * l[2];
        ms_v3f_normalize(d);
        memcpy(fr->lcol + 3 * fr->nlights, s->settings.lights[i].color, 3 * sizeof(float));
        fr->nlights++;
    }
    fr->fog = !s->settings.depthcue ? 0 : s->settings.cuemode == MS_CUE_LINEAR ? 1 : s->settings.cuemode == MS_CUE_EXP ? 2 : 3;
    fr->fogp[0] = s->settings.cue_start;
    fr->fogp[1] = s->settings.cue_end;
    fr->fogp[2] = s->settings.cue_density;
    memcpy(fr->bg_top, s->settings.bg_gradient ? s->bg_top : s->background, sizeof fr->bg_top);
    memcpy(fr->bg_bot, s->settings.bg_gradient ? s->bg_bottom : s->background, sizeof fr->bg_bot);
}

/* Uniforms of the frame, in every program that has them. */
static void frame_uniforms(frame *fr)
{
    const ms_glfn *f = &fr->g->f;
    for (int i = 0; i < MS_GLR_NPROGS; i++) {
        const ms_glr_prog *p = &fr->g->r.prog[i];
        f->UseProgram(p->id);
        f->UniformMatrix4fv(p->u[MS_U_PROJ], 1, GL_TRUE, fr->proj);
        f->Uniform2f(p->u[MS_U_VIEWPORT], (float)fr->s->width, (float)fr->s->height);
        f->Uniform3fv(p->u[MS_U_RAY], 1, fr->ray);
        f->Uniform2f(p->u[MS_U_NEARFAR], fr->nearfar[0], fr->nearfar[1]);
        f->Uniform1i(p->u[MS_U_NLIGHTS], fr->nlights);
        if (fr->nlights) {
            f->Uniform3fv(p->u[MS_U_LIGHT_DIR], fr->nlights, fr->ldir);
            f->Uniform3fv(p->u[MS_U_LIGHT_COL], fr->nlights, fr->lcol);
        }
        f->Uniform1i(p->u[MS_U_FOG], fr->fog);
        f->Uniform3fv(p->u[MS_U_FOGP], 1, fr->fogp);
        f->Uniform3fv(p->u[MS_U_BG_TOP], 1, fr->bg_top);
        f->Uniform3fv(p->u[MS_U_BG_BOT], 1, fr->bg_bot);
        f->Uniform1i(p->u[MS_U_ACCUM], 0);
        f->Uniform1i(p->u[MS_U_WSUM], 1);
    }
}

/* ---------------------------------------------------------------- upload */

typedef struct stroke_ctx {
    ms_displaylist *dl;
    float width;
    ms_rgba8 color;
    int failed;
} stroke_ctx;

static void add_stroke(void *ud, const float a[3], const float b[3])
{
    stroke_ctx *c = ud;
    if (ms_dl_line(c->dl, a, b, c->width, c->color, MS_LINE_SOLID)) c->failed = 1;
}

/* The strokes of an item's texts, placed in world coordinates. */
static int text_strokes(glitem *gi, ms_error *err)
{
    const ms_dl_texts *t = &gi->it->dl->texts;
    gi->text = malloc(sizeof *gi->text);
    if (!gi->text) goto oom;
    ms_dl_init(gi->text);
    for (size_t i = 0; i < t->n; i++) {
        float anchor[3];
        ms_mat4_point(gi->it->xform, t->xyz + 3 * i, anchor);
        stroke_ctx c = {gi->text, t->thickness[i], t->color[i], 0};
        ms_export_text(t->chars + t->start[i], anchor, t->size[i], add_stroke, &c);
        if (c.failed) goto oom;
    }
    return 0;
oom:
    ms_error_set(err, "out of memory");
    return -1;
}

static int any_translucent(const ms_rgba8 *c, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (c[i].a < 255) return 1;
    return 0;
}

typedef struct arr {
    const void *data;
    size_t elsize, count;
    GLenum target;
} arr;

/* The arrays of one kind, in the order the draw binds them; *n is the primitive count. */
static int kind_arrays(const ms_displaylist *dl, int k, arr a[MAX_ARRAYS], const ms_rgba8 **col,
                       size_t *n)
{
    const ms_dl_spheres *sp = &dl->spheres;
    const ms_dl_cylinders *cy = &dl->cylinders;
    const ms_dl_cones *co = &dl->cones;
    const ms_dl_mesh *me = &dl->mesh;
    const ms_dl_lines *li = &dl->lines;
    const ms_dl_points *pt = &dl->points;
    size_t f3 = 3 * sizeof(float), f1 = sizeof(float), c4 = sizeof(ms_rgba8);
#define A(i, p, sz) a[i] = (arr){(p), (sz), *n, GL_ARRAY_BUFFER}
    switch (k) {
    case K_SPHERES: *n = sp->n; *col = sp->color;
        A(0, sp->xyz, f3); A(1, sp->radius, f1); A(2, sp->color, c4); return 3;
    case K_CYLINDERS: *n = cy->n; *col = cy->color;
        A(0, cy->base, f3); A(1, cy->apex, f3); A(2, cy->radius, f1); A(3, cy->color, c4);
        A(4, cy->flags, 1); A(5, cy->color2, c4); A(6, cy->joint, f3); return 7;
    case K_CONES: *n = co->n; *col = co->color;
        A(0, co->base, f3); A(1, co->apex, f3); A(2, co->rbase, f1); A(3, co->rapex, f1);
        A(4, co->color, c4); return 5;
    case K_MESH: *n = me->nverts; *col = me->color;
        A(0, me->xyz, f3); A(1, me->normal, 3); A(2, me->color, c4);
        a[3] = (arr){me->tri, 3 * sizeof(uint32_t), me->ntris, GL_ELEMENT_ARRAY_BUFFER};
        return me->ntris ? 4 : 0;
    case K_LINES: case K_TEXT: *n = li->n; *col = li->color;
        A(0, li->a, f3); A(1, li->b, f3); A(2, li->width, f1); A(3, li->color, c4);
        A(4, li->style, 1); return 5;
    case K_POINTS: *n = pt->n; *col = pt->color;
        A(0, pt->xyz, f3); A(1, pt->size, f1); A(2, pt->color, c4); return 3;
    }
#undef A
    return 0;
}

/* The display-list kind a culled kind tests as; -1 for kinds never culled. */
static int cull_kind(int k)
{
    return k == K_SPHERES ? MS_DL_SPHERES : k == K_CYLINDERS ? MS_DL_CYLINDERS
         : k == K_CONES ? MS_DL_CONES : -1;
}

/* Upload the arrays, packed to the kept primitives when sel is given. */
static int upload_arrays(frame *fr, glitem *gi, int k, const arr *a, int na,
                         const ms_glcull_sel *sel, ms_error *err)
{
    for (int i = 0; i < na; i++) {
        const void *data = a[i].data;
        void *packed = NULL;
        size_t count = a[i].count;
        if (sel) {
            packed = ms_glcull_gather(sel, data, a[i].elsize);
            if (!packed) {
                ms_error_set(err, "out of memory");
                return -1;
            }
            data = packed;
            count = sel->kept;
        }
        gi->buf[k][i] = ms_glr_upload(fr->g, a[i].target, data, a[i].elsize * count, err);
        free(packed);
        if (!gi->buf[k][i]) return -1;
    }
    return 0;
}

/* One kind of a list (the item's own, or its text strokes). */
static int upload_kind(frame *fr, glitem *gi, int k, ms_error *err)
{
    const ms_displaylist *dl = k == K_TEXT ? gi->text : gi->it->dl;
    arr a[MAX_ARRAYS];
    const ms_rgba8 *col = NULL;
    size_t n = 0;
    int na = kind_arrays(dl, k, a, &col, &n);
    if (n == 0 || na == 0) return 0;
    if (n > INT_MAX / 3 || (k == K_MESH && a[3].count > INT_MAX / 3)) {
        ms_error_set(err, "%zu primitives in one display list: too many for one draw", n);
        return -1;
    }
    ms_glcull_sel sel = {0};
    int culled = fr->cull && cull_kind(k) >= 0;
    if (culled && ms_glcull_test(fr->cull, dl, cull_kind(k), gi->mv, gi->rscale, &sel, err))
        return -1;
    int rc = upload_arrays(fr, gi, k, a, na, culled ? &sel : NULL, err);
    gi->count[k] = culled ? sel.kept : k == K_MESH ? a[3].count : n;
    ms_glcull_sel_free(&sel);
    gi->translucent[k] = gi->it->mat.opacity < 1.0f || any_translucent(col, n);
    return rc;
}

/* Cull on a software rasterizer when the scene holds many impostors (and the occlusion
 * buffer, 4 bytes a pixel, is at most 256 MB); a GPU draws them faster than the CPU culls.
 * MOLSCOPE_GL_CULL=0 or 1 decides instead. */
static int want_cull(const ms_gl *g, const ms_scene *s)
{
    const char *v = getenv("MOLSCOPE_GL_CULL");
    if (v && *v) return strcmp(v, "0") != 0;
    if (ms_gl_hardware(g)) return 0;
    if ((size_t)s->width * (size_t)s->height > (size_t)8192 * 8192) return 0;
    size_t n = 0;
    for (size_t i = 0; i < s->nitems; i++) {
        const ms_displaylist *dl = s->items[i].dl;
        n += dl->spheres.n + dl->cylinders.n + dl->cones.n;
    }
    return n >= 20000;
}

static int place_items(frame *fr, ms_error *err)
{
    fr->items = calloc(fr->s->nitems ? fr->s->nitems : 1, sizeof *fr->items);
    if (!fr->items) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (size_t i = 0; i < fr->s->nitems; i++) {
        glitem *gi = &fr->items[fr->n++];
        gi->it = &fr->s->items[i];
        ms_mat4_mul(fr->view, gi->it->xform, gi->mv);
        gi->rscale = ms_mat4_scale_factor(gi->it->xform);
        if (gi->it->dl->texts.n && text_strokes(gi, err)) return -1;
    }
    return 0;
}

static int upload(frame *fr, ms_error *err)
{
    if (place_items(fr, err)) return -1;
    if (want_cull(fr->g, fr->s)) {
        if (!(fr->cull = ms_glcull_new(&fr->cam, err))) return -1;
        for (size_t i = 0; i < fr->n; i++) {
            const glitem *gi = &fr->items[i];
            if (gi->it->mat.opacity >= 1.0f)
                ms_glcull_occluders(fr->cull, gi->it->dl, gi->mv, gi->rscale);
        }
    }
    fr->g->r.used = 0;
    for (size_t i = 0; i < fr->n; i++)
        for (int k = 0; k < K_N; k++) {
            if (k == K_TEXT && !fr->items[i].text) continue;
            if (upload_kind(fr, &fr->items[i], k, err)) return -1;
        }
    return 0;
}

static void free_frame(frame *fr)
{
    ms_glcull_free(fr->cull);
    for (size_t i = 0; i < fr->n; i++) {
        if (!fr->items[i].text) continue;
        ms_dl_free(fr->items[i].text);
        free(fr->items[i].text);
    }
    free(fr->items);
}

/* ---------------------------------------------------------------- drawing */

/* Attribute loc from the buffer b: size components of type, per instance or per vertex. */
static void attrib(const ms_glfn *f, int loc, GLuint b, int size, GLenum type, int norm, int inst)
{
    f->BindBuffer(GL_ARRAY_BUFFER, b);
    f->VertexAttribPointer(loc, size, type, norm ? GL_TRUE : GL_FALSE, 0, NULL);
    f->VertexAttribDivisor(loc, inst ? 1 : 0);
    f->EnableVertexAttribArray(loc);
}

static void attribs_off(const ms_glfn *f)
{
    for (int loc = 0; loc <= MAX_ARRAYS; loc++) f->DisableVertexAttribArray(loc);
}

static int kind_program(int k)
{
    static const int progs[K_N] = {MS_GLR_SPHERE, MS_GLR_CONE, MS_GLR_CONE, MS_GLR_MESH,
                                   MS_GLR_LINE, MS_GLR_LINE, MS_GLR_LINE};
    return progs[k];
}

/* The item's clip planes in eye space. */
static void clip_uniforms(frame *fr, const glitem *gi, const ms_glr_prog *p)
{
    const ms_glfn *f = &fr->g->f;
    const ms_scene_item *it = gi->it;
    float eq[MS_SCENE_CLIPS][4], col[MS_SCENE_CLIPS][4];
    for (int i = 0; i < it->nclip; i++) {
        ms_plane_map(it->clip[i].eq, fr->view, eq[i]);
        memcpy(col[i], it->clip[i].color, 3 * sizeof(float));
        col[i][3] = (float)it->clip[i].solid;
    }
    f->Uniform1i(p->u[MS_U_NCLIP], it->nclip);
    if (!it->nclip) return;
    f->Uniform4fv(p->u[MS_U_CLIP], it->nclip, &eq[0][0]);
    f->Uniform4fv(p->u[MS_U_CLIPCOL], it->nclip, &col[0][0]);
}

static void item_uniforms(frame *fr, const glitem *gi, int k, int pass)
{
    const ms_glfn *f = &fr->g->f;
    const ms_glr_prog *p = &fr->g->r.prog[kind_program(k)];
    const ms_material *m = &gi->it->mat;
    float mat[4] = {m->ambient, m->diffuse, m->specular, m->shininess};
    float mat2[4] = {m->opacity, m->outline, m->outlinewidth, m->transmode};
    f->UseProgram(p->id);
    f->UniformMatrix4fv(p->u[MS_U_MV], 1, GL_TRUE, k == K_TEXT ? fr->view : gi->mv);
    f->Uniform1f(p->u[MS_U_RSCALE], gi->rscale);
    f->Uniform4fv(p->u[MS_U_MAT], 1, mat);
    f->Uniform4fv(p->u[MS_U_MAT2], 1, mat2);
    f->Uniform1i(p->u[MS_U_LIT], gi->it->dl->lit);
    f->Uniform1i(p->u[MS_U_PASS], pass);
    f->Uniform1i(p->u[MS_U_SQUARE], k == K_POINTS);
    clip_uniforms(fr, gi, p);
}

/* Bind the arrays of kind k and draw them (n primitives, or n indices of a mesh). */
static void draw_arrays(const ms_glfn *f, int k, const GLuint *b, size_t n)
{
    GLsizei cnt = (GLsizei)n;
    switch (k) {
    case K_SPHERES:
        attrib(f, 0, b[0], 3, GL_FLOAT, 0, 1); attrib(f, 1, b[1], 1, GL_FLOAT, 0, 1);
        attrib(f, 2, b[2], 4, GL_UNSIGNED_BYTE, 1, 1);
        break;
    case K_CYLINDERS: case K_CONES:
        attrib(f, 0, b[0], 3, GL_FLOAT, 0, 1); attrib(f, 1, b[1], 3, GL_FLOAT, 0, 1);
        attrib(f, 2, b[2], 1, GL_FLOAT, 0, 1);
        attrib(f, 3, k == K_CONES ? b[3] : b[2], 1, GL_FLOAT, 0, 1);
        attrib(f, 4, k == K_CONES ? b[4] : b[3], 4, GL_UNSIGNED_BYTE, 1, 1);
        attrib(f, 6, k == K_CONES ? b[4] : b[5], 4, GL_UNSIGNED_BYTE, 1, 1);
        if (k == K_CYLINDERS) {
            attrib(f, 5, b[4], 1, GL_UNSIGNED_BYTE, 0, 1);
            attrib(f, 7, b[6], 3, GL_FLOAT, 0, 1);
        } else {
            f->VertexAttrib1f(5, (float)MS_CAP_BASE);
            f->VertexAttrib3f(7, 0.0f, 0.0f, 0.0f);
        }
        break;
    case K_LINES: case K_TEXT: case K_POINTS:
        attrib(f, 0, b[0], 3, GL_FLOAT, 0, 1);
        attrib(f, 1, b[k == K_POINTS ? 0 : 1], 3, GL_FLOAT, 0, 1);
        attrib(f, 2, b[k == K_POINTS ? 1 : 2], 1, GL_FLOAT, 0, 1);
        attrib(f, 3, b[k == K_POINTS ? 2 : 3], 4, GL_UNSIGNED_BYTE, 1, 1);
        if (k == K_POINTS) f->VertexAttrib1f(4, 0.0f);
        else attrib(f, 4, b[4], 1, GL_UNSIGNED_BYTE, 0, 1);
        break;
    case K_MESH:
        attrib(f, 0, b[0], 3, GL_FLOAT, 0, 0); attrib(f, 1, b[1], 3, GL_BYTE, 0, 0);
        attrib(f, 2, b[2], 4, GL_UNSIGNED_BYTE, 1, 0);
        f->BindBuffer(GL_ELEMENT_ARRAY_BUFFER, b[3]);
        f->DrawElements(GL_TRIANGLES, (GLsizei)(3 * n), GL_UNSIGNED_INT, NULL);
        attribs_off(f);
        return;
    }
    f->DrawArraysInstanced(GL_TRIANGLE_STRIP, 0, 4, cnt);
    attribs_off(f);
}

/* Pass 0 draws what is opaque, pass 1 what is translucent (the shaders discard the rest). */
static void draw_items(frame *fr, int pass)
{
    for (size_t i = 0; i < fr->n; i++) {
        const glitem *gi = &fr->items[i];
        for (int k = 0; k < K_N; k++) {
            size_t n = gi->count[k];
            int skip = pass == 1 ? !gi->translucent[k] : gi->it->mat.opacity < 1.0f;
            if (!n || skip) continue;
            item_uniforms(fr, gi, k, pass);
            draw_arrays(&fr->g->f, k, gi->buf[k], n);
        }
    }
}

static int any_translucent_item(const frame *fr)
{
    for (size_t i = 0; i < fr->n; i++)
        for (int k = 0; k < K_N; k++)
            if (fr->items[i].translucent[k] && fr->items[i].count[k]) return 1;
    return 0;
}

static void background(frame *fr)
{
    const ms_glfn *f = &fr->g->f;
    f->BindFramebuffer(GL_FRAMEBUFFER, fr->g->r.fbo);
    f->Viewport(0, 0, fr->s->width, fr->s->height);
    f->Disable(GL_BLEND);
    f->DepthMask(GL_TRUE);
    f->ClearColor(fr->bg_bot[0], fr->bg_bot[1], fr->bg_bot[2], 1.0f);
    f->ClearDepth(1.0);
    f->Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
    if (!fr->s->settings.bg_gradient) return;
    f->Disable(GL_DEPTH_TEST);
    f->UseProgram(fr->g->r.prog[MS_GLR_GRADIENT].id);
    f->DrawArrays(GL_TRIANGLES, 0, 3);
}

/* Translucent surfaces into the weighted sums, then their resolve over the image. */
static int translucent(frame *fr, ms_error *err)
{
    const ms_glfn *f = &fr->g->f;
    static const float acc0[4] = {0, 0, 0, 1}, w0[4] = {0, 0, 0, 0};
    if (!any_translucent_item(fr)) return 0;
    if (ms_glr_oit_targets(fr->g, err)) return -1;
    f->BindFramebuffer(GL_FRAMEBUFFER, fr->g->r.oit_fbo);
    f->ClearBufferfv(GL_COLOR, 0, acc0);
    f->ClearBufferfv(GL_COLOR, 1, w0);
    f->DepthMask(GL_FALSE);
    f->Enable(GL_BLEND);
    f->BlendFuncSeparate(GL_ONE, GL_ONE, GL_ZERO, GL_ONE_MINUS_SRC_ALPHA);
    draw_items(fr, 1);
    f->BindFramebuffer(GL_FRAMEBUFFER, fr->g->r.fbo);
    f->Disable(GL_DEPTH_TEST);
    f->BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
    f->ActiveTexture(GL_TEXTURE0);
    f->BindTexture(GL_TEXTURE_2D, fr->g->r.accum_tex);
    f->ActiveTexture(GL_TEXTURE1);
    f->BindTexture(GL_TEXTURE_2D, fr->g->r.wsum_tex);
    f->UseProgram(fr->g->r.prog[MS_GLR_COMPOSITE].id);
    f->DrawArrays(GL_TRIANGLES, 0, 3);
    f->ActiveTexture(GL_TEXTURE0);
    f->Disable(GL_BLEND);
    f->DepthMask(GL_TRUE);
    return 0;
}

static int passes(frame *fr, ms_error *err)
{
    const ms_glfn *f = &fr->g->f;
    background(fr);
    f->Enable(GL_DEPTH_TEST);
    f->DepthFunc(GL_LESS);
    draw_items(fr, 0);
    if (translucent(fr, err)) return -1;
    f->Finish();
    GLenum e = f->GetError();
    if (e == GL_NO_ERROR) return 0;
    ms_error_set(err, "%s: drawing failed (%s)", ms_gl_kind_name(fr->g->kind),
                 e == GL_OUT_OF_MEMORY ? "out of memory" : "GL error");
    return -1;
}

int ms_glr_draw_scene(ms_gl *g, const ms_scene *s, ms_gl_times *t, ms_error *err)
{
    frame fr;
    memset(&fr, 0, sizeof fr);
    fr.g = g;
    fr.s = s;
    view_matrix(&s->settings.cam, fr.view);
    projection(&fr);
    lights_and_fog(&fr);
    g->f.BindVertexArray(g->r.vao);
    while (g->f.GetError() != GL_NO_ERROR) {}
    double t0 = ms_now();
    int rc = upload(&fr, err);
    double t1 = ms_now();
    if (rc == 0) {
        frame_uniforms(&fr);
        rc = passes(&fr, err);
    }
    t->upload = t1 - t0;
    t->draw = ms_now() - t1;
    free_frame(&fr);
    return rc;
}
