/* beads.c: VMD's bead mode for cellular-scale systems: each residue's atoms become one
 * particle at their unweighted centroid, with a radius reaching the farthest of them plus
 * 1 A and the colour of the residue's last atom. Two linear passes over the atoms. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <stdlib.h>
#include <string.h>

/* Atoms [k, end) of `a` that form the residue starting at k. */
static size_t residue_end(const ms_qsurf_atoms *a, const int32_t *residue, size_t k)
{
    int32_t res = residue[ms_qsurf_atom_index(a, k)];
    size_t e = k + 1;
    while (e < a->n && residue[ms_qsurf_atom_index(a, e)] == res) e++;
    return e;
}

static size_t count_residues(const ms_qsurf_atoms *a, const int32_t *residue)
{
    size_t n = 0;
    for (size_t k = 0; k < a->n; k = residue_end(a, residue, k)) n++;
    return n;
}

static void make_bead(const ms_qsurf_atoms *a, size_t k, size_t e, ms_qsurf_beads *b, size_t i)
{
    double c[3] = {0, 0, 0};
    for (size_t m = k; m < e; m++)
        for (int d = 0; d < 3; d++) c[d] += a->pos[3 * ms_qsurf_atom_index(a, m) + d];
    double r2 = 0.0;
    for (int d = 0; d < 3; d++) c[d] /= (double)(e - k);
    for (size_t m = k; m < e; m++) {
        const float *p = a->pos + 3 * ms_qsurf_atom_index(a, m);
        double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
        r2 = MS_MAX(r2, dx * dx + dy * dy + dz * dz);
    }
    for (int d = 0; d < 3; d++) b->pos[3 * i + d] = (float)c[d];
    b->radius[i] = (float)sqrt(r2) + 1.0f;
    if (b->rgb)
        memcpy(b->rgb + 3 * i, a->rgb + 3 * ms_qsurf_atom_index(a, e - 1), 3 * sizeof(float));
}

int ms_qsurf_beads_build(const ms_qsurf_atoms *a, const int32_t *residue, ms_qsurf_beads *out,
                         ms_error *err)
{
    memset(out, 0, sizeof *out);
    memcpy(out->solid, a->solid, sizeof out->solid);
    size_t n = count_residues(a, residue);
    out->pos = ms_alloc_array(n, 3 * sizeof(float));
    out->radius = ms_alloc_array(n, sizeof(float));
    if (a->rgb) out->rgb = ms_alloc_array(n, 3 * sizeof(float));
    if (!out->pos || !out->radius || (a->rgb && !out->rgb)) {
        ms_qsurf_beads_free(out);
        ms_error_set(err, "out of memory for %zu beads", n);
        return -1;
    }
    size_t i = 0;
    for (size_t k = 0, e; k < a->n; k = e, i++) {
        e = residue_end(a, residue, k);
        make_bead(a, k, e, out, i);
    }
    out->n = n;
    return 0;
}

void ms_qsurf_beads_atoms(const ms_qsurf_beads *b, ms_qsurf_atoms *a)
{
    memset(a, 0, sizeof *a);
    a->n = b->n;
    a->pos = b->pos;
    a->radius = b->radius;
    a->rgb = b->rgb;
    memcpy(a->solid, b->solid, sizeof a->solid);
}

void ms_qsurf_beads_free(ms_qsurf_beads *b)
{
    free(b->pos);
    free(b->radius);
    free(b->rgb);
    memset(b, 0, sizeof *b);
}
