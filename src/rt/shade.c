/* shade.c: the integrator, Tachyon's shaders as VMD drives them (doc/vmd-behaviour.md sec. 8).
 * At the nearest hit: the lights' diffuse terms (N.L, scaled by aodirect when ambient
 * occlusion is on) and Blinn highlights, each light tested by a shadow ray in the Full
 * shader (shadows or AO on); ambient occlusion added to the diffuse light; outline
 * darkening; colour times (diffuse + ambient) plus highlights; a mirror ray; for opacity
 * below 1 a transmission ray, the surface weighted by its (angle-modulated) opacity as
 * Trans_VMD does; then planar fog (Fog_VMD: the depth along the view for camera rays, the
 * ray length for others). Shadow and occlusion rays pass transparent surfaces, each one
 * letting (1 - opacity) of the light through. Rays that leave the scene see the background
 * or its gradient.
 * src/oclrt/kernels.cl mirrors this file function by function for the OpenCL tracer: change
 * both together. One shortcut is this file's alone: a transmission ray takes the opaque hit
 * its parent found beyond the transparent one (beyond, below); the kernel walks one tree for
 * both kinds and has nothing to carry. */
#include "config.h"
#include "rt/rt_internal.h"

#include <math.h>
#include <string.h>



static void background(const rt_shader *sh, const float org[3], const float dir[3], float out[3])
{
    if (sh->bg_mode == RT_BG_SOLID) {
        memcpy(out, sh->bg, 3 * sizeof(float));
        return;
    }
    float v = sh->bg_mode == RT_BG_SKY_SPHERE ? dir[1] : org[1];
    v = (v - sh->grad_bot) / (sh->grad_top - sh->grad_bot);
    v = v < 0.0f ? 0.0f : v > 1.0f ? 1.0f : v;
    for (int k = 0; k < 3; k++) out[k] = v * sh->bg_top[k] + (1.0f - v) * sh->bg_bot[k];
}

static void fog(const rt_shader *sh, float z, float col[3])
{
    float f;
    if (sh->cuemode == MS_CUE_LINEAR) {
        f = (sh->fog_end - z) / (sh->fog_end - sh->fog_start);
    } else {
        float v = sh->fog_density * (z - sh->fog_start);
        f = expf(sh->cuemode == MS_CUE_EXP ? -v : -v * v);
    }
    f = f > 1.0f ? 1.0f : f < 0.0f ? 0.0f : f;
    for (int k = 0; k < 3; k++) col[k] = f * col[k] + (1.0f - f) * sh->bg[k];
}

/* ---------------------------------------------------------------- hits */

typedef struct surface {
    float p[3], n[3], t;
    float col[3], opacity;
    const rt_material *mat;
} surface;

/* The inside of a surface seen through a cut of a solid clip plane (VMD's status 2) takes
 * the plane's colour and faces the viewer as the plane does. */
static void solid_cut(const ms_scene_item *it, const float d[3], surface *s)
{
    for (int i = 0; it && i < it->nclip; i++) {
        const ms_clip_plane *cp = &it->clip[i];
        if (!cp->solid) continue;
        float n[3] = {cp->eq[0], cp->eq[1], cp->eq[2]};
        if (!(ms_v3f_normalize_rcp(n) > 0.0f)) continue;
        float side = ms_v3f_dot(n, d) > 0.0f ? -1.0f : 1.0f;
        for (int k = 0; k < 3; k++) s->n[k] = side * n[k], s->col[k] = cp->color[k];
        return;
    }
}

/* Position, normal facing the ray's origin, colour and material at a hit of g. */
static void surface_at(const rt_geom *g, const struct RTCRayHit *rh, surface *s)
{
    float o[3] = {rh->ray.org_x, rh->ray.org_y, rh->ray.org_z};
    float d[3] = {rh->ray.dir_x, rh->ray.dir_y, rh->ray.dir_z}, ng[3];
    ms_rgba8 c;
    s->t = rh->ray.tfar;
    for (int k = 0; k < 3; k++) s->p[k] = o[k] + s->t * d[k];
    rt_prims[g->kind]->surface(g, &rh->hit, s->p, s->n, ng, &c);
    /* Tachyon's rule: the geometric normal decides the side seen (for a mesh, its winding),
     * and the shading normal turns with it */
    float side = ms_v3f_dot(ng, d) > 0.0f ? -1.0f : 1.0f;
    if (!(ms_v3f_normalize_rcp(s->n) > 0.0f) || !isfinite(s->n[0] + s->n[1] + s->n[2])) {
        memcpy(s->n, d, sizeof d);
        side = -1.0f;
    }
    for (int k = 0; k < 3; k++) s->n[k] *= side;
    ms_rgba8_to_float(c, s->col);
    if (side < 0.0f) solid_cut(g->item, d, s);
    s->mat = &g->mat;
    s->opacity = g->mat.opacity * (float)c.a * (1.0f / 255.0f);
}

/* Embree refuses rays beyond its float range (1.8e18) and non-numbers, and its checks abort:
 * a degenerate camera or primitive must not get that far. */
static int point_ok(const float p[3])
{
    return fabsf(p[0]) <= 1e18f && fabsf(p[1]) <= 1e18f && fabsf(p[2]) <= 1e18f;
}

static int ray_ok(const float o[3], const float d[3])
{
    return point_ok(o) && point_ok(d) && (d[0] != 0 || d[1] != 0 || d[2] != 0);
}

static void ray_init(struct RTCRay *r, const float org[3], const float dir[3], float tnear)
{
    r->org_x = org[0], r->org_y = org[1], r->org_z = org[2];
    r->dir_x = dir[0], r->dir_y = dir[1], r->dir_z = dir[2];
    r->tnear = tnear;
    r->tfar = INFINITY;
    r->time = 0.0f;
    r->mask = 0xffffffffu;
    r->id = 0;
    r->flags = 0;
}

/* ---------------------------------------------------------------- shadow and occlusion */

/* Visibility of the sky along d from p: 0 blocked, 1 open, between through glass (one
 * visibility ray: the opaque scene, then the transparent one when it got through). The
 * caller has checked p (point_ok); d is a light's direction or one of the hemisphere's, unit
 * and finite. */
static float visibility(const rt_shader *sh, rt_thread *th, const float p[3], const float d[3],
                        int kind)
{
    struct RTCRay r;
    float f = 1.0f;
    ray_init(&r, p, d, sh->w->eps);
    th->ctx.filter = &f;
    th->rays[kind]++;
    if (th->dump) rt_raybuf_add(th->dump, kind, 0xffu, p, d, r.tnear);
    rtcOccluded1(sh->w->scene[RT_OPAQUE], &th->ctx.ec, &r);
    if (r.tfar < 0.0f) return 0.0f;
    if (!sh->w->scene[RT_TRANS]) return 1.0f;
    r.tfar = INFINITY;
    rtcOccluded1(sh->w->scene[RT_TRANS], &th->ctx.ec, &r);
    return r.tfar < 0.0f ? 0.0f : f;
}

/* Tachyon's ambient occlusion: (2 / n) sum of N.d over the open directions d of n rays
 * (sample.c's stratified hemisphere), times the AO ambient colour. */
static void occlusion(const rt_shader *sh, rt_thread *th, const surface *s, float out[3])
{
    rt_hemisphere h;
    rt_hemisphere_init(&h, s->n, sh->ao_samples, &th->rng);
    float sum = 0.0f, d[3];
    for (int i = 0; i < sh->ao_samples; i++) {
        float cosine = rt_hemisphere_next(&h, d);
        sum += cosine * visibility(sh, th, s->p, d, MS_RT_AO);
    }
    for (int k = 0; k < 3; k++) out[k] = 2.0f / (float)sh->ao_samples * sum * sh->ao_col[k];
}

/* Blinn's half-vector highlight (Tachyon's shade_blinn). */
static float blinn(const float n[3], const float l[3], const float d[3], float exponent)
{
    float h[3] = {l[0] - d[0], l[1] - d[1], l[2] - d[2]};
    float i = ms_v3f_dot(n, h);
    if (!(i > RT_MINCONTRIB)) return 0.0f;
    return powf(i / sqrtf(ms_v3f_dot(h, h)), exponent);
}

/* Diffuse light (with occlusion) and highlights at s. */
static void direct(const rt_shader *sh, rt_thread *th, const surface *s, const float dir[3],
                   float diffuse[3], float phong[3])
{
    const rt_material *m = s->mat;
    memset(diffuse, 0, 3 * sizeof(float));
    memset(phong, 0, 3 * sizeof(float));
    if (!(m->diffuse > RT_MINCONTRIB || m->phong > RT_MINCONTRIB)) return;
    int open = point_ok(s->p);          /* else no ray leaves s: all in shadow */
    for (int i = 0; i < sh->nlights; i++) {
        const float *l = sh->ldir[i];
        float inten = sh->light_scale * ms_v3f_dot(s->n, l);
        if (!(inten > RT_MINCONTRIB)) continue;
        if (sh->full) {
            float v = open ? visibility(sh, th, s->p, l, MS_RT_SHADOW) : 0.0f;
            if (v <= 0.0f) continue;
            inten *= v;
        }
        float pv = m->phong > RT_MINCONTRIB ? sh->light_scale * blinn(s->n, l, dir, m->phongexp) * m->phong : 0.0f;
        for (int k = 0; k < 3; k++) {
            diffuse[k] += inten * sh->lcol[i][k];
            phong[k] += pv * sh->lcol[i][k];
        }
    }
    if (sh->full && sh->ao_samples > 0 && open) {
        float ao[3];
        occlusion(sh, th, s, ao);
        for (int k = 0; k < 3; k++) diffuse[k] += ao[k];
    }
}

/* ---------------------------------------------------------------- tracing */

/* What a ray found in the opaque scene beyond the transparent hit it stopped at: a straight
 * transmission ray from that hit goes on to the same opaque hit (or to none), so it walks
 * the transparent scene alone, up to it. */
typedef struct beyond {
    int known;                  /* 0: the transmission ray walks both scenes */
    float t;                    /* the opaque hit's distance from the ray's origin, or INFINITY */
    struct RTCHit hit;
    const rt_geom *g;           /* its geometry, or NULL for none */
} beyond;

static void trace(const rt_shader *sh, rt_thread *th, const float org[3], const float dir[3],
                  int depth, int primary, const beyond *op, float out[3]);

/* The colour of a secondary ray from p along d (the background once depth runs out); op:
 * what lies beyond in the opaque scene when it is known (a transmission), else NULL. */
static void secondary(const rt_shader *sh, rt_thread *th, const float p[3], const float d[3],
                      const float in_org[3], const float in_dir[3], int depth, const beyond *op,
                      float out[3])
{
    if (depth <= 1) {
        background(sh, in_org, in_dir, out);
        return;
    }
    trace(sh, th, p, d, depth - 1, 0, op, out);
}

static void shade(const rt_shader *sh, rt_thread *th, const surface *s, const float org[3],
                  const float dir[3], int depth, int primary, const beyond *op, float out[3])
{
    const rt_material *m = s->mat;
    float diffuse[3], phong[3], nd = ms_v3f_dot(s->n, dir), f = m->diffuse;
    direct(sh, th, s, dir, diffuse, phong);
    if (m->outline > 0.0f) {
        float e = 1.0f - powf(1.0f - nd * nd, (1.0f - m->outlinewidth) * 32.0f);
        f *= (1.0f - m->outline) + e * m->outline;
    }
    for (int k = 0; k < 3; k++) out[k] = s->col[k] * (diffuse[k] * f + m->ambient) + phong[k];
    if (m->mirror > RT_MINCONTRIB) {
        float r[3], c[3];
        for (int k = 0; k < 3; k++) r[k] = dir[k] - 2.0f * nd * s->n[k];
        secondary(sh, th, s->p, r, org, dir, depth, NULL, c);
        for (int k = 0; k < 3; k++) out[k] += m->mirror * c[k];
    }
    if (s->opacity < 1.0f - RT_MINCONTRIB) {
        float a = s->opacity, c[3];
        if (m->r3d) {
            a = 1.0f + cosf(3.1415926f * (1.0f - a) * nd);
            a = a * a * 0.25f;
        }
        beyond next;
        next.known = 0;
        if (op && op->known) {      /* the same opaque hit, from this one */
            next = *op;
            next.t = op->t - s->t;
            next.known = next.t > 2.0f * sh->w->eps;    /* else walked again, as tnear moves */
        }
        secondary(sh, th, s->p, dir, org, dir, depth, &next, c);
        for (int k = 0; k < 3; k++) out[k] = a * out[k] + (1.0f - a) * c[k];
    }
    if (sh->fog) fog(sh, primary ? s->t * ms_v3f_dot(dir, sh->cam.dir) : s->t, out);
}

/* The geometry of a hit in a scene of the world (part: its table, rt_world). */
static const rt_geom *hit_geom(rt_geom *const *part, const struct RTCHit *h)
{
    if (h->instID[0] == RTC_INVALID_GEOMETRY_ID) return part[h->geomID];
    return &part[h->instID[0]][h->geomID];      /* a mesh under its transform's instance */
}

/* Whether no clip plane can cut a hit on g. */
static int clip_free(const rt_geom *g)
{
    return !g || !g->item || !g->item->nclip;
}

/* The nearest hit in the opaque scene (or op's, when known), then in the transparent one (up
 * to the opaque hit): its geometry, or NULL for none. When the transparent hit is the
 * nearest, *next is what lies beyond it in the opaque scene, for its transmission ray. */
static const rt_geom *nearest(const rt_world *w, rt_thread *th, struct RTCRayHit *rh,
                              const beyond *op, beyond *next)
{
    const rt_geom *g;
    if (op && op->known) {
        rh->ray.tfar = op->t;
        rh->hit = op->hit;
        g = op->g;
    } else {
        rh->hit.geomID = rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(w->scene[RT_OPAQUE], &th->ctx.ec, rh);
        g = rh->hit.geomID == RTC_INVALID_GEOMETRY_ID ? NULL : hit_geom(w->part[RT_OPAQUE], &rh->hit);
    }
    next->known = 0;
    if (!w->scene[RT_TRANS]) return g;
    struct RTCHit opaque = rh->hit;
    float t = rh->ray.tfar;
    rh->hit.geomID = rh->hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(w->scene[RT_TRANS], &th->ctx.ec, rh);
    if (rh->hit.geomID == RTC_INVALID_GEOMETRY_ID) {
        rh->hit = opaque;       /* a miss leaves the opaque hit's record as it was */
        return g;
    }
    *next = (beyond){clip_free(g), t, opaque, g};
    return hit_geom(w->part[RT_TRANS], &rh->hit);
}

/* The nearest hit that no clip plane of its item cuts away: a cut hit is passed and the ray
 * goes on beyond it (a bound on the passes keeps a pathological scene finite). Its geometry,
 * or NULL for none; op and next as for nearest (op is used by the first pass only). */
static const rt_geom *intersect_unclipped(const rt_shader *sh, rt_thread *th, struct RTCRayHit *rh,
                                          const beyond *op, beyond *next)
{
    for (int pass = 0; pass < 256; pass++) {
        const rt_geom *g = nearest(sh->w, th, rh, pass ? NULL : op, next);
        if (clip_free(g)) return g;
        float t = rh->ray.tfar;
        float p[3] = {rh->ray.org_x + t * rh->ray.dir_x, rh->ray.org_y + t * rh->ray.dir_y,
                      rh->ray.org_z + t * rh->ray.dir_z};
        if (!ms_scene_clipped(g->item, p)) return g;
        rh->ray.tnear = t + MS_MAX(sh->w->eps * 1e-3f, t * 1e-6f);
        rh->ray.tfar = INFINITY;
    }
    return NULL;
}

static void trace(const rt_shader *sh, rt_thread *th, const float org[3], const float dir[3],
                  int depth, int primary, const beyond *op, float out[3])
{
    struct RTCRayHit rh;
    beyond next;
    if (!ray_ok(org, dir)) {
        memcpy(out, sh->bg, 3 * sizeof(float));
        return;
    }
    int kind = primary ? MS_RT_PRIMARY : MS_RT_SECONDARY;
    ray_init(&rh.ray, org, dir, primary ? 0.0f : sh->w->eps);
    if (th->dump) rt_raybuf_add(th->dump, kind, 0xffu, org, dir, rh.ray.tnear);
    const rt_geom *g = intersect_unclipped(sh, th, &rh, op, &next);
    th->rays[kind]++;
    if (!g) {
        background(sh, org, dir, out);
        return;
    }
    surface s;
    surface_at(g, &rh, &s);
    if (!clip_free(g)) next.known = 0;
    shade(sh, th, &s, org, dir, depth, primary, &next, out);
}

void rt_trace(const rt_shader *sh, rt_thread *th, const float org[3], const float dir[3],
              int depth, int primary, float out[3])
{
    trace(sh, th, org, dir, depth, primary, NULL, out);
}
