/* backbone.c: the polymer chains the backbone methods (Trace, Tube, NewRibbons, NewCartoon)
 * draw along: runs of bonded protein (or nucleic) residues, each residue with its
 * control atom (CA; P for nucleic acids) and guide atoms (O; the phosphate oxygens), and the
 * cubic splines through the control points. */
#include "config.h"
#include "rep/rep_int.h"
#include "vecmath/vecf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- splines */

void ms_rep_spline_basis(float basis[4][4], int bspline)
{
    if (bspline) {   /* uniform cubic B-spline */
        static const float bs[4][4] = {{-1.0f / 6, 3.0f / 6, -3.0f / 6, 1.0f / 6},
                                       {3.0f / 6, -6.0f / 6, 3.0f / 6, 0},
                                       {-3.0f / 6, 0, 3.0f / 6, 0},
                                       {1.0f / 6, 4.0f / 6, 1.0f / 6, 0}};
        memcpy(basis, bs, sizeof bs);
        return;
    }
    /* cardinal spline with tension s = 1 / 1.25: VMD's "Catmull-Rom with slope 1.25" */
    const float s = 1.0f / 1.25f;
    const float cr[4][4] = {{-s, 2 - s, s - 2, s},
                            {2 * s, s - 3, 3 - 2 * s, -s},
                            {-s, 0, s, 0},
                            {0, 1, 0, 0}};
    memcpy(basis, cr, sizeof cr);
}

void ms_rep_spline_eval(const float basis[4][4], const float *p0, const float *p1,
                        const float *p2, const float *p3, float t, float out[3])
{
    const float *g[4] = {p0, p1, p2, p3};
    for (int k = 0; k < 3; k++) {
        float q[4];
        for (int i = 0; i < 4; i++)
            q[i] = basis[i][0] * g[0][k] + basis[i][1] * g[1][k] + basis[i][2] * g[2][k] +
                   basis[i][3] * g[3][k];
        out[k] = ((q[0] * t + q[1]) * t + q[2]) * t + q[3];
    }
}

/* ---------------------------------------------------------------- chains */

typedef struct names {
    ms_str ca, o, ot1, p, c5p, c5s, o1p, op1, o2p, op2;
} names;

static void find_names(const ms_molecule *m, names *n)
{
    n->ca = ms_strtab_find(m->strings, "CA");
    n->o = ms_strtab_find(m->strings, "O");
    n->ot1 = ms_strtab_find(m->strings, "OT1");
    n->p = ms_strtab_find(m->strings, "P");
    n->c5p = ms_strtab_find(m->strings, "C5'");
    n->c5s = ms_strtab_find(m->strings, "C5*");
    n->o1p = ms_strtab_find(m->strings, "O1P");
    n->op1 = ms_strtab_find(m->strings, "OP1");
    n->o2p = ms_strtab_find(m->strings, "O2P");
    n->op2 = ms_strtab_find(m->strings, "OP2");
}

/* The first atom of residue r named a (or b when a is missing), or -1. */
static int32_t named(const ms_molecule *m, size_t r, ms_str a, ms_str b)
{
    int32_t found = -1;
    for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++) {
        ms_str s = m->atoms.name[i];
        if (s == a && a != MS_STR_NONE) return (int32_t)i;
        if (s == b && b != MS_STR_NONE && found < 0) found = (int32_t)i;
    }
    return found;
}

static int push(ms_rep_backbone *bb, uint32_t atom, int32_t g1, int32_t g2, int newchain,
                int nucleic)
{
    if (ms_grow((void **)&bb->atom, &bb->cap, bb->n + 1, sizeof *bb->atom)) return -1;
    size_t c1 = bb->cap;
    int32_t *a = realloc(bb->guide, c1 * sizeof *a), *b2;
    if (!a) return -1;
    bb->guide = a;
    if (!(b2 = realloc(bb->guide2, c1 * sizeof *b2))) return -1;
    bb->guide2 = b2;
    if (newchain) {
        if (ms_grow((void **)&bb->chains, &bb->chcap, bb->nchains + 1, sizeof *bb->chains))
            return -1;
        bb->chains[bb->nchains++] = (ms_rep_chain){bb->n, 0, nucleic};
    }
    bb->atom[bb->n] = atom;
    bb->guide[bb->n] = g1;
    bb->guide2[bb->n] = g2;
    bb->n++;
    bb->chains[bb->nchains - 1].n++;
    return 0;
}

/* VMD's rule for a structure with no protein: atoms named CA with consecutive resids. */
static int ca_only(const ms_molecule *m, const names *nm, ms_rep_backbone *bb)
{
    long last = 0;
    int have = 0;
    for (size_t i = 0; i < m->atoms.n; i++) {
        if (m->atoms.name[i] != nm->ca) continue;
        long r = m->atoms.resid[i];
        if (push(bb, (uint32_t)i, -1, -1, !(have && r == last + 1), 0)) return -1;
        have = 1;
        last = r;
    }
    return 0;
}

/* Is residue r bonded to residue r - 1 (a peptide or phosphodiester link)? */
static int linked(const ms_molecule *m, size_t r)
{
    if (!m->has_bonds) return 0;
    uint32_t lo = m->res_start[r], hi = m->res_start[r + 1];
    for (uint32_t i = m->res_start[r - 1]; i < lo; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
            if (m->bonds.to[k] >= lo && m->bonds.to[k] < hi) return 1;
    return 0;
}

/* 0 protein, 1 nucleic, -1 neither: from the residue's atoms' classification. */
static int residue_kind(const ms_molecule *m, size_t r)
{
    for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++) {
        if (m->atoms.flags[i] & MS_AF_PROTEIN) return 0;
        if (m->atoms.flags[i] & MS_AF_NUCLEIC) return 1;
    }
    return -1;
}

int ms_rep_backbone_build(ms_molecule *m, ms_rep_backbone *bb, ms_error *err)
{
    bb->n = bb->nchains = 0;
    if (!m->res_start || m->atoms.n == 0) return 0;
    names nm;
    find_names(m, &nm);
    int prev_kind = -1;
    size_t nprot = 0;
    for (size_t r = 0; r < m->nresidues; r++) {
        int rc = 0, kind = residue_kind(m, r);
        int newchain = r == 0 || kind != prev_kind || !linked(m, r);
        uint32_t a0 = m->res_start[r];
        if (kind == 0) {
            int32_t ca = named(m, r, nm.ca, MS_STR_NONE);
            nprot++;
            rc = push(bb, (uint32_t)(ca >= 0 ? ca : (int32_t)a0), named(m, r, nm.o, nm.ot1), -1,
                      newchain, 0);
        } else if (kind == 1) {
            int32_t p = named(m, r, nm.p, MS_STR_NONE);
            if (p < 0) p = named(m, r, nm.c5p, nm.c5s);
            rc = push(bb, (uint32_t)(p >= 0 ? p : (int32_t)a0), named(m, r, nm.o1p, nm.op1),
                      named(m, r, nm.o2p, nm.op2), newchain, 1);
        }
        if (rc) goto oom;
        prev_kind = kind;
    }
    if (nprot == 0 && nm.ca != MS_STR_NONE && ca_only(m, &nm, bb)) goto oom;
    return 0;
oom:
    ms_error_set(err, "out of memory finding polymer chains");
    return -1;
}

void ms_rep_backbone_free(ms_rep_backbone *bb)
{
    free(bb->atom);
    free(bb->guide);
    free(bb->guide2);
    free(bb->chains);
    memset(bb, 0, sizeof *bb);
}

/* ---------------------------------------------------------------- guide vectors */

void ms_rep_chain_perps(const ms_rep_build *b, const ms_rep_backbone *bb,
                        const ms_rep_chain *ch, float *perp)
{
    float g[3] = {0, 0, 0}, lastc[3], lasto[3];
    for (size_t q = 0; q < ch->n; q++) {
        size_t r = ch->first + q;
        const float *c = ms_rep_xyz(b, bb->atom[r]);
        float o[3];
        if (!ch->nucleic) {
            if (bb->guide[r] >= 0) memcpy(o, ms_rep_xyz(b, (size_t)bb->guide[r]), sizeof o);
            else memcpy(o, q ? lasto : c, sizeof o);
        } else if (bb->guide[r] >= 0 && bb->guide2[r] >= 0) {   /* the oxygens' bisector */
            const float *o1 = ms_rep_xyz(b, (size_t)bb->guide[r]), *o2 = ms_rep_xyz(b, (size_t)bb->guide2[r]);
            for (int k = 0; k < 3; k++) o[k] = c[k] + 0.5f * (o1[k] - c[k] + o2[k] - c[k]);
        } else {
            memcpy(o, q ? lasto : c, sizeof o);
        }
        if (q == 0) {
            memcpy(lastc, c, sizeof lastc);
            memcpy(lasto, o, sizeof lasto);
        }
        float a[3], bv[3], cv[3], d[3];
        ms_v3f_sub(c, lastc, a);                /* CA(i) - CA(i-1) */
        ms_v3f_sub(ch->nucleic ? o : lasto, ch->nucleic ? c : lastc, bv);   /* the guide */
        ms_v3f_cross(a, bv, cv);                /* normal of the peptide plane */
        ms_v3f_cross(cv, a, d);                 /* in the plane, across the backbone */
        if (ms_v3f_dot(d, g) < 0) for (int k = 0; k < 3; k++) d[k] = -d[k];
        for (int k = 0; k < 3; k++) g[k] += d[k];
        ms_v3f_normalize(g);
        memcpy(perp + 3 * q, g, sizeof g);
        memcpy(lastc, c, sizeof lastc);
        memcpy(lasto, o, sizeof lasto);
    }
    if (ch->n > 1) memcpy(perp, perp + 3, 3 * sizeof(float));
}
