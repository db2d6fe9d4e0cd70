/* pairs.c: contacts and hydrogen bonds. Both search the atoms of one set against a cell grid
 * built over the other, in parallel over the first set; each thread collects its own pairs,
 * which are merged and sorted at the end so the output does not depend on the schedule. */
#include "config.h"
#include "measure/internal.h"
#include "base/threads.h"
#include "vecmath/vecmath.h"

#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- per-thread buffers */

typedef struct triple {
    uint32_t v[3];
} triple;

typedef struct tbuf {
    triple *items;
    size_t n, cap;
    int failed;
} tbuf;

static void push(tbuf *b, uint32_t x, uint32_t y, uint32_t z)
{
    if (b->failed) return;
    if (ms_grow((void **)&b->items, &b->cap, b->n + 1, sizeof *b->items)) {
        b->failed = 1;
        return;
    }
    b->items[b->n++] = (triple){{x, y, z}};
}

static int cmp_triple(const void *pa, const void *pb)
{
    const triple *a = pa, *b = pb;
    for (int k = 0; k < 3; k++)
        if (a->v[k] != b->v[k]) return a->v[k] < b->v[k] ? -1 : 1;
    return 0;
}

/* Concatenate the thread buffers into one sorted array (freeing them); NULL with *n = 0 on
 * failure, which is reported in err. */
static triple *merge(tbuf *bufs, int nb, size_t *n, ms_error *err)
{
    size_t total = 0;
    int failed = 0;
    for (int t = 0; t < nb; t++) total += bufs[t].n, failed |= bufs[t].failed;
    triple *all = failed ? NULL : ms_alloc_array(total, sizeof *all);
    size_t at = 0;
    for (int t = 0; t < nb; t++) {
        if (all && bufs[t].n) memcpy(all + at, bufs[t].items, bufs[t].n * sizeof *all);
        at += bufs[t].n;
        free(bufs[t].items);
    }
    free(bufs);
    *n = all ? total : 0;
    if (!all) {
        ms_error_set(err, "out of memory for %zu pairs", total);
        return NULL;
    }
    qsort(all, total, sizeof *all, cmp_triple);
    return all;
}

/* ---------------------------------------------------------------- contacts */

enum { SAME_SET, SAME_FRAME, APART };

typedef struct contact_ctx {
    const ms_atomset *a, *b;
    const float *pa, *pb;
    ms_grid grid;            /* over b */
    double cut2;
    int mode, same_mol;
    uint8_t *in_a, *in_b;        /* membership by atom index (SAME_FRAME) */
    tbuf *bufs;
} contact_ctx;

/* Is (i of a, j of b) a pair VMD reports, before the distance test? */
static int contact_wanted(const contact_ctx *c, uint32_t i, uint32_t j)
{
    if (c->mode == SAME_SET) return j > i;
    if (c->mode == SAME_FRAME) return !(c->in_b[i] && c->in_a[j] && j <= i);
    return 1;
}

static void contact_range(void *vctx, size_t begin, size_t end, int thread)
{
    contact_ctx *c = vctx;
    ms_grid_run runs[9];
    for (size_t k = begin; k < end; k++) {
        uint32_t i = c->a->atoms[k];
        const float *p = c->pa + 3 * (size_t)i;
        int nr = ms_grid_near(&c->grid, p, runs);
        for (int ci = 0; ci < nr; ci++)
            for (uint32_t q = runs[ci].begin; q < runs[ci].end; q++) {
                uint32_t j = c->grid.items[q];
                if (!contact_wanted(c, i, j)) continue;
                double d2 = ms_dist2f(p, c->pb + 3 * (size_t)j);
                if (d2 > c->cut2 || (c->mode == SAME_SET && d2 < 0.001)) continue;
                if (c->same_mol && ms_measure_bonded(c->a->mol, i, j)) continue;
                push(&c->bufs[thread], i, j, 0);
            }
    }
}

static int same_atoms(const ms_atomset *a, const ms_atomset *b)
{
    return a->n == b->n && (a->atoms == b->atoms || !memcmp(a->atoms, b->atoms, a->n * sizeof *a->atoms));
}

/* Mark the atoms of a set in a per-atom byte array. */
static uint8_t *membership(const ms_atomset *s)
{
    uint8_t *in = calloc(s->mol->atoms.n + 1, 1);
    for (size_t i = 0; in && i < s->n; i++) in[s->atoms[i]] = 1;
    return in;
}

static int contacts_setup(contact_ctx *c, double cutoff, ms_error *err)
{
    const ms_atomset *a = c->a, *b = c->b;
    c->same_mol = a->mol == b->mol;
    c->mode = APART;
    if (c->same_mol && a->frame == b->frame) c->mode = same_atoms(a, b) ? SAME_SET : SAME_FRAME;
    if (c->mode == SAME_FRAME && (!(c->in_a = membership(a)) || !(c->in_b = membership(b)))) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    c->bufs = calloc((size_t)ms_threads_count(), sizeof *c->bufs);
    if (!c->bufs) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    return ms_measure_grid(&c->grid, c->pb, b->atoms, b->n, cutoff, err);
}

static int pairs_from(triple *t, size_t n, ms_pairs *out, ms_error *err)
{
    out->a = ms_alloc_array(n, sizeof *out->a);
    out->b = ms_alloc_array(n, sizeof *out->b);
    if (!out->a || !out->b) {
        ms_pairs_free(out);
        ms_error_set(err, "out of memory for %zu pairs", n);
        return -1;
    }
    for (size_t k = 0; k < n; k++) out->a[k] = t[k].v[0], out->b[k] = t[k].v[1];
    out->n = out->cap = n;
    return 0;
}

int ms_measure_contacts(const ms_atomset *a, const ms_atomset *b, double cutoff,
                        ms_pairs *out, ms_error *err)
{
    memset(out, 0, sizeof *out);
    if (!b) b = a;
    if (ms_atomset_check(a, err) || ms_atomset_check(b, err)) return -1;
    contact_ctx c = {.a = a, .b = b, .pa = ms_atomset_pos(a), .pb = ms_atomset_pos(b),
                     .cut2 = cutoff * cutoff};
    int rc = -1;
    if (contacts_setup(&c, cutoff, err) == 0) {
        if (cutoff >= 0) ms_parallel_for(a->n, 256, contact_range, &c);
        size_t n;
        triple *t = merge(c.bufs, ms_threads_count(), &n, err);
        c.bufs = NULL;
        if (t) rc = pairs_from(t, n, out, err);
        free(t);
    }
    free(c.bufs);
    free(c.in_a);
    free(c.in_b);
    ms_grid_free(&c.grid);
    return rc;
}

/* ---------------------------------------------------------------- hydrogen bonds */

typedef struct hbond_ctx {
    const ms_atomset *don;
    const ms_molecule *m;
    const float *pos;
    ms_grid grid;            /* over the acceptors */
    double cut2, maxangle;
    tbuf *bufs;
} hbond_ctx;

static int is_h(const ms_molecule *m, uint32_t i) { return (m->atoms.flags[i] & MS_AF_HYDROGEN) != 0; }

/* Record d-h...a for every hydrogen h bonded to d with a straight enough angle. */
static void try_hydrogens(hbond_ctx *c, uint32_t d, uint32_t a, tbuf *buf)
{
    const ms_bonds *b = &c->m->bonds;
    double pd[3], pa[3], ph[3], dh[3], ha[3];
    ms_pos3(c->pos, d, pd);
    ms_pos3(c->pos, a, pa);
    for (uint32_t k = b->start[d]; k < b->start[d + 1]; k++) {
        uint32_t h = b->to[k];
        if (!is_h(c->m, h)) continue;
        ms_pos3(c->pos, h, ph);
        ms_v3_sub(ph, pd, dh);
        ms_v3_sub(pa, ph, ha);
        if (ms_v3_angle(dh, ha) < c->maxangle) push(buf, d, a, h);
    }
}

static int has_hydrogen(const ms_molecule *m, uint32_t d)
{
    for (uint32_t k = m->bonds.start[d]; k < m->bonds.start[d + 1]; k++)
        if (is_h(m, m->bonds.to[k])) return 1;
    return 0;
}

static void hbond_range(void *vctx, size_t begin, size_t end, int thread)
{
    hbond_ctx *c = vctx;
    ms_grid_run runs[9];
    for (size_t k = begin; k < end; k++) {
        uint32_t d = c->don->atoms[k];
        if (is_h(c->m, d) || !has_hydrogen(c->m, d)) continue;
        const float *p = c->pos + 3 * (size_t)d;
        int nr = ms_grid_near(&c->grid, p, runs);
        for (int ci = 0; ci < nr; ci++)
            for (uint32_t q = runs[ci].begin; q < runs[ci].end; q++) {
                uint32_t a = c->grid.items[q];
                if (a == d || is_h(c->m, a) || ms_dist2f(p, c->pos + 3 * (size_t)a) > c->cut2)
                    continue;
                if (!ms_measure_bonded(c->m, d, a)) try_hydrogens(c, d, a, &c->bufs[thread]);
            }
    }
}

static int hbonds_from(triple *t, size_t n, ms_hbonds *out, ms_error *err)
{
    out->donor = ms_alloc_array(n, sizeof(uint32_t));
    out->acceptor = ms_alloc_array(n, sizeof(uint32_t));
    out->hydrogen = ms_alloc_array(n, sizeof(uint32_t));
    if (!out->donor || !out->acceptor || !out->hydrogen) {
        ms_hbonds_free(out);
        ms_error_set(err, "out of memory for %zu hydrogen bonds", n);
        return -1;
    }
    for (size_t k = 0; k < n; k++)
        out->donor[k] = t[k].v[0], out->acceptor[k] = t[k].v[1], out->hydrogen[k] = t[k].v[2];
    out->n = out->cap = n;
    return 0;
}

int ms_measure_hbonds(const ms_atomset *donors, const ms_atomset *acceptors, double cutoff,
                      double angle, ms_hbonds *out, ms_error *err)
{
    memset(out, 0, sizeof *out);
    const ms_atomset *acc = acceptors ? acceptors : donors;
    if (ms_atomset_check(donors, err)) return -1;
    if (acc->mol != donors->mol) {
        ms_error_set(err, "donors and acceptors must come from the same molecule");
        return -1;
    }
    if (!donors->mol->has_bonds || cutoff < 0) return 0;
    hbond_ctx c = {.don = donors, .m = donors->mol, .pos = ms_atomset_pos(donors),
                   .cut2 = cutoff * cutoff, .maxangle = angle,
                   .bufs = calloc((size_t)ms_threads_count(), sizeof(tbuf))};
    int rc = -1;
    if (!c.bufs) ms_error_set(err, "out of memory");
    else if (ms_measure_grid(&c.grid, c.pos, acc->atoms, acc->n, cutoff, err) == 0) {
        ms_parallel_for(donors->n, 256, hbond_range, &c);
        size_t n;
        triple *t = merge(c.bufs, ms_threads_count(), &n, err);
        c.bufs = NULL;
        if (t) rc = hbonds_from(t, n, out, err);
        free(t);
    }
    free(c.bufs);
    ms_grid_free(&c.grid);
    return rc;
}
