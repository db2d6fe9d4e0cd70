/* bench_system.c: the benchmarks' replicated 1tii and its VDW and Licorice lists (see
 * bench_system.h). */
#include "config.h"
#include "bench_system.h"
#include "base/threads.h"
#include "fileio/load.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#include "builtin/builtin.h"

static void place_copies(const ms_molecule *m, int copies, bench_sys *s)
{
    size_t n0 = m->atoms.n, nb0 = m->bonds.start[n0];
    const float *p0 = ms_mol_pos(m);
    int side = 1;
    while (side * side * side < copies) side++;
    for (int c = 0; c < copies; c++) {
        float off[3] = {(float)(c % side) * 120.0f, (float)(c / side % side) * 120.0f,
                        (float)(c / side / side) * 180.0f};
        for (size_t i = 0; i < n0; i++) {
            size_t a = (size_t)c * n0 + i;
            for (int k = 0; k < 3; k++) s->pos[3 * a + k] = p0[3 * i + k] + off[k];
            s->radius[a] = m->atoms.radius[i];
            int z = m->atoms.atomicnumber[i];
            s->color[a] = z == 6 ? (ms_rgba8){64, 191, 191, 255} : z == 8 ? (ms_rgba8){255, 0, 0, 255}
                          : z == 7 ? (ms_rgba8){0, 0, 255, 255} : (ms_rgba8){255, 255, 0, 255};
            s->bstart[a] = (uint32_t)((size_t)c * nb0 + m->bonds.start[i]);
        }
        for (size_t b = 0; b < nb0; b++) s->bto[(size_t)c * nb0 + b] = m->bonds.to[b] + (uint32_t)((size_t)c * n0);
    }
    s->bstart[s->n] = (uint32_t)(nb0 * (size_t)copies);
}

static void bounds(bench_sys *s)
{
    for (int k = 0; k < 3; k++) s->lo[k] = s->hi[k] = s->pos[k];
    for (size_t i = 0; i < s->n; i++)
        for (int k = 0; k < 3; k++) {
            float v = s->pos[3 * i + k];
            if (v < s->lo[k]) s->lo[k] = v;
            if (v > s->hi[k]) s->hi[k] = v;
        }
}

int bench_system_make(const char *data, int copies, bench_sys *s)
{
    memset(s, 0, sizeof *s);
    ms_registry reg;
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    char path[1024];
    snprintf(path, sizeof path, "%s/1tii.pdb", data);
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    ms_error err = {{0}};
    ms_molecule *m = ms_load_new(&reg, path, &o, &err);
    ms_registry_free(&reg);
    if (!m) {
        fprintf(stderr, "bench: %s: %s\n", path, err.msg);
        return -1;
    }
    size_t n0 = m->atoms.n, nb0 = m->bonds.start[n0];
    s->n0 = n0;
    s->n = n0 * (size_t)copies;
    s->pos = malloc(3 * s->n * sizeof(float));
    s->radius = malloc(s->n * sizeof(float));
    s->color = malloc(s->n * sizeof(ms_rgba8));
    s->bstart = malloc((s->n + 1) * sizeof(uint32_t));
    s->bto = malloc(nb0 * (size_t)copies * sizeof(uint32_t));
    if (!s->pos || !s->radius || !s->color || !s->bstart || !s->bto) {
        fprintf(stderr, "bench: out of memory\n");
        ms_mol_free(m);
        return -1;
    }
    place_copies(m, copies, s);
    bounds(s);
    ms_mol_free(m);
    return 0;
}

void bench_system_free(bench_sys *s)
{
    free(s->pos);
    free(s->radius);
    free(s->color);
    free(s->bstart);
    free(s->bto);
    memset(s, 0, sizeof *s);
}

/* ---------------------------------------------------------------- lists */

typedef struct job {
    const bench_sys *s;
    ms_displaylist *dl;
    size_t s0, c0;            /* first sphere and cylinder of the block */
    const uint32_t *first;    /* Licorice: first bond cylinder of each atom */
} job;

static void fill_spheres(void *ctx, size_t b, size_t e, int t)
{
    job *j = ctx;
    ms_dl_spheres *sp = &j->dl->spheres;
    for (size_t i = b; i < e; i++) {
        size_t o = j->s0 + i;
        memcpy(sp->xyz + 3 * o, j->s->pos + 3 * i, 3 * sizeof(float));
        sp->radius[o] = j->first ? 0.3f : j->s->radius[i];
        sp->color[o] = j->s->color[i];
        sp->res[o] = 12;
    }
}

/* Bond k of atom i (i < j) is cylinder (its rank among i's upper bonds + the upper bonds of
 * the atoms before i): the ranks come from a prefix sum. Each bond is one two-coloured
 * cylinder, its halves running inward to the midpoint, as Licorice draws it. */
static void fill_bonds(void *ctx, size_t b, size_t e, int t)
{
    job *jb = ctx;
    const bench_sys *s = jb->s;
    ms_dl_cylinders *cy = &jb->dl->cylinders;
    for (size_t i = b; i < e; i++) {
        size_t c = jb->c0 + (size_t)jb->first[i];
        for (uint32_t k = s->bstart[i]; k < s->bstart[i + 1]; k++) {
            uint32_t j = s->bto[k];
            if (j < i) continue;
            for (int d = 0; d < 3; d++)
                cy->joint[3 * c + d] = 0.5f * (s->pos[3 * i + d] + s->pos[3 * j + d]);
            memcpy(cy->base + 3 * c, s->pos + 3 * i, 12);
            memcpy(cy->apex + 3 * c, s->pos + 3 * (size_t)j, 12);
            cy->radius[c] = 0.3f;
            cy->color[c] = s->color[i];
            cy->color2[c] = s->color[j];
            cy->flags[c] = MS_CYL_BOND | MS_CYL_INWARD;
            cy->res[c] = 12;
            c++;
        }
    }
}

int bench_vdw_list(const bench_sys *s, ms_displaylist *dl, ms_error *err)
{
    job j = {s, dl, 0, 0, NULL};
    long s0 = ms_dl_extend(dl, MS_DL_SPHERES, s->n, err);
    if (s0 < 0) return -1;
    j.s0 = (size_t)s0;
    ms_parallel_for(s->n, 16384, fill_spheres, &j);
    return 0;
}

int bench_licorice_list(const bench_sys *s, ms_displaylist *dl, ms_error *err)
{
    uint32_t *first = malloc((s->n + 1) * sizeof *first);
    if (!first) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    uint32_t acc = 0;
    for (size_t i = 0; i < s->n; i++) {
        first[i] = acc;
        for (uint32_t k = s->bstart[i]; k < s->bstart[i + 1]; k++) acc += s->bto[k] > i;
    }
    job j = {s, dl, 0, 0, first};
    long s0 = ms_dl_extend(dl, MS_DL_SPHERES, s->n, err);
    long c0 = s0 < 0 ? -1 : ms_dl_extend(dl, MS_DL_CYLINDERS, (size_t)acc, err);
    if (c0 >= 0) {
        j.s0 = (size_t)s0;
        j.c0 = (size_t)c0;
        ms_parallel_for(s->n, 16384, fill_spheres, &j);
        ms_parallel_for(s->n, 16384, fill_bonds, &j);
    }
    free(first);
    return c0 < 0 ? -1 : 0;
}
