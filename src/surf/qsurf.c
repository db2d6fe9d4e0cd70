/* qsurf.c: the QuickSurf driver: parameters, VMD's grid rules, and the slab loop that
 * plans memory, builds the acceleration grid, and turns each slab into mesh: on the OpenCL
 * device from density to triangles, or on the CPU (density, then marching cubes), the
 * CPU taking over from the device on any device error. Also the public density-only and
 * marching-cubes-only entry points. */
#include "config.h"
#include "surf/qsurf_impl.h"
#include "base/threads.h"

#include <stdatomic.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

void ms_qsurf_params_default(ms_qsurf_params *p)
{
    memset(p, 0, sizeof *p);
    p->radscale = 1.0f;
    p->isovalue = 0.5f;
    p->gridspacing = 1.0f;
    p->quality = 0;
    p->backend = MS_QSURF_AUTO;
}

static float gausslim_of(int quality)
{
    switch (quality) {
    case 1: return 2.5f;
    case 2: return 3.0f;
    case 3: return 4.0f;
    default: return 2.0f;
    }
}

static void range_over(const float *radius, size_t n, const uint32_t *sel, float *lo, float *hi)
{
    *lo = INFINITY, *hi = 0.0f;
    for (size_t k = 0; k < n; k++) {
        float r = radius[sel ? sel[k] : k];
        if (!isfinite(r)) continue;
        *lo = MS_MIN(*lo, r), *hi = MS_MAX(*hi, r);
    }
    if (*lo > *hi) *lo = *hi = 0.0f;
}

void ms_qsurf_radius_range(const float *radius, size_t natoms, const uint32_t *sel,
                           size_t nsel, float *minrad, float *maxrad)
{
    range_over(radius, natoms, NULL, minrad, maxrad);
    if (*minrad <= 0.001f || *maxrad / *minrad > 2.5f)
        range_over(radius, sel ? nsel : natoms, sel, minrad, maxrad);
}

/* ---------------------------------------------------------------- grid */

typedef struct bounds {
    float lo[3], hi[3], rmin, rmax;
    size_t n;
} bounds;

typedef struct bounds_job {
    const ms_qsurf_atoms *a;
    bounds *part;            /* one per thread */
} bounds_job;

static void bounds_range(void *ctx, size_t begin, size_t end, int thread)
{
    bounds_job *j = ctx;
    bounds *b = j->part + thread;
    for (size_t k = begin; k < end; k++) {
        size_t i = ms_qsurf_atom_index(j->a, k);
        const float *p = j->a->pos + 3 * i;
        float r = j->a->radius[i];
        if (!ms_qsurf_atom_ok(p, r)) continue;
        for (int d = 0; d < 3; d++)
            b->lo[d] = MS_MIN(b->lo[d], p[d]), b->hi[d] = MS_MAX(b->hi[d], p[d]);
        b->rmin = MS_MIN(b->rmin, r), b->rmax = MS_MAX(b->rmax, r);
        b->n++;
    }
}

static int atom_bounds(const ms_qsurf_atoms *a, bounds *out)
{
    int nt = ms_threads_count();
    bounds *part = ms_alloc_array((size_t)nt, sizeof *part);
    if (!part) return -1;
    for (int t = 0; t <= nt; t++) {
        bounds *b = t < nt ? part + t : out;
        for (int d = 0; d < 3; d++) b->lo[d] = INFINITY, b->hi[d] = -INFINITY;
        b->rmin = INFINITY, b->rmax = 0.0f, b->n = 0;
    }
    bounds_job j = {.a = a, .part = part};
    ms_parallel_for(a->n, 65536, bounds_range, &j);
    for (int t = 0; t < nt; t++) {
        for (int d = 0; d < 3; d++) {
            out->lo[d] = MS_MIN(out->lo[d], part[t].lo[d]);
            out->hi[d] = MS_MAX(out->hi[d], part[t].hi[d]);
        }
        out->rmin = MS_MIN(out->rmin, part[t].rmin), out->rmax = MS_MAX(out->rmax, part[t].rmax);
        out->n += part[t].n;
    }
    free(part);
    return 0;
}

static int check_params(const ms_qsurf_params *p, ms_error *err)
{
    if (!(p->radscale > 0.0f && isfinite(p->radscale))) {
        ms_error_set(err, "radius scale must be positive (%g)", p->radscale);
        return -1;
    }
    if (!(p->isovalue > 0.0f && isfinite(p->isovalue))) {
        ms_error_set(err, "isovalue must be positive (%g)", p->isovalue);
        return -1;
    }
    if (!(p->gridspacing > 0.0f && isfinite(p->gridspacing))) {
        ms_error_set(err, "grid spacing must be positive (%g)", p->gridspacing);
        return -1;
    }
    return 0;
}

/* Lay the grid over the atoms' box: padding, origin, points per axis. */
static int grid_axes(ms_qsurf_grid *g, const bounds *b, ms_error *err)
{
    float pr = 1.7f * g->radscale * g->maxrad;
    g->pad = MS_MAX(pr, 0.65f * sqrtf(4.0f / 3.0f * (float)M_PI * pr * pr * pr));
    double voxels = 1.0;
    for (int d = 0; d < 3; d++) {
        g->origin[d] = b->lo[d] - g->pad;
        double n = ceil(((double)b->hi[d] - b->lo[d] + 2.0 * g->pad) / g->h);
        if (!(n < (double)(1 << 24))) {
            ms_error_set(err, "the grid would have %g points along %c", n, "xyz"[d]);
            return -1;
        }
        g->n[d] = n < 1.0 ? 1 : (int)n;
        voxels *= g->n[d];
    }
    if (voxels > 1e12) {
        ms_error_set(err, "the grid would have %g points", voxels);
        return -1;
    }
    return 0;
}

int ms_qsurf_grid_setup(const ms_qsurf_atoms *a, const ms_qsurf_params *p, ms_qsurf_grid *g,
                        ms_error *err)
{
    bounds b;
    memset(g, 0, sizeof *g);
    if (check_params(p, err) < 0) return -1;
    if (atom_bounds(a, &b) < 0) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    if (b.n == 0) {
        ms_error_set(err, "no atoms with coordinates and a positive radius");
        return -1;
    }
    g->natoms = b.n;
    g->radscale = p->radscale, g->isovalue = p->isovalue, g->gausslim = gausslim_of(p->quality);
    g->minrad = a->minrad > 0.0f ? a->minrad : b.rmin;
    g->maxrad = MS_MAX(a->maxrad > 0.0f ? a->maxrad : b.rmax, b.rmax);
    g->h = p->gridspacing;
    if (g->minrad > 4.0f) g->h *= g->minrad;   /* coarse-grained models */
    return grid_axes(g, &b, err);
}

/* ---------------------------------------------------------------- fallback notices */

static atomic_int noticed;

/* Record why OpenCL is not used; say it once per process when `loud`. */
static void fallback(const ms_qsurf_params *p, ms_qsurf_stats *st, const char *why, int loud)
{
    snprintf(st->note, sizeof st->note, "QuickSurf: OpenCL not used: %s; computing on the CPU",
             why);
    if (!loud || atomic_exchange(&noticed, 1)) return;
    if (p->notice) p->notice(p->notice_ctx, st->note);
    else fprintf(stderr, "%s\n", st->note);
}

/* ---------------------------------------------------------------- the surface */

typedef struct run {
    const ms_qsurf_atoms *a;
    const ms_qsurf_params *p;
    ms_qsurf_stats *st;
    const ms_qsurf_grid *g;
    int colored;
    ms_qsurf_plan plan;
    ms_qsurf_cl *cl;
    ms_qsurf_atomgrid ag;
    ms_qsurf_slab slab;
    ms_qsurf_extract mc;
} run;

static void drop_device(run *r, const char *why)
{
    fallback(r->p, r->st, why, 1);
    ms_qsurf_cl_release(r->cl);
    r->cl = NULL;
}

/* The OpenCL engine when asked for and present. Its absence is said only when OpenCL was
 * asked for by name; an error of a present device is always said (once). */
static void open_device(run *r)
{
    if (r->p->backend == MS_QSURF_CPU) return;
    int absent = 0;
    ms_error e = {{0}};
    if (ms_env_flag("MOLSCOPE_NOOPENCL")) {
        fallback(r->p, r->st, "MOLSCOPE_NOOPENCL is set", r->p->backend == MS_QSURF_OPENCL);
        return;
    }
    r->cl = ms_qsurf_cl_acquire(r->p->backend == MS_QSURF_OPENCL, &absent, &e);
    if (!r->cl) fallback(r->p, r->st, e.msg, !absent || r->p->backend == MS_QSURF_OPENCL);
}

/* Slabs for the host budget, then smaller if the device needs it. */
static int plan(run *r, ms_error *err)
{
    r->st->budget = ms_qsurf_budget(r->p);
    if (ms_qsurf_plan_slabs(r->g, r->colored, r->st->budget, 0, &r->plan, err) < 0) return -1;
    if (!r->cl) return 0;
    ms_error e = {{0}};
    int maxl = ms_qsurf_cl_max_layers(r->cl, r->g, r->colored);
    if (maxl > 0 && ms_qsurf_plan_slabs(r->g, r->colored, r->st->budget, maxl, &r->plan, &e) == 0)
        return 0;
    drop_device(r, "the device memory cannot hold a slab of 8 planes");
    return ms_qsurf_plan_slabs(r->g, r->colored, r->st->budget, 0, &r->plan, err);
}

static int prepare(run *r, ms_error *err)
{
    const ms_qsurf_grid *g = r->g;
    int planes = MS_MIN(r->plan.layers + 3, g->n[2]);
    float axis[3][3] = {{g->h, 0, 0}, {0, g->h, 0}, {0, 0, g->h}};
    if (ms_qsurf_atomgrid_build(r->a, g, &r->ag, err) < 0) return -1;
    if (ms_qsurf_slab_alloc(&r->slab, g->n[0], g->n[1], planes, r->colored) < 0) {
        ms_error_set(err, "out of memory for a slab of %d planes of %d x %d voxels", planes,
                     g->n[0], g->n[1]);
        return -1;
    }
    ms_error e = {{0}};
    if (r->cl && ms_qsurf_cl_upload(r->cl, &r->ag, g->n[0], g->n[1], r->plan.layers, &e) < 0)
        drop_device(r, e.msg);
    if (ms_qsurf_extract_begin(&r->mc, g->n, g->origin, axis, g->isovalue, r->colored,
                               r->a->solid, r->plan.layers, r->mc.mesh, err) < 0)
        return -1;
    /* the mesh grows within what the planned slabs leave of the budget */
    r->mc.budget = r->st->budget;
    r->mc.mesh_room = r->st->budget > r->plan.bytes ? r->st->budget - r->plan.bytes : 0;
    return 0;
}

/* Move the planes the next slab [z0, z1) shares with the current one to the start of the
 * buffers; the next slab computes only the planes after them. Both slabs then see the very
 * same density on their shared plane. */
static void next_slab(ms_qsurf_slab *s, int z0, int z1, int nz)
{
    int zb = MS_MAX(z0 - 1, 0), kept = z0 > 0 ? s->ze - zb + 1 : 0;
    size_t plane = (size_t)s->nx * s->ny;
    if (kept > 0) {
        size_t from = (size_t)(zb - s->zb) * plane, n = (size_t)kept * plane;
        memmove(s->dens, s->dens + from, n * sizeof(float));
        for (int k = 0; s->rgb[0] && k < 3; k++)
            memmove(s->rgb[k], s->rgb[k] + from, n * sizeof(float));
    }
    s->zb = zb, s->ze = MS_MIN(z1 + 1, nz - 1), s->cz = zb + kept;
}

/* Slab [z0, z1) on the OpenCL device: 1 when done there. When the device fails it is
 * dropped and the host takes the slab over (0): all of its density, since the planes
 * shared with the slab before were on the device. A mesh past the memory budget fails the
 * surface (-1, err set): the host could not hold it either. */
static int device_slab(run *r, int z0, int z1, ms_error *err)
{
    ms_error e = {{0}};
    double t[2];
    if (ms_qsurf_cl_slab(r->cl, &r->ag, &r->slab, &r->mc, z0, z1, t, &e) == 0) {
        r->st->opencl++;
        r->st->t_density += t[0], r->st->t_mc += t[1];
        return 1;
    }
    if (r->mc.over_budget) {
        ms_error_set(err, "%s", e.msg);
        return -1;
    }
    drop_device(r, e.msg);
    r->slab.cz = r->slab.zb;
    return 0;
}

static int slabs(run *r, ms_error *err)
{
    int nz = r->g->n[2];
    for (int z0 = 0, z1; z0 < nz - 1; z0 = z1) {
        z1 = MS_MIN(z0 + r->plan.layers, nz - 1);
        next_slab(&r->slab, z0, z1, nz);
        r->st->nslabs++;
        int on_device = r->cl != NULL, done = on_device ? device_slab(r, z0, z1, err) : 0;
        if (done < 0) return -1;
        if (done) continue;
        double t = ms_now();
        if (r->slab.cz <= r->slab.ze) ms_qsurf_density_cpu(&r->ag, &r->slab);
        double t2 = ms_now();
        r->st->t_density += t2 - t;
        /* Marching cubes resumed where the device left the mesh. */
        if (on_device && z0 > 0 && ms_qsurf_extract_resume(&r->mc, &r->slab, z0, err) < 0)
            return -1;
        if (ms_qsurf_extract_slab(&r->mc, &r->slab, z0, z1, err) < 0) return -1;
        r->st->t_mc += ms_now() - t2;
    }
    return 0;
}

int ms_qsurf_surface(const ms_qsurf_atoms *a, const ms_qsurf_params *p, ms_qsurf_mesh *out,
                     ms_qsurf_stats *stats, ms_error *err)
{
    ms_qsurf_stats local;
    ms_qsurf_stats *st = stats ? stats : &local;
    memset(st, 0, sizeof *st);
    ms_qsurf_mesh_free(out);
    double t0 = ms_now();
    if (ms_qsurf_grid_setup(a, p, &st->grid, err) < 0) return -1;
    run r = {.a = a, .p = p, .st = st, .g = &st->grid, .colored = a->rgb != NULL};
    r.mc.mesh = out;
    st->kernel = ms_qsurf_kernel_name(ms_qsurf_cpu_kernel());
    open_device(&r);
    int rc = plan(&r, err);
    if (rc == 0) rc = prepare(&r, err);
    st->t_setup = ms_now() - t0;
    if (rc == 0) rc = slabs(&r, err);
    ms_qsurf_extract_end(&r.mc);
    ms_qsurf_slab_free(&r.slab);
    ms_qsurf_atomgrid_free(&r.ag);
    if (r.cl) ms_qsurf_cl_release(r.cl);
    st->slab_layers = r.plan.layers;
    st->plan_bytes = r.plan.bytes;
    if (rc < 0) ms_qsurf_mesh_free(out);
    return rc;
}

/* ---------------------------------------------------------------- the parts */

int ms_qsurf_density(const ms_qsurf_atoms *a, const ms_qsurf_params *p, ms_qsurf_volume *v,
                     ms_error *err)
{
    ms_qsurf_grid g;
    ms_qsurf_atomgrid ag;
    ms_qsurf_slab s;
    memset(v, 0, sizeof *v);
    if (ms_qsurf_grid_setup(a, p, &g, err) < 0) return -1;
    if (ms_qsurf_atomgrid_build(a, &g, &ag, err) < 0) return -1;
    if (ms_qsurf_slab_alloc(&s, g.n[0], g.n[1], g.n[2], a->rgb != NULL) < 0) {
        ms_qsurf_atomgrid_free(&ag);
        ms_error_set(err, "out of memory for a %d x %d x %d map", g.n[0], g.n[1], g.n[2]);
        return -1;
    }
    s.zb = s.cz = 0, s.ze = g.n[2] - 1;
    ms_qsurf_density_cpu(&ag, &s);
    ms_qsurf_atomgrid_free(&ag);
    for (int d = 0; d < 3; d++) {
        v->n[d] = g.n[d];
        v->origin[d] = g.origin[d];
        v->axis[d][d] = g.h;
        v->rgb[d] = s.rgb[d];
        v->solid[d] = a->solid[d];
    }
    v->data = s.dens;
    return 0;
}

void ms_qsurf_volume_free(ms_qsurf_volume *v)
{
    free(v->data);
    for (int k = 0; k < 3; k++) free(v->rgb[k]);
    v->data = NULL;
    v->rgb[0] = v->rgb[1] = v->rgb[2] = NULL;
}

int ms_qsurf_mc(const ms_qsurf_volume *v, float iso, ms_qsurf_mesh *out, ms_error *err)
{
    ms_qsurf_mesh_free(out);
    if (!v->data || v->n[0] < 1 || v->n[1] < 1 || v->n[2] < 1 || !isfinite(iso)) {
        ms_error_set(err, "marching cubes: empty volume or bad isovalue");
        return -1;
    }
    if (v->n[2] < 2) return 0;
    ms_qsurf_extract mc;
    ms_qsurf_slab s = {.nx = v->n[0], .ny = v->n[1], .zb = 0, .ze = v->n[2] - 1, .cz = 0,
                       .dens = v->data, .rgb = {v->rgb[0], v->rgb[1], v->rgb[2]}};
    int colored = v->rgb[0] && v->rgb[1] && v->rgb[2];
    if (ms_qsurf_extract_begin(&mc, v->n, v->origin, v->axis, iso, colored, v->solid,
                               v->n[2] - 1, out, err) < 0)
        return -1;
    int rc = ms_qsurf_extract_slab(&mc, &s, 0, v->n[2] - 1, err);
    ms_qsurf_extract_end(&mc);
    if (rc < 0) ms_qsurf_mesh_free(out);
    return rc;
}
