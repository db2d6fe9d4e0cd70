/* util.c: what the measurements share: checking an atom set, per-atom values used as
 * weights, a deterministic parallel reduction, bond lookups and result lists. */
#include "config.h"
#include "measure/internal.h"
#include "base/threads.h"

#include <stdlib.h>
#include <string.h>

int ms_atomset_check(const ms_atomset *s, ms_error *err)
{
    if (s->frame >= s->mol->nframes) {
        ms_error_set(err, "molecule %d has no frame %zu (it has %zu)", s->mol->id, s->frame,
                     s->mol->nframes);
        return -1;
    }
    /* A streamed frame is read into the window, a cache: the molecule does not change. */
    return ms_mol_frame((ms_molecule *)s->mol, s->frame, err) ? 0 : -1;
}

/* ---------------------------------------------------------------- per-atom values */

static const char *const float_keywords[] = {
    "mass", "charge", "beta", "occupancy", "radius", "user", "user2", "user3", "user4",
    "x", "y", "z", "vx", "vy", "vz", NULL};
static const char *const other_keywords[] = {
    "index", "serial", "resid", "residue", "fragment", "pfrag", "nfrag", "numbonds",
    "atomicnumber", "name", "type", "element", "resname", "altloc", "insertion", "chain",
    "segname", "segid", "structure", "backbonetype", "residuetype", NULL};

static int find_word(const char *const *list, const char *w)
{
    for (int i = 0; list[i]; i++)
        if (!strcmp(list[i], w)) return i;
    return -1;
}

int ms_measure_is_float_keyword(const char *k) { return find_word(float_keywords, k) >= 0; }

int ms_measure_is_atom_keyword(const char *k)
{
    return ms_measure_is_float_keyword(k) || find_word(other_keywords, k) >= 0;
}

/* The per-atom float array behind a keyword; *coord is 0..2 for x y z (positions), 3..5 for
 * vx vy vz (velocities), -1 otherwise. NULL with *coord -1 for user fields never set. */
static const float *keyword_array(const ms_atomset *s, int which, int *coord)
{
    const ms_atoms *a = &s->mol->atoms;
    const float *arrays[] = {a->mass, a->charge, a->beta, a->occupancy, a->radius,
                             s->mol->user[0], s->mol->user[1], s->mol->user[2], s->mol->user[3]};
    *coord = which >= 9 ? which - 9 : -1;
    return which < 9 ? arrays[which] : NULL;
}

int ms_measure_atom_values(const ms_atomset *s, const char *keyword, double *out,
                           ms_error *err)
{
    int which = find_word(float_keywords, keyword), coord;
    if (which < 0) {
        ms_error_set(err, "'%s' is not a floating-point atom keyword", keyword);
        return -1;
    }
    if (ms_atomset_check(s, err)) return -1;
    const float *arr = keyword_array(s, which, &coord);
    const ms_frame *f = &s->mol->frames[s->frame];
    if (coord >= 3 && !f->vel) {
        ms_error_set(err, "molecule %d has no velocities for '%s'", s->mol->id, keyword);
        return -1;
    }
    for (size_t i = 0; i < s->n; i++) {
        size_t a = s->atoms[i];
        if (coord >= 3) out[i] = f->vel[3 * a + (size_t)coord - 3];
        else if (coord >= 0) out[i] = f->pos[3 * a + (size_t)coord];
        else out[i] = arr ? arr[a] : 0.0;
    }
    return 0;
}

double ms_measure_sumweights(const double *w, size_t n)
{
    double sum = 0.0;
    for (size_t i = 0; i < n; i++) sum += w ? w[i] : 1.0;
    return sum;
}

/* ---------------------------------------------------------------- reduction */

#define CHUNK 32768

typedef struct chunk_job {
    size_t n, k;
    ms_chunk_fn fn;
    void *ctx;
    double *acc;
} chunk_job;

static void run_chunk(void *vjob, size_t begin, size_t end, int thread)
{
    chunk_job *j = vjob;
    for (size_t c = begin; c < end; c++) {
        size_t b = c * CHUNK, e = b + CHUNK < j->n ? b + CHUNK : j->n;
        j->fn(j->ctx, b, e, j->acc + c * j->k);
    }
}

double *ms_measure_chunks(size_t n, size_t k, ms_chunk_fn fn, void *ctx, size_t *nchunks)
{
    size_t nc = n ? (n + CHUNK - 1) / CHUNK : 1;
    chunk_job job = {n, k, fn, ctx, ms_calloc_array(nc * k, sizeof(double))};
    if (!job.acc) return NULL;
    if (n == 0) fn(ctx, 0, 0, job.acc);
    else if (nc == 1) fn(ctx, 0, n, job.acc);
    else ms_parallel_for(nc, 1, run_chunk, &job);
    *nchunks = nc;
    return job.acc;
}

/* ---------------------------------------------------------------- bonds, lists */

int ms_measure_bonded(const ms_molecule *m, uint32_t i, uint32_t j)
{
    if (!m->has_bonds) return 0;
    uint32_t lo = m->bonds.start[i], hi = m->bonds.start[i + 1];
    while (lo < hi) {   /* partners are sorted ascending */
        uint32_t mid = lo + (hi - lo) / 2, v = m->bonds.to[mid];
        if (v == j) return 1;
        if (v < j) lo = mid + 1;
        else hi = mid;
    }
    return 0;
}

void ms_pairs_free(ms_pairs *p)
{
    free(p->a);
    free(p->b);
    memset(p, 0, sizeof *p);
}

void ms_hbonds_free(ms_hbonds *h)
{
    free(h->donor);
    free(h->acceptor);
    free(h->hydrogen);
    memset(h, 0, sizeof *h);
}
