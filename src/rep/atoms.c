/* atoms.c: helpers of the atom and bond methods: scratch memory, prefix sums, a sphere per
 * selected atom, the bonds drawn (the molecule's, or by a distance cutoff) and a
 * two-coloured cylinder per bond. Every fill is claimed as one block and written in
 * parallel. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

void *ms_rep_scratch_get(ms_rep_scratch *s, int slot, size_t bytes, ms_error *err)
{
    if (bytes == 0) bytes = 1;
    if (s->cap[slot] < bytes) {
        size_t want = bytes + bytes / 8;
        void *p = realloc(s->buf[slot], want);
        if (!p) {
            ms_error_set(err, "out of memory (%zu bytes of scratch space)", bytes);
            return NULL;
        }
        s->buf[slot] = p;
        s->cap[slot] = want;
    }
    return s->buf[slot];
}

void ms_rep_scratch_free(ms_rep_scratch *s)
{
    for (int k = 0; k < MS_REP_NSCRATCH; k++) free(s->buf[k]);
    memset(s, 0, sizeof *s);
}

size_t ms_rep_scan(size_t *v, size_t n)
{
    size_t acc = 0;
    for (size_t i = 0; i < n; i++) {
        size_t c = v[i];
        v[i] = acc;
        acc += c;
    }
    return acc;
}

/* ---------------------------------------------------------------- spheres */

typedef struct sphere_job {
    const ms_rep_build *b;
    ms_dl_spheres *sp;
    size_t s0;
    float radscale, fixrad;
    uint16_t res;
} sphere_job;

static void fill_spheres(void *ctxp, size_t begin, size_t end, int thread)
{
    const sphere_job *j = ctxp;
    const ms_rep_build *b = j->b;
    const float *radius = b->m->atoms.radius;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = b->idx[s];
        size_t o = j->s0 + s;
        memcpy(j->sp->xyz + 3 * o, ms_rep_xyz(b, i), 3 * sizeof(float));
        j->sp->radius[o] = radius[i] * j->radscale + j->fixrad;
        j->sp->color[o] = ms_rep_rgba(b, i);
        j->sp->res[o] = j->res;
    }
}

int ms_rep_atom_spheres(const ms_rep_build *b, float radscale, float fixrad, int res,
                        ms_displaylist *dl, ms_error *err)
{
    if (!(radscale + fixrad > 0) || b->nsel == 0) return 0;
    long s0 = ms_dl_extend(dl, MS_DL_SPHERES, b->nsel, err);
    if (s0 < 0) return -1;
    sphere_job j = {b, &dl->spheres, (size_t)s0, radscale, fixrad, (uint16_t)res};
    ms_parallel_for(b->nsel, 16384, fill_spheres, &j);
    return 0;
}

/* ---------------------------------------------------------------- bonds */

int ms_rep_may_bond(const ms_molecule *m, uint32_t i, uint32_t j)
{
    const ms_atoms *a = &m->atoms;
    if ((a->flags[i] & MS_AF_HYDROGEN) && (a->flags[j] & MS_AF_HYDROGEN)) return 0;
    return !(a->altloc[i] != a->altloc[j] && a->altloc[i] && a->altloc[j]);
}

static int keep_bond(const void *ctx, uint32_t i, uint32_t j)
{
    return ms_rep_may_bond(ctx, i, j);
}

int ms_rep_bonds_get(const ms_rep_build *b, float cutoff, ms_rep_bondlist *out, ms_error *err)
{
    const ms_molecule *m = b->m;
    size_t n = m->atoms.n;
    if (!(cutoff > 0) && m->has_bonds) {
        out->start = m->bonds.start;
        out->to = m->bonds.to;
        return 0;
    }
    uint32_t *pairs = NULL;
    size_t np = 0;
    if (cutoff > 0 && ms_rep_pairs(b, cutoff, keep_bond, m, &pairs, &np, err)) return -1;
    uint32_t *start = ms_rep_scratch_get(b->scratch, MS_SCR_BONDSTART, (n + 1) * sizeof *start, err);
    uint32_t *to = ms_rep_scratch_get(b->scratch, MS_SCR_BONDTO, (2 * np + 1) * sizeof *to, err);
    if (!start || !to) return -1;
    memset(start, 0, (n + 1) * sizeof *start);
    for (size_t k = 0; k < 2 * np; k++) start[pairs[k] + 1]++;
    for (size_t i = 0; i < n; i++) start[i + 1] += start[i];
    for (size_t k = 0; k < np; k++) {   /* start[i] walks forward, then is restored */
        to[start[pairs[2 * k]]++] = pairs[2 * k + 1];
        to[start[pairs[2 * k + 1]]++] = pairs[2 * k];
    }
    for (size_t i = n; i > 0; i--) start[i] = start[i - 1];
    start[0] = 0;
    out->start = start;
    out->to = to;
    return 0;
}

/* ---------------------------------------------------------------- bond cylinders */

/* Every bond between selected atoms is one cylinder, made at its lower atom. The pieces'
 * order is VMD's: each selected atom in turn, a half from it to the middle of each of its
 * bonds in the order of its bond list; rank[] is where each atom's halves start. */
typedef struct bond_job {
    const ms_rep_build *b;
    const ms_rep_bondlist *bl;
    ms_dl_cylinders *cy;
    uint32_t *order;
    size_t *rank, *first;       /* per selected position: first half, first cylinder */
    uint32_t *pos;              /* per selected atom: its position in the selection */
    size_t c0;
    float radius;
    uint16_t res;
} bond_job;

static void count_bonds(void *ctxp, size_t begin, size_t end, int thread)
{
    const bond_job *j = ctxp;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = j->b->idx[s];
        size_t h = 0, c = 0;
        for (uint32_t k = j->bl->start[i]; k < j->bl->start[i + 1]; k++) {
            uint32_t o = j->bl->to[k];
            if (!ms_rep_on(j->b, o)) continue;
            h++;
            c += o > i;
        }
        j->rank[s] = h;
        j->first[s] = c;
        j->pos[i] = (uint32_t)s;
    }
}

/* The cylinder of bond (o, i), o < i: made at o, after o's bonds to selected atoms above o
 * that come before i in o's list. */
static size_t cylinder_of(const bond_job *j, uint32_t o, uint32_t i)
{
    size_t c = j->c0 + j->first[j->pos[o]];
    for (uint32_t k = j->bl->start[o]; k < j->bl->start[o + 1] && j->bl->to[k] != i; k++)
        c += j->bl->to[k] > o && ms_rep_on(j->b, j->bl->to[k]);
    return c;
}

static void put_bond(const bond_job *j, size_t c, uint32_t i, uint32_t o)
{
    ms_dl_cylinders *cy = j->cy;
    const float *p = ms_rep_xyz(j->b, i), *q = ms_rep_xyz(j->b, o);
    for (int d = 0; d < 3; d++) {
        cy->base[3 * c + d] = p[d];
        cy->apex[3 * c + d] = q[d];
        cy->joint[3 * c + d] = 0.5f * (p[d] + q[d]);
    }
    cy->radius[c] = j->radius;
    cy->color[c] = ms_rep_rgba(j->b, i);
    cy->color2[c] = ms_rep_rgba(j->b, o);
    cy->flags[c] = MS_CYL_BOND | MS_CYL_INWARD;
    cy->res[c] = j->res;
}

static void fill_bonds(void *ctxp, size_t begin, size_t end, int thread)
{
    const bond_job *j = ctxp;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = j->b->idx[s];
        size_t h = j->rank[s], c = j->c0 + j->first[s];
        for (uint32_t k = j->bl->start[i]; k < j->bl->start[i + 1]; k++) {
            uint32_t o = j->bl->to[k];
            if (!ms_rep_on(j->b, o)) continue;
            if (o > i) {
                put_bond(j, c, i, o);
                j->order[h++] = (uint32_t)(2 * c++);
            } else {
                j->order[h++] = (uint32_t)(2 * cylinder_of(j, o, i) + 1);
            }
        }
    }
}

int ms_rep_bond_cylinders(const ms_rep_build *b, const ms_rep_bondlist *bl, float radius, int res,
                          ms_displaylist *dl, ms_error *err)
{
    if (b->nsel == 0) return 0;
    bond_job j = {b, bl, NULL, NULL, NULL, NULL, NULL, 0, radius, (uint16_t)res};
    j.rank = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (b->nsel + 1) * sizeof(size_t), err);
    j.first = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA, (b->nsel + 1) * sizeof(size_t), err);
    j.pos = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA2, b->m->atoms.n * sizeof(uint32_t), err);
    if (!j.rank || !j.first || !j.pos) return -1;
    ms_parallel_for(b->nsel, 16384, count_bonds, &j);
    size_t halves = ms_rep_scan(j.rank, b->nsel), total = ms_rep_scan(j.first, b->nsel);
    if (2 * (dl->cylinders.n + total) > UINT32_MAX) {
        ms_error_set(err, "%zu bonds: too many for one display list", total);
        return -1;
    }
    long c0 = ms_dl_extend(dl, MS_DL_CYLINDERS, total, err);
    if (c0 < 0) return -1;
    j.c0 = (size_t)c0;
    j.cy = &dl->cylinders;
    if (!(j.order = ms_dl_cylinder_order(dl, halves, err))) return -1;
    ms_parallel_for(b->nsel, 16384, fill_bonds, &j);
    return 0;
}

/* ---------------------------------------------------------------- joints */

/* VMD's gap-free joint: move start back (end forward) by r tan(angle / 2) to meet the
 * cylinder from prev (to next). */
void ms_rep_stretch(const float *prev, const float *start, const float *end,
                    const float *next, float r, float *s, float *e)
{
    float dir[3], l = 0;
    for (int k = 0; k < 3; k++) {
        dir[k] = end[k] - start[k];
        l += dir[k] * dir[k];
    }
    l = sqrtf(l);
    for (int k = 0; k < 3; k++) dir[k] = l > 0 ? dir[k] / l : 0;
    float ls = 0, le = 0;
    for (int pass = 0; pass < 2; pass++) {
        const float *a = pass ? end : prev, *b = pass ? next : start;
        if (!a || !b) continue;
        float o[3], ol = 0, c = 0;
        for (int k = 0; k < 3; k++) {
            o[k] = b[k] - a[k];
            ol += o[k] * o[k];
        }
        ol = sqrtf(ol);
        if (!(ol > 0)) continue;
        for (int k = 0; k < 3; k++) c += o[k] / ol * dir[k];
        if (c > 0.0f && c < 0.9999f) *(pass ? &le : &ls) = r * sqrtf((1 - c) / (1 + c));
    }
    for (int k = 0; k < 3; k++) {
        s[k] = start[k] - ls * dir[k];
        e[k] = end[k] + le * dir[k];
    }
}
