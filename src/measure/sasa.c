/* sasa.c: solvent-accessible surface area by the Shrake-Rupley method. Every atom's sphere
 * (radius + probe) carries the same golden-spiral point set, which spreads points evenly
 * and deterministically; a point is buried when it lies inside another sphere of the set.
 * Neighbours come from a cell grid; the atoms are processed in parallel, and each keeps the
 * last sphere that buried a point, since the next point is usually buried by it too. */
#include "config.h"
#include "measure/internal.h"
#include "base/threads.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

void ms_sphere_point(size_t k, size_t n, double p[3])
{
    double z = 1.0 - (2.0 * (double)k + 1.0) / (double)n;
    double r = sqrt(fmax(0.0, 1.0 - z * z));
    double phi = (double)k * M_PI * (3.0 - sqrt(5.0));   /* the golden angle */
    p[0] = r * cos(phi);
    p[1] = r * sin(phi);
    p[2] = z;
}

typedef struct sasa_ctx {
    const ms_atomset *s;
    const float *pos;
    double srad;
    size_t npts;
    double *sphere;          /* npts unit vectors */
    ms_grid grid;        /* over the set */
    uint8_t *contributes;    /* per set position */
    uint32_t *exposed;       /* per set position */
    size_t *first_point;     /* per set position, for writing points (pass 2) */
    float *points;
    atomic_int failed;       /* a thread ran out of memory */
} sasa_ctx;

typedef struct nbr {
    double x, y, z, r2;
} nbr;

typedef struct nbr_list {
    nbr *items;
    size_t n, cap;
} nbr_list;

static double sphere_radius(const sasa_ctx *c, uint32_t atom)
{
    return c->s->mol->atoms.radius[atom] + c->srad;
}

/* The spheres that can bury part of atom i's sphere (radius ri). */
static int gather(sasa_ctx *c, uint32_t i, double ri, nbr_list *l)
{
    ms_grid_run runs[9];
    const float *p = c->pos + 3 * (size_t)i;
    int nr = ms_grid_near(&c->grid, p, runs);
    l->n = 0;
    for (int ci = 0; ci < nr; ci++)
        for (uint32_t q = runs[ci].begin; q < runs[ci].end; q++) {
            uint32_t j = c->grid.items[q];
            const float *pj = c->pos + 3 * (size_t)j;
            double d2 = ms_dist2f(p, pj), rj = sphere_radius(c, j);
            /* As VMD: an atom at (nearly) the same place is not a neighbour. */
            if (j == i || d2 < 0.001 || d2 > (ri + rj) * (ri + rj)) continue;
            if (ms_grow((void **)&l->items, &l->cap, l->n + 1, sizeof *l->items)) return -1;
            l->items[l->n++] = (nbr){pj[0], pj[1], pj[2], rj * rj};
        }
    return 0;
}

/* Is point (x, y, z) inside a neighbour? *last is the index of the last burying one. */
static int buried(const nbr_list *l, double x, double y, double z, size_t *last)
{
    for (size_t t = 0; t < l->n; t++) {
        size_t k = (*last + t) % l->n;
        const nbr *b = &l->items[k];
        double dx = x - b->x, dy = y - b->y, dz = z - b->z;
        if (dx * dx + dy * dy + dz * dz <= b->r2) {
            *last = k;
            return 1;
        }
    }
    return 0;
}

/* Count (pass 1) or write (pass 2) the exposed points of set position k. */
static void atom_points(sasa_ctx *c, size_t k, const nbr_list *l, int write)
{
    uint32_t i = c->s->atoms[k];
    const float *p = c->pos + 3 * (size_t)i;
    double r = sphere_radius(c, i);
    size_t last = 0, count = 0;
    float *out = write ? c->points + 3 * c->first_point[k] : NULL;
    for (size_t t = 0; t < c->npts; t++) {
        const double *u = c->sphere + 3 * t;
        double x = p[0] + r * u[0], y = p[1] + r * u[1], z = p[2] + r * u[2];
        if (buried(l, x, y, z, &last)) continue;
        if (out) {
            out[3 * count] = (float)x;
            out[3 * count + 1] = (float)y;
            out[3 * count + 2] = (float)z;
        }
        count++;
    }
    c->exposed[k] = (uint32_t)count;
}

static void sasa_range(sasa_ctx *c, size_t begin, size_t end, int write)
{
    nbr_list l = {0};
    for (size_t k = begin; k < end && !atomic_load(&c->failed); k++) {
        if (!c->contributes[k]) {
            c->exposed[k] = 0;
            continue;
        }
        uint32_t i = c->s->atoms[k];
        if (gather(c, i, sphere_radius(c, i), &l)) {
            atomic_store(&c->failed, 1);
            break;
        }
        atom_points(c, k, &l, write);
    }
    free(l.items);
}

static void count_range(void *v, size_t b, size_t e, int thread) { sasa_range(v, b, e, 0); }
static void write_range(void *v, size_t b, size_t e, int thread) { sasa_range(v, b, e, 1); }

/* Which set positions contribute: all, or those also in the (ascending) restriction. */
static int mark_contributors(sasa_ctx *c, const ms_sasa_opts *o)
{
    const ms_atomset *s = c->s;
    if (!(c->contributes = ms_alloc_array(s->n, 1))) return -1;
    memset(c->contributes, o->restrict_to ? 0 : 1, s->n);
    for (size_t k = 0, r = 0; o->restrict_to && k < s->n; k++) {
        while (r < o->nrestrict && o->restrict_to[r] < s->atoms[k]) r++;
        c->contributes[k] = r < o->nrestrict && o->restrict_to[r] == s->atoms[k];
    }
    return 0;
}

static int sasa_setup(sasa_ctx *c, const ms_sasa_opts *o, ms_error *err)
{
    const ms_atomset *s = c->s;
    double maxr = 0.0;
    c->sphere = ms_alloc_array(c->npts, 3 * sizeof *c->sphere);
    c->exposed = ms_calloc_array(s->n, sizeof *c->exposed);
    if (!c->sphere || !c->exposed || mark_contributors(c, o)) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (size_t k = 0; k < c->npts; k++) ms_sphere_point(k, c->npts, c->sphere + 3 * k);
    for (size_t k = 0; k < s->n; k++) maxr = fmax(maxr, sphere_radius(c, s->atoms[k]));
    return ms_measure_grid(&c->grid, c->pos, s->atoms, s->n, 2.0 * maxr, err);
}

/* Lay the exposed points out in atom order and write them. */
static int collect_points(sasa_ctx *c, float **points, size_t *npoints, ms_error *err)
{
    size_t n = c->s->n, total = 0;
    if (!(c->first_point = ms_alloc_array(n, sizeof *c->first_point))) goto oom;
    for (size_t k = 0; k < n; k++) c->first_point[k] = total, total += c->exposed[k];
    if (!(c->points = ms_alloc_array(total, 3 * sizeof *c->points))) goto oom;
    ms_parallel_for(n, 64, write_range, c);
    if (atomic_load(&c->failed)) goto oom;
    *points = c->points;
    *npoints = total;
    c->points = NULL;
    return 0;
oom:
    ms_error_set(err, "out of memory for the surface points");
    return -1;
}

static void sasa_free(sasa_ctx *c)
{
    free(c->sphere);
    free(c->contributes);
    free(c->exposed);
    free(c->first_point);
    free(c->points);
    ms_grid_free(&c->grid);
}

int ms_measure_sasa(const ms_atomset *s, const ms_sasa_opts *o, double *area, float **points,
                    size_t *npoints, ms_error *err)
{
    *area = 0.0;
    if (points) *points = NULL;
    if (npoints) *npoints = 0;
    if (ms_atomset_check(s, err)) return -1;
    if (o->samples < 1 || o->samples > 10000000 || !isfinite(o->srad)) {
        ms_error_set(err, "need 1 to 10000000 samples and a finite probe radius");
        return -1;
    }
    sasa_ctx c = {.s = s, .pos = ms_atomset_pos(s), .srad = o->srad, .npts = (size_t)o->samples};
    atomic_init(&c.failed, 0);
    int rc = sasa_setup(&c, o, err);
    if (!rc) {
        ms_parallel_for(s->n, 64, count_range, &c);
        if (atomic_load(&c.failed)) {
            ms_error_set(err, "out of memory for the surface neighbours");
            rc = -1;
        }
    }
    for (size_t k = 0; !rc && k < s->n; k++) {
        double r = sphere_radius(&c, s->atoms[k]);
        *area += 4.0 * M_PI * r * r * (double)c.exposed[k] / (double)c.npts;
    }
    if (!rc && o->want_points && points && npoints) rc = collect_points(&c, points, npoints, err);
    sasa_free(&c);
    return rc;
}
