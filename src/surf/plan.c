/* plan.c: the memory planner. The budget bounds a surface's whole working set, mesh
 * included. Before anything is allocated, the slabs' part is sized: the atom table and
 * cell grid, the slab buffers (density and colour texture with the planes around the
 * slab), and the extractor's per-point scratch; it may take half the budget, the mesh
 * (whose size is known only as it grows) the rest. The slab is the whole volume when it
 * fits, else the largest multiple of 8 cell layers that does; when not even 8 fit, the
 * surface fails with a message saying what it needed. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/sysinfo.h>

size_t ms_qsurf_parse_bytes(const char *s)
{
    char *end;
    if (!s || !isdigit((unsigned char)*s)) return 0;
    double v = strtod(s, &end);
    double mult = 1.0;
    switch (toupper((unsigned char)*end)) {
    case 'K': mult = 1024.0; end++; break;
    case 'M': mult = 1024.0 * 1024.0; end++; break;
    case 'G': mult = 1024.0 * 1024.0 * 1024.0; end++; break;
    default: break;
    }
    if (toupper((unsigned char)*end) == 'B') end++;
    if (*end || !(v > 0.0) || v * mult >= 1.8e19) return 0;
    return (size_t)(v * mult);
}

/* MemAvailable from /proc/meminfo, else free RAM from sysinfo. */
static size_t available_memory(void)
{
    size_t avail = ms_mem_available();
    if (avail) return avail;
    struct sysinfo si;
    if (sysinfo(&si) == 0) return (size_t)si.freeram * si.mem_unit;
    return (size_t)1 << 30;
}

size_t ms_qsurf_budget(const ms_qsurf_params *p)
{
    if (p && p->memlimit) return p->memlimit;
    size_t env = ms_qsurf_parse_bytes(getenv("MOLSCOPE_QUICKSURF_MEMLIMIT"));
    if (env) return env;
    return available_memory();
}

size_t ms_qsurf_slab_bytes(int nx, int ny, int planes, int colored)
{
    return (size_t)nx * (size_t)ny * (size_t)planes * sizeof(float) * (colored ? 4 : 1);
}

/* Planes a slab of `layers` layers holds: one more than its layers, and one on each side
 * for the gradients. */
static int slab_planes(const ms_qsurf_grid *g, int layers)
{
    return MS_MIN(layers + 3, g->n[2]);
}

size_t ms_qsurf_plan_bytes(const ms_qsurf_grid *g, int colored, int layers)
{
    return ms_qsurf_atomgrid_bytes(g, colored) +
           ms_qsurf_slab_bytes(g->n[0], g->n[1], slab_planes(g, layers), colored) +
           ms_qsurf_extract_bytes(g->n[0], g->n[1], layers);
}

/* Slabs are kept near this working set even when memory allows more: a slab's density is
 * then still in cache when marching cubes reads it, and its pages are reused slab after
 * slab instead of faulted in once for the whole volume. */
#define SLAB_TARGET ((size_t)192 << 20)

static int plan_within(const ms_qsurf_grid *g, int colored, size_t budget, int maxlayers,
                       ms_qsurf_plan *pl, ms_error *err);

int ms_qsurf_plan_slabs(const ms_qsurf_grid *g, int colored, size_t whole, int maxlayers,
                        ms_qsurf_plan *pl, ms_error *err)
{
    size_t budget = whole / 2;      /* the other half is the mesh's */
    size_t preferred = ms_qsurf_atomgrid_bytes(g, colored) + SLAB_TARGET;
    if (preferred < budget) {
        if (plan_within(g, colored, preferred, maxlayers, pl, NULL) == 0) return 0;
        /* Planes too large for the target: the smallest slab, if the budget holds it. */
        int smallest = maxlayers > 0 ? MS_MIN(maxlayers, 8) : 8;
        if (plan_within(g, colored, budget, smallest, pl, NULL) == 0) return 0;
    }
    return plan_within(g, colored, budget, maxlayers, pl, err);
}

static int plan_within(const ms_qsurf_grid *g, int colored, size_t budget, int maxlayers,
                       ms_qsurf_plan *pl, ms_error *err)
{
    int total = MS_MAX(g->n[2] - 1, 1), limit = total, layers = 0;
    if (maxlayers > 0 && maxlayers < total) limit = maxlayers;
    if (limit == total && ms_qsurf_plan_bytes(g, colored, total) <= budget) {
        layers = total;
    } else {
        /* The largest multiple of 8 that fits: bytes grow with the layers. */
        int lo = 0, hi = limit / 8;
        while (lo < hi) {
            int mid = (lo + hi + 1) / 2;
            if (ms_qsurf_plan_bytes(g, colored, 8 * mid) <= budget) lo = mid;
            else hi = mid - 1;
        }
        layers = 8 * lo;
    }
    if (layers == 0) {
        int want = MS_MIN(8, total);
        size_t need = ms_qsurf_plan_bytes(g, colored, want);
        /* a slab's planes shrink with the square of the spacing */
        double fit = g->h * sqrt((double)need / (double)MS_MAX(budget, 1)) * 1.05;
        ms_error_set(err, "a slab of %d layers of %d x %d voxels needs %zu bytes, more than "
                     "half the memory budget of %zu bytes (MOLSCOPE_QUICKSURF_MEMLIMIT or the "
                     "memory available; the other half is kept for the mesh): a grid spacing "
                     "of about %.2g A instead of %.2g A would fit", want, g->n[0], g->n[1],
                     need, 2 * budget, fit, g->h);
        return -1;
    }
    pl->layers = layers;
    pl->nslabs = (total + layers - 1) / layers;
    pl->bytes = ms_qsurf_plan_bytes(g, colored, layers);
    return 0;
}

int ms_qsurf_slab_alloc(ms_qsurf_slab *s, int nx, int ny, int planes, int colored)
{
    memset(s, 0, sizeof *s);
    size_t n = (size_t)nx * (size_t)ny * (size_t)planes;
    s->nx = nx, s->ny = ny;
    s->dens = ms_alloc_array(n, sizeof(float));
    ms_advise_huge(s->dens, n * sizeof(float));
    for (int k = 0; colored && k < 3; k++) {
        s->rgb[k] = ms_alloc_array(n, sizeof(float));
        ms_advise_huge(s->rgb[k], n * sizeof(float));
    }
    if (!s->dens || (colored && (!s->rgb[0] || !s->rgb[1] || !s->rgb[2]))) {
        ms_qsurf_slab_free(s);
        return -1;
    }
    return 0;
}

void ms_qsurf_slab_free(ms_qsurf_slab *s)
{
    free(s->dens);
    for (int k = 0; k < 3; k++) free(s->rgb[k]);
    memset(s, 0, sizeof *s);
}
