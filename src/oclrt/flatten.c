/* flatten.c: the scene as the OpenCL kernels read it. Each source of the pass both tracers
 * share (rt_sources_make: a placed display list, or the world-space list of its lines,
 * points and text, with the discs closing its cylinder ends and cone bases) gives one
 * geometry per primitive kind with TachyonInternal's texture terms; its primitives are
 * moved to world space here (positions by the transform, radii by its scale: VMD's
 * transforms are rotations, translations and uniform scales), while mesh normals stay the
 * list's quantized bytes and the kernel turns them with the list's normal matrix. A bond is
 * one cylinder with its second colour and the joint's distance along the axis. Each item
 * carries its scene item's clip planes (world space), which the kernels test at every hit. */
#include "config.h"
#include "oclrt/oclrt_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

typedef rt_source source;

static int any_alpha(const ms_rgba8 *c, size_t n)
{
    for (size_t i = 0; i < n; i++)
        if (c[i].a < 255) return 1;
    return 0;
}

/* A triangle naming a vertex that does not exist is an error (as rt/mesh.c says it). */
static int check_mesh(const ms_dl_mesh *m, ms_error *err)
{
    for (size_t i = 0; i < 3 * m->ntris; i++)
        if (m->tri[i] >= m->nverts) {
            ms_error_set(err, "mesh: triangle %zu names a vertex beyond the %zu vertices", i / 3, m->nverts);
            return MS_OCLRT_EINPUT;
        }
    return 0;
}

static int alloc_arrays(orc_world *w, size_t nsrc, ms_error *err)
{
    size_t nq = w->nq ? w->nq : 1, nt = w->ntri ? w->ntri : 1, nv = w->nverts ? w->nverts : 1;
    size_t ng = 5 * nsrc + 1;
    w->qa = ms_alloc_array(nq, 4 * sizeof(float));
    w->qb = ms_alloc_array(nq, 4 * sizeof(float));
    w->qm = ms_alloc_array(nq, 4 * sizeof(uint32_t));
    w->qkind = ms_alloc_array(nq, sizeof(uint32_t));
    w->tri = ms_alloc_array(nt, 4 * sizeof(uint32_t));
    w->vxyz = ms_alloc_array(nv, 4 * sizeof(float));
    w->vnorm = ms_calloc_array(nv, 4);
    w->vcol = ms_alloc_array(nv, sizeof(ms_rgba8));
    w->gmat0 = ms_alloc_array(ng, 4 * sizeof(float));
    w->gmat1 = ms_alloc_array(ng, 4 * sizeof(float));
    w->gflag = ms_calloc_array(ng, 4 * sizeof(int32_t));
    w->item = ms_calloc_array(nsrc + 1, ORC_ITEM * 4 * sizeof(float));
    if (w->qa && w->qb && w->qm && w->qkind && w->tri && w->vxyz && w->vnorm && w->vcol &&
        w->gmat0 && w->gmat1 && w->gflag && w->item)
        return 0;
    ms_error_set(err, "out of memory for the scene's %zu primitives", w->nq + w->ntri);
    return -1;
}

/* ---------------------------------------------------------------- one list */

typedef struct placer {
    orc_world *w;
    rt_xform ri;
    uint32_t item;
    int nclip;                  /* the item's clip planes */
} placer;

static uint32_t add_geom(placer *pl, const rt_material *m, int alpha)
{
    orc_world *w = pl->w;
    size_t g = w->ngeoms++;
    float *a = w->gmat0 + 4 * g, *b = w->gmat1 + 4 * g;
    a[0] = m->ambient, a[1] = m->diffuse, a[2] = m->mirror, a[3] = m->phong;
    b[0] = m->phongexp, b[1] = m->opacity, b[2] = m->outline, b[3] = m->outlinewidth;
    int32_t *f = w->gflag + 4 * g;
    f[0] = m->r3d, f[1] = alpha, f[2] = (int32_t)pl->item, f[3] = pl->nclip;
    return (uint32_t)g;
}

/* A quadric; c2 and split: a cylinder's colour beyond its joint, and the joint's distance. */
static void put_quadric(placer *pl, uint32_t kind, uint32_t g, const float a[4], const float b[4],
                        ms_rgba8 c, ms_rgba8 c2, float split)
{
    orc_world *w = pl->w;
    size_t i = w->nq++;
    memcpy(w->qa + 4 * i, a, 4 * sizeof(float));
    memcpy(w->qb + 4 * i, b, 4 * sizeof(float));
    w->qm[4 * i] = g;
    memcpy(&w->qm[4 * i + 1], &c, 4);
    memcpy(&w->qm[4 * i + 2], &c2, 4);
    memcpy(&w->qm[4 * i + 3], &split, 4);
    w->qkind[i] = kind;
}

/* p moved to world space, with w = r times the scale. */
static void world_point(const placer *pl, const float p[3], float r, float out[4])
{
    ms_mat4_point(pl->ri.xf, p, out);
    out[3] = r * pl->ri.scale;
}

static void place_spheres(placer *pl, const source *s)
{
    const ms_dl_spheres *sp = &s->dl->spheres;
    if (!sp->n) return;
    uint32_t g = add_geom(pl, &s->mat, any_alpha(sp->color, sp->n));
    float none[4] = {0, 0, 0, 0};
    for (size_t i = 0; i < sp->n; i++) {
        float a[4];
        world_point(pl, sp->xyz + 3 * i, sp->radius[i], a);
        put_quadric(pl, ORC_SPHERE, g, a, none, sp->color[i], sp->color[i], 0);
    }
}

static void place_cylinders(placer *pl, const source *s)
{
    const ms_dl_cylinders *cy = &s->dl->cylinders;
    if (!cy->n) return;
    uint32_t g = add_geom(pl, &s->mat, any_alpha(cy->color, cy->n));
    for (size_t i = 0; i < cy->n; i++) {
        float a[4], b[4], j[4];
        world_point(pl, cy->base + 3 * i, cy->radius[i], a);
        world_point(pl, cy->apex + 3 * i, 0, b);
        world_point(pl, cy->joint + 3 * i, 0, j);
        for (int k = 0; k < 3; k++) {
            b[k] -= a[k];
            j[k] -= a[k];
        }
        b[3] = ms_v3f_normalize_rcp(b);
        put_quadric(pl, ORC_CYLINDER, g, a, b, cy->color[i], cy->color2[i], sqrtf(ms_v3f_dot(j, j)));
    }
}

static void place_cones(placer *pl, const source *s)
{
    const ms_dl_cones *co = &s->dl->cones;
    if (!co->n) return;
    uint32_t g = add_geom(pl, &s->mat, any_alpha(co->color, co->n));
    for (size_t i = 0; i < co->n; i++) {
        float a[4], b[4];
        world_point(pl, co->base + 3 * i, co->rbase[i], a);
        world_point(pl, co->apex + 3 * i, co->rapex[i], b);
        put_quadric(pl, ORC_CONE, g, a, b, co->color[i], co->color[i], 0);
    }
}

/* The cap discs of the sources pass (rt/common.c), moved to world space. */
static void place_discs(placer *pl, const source *s)
{
    const rt_discs *d = &s->discs;
    if (!d->n) return;
    uint32_t g = add_geom(pl, &s->mat, d->alpha);
    for (size_t i = 0; i < d->n; i++) {
        float c[4], n[4];
        world_point(pl, d->centre + 3 * i, d->outer[i], c);
        rt_xf_dir(pl->ri.xf, d->normal + 3 * i, n);
        n[3] = d->inner[i];
        put_quadric(pl, ORC_RING, g, c, n, d->color[i], d->color[i], 0);
    }
}

static void place_mesh(placer *pl, const source *s)
{
    const ms_dl_mesh *m = &s->dl->mesh;
    orc_world *w = pl->w;
    if (!m->nverts || !m->ntris) return;
    uint32_t g = add_geom(pl, &s->mat, any_alpha(m->color, m->nverts));
    size_t v0 = w->nverts;
    for (size_t i = 0; i < m->nverts; i++) {
        float *p = w->vxyz + 4 * (v0 + i);
        world_point(pl, m->xyz + 3 * i, 0, p);
        memcpy(w->vnorm + 4 * (v0 + i), m->normal + 3 * i, 3);
        w->vcol[v0 + i] = m->color[i];
    }
    w->nverts += m->nverts;
    for (size_t i = 0; i < m->ntris; i++) {
        uint32_t *t = w->tri + 4 * (w->ntri + i);
        for (int k = 0; k < 3; k++) t[k] = (uint32_t)(v0 + m->tri[3 * i + k]);
        t[3] = g;
    }
    w->ntri += m->ntris;
}

/* The clip planes of the scene item a source comes from (already in world space, as the
 * flattened primitives are) into the item's record. */
static int put_clips(float *it, const ms_scene_item *si)
{
    int n = si ? si->nclip : 0;
    for (int i = 0; i < n; i++) {
        const ms_clip_plane *cp = &si->clip[i];
        float *eq = it + 4 * (ORC_ITEM_PLANES + i), *col = it + 4 * (ORC_ITEM_COLORS + i);
        memcpy(eq, cp->eq, 4 * sizeof(float));
        memcpy(col, cp->color, 3 * sizeof(float));
        col[3] = cp->solid ? 1.0f : 0.0f;
    }
    return n;
}

/* A list's item (normal matrix, clip planes; -1 when its transform is singular) and its
 * primitives. */
static void place_source(orc_world *w, const source *s)
{
    placer pl;
    memset(&pl, 0, sizeof pl);
    pl.w = w, pl.item = (uint32_t)w->nitems;
    if (rt_xform_make(&pl.ri, s->xform)) return;
    float *it = w->item + 4 * ORC_ITEM * w->nitems++;
    for (int r = 0; r < 3; r++)
        for (int c = 0; c < 3; c++) it[4 * r + c] = pl.ri.nm[3 * r + c];
    it[3] = pl.ri.sign;
    pl.nclip = put_clips(it, s->item);
    w->nclipped += pl.nclip > 0;
    place_spheres(&pl, s);
    place_cylinders(&pl, s);
    place_cones(&pl, s);
    place_discs(&pl, s);
    place_mesh(&pl, s);
}

int orc_world_build(orc_world *w, const ms_scene *s, ms_error *err)
{
    memset(w, 0, sizeof *w);
    size_t nq = 0, ntri = 0, nv = 0;
    if (rt_sources_make(&w->set, s, err)) return -1;
    const source *src = w->set.src;
    size_t nsrc = w->set.n;
    for (size_t i = 0; i < nsrc; i++) {
        const ms_displaylist *dl = src[i].dl;
        if (check_mesh(&dl->mesh, err)) {
            orc_world_free(w);
            return MS_OCLRT_EINPUT;
        }
        nq += dl->spheres.n + dl->cylinders.n + dl->cones.n + src[i].discs.n;
        ntri += dl->mesh.ntris, nv += dl->mesh.nverts;
    }
    if (nq > ORC_INDEX_MASK || ntri > ORC_INDEX_MASK || nv > 0xffffffffu) {
        ms_error_set(err, "more than 2^29 primitives of one kind");
        orc_world_free(w);
        return MS_OCLRT_EINPUT;
    }
    w->nq = nq, w->ntri = ntri, w->nverts = nv;
    if (alloc_arrays(w, nsrc, err)) goto fail;
    w->nq = w->ntri = w->nverts = 0;
    for (size_t i = 0; i < nsrc; i++) place_source(w, &src[i]);
    w->eps = rt_world_eps(s);
    return 0;
fail:
    orc_world_free(w);
    return -1;
}

void orc_world_free(orc_world *w)
{
    void *all[] = {w->qa, w->qb, w->qm, w->qkind, w->tri, w->vxyz, w->vnorm, w->vcol, w->gmat0,
                   w->gmat1, w->gflag, w->item, w->lo0, w->hi0, w->lo1, w->hi1, w->child, w->leaf};
    for (size_t i = 0; i < sizeof all / sizeof *all; i++) free(all[i]);
    rt_sources_free(&w->set);
    memset(w, 0, sizeof *w);
}
