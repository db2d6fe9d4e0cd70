/* common.c: the parts of TachyonInternal the OpenCL tracer (src/oclrt) uses too, free of
 * Embree: transforms, Tachyon's texture terms of a material, the secondary-ray offset,
 * the shader settings of a scene, the option checks, and the pass both tracers start
 * from: the scene's lists as sources, with their strokes (strokes.c) and cap discs
 * derived once. */
#include "config.h"
#include "rt/rt_common.h"
#include "vecmath/vecmath.h"
#include "base/base.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void rt_xf_dir(const float m[12], const float v[3], float out[3])
{
    float x = v[0], y = v[1], z = v[2];
    for (int r = 0; r < 3; r++) out[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z;
}

void rt_m3_vec(const float m[9], const float v[3], float out[3])
{
    float x = v[0], y = v[1], z = v[2];
    for (int r = 0; r < 3; r++) out[r] = m[3 * r] * x + m[3 * r + 1] * y + m[3 * r + 2] * z;
}

/* Tachyon's texture terms for a list, as render/tachyon.c writes them (unlit lists: ambient
 * 1, no diffuse, no mirror; the highlight stays, as in VMD's files). */
void rt_material_terms(const ms_material *m, int lit, rt_material *t)
{
    t->ambient = lit ? m->ambient : 1.0f;
    t->diffuse = lit ? m->diffuse : 0.0f;
    t->mirror = lit ? m->mirror : 0.0f;
    t->phong = m->specular;
    t->phongexp = m->shininess;
    t->opacity = m->opacity;
    t->outline = m->outline;
    t->outlinewidth = m->outlinewidth;
    t->r3d = m->transmode != 0;
}

/* xf, its inverse, its normal matrix and its scale; -1 when xf is singular (nothing to see). */
int rt_xform_make(rt_xform *out, const float x[16])
{
    double a[3][3], inv[3][3];
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) a[r][c] = x[4 * r + c];
    if (ms_m3d_inverse(a, inv)) return -1;
    for (int r = 0; r < 3; r++) {
        double t = 0;
        for (int c = 0; c < 3; c++) {
            out->xf[4 * r + c] = (float)a[r][c];
            out->inv[4 * r + c] = (float)inv[r][c];
            out->nm[3 * r + c] = (float)inv[c][r];
            t -= inv[r][c] * x[4 * c + 3];
        }
        out->xf[4 * r + 3] = x[4 * r + 3];
        out->inv[4 * r + 3] = (float)t;
    }
    const float *m = out->xf;
    float det = m[0] * (m[5] * m[10] - m[6] * m[9]) - m[1] * (m[4] * m[10] - m[6] * m[8]) +
                m[2] * (m[4] * m[9] - m[5] * m[8]);
    out->scale = cbrtf(fabsf(det));
    out->sign = det < 0 ? -1.0f : 1.0f;
    return 0;
}

/* The secondary-ray offset: two millionths of the scene's size (its largest coordinate), at
 * least 1e-5: well above float rounding at a hit, far below any feature. */
float rt_world_eps(const ms_scene *s)
{
    float big = fabsf(s->settings.cam.eye[0]) + fabsf(s->settings.cam.eye[1]) + fabsf(s->settings.cam.eye[2]);
    for (size_t i = 0; i < s->nitems; i++) {
        float lo[3], hi[3], a[3], b[3];
        if (!ms_dl_bounds(s->items[i].dl, lo, hi)) continue;
        ms_mat4_point(s->items[i].xform, lo, a);
        ms_mat4_point(s->items[i].xform, hi, b);
        for (int k = 0; k < 3; k++)
            if (isfinite(a[k]) && isfinite(b[k])) big = fmaxf(big, fmaxf(fabsf(a[k]), fabsf(b[k])));
    }
    return fmaxf(1e-5f, big * 2e-6f);
}

/* The Tachyon gradient the exporter writes: top and bottom values of the sky sphere (ray
 * direction) or the orthographic sky plane (ray origin) along +y. */
static void background_init(rt_shader *sh, const ms_scene *s)
{
    memcpy(sh->bg, s->background, sizeof sh->bg);
    memcpy(sh->bg_top, s->bg_top, sizeof sh->bg_top);
    memcpy(sh->bg_bot, s->bg_bottom, sizeof sh->bg_bot);
    sh->bg_mode = RT_BG_SOLID;
    if (!s->settings.bg_gradient) return;
    int ortho = s->settings.cam.projection == MS_PROJ_ORTHOGRAPHIC;
    float mag = ortho ? s->settings.cam.height / 4.0f
                      : fminf(1.0f, (s->settings.cam.height / 2.0f) / (s->settings.cam.eye[2] - s->settings.cam.distance));
    sh->bg_mode = ortho ? RT_BG_SKY_PLANE : RT_BG_SKY_SPHERE;
    sh->grad_top = mag;
    sh->grad_bot = -mag;
}

/* The lights that shade: on, with a direction. */
static int light_dir(const ms_light *l, float d[3])
{
    memcpy(d, l->pos, 3 * sizeof(float));
    return l->on && ms_v3f_normalize_rcp(d) != 0.0f;
}

double rt_rays_per_sample(const ms_scene *s, int aosamples)
{
    int lights = 0;
    float d[3];
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) lights += light_dir(&s->settings.lights[i], d);
    int full = s->settings.shadows || s->settings.ao, glass = 0;
    for (size_t i = 0; i < s->nitems && !glass; i++) glass = s->items[i].mat.opacity < 1.0f;
    /* behind glass a hit is shaded again, and shadow rays walk the transparent scene too */
    return (1.0 + (full ? lights : 0) + (s->settings.ao ? aosamples : 0)) * (glass ? 2.0 : 1.0);
}

void rt_shader_init(rt_shader *sh, const ms_scene *s, const struct rt_world *w, int aosamples)
{
    memset(sh, 0, sizeof *sh);
    sh->w = w;
    rt_camera_init(&sh->cam, s);
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        const ms_light *l = &s->settings.lights[i];
        float d[3];
        if (!light_dir(l, d)) continue;
        memcpy(sh->ldir[sh->nlights], d, sizeof d);
        memcpy(sh->lcol[sh->nlights], l->color, sizeof d);
        sh->nlights++;
    }
    sh->full = s->settings.shadows || s->settings.ao;
    sh->light_scale = s->settings.ao ? s->settings.ao_direct : 1.0f;
    sh->ao_samples = s->settings.ao ? aosamples : 0;
    for (int k = 0; k < 3; k++) sh->ao_col[k] = s->settings.ao_ambient;
    background_init(sh, s);
    sh->fog = s->settings.depthcue;
    sh->cuemode = s->settings.cuemode;
    sh->fog_start = s->settings.cuemode == MS_CUE_LINEAR ? s->settings.cue_start : 0.0f;
    sh->fog_end = s->settings.cue_end;
    sh->fog_density = s->settings.cue_density;
}

int rt_check_options(const ms_scene *s, const ms_rt_options *o, ms_error *err)
{
    if (o->aasamples < 0 || o->aasamples > MS_RT_MAX_AASAMPLES) {
        ms_error_set(err, "aasamples %d: expected 0 to %d", o->aasamples, MS_RT_MAX_AASAMPLES);
        return -1;
    }
    if (o->aosamples < 0 || o->aosamples > MS_RT_MAX_AOSAMPLES) {
        ms_error_set(err, "aosamples %d: expected 0 to %d", o->aosamples, MS_RT_MAX_AOSAMPLES);
        return -1;
    }
    if (s->width < 1 || s->height < 1 || s->width > MS_IMAGE_MAX_SIDE || s->height > MS_IMAGE_MAX_SIDE) {
        ms_error_set(err, "image size %dx%d: expected 1 to %d pixels a side", s->width, s->height,
                     MS_IMAGE_MAX_SIDE);
        return -1;
    }
    return 0;
}

/* A new empty list appended to the set's; NULL when memory runs out. */
static ms_displaylist *stroke_list(rt_sources *set)
{
    ms_displaylist *dl = malloc(sizeof *dl);
    if (!dl || ms_grow((void **)&set->lists, &set->caplists, set->nlists + 1, sizeof *set->lists)) {
        free(dl);
        return NULL;
    }
    ms_dl_init(dl);
    set->lists[set->nlists++] = dl;
    return dl;
}

/* End e (0 base, 1 apex, 2 a cone's base) of primitive i: closed or not. */
static int disc_wanted(const ms_displaylist *dl, int e, size_t i)
{
    if (e == 2) return dl->cones.rbase[i] > 0;
    return (dl->cylinders.flags[i] & (e ? MS_CAP_APEX : MS_CAP_BASE)) != 0;
}

static void put_disc(rt_discs *d, size_t k, const float *at, const float *a, const float *b,
                     float r, ms_rgba8 col)
{
    for (int c = 0; c < 3; c++) {
        d->centre[3 * k + c] = at[c];
        d->normal[3 * k + c] = b[c] - a[c];
    }
    d->outer[k] = r;
    d->inner[k] = 0;
    d->color[k] = col;
    d->alpha |= col.a < 255;
}

/* The cap discs of a list (one block, freed through d->centre). */
static int make_discs(const ms_displaylist *dl, rt_discs *d)
{
    const ms_dl_cylinders *cy = &dl->cylinders;
    const ms_dl_cones *co = &dl->cones;
    size_t n = 0;
    memset(d, 0, sizeof *d);
    for (int e = 0; e < 3; e++)
        for (size_t i = 0; i < (e == 2 ? co->n : cy->n); i++) n += (size_t)disc_wanted(dl, e, i);
    if (!n) return 0;
    float *f = ms_alloc_array(n, 8 * sizeof(float) + sizeof(ms_rgba8));
    if (!f) return -1;
    d->n = n, d->centre = f, d->normal = f + 3 * n, d->outer = f + 6 * n, d->inner = f + 7 * n;
    d->color = (ms_rgba8 *)(f + 8 * n);
    size_t k = 0;
    for (int e = 0; e < 3; e++)
        for (size_t i = 0; i < (e == 2 ? co->n : cy->n); i++) {
            if (!disc_wanted(dl, e, i)) continue;
            const float *a = (e == 2 ? co->base : cy->base) + 3 * i;
            const float *b = (e == 2 ? co->apex : cy->apex) + 3 * i;
            put_disc(d, k++, e == 1 ? b : a, a, b, e == 2 ? co->rbase[i] : cy->radius[i],
                     e == 2 ? co->color[i] : cy->color[i]);
        }
    return 0;
}

/* The next source: a list, its transform, its terms (lit or not) and its discs. */
static int add_source(rt_sources *set, const ms_displaylist *dl, const float *xform,
                      const ms_material *m, int lit, const ms_scene_item *item)
{
    rt_source *o = &set->src[set->n++];
    o->dl = dl, o->xform = xform, o->item = item;
    rt_material_terms(m, lit, &o->mat);
    return make_discs(dl, &o->discs);
}

int rt_sources_make(rt_sources *set, const ms_scene *s, ms_error *err)
{
    static const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memset(set, 0, sizeof *set);
    set->src = ms_calloc_array(2 * s->nitems + 1, sizeof *set->src);
    if (!set->src) goto oom;
    for (size_t i = 0; i < s->nitems; i++) {
        const ms_scene_item *it = &s->items[i];
        if (add_source(set, it->dl, it->xform, &it->mat, it->dl->lit, it)) goto oom;
        if (!it->dl->lines.n && !it->dl->points.n && !it->dl->texts.n) continue;
        ms_displaylist *extra = stroke_list(set);
        if (!extra || rt_strokes(it, extra) || add_source(set, extra, identity, &it->mat, 0, it))
            goto oom;
    }
    return 0;
oom:
    rt_sources_free(set);
    ms_error_set(err, "out of memory");
    return -1;
}

void rt_sources_free(rt_sources *set)
{
    for (size_t i = 0; set->src && i < set->n; i++) free(set->src[i].discs.centre);
    for (size_t i = 0; i < set->nlists; i++) {
        ms_dl_free(set->lists[i]);
        free(set->lists[i]);
    }
    free(set->lists);
    free(set->src);
    memset(set, 0, sizeof *set);
}
