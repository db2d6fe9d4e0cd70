/* hbonds.c: VMD's HBonds method (distance, angle, line thickness): for selected heavy atoms
 * D and A at most the distance apart and not bonded, and a hydrogen H bonded to D with the
 * angle between D->H and H->A under the cutoff (0 for a straight bond), a dashed line from A
 * to H in D's colour; unlit. */
#include "config.h"
#include "rep/rep_int.h"

#include <math.h>

static int not_bonded(const void *ctx, uint32_t i, uint32_t j)
{
    const ms_molecule *m = ctx;
    if (!m->has_bonds) return 1;
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
        if (m->bonds.to[k] == j) return 0;
    return 1;
}

/* Angle in degrees between u and v (NaN for a zero vector, which never passes). */
static float angle(const float *u, const float *v)
{
    float uu = u[0] * u[0] + u[1] * u[1] + u[2] * u[2], vv = v[0] * v[0] + v[1] * v[1] + v[2] * v[2];
    float c = (u[0] * v[0] + u[1] * v[1] + u[2] * v[2]) / sqrtf(uu * vv);
    c = c > 1 ? 1 : c < -1 ? -1 : c;
    return acosf(c) * (float)(180.0 / 3.14159265358979323846);
}

/* Lines for the hydrogens of donor d towards acceptor a. */
static int donor(const ms_rep_build *b, uint32_t d, uint32_t a, float maxangle, float width,
                 int acceptor_first, ms_displaylist *dl)
{
    const ms_molecule *m = b->m;
    const float *pd = ms_rep_xyz(b, d), *pa = ms_rep_xyz(b, a);
    for (uint32_t k = m->bonds.start[d]; k < m->bonds.start[d + 1]; k++) {
        uint32_t h = m->bonds.to[k];
        if (!(m->atoms.flags[h] & MS_AF_HYDROGEN)) continue;
        const float *ph = ms_rep_xyz(b, h);
        float dh[3] = {ph[0] - pd[0], ph[1] - pd[1], ph[2] - pd[2]};
        float ha[3] = {pa[0] - ph[0], pa[1] - ph[1], pa[2] - ph[2]};
        if (!(angle(dh, ha) < maxangle)) continue;
        if (ms_dl_line(dl, acceptor_first ? pa : ph, acceptor_first ? ph : pa, width,
                       ms_rep_rgba(b, d), MS_LINE_DASHED))
            return -1;
    }
    return 0;
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    dl->lit = 0;
    float maxdist = b->p[0], maxangle = b->p[1], width = (float)(int)b->p[2];
    if (maxdist <= 0.1f || b->nsel == 0 || !b->m->has_bonds) return 0;
    uint32_t *heavy = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA2, b->nsel * sizeof *heavy, err);
    if (!heavy) return -1;
    size_t n = 0;
    for (size_t s = 0; s < b->nsel; s++)
        if (!(b->m->atoms.flags[b->idx[s]] & MS_AF_HYDROGEN)) heavy[n++] = b->idx[s];
    ms_rep_build hb = *b;
    hb.idx = heavy;
    hb.nsel = n;
    uint32_t *pairs;
    size_t np;
    if (ms_rep_pairs(&hb, maxdist, not_bonded, b->m, &pairs, &np, err)) return -1;
    for (size_t k = 0; k < np; k++) {
        uint32_t a1 = pairs[2 * k], a2 = pairs[2 * k + 1];
        if (donor(b, a2, a1, maxangle, width < 1 ? 1 : width, 1, dl) ||
            donor(b, a1, a2, maxangle, width < 1 ? 1 : width, 0, dl)) {
            ms_error_set(err, "out of memory for display list");
            return -1;
        }
    }
    return 0;
}

const ms_rep_method ms_rep_hbonds = {
    "HBonds", 3, {{"distance", 3.0f}, {"angle", 20.0f}, {"line thickness", 1.0f}}, 0, build};
