/* bonds.c: VMD's Bonds method (bond radius, resolution): every bond between selected atoms
 * as one cylinder whose halves (VMD's two half cylinders) take their atoms' colours, its ends
 * stretched to meet the neighbouring bond without a gap; double and triple bonds add wider
 * inner cylinders; at a resolution of 2 or less or a radius under 0.01, unlit half lines of
 * width 2 instead. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <string.h>

typedef struct bond_job {
    const ms_rep_build *b;
    ms_displaylist *dl;
    size_t *first;              /* per selected position: first primitive */
    size_t c0;
    uint32_t *order;            /* VMD's order of the pieces, when bonds have orders */
    float radius;
    uint16_t res;
    int cyl;
} bond_job;

static float bond_order(const ms_molecule *m, uint32_t k)
{
    return m->bonds.order ? m->bonds.order[k] : 1.0f;
}

/* The tubes of a bond: itself, and the inner ones of a double and a triple bond. */
static int tubes(float order) { return 1 + (order > 1) + (order > 2); }

/* Tube t of the n of a bond whose primitives start at c: two half lines (VMD's order: the
 * first atom's halves, then the second's), or one tube whose halves are VMD's: from start to
 * mid stretched to meet prev, from mid to end stretched to meet next. */
static void emit(const bond_job *j, size_t c, int t, int n, const float *prev, const float *start,
                 const float *mid, const float *end, const float *next, float r, ms_rgba8 ci,
                 ms_rgba8 ck)
{
    c += (size_t)t;
    if (!j->cyl) {
        ms_dl_lines *ln = &j->dl->lines;
        const float *ends[4] = {start, mid, mid, end};
        for (int h = 0; h < 2; h++, c += (size_t)n) {
            memcpy(ln->a + 3 * c, ends[2 * h], 3 * sizeof(float));
            memcpy(ln->b + 3 * c, ends[2 * h + 1], 3 * sizeof(float));
            ln->width[c] = 2;
            ln->color[c] = h ? ck : ci;
            ln->style[c] = MS_LINE_SOLID;
        }
        return;
    }
    ms_dl_cylinders *cy = &j->dl->cylinders;
    float unused[3];
    ms_rep_stretch(prev, start, mid, end, r, cy->base + 3 * c, cy->joint + 3 * c);
    ms_rep_stretch(start, mid, end, next, r, unused, cy->apex + 3 * c);
    cy->radius[c] = r;
    cy->color[c] = ci;
    cy->color2[c] = ck;
    cy->flags[c] = MS_CYL_BOND;
    cy->res[c] = j->res;
}

/* The last bonded atom of a, when it is selected and not `not` (VMD's choice). */
static const float *neighbour(const ms_rep_build *b, uint32_t a, uint32_t not)
{
    const ms_molecule *m = b->m;
    uint32_t s = m->bonds.start[a], e = m->bonds.start[a + 1];
    if (e == s) return NULL;
    uint32_t o = m->bonds.to[e - 1];
    return o != not && ms_rep_on(b, o) ? ms_rep_xyz(b, o) : NULL;
}

/* VMD's order of a bond's pieces: the first atom's halves, then the second's. */
static void put_order(const bond_job *j, size_t c, int n)
{
    uint32_t *o = j->order + 2 * (c - j->c0);
    for (int k = 0; k < n; k++) {
        o[k] = (uint32_t)(2 * (c + (size_t)k));
        o[n + k] = (uint32_t)(2 * (c + (size_t)k) + 1);
    }
}

static void one_bond(const bond_job *j, size_t c, uint32_t i, uint32_t k, float order)
{
    const ms_rep_build *b = j->b;
    const float *p2 = ms_rep_xyz(b, i), *p4 = ms_rep_xyz(b, k);
    const float *p1 = neighbour(b, i, k), *p5 = neighbour(b, k, i);
    float p3[3], dbl[2][3], tri[2][3], r = j->radius;
    for (int d = 0; d < 3; d++) {
        p3[d] = 0.5f * (p2[d] + p4[d]);
        dbl[0][d] = p2[d] + 0.333f * (p4[d] - p2[d]);
        dbl[1][d] = p2[d] + 0.666f * (p4[d] - p2[d]);
        tri[0][d] = p2[d] + 0.450f * (p4[d] - p2[d]);
        tri[1][d] = p2[d] + 0.550f * (p4[d] - p2[d]);
    }
    ms_rgba8 ci = ms_rep_rgba(b, i), ck = ms_rep_rgba(b, k);
    int n = tubes(order);
    if (j->order) put_order(j, c, n);
    emit(j, c, 0, n, p1, p2, p3, p4, p5, r, ci, ck);
    if (order > 1) emit(j, c, 1, n, NULL, dbl[0], p3, dbl[1], NULL, 1.5f * r, ci, ck);
    if (order > 2) emit(j, c, 2, n, NULL, tri[0], p3, tri[1], NULL, 2.0f * r, ci, ck);
}

static void run(void *ctxp, size_t begin, size_t end, int fillpass)
{
    const bond_job *j = ctxp;
    const ms_rep_build *b = j->b;
    const ms_molecule *m = b->m;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = b->idx[s];
        size_t n = 0;
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            uint32_t o = m->bonds.to[k];
            if (o <= i || !ms_rep_on(b, o)) continue;
            if (fillpass) one_bond(j, j->c0 + j->first[s] + n, i, o, bond_order(m, k));
            n += (size_t)(tubes(bond_order(m, k)) * (j->cyl ? 1 : 2));
        }
        if (!fillpass) j->first[s] = n;
    }
}

static void count(void *c, size_t b, size_t e, int t) { run(c, b, e, 0); }
static void fill(void *c, size_t b, size_t e, int t) { run(c, b, e, 1); }

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    if (!b->m->has_bonds || b->nsel == 0) return 0;
    float r = b->p[0];
    int res = ms_rep_res(b->p[1]);
    bond_job j = {b, dl, NULL, 0, NULL, r, (uint16_t)res, !(res <= 2 || r < 0.01f)};
    if (!j.cyl) dl->lit = 0;
    j.first = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (b->nsel + 1) * sizeof(size_t), err);
    if (!j.first) return -1;
    ms_parallel_for(b->nsel, 16384, count, &j);
    size_t total = ms_rep_scan(j.first, b->nsel);
    long c0 = ms_dl_extend(dl, j.cyl ? MS_DL_CYLINDERS : MS_DL_LINES, total, err);
    if (c0 < 0) return -1;
    j.c0 = (size_t)c0;
    if (j.cyl && b->m->bonds.order && !(j.order = ms_dl_cylinder_order(dl, 2 * total, err)))
        return -1;
    ms_parallel_for(b->nsel, 16384, fill, &j);
    return 0;
}

const ms_rep_method ms_rep_bonds = {
    "Bonds", 2, {{"bond radius", 0.3f}, {"bond resolution", 12.0f}}, 0, build};
