/* place.c: a display list's spheres, cylinders, cones and discs moved to world space for
 * TachyonInternal, so that rays meet them with no instance to walk (issue 21: the instance
 * each transform was placed by cost 4-6% of the tracing on ambient occlusion, doc/rt.md).
 * Positions go through the list's transform, radii by its scale (VMD's transforms are
 * rotations, translations and uniform scales), cap discs' axes as directions. Meshes are not
 * moved: Embree traces the list's own vertices under an instance of the transform (a copy
 * would cost 12 bytes a vertex). A list whose transform is the identity (the world-space
 * strokes) keeps its own arrays. Colours and flags are always the list's. The copies belong
 * to the world (rt_world_alloc). */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/threads.h"

#include <string.h>

/* A transform of n points (or directions, dir) of in into out, by ms_parallel_for. */
typedef struct move {
    const float *xf, *in;
    float *out;
    int dir;
} move;

static void move_range(void *ctx, size_t b, size_t e, int thread)
{
    const move *m = ctx;
    for (size_t i = b; i < e; i++) {
        if (m->dir) rt_xf_dir(m->xf, m->in + 3 * i, m->out + 3 * i);
        else ms_mat4_point(m->xf, m->in + 3 * i, m->out + 3 * i);
    }
}

/* n points (or directions, dir) of in, moved; NULL with err set. */
static float *moved(rt_world *w, const rt_xform *x, const float *in, size_t n, int dir, ms_error *err)
{
    float *out = rt_world_alloc(w, 3 * n, sizeof(float), err);
    if (!out) return NULL;
    move m = {x->xf, in, out, dir};
    ms_parallel_for(n, 65536, move_range, &m);
    return out;
}

/* n radii of in, scaled; NULL with err set. */
static float *scaled(rt_world *w, const rt_xform *x, const float *in, size_t n, ms_error *err)
{
    float *out = rt_world_alloc(w, n, sizeof(float), err);
    if (!out) return NULL;
    for (size_t i = 0; i < n; i++) out[i] = in[i] * x->scale;
    return out;
}

static int place_spheres(rt_world *w, const rt_xform *x, ms_dl_spheres *s, ms_error *err)
{
    if (!s->n) return 0;
    s->xyz = moved(w, x, s->xyz, s->n, 0, err);
    s->radius = s->xyz ? scaled(w, x, s->radius, s->n, err) : NULL;
    return s->radius ? 0 : -1;
}

static int place_cylinders(rt_world *w, const rt_xform *x, ms_dl_cylinders *c, ms_error *err)
{
    if (!c->n) return 0;
    if (!(c->base = moved(w, x, c->base, c->n, 0, err)) ||
        !(c->apex = moved(w, x, c->apex, c->n, 0, err)) ||
        !(c->joint = moved(w, x, c->joint, c->n, 0, err)))
        return -1;
    c->radius = scaled(w, x, c->radius, c->n, err);
    return c->radius ? 0 : -1;
}

static int place_cones(rt_world *w, const rt_xform *x, ms_dl_cones *c, ms_error *err)
{
    if (!c->n) return 0;
    if (!(c->base = moved(w, x, c->base, c->n, 0, err)) ||
        !(c->apex = moved(w, x, c->apex, c->n, 0, err)) ||
        !(c->rbase = scaled(w, x, c->rbase, c->n, err)))
        return -1;
    c->rapex = scaled(w, x, c->rapex, c->n, err);
    return c->rapex ? 0 : -1;
}

static int place_discs(rt_world *w, const rt_xform *x, rt_discs *d, ms_error *err)
{
    if (!d->n) return 0;
    if (!(d->centre = moved(w, x, d->centre, d->n, 0, err)) ||
        !(d->normal = moved(w, x, d->normal, d->n, 1, err)) ||
        !(d->outer = scaled(w, x, d->outer, d->n, err)))
        return -1;
    d->inner = scaled(w, x, d->inner, d->n, err);
    return d->inner ? 0 : -1;
}

static int is_identity(const float x[16])
{
    static const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    return !memcmp(x, id, sizeof id);
}

size_t rt_place_bytes(const ms_scene *s)
{
    size_t bytes = 0;
    for (size_t i = 0; i < s->nitems; i++) {
        const ms_displaylist *dl = s->items[i].dl;
        /* a sphere's centre and radius; a cylinder's three points and radius, its two cap
         * discs; a cone, its two points and radii and its base disc */
        bytes += (16 * dl->spheres.n + 104 * dl->cylinders.n + 64 * dl->cones.n) *
                 (size_t)!is_identity(s->items[i].xform);
    }
    return bytes;
}

int rt_place(rt_world *w, const rt_source *src, rt_placed *p, ms_error *err)
{
    memset(p, 0, sizeof *p);
    p->dl = *src->dl;
    p->discs = src->discs;
    if (rt_xform_make(&p->x, src->xform)) return 1;        /* singular: nothing to see */
    if (is_identity(src->xform)) return 0;
    if (place_spheres(w, &p->x, &p->dl.spheres, err) || place_cylinders(w, &p->x, &p->dl.cylinders, err) ||
        place_cones(w, &p->x, &p->dl.cones, err) || place_discs(w, &p->x, &p->discs, err))
        return -1;
    return 0;
}
