/* ss.c: secondary structure of a molecule: the backbone (N, CA, C, O) of each protein
 * residue is gathered from a frame, DSSP runs on it (hbond.c, patterns.c) and the codes are
 * written to every atom of each residue, coil elsewhere. Also the on-demand rule: compute
 * once, when nothing has given the molecule a structure yet. */
#include "config.h"
#include "ss/ssint.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- DSSP on a backbone */

int ms_ss_dssp(size_t nres, const float *bb, const uint32_t *seg, const uint8_t *proline,
               char *out, ms_error *err)
{
    ms_ss_chain c = {nres, bb, seg, proline, NULL, NULL, NULL, NULL, NULL};
    size_t n = nres ? nres : 1;
    c.h = ms_alloc_array(n, 3 * sizeof *c.h);
    c.donor = malloc(n);
    c.piece = ms_alloc_array(n, sizeof *c.piece);
    c.acc = ms_alloc_array(n, 2 * sizeof *c.acc);
    c.energy = ms_alloc_array(n, 2 * sizeof *c.energy);
    int rc = -1;
    if (!c.h || !c.donor || !c.piece || !c.acc || !c.energy) {
        ms_error_set(err, "out of memory for the secondary structure of %zu residues", nres);
    } else if (ms_ss_hbonds(&c, err) == 0) {
        memset(out, MS_SS_COIL_CODE, nres);
        rc = ms_ss_patterns(&c, out, err);
    }
    free(c.h);
    free(c.donor);
    free(c.piece);
    free(c.acc);
    free(c.energy);
    return rc;
}

/* ---------------------------------------------------------------- the molecule's backbone */

/* Interned names the gathering looks for (MS_STR_NONE when the molecule has none). */
typedef struct bb_names {
    ms_str atom[4];          /* N CA C O */
    ms_str oterm[2];         /* OT1 OC1: the carbonyl O of C-terminal residues */
    ms_str pro;
} bb_names;

typedef struct backbone {
    size_t n;
    float *bb;
    uint32_t *seg, *residue;
    uint8_t *proline;
} backbone;

static void find_names(const ms_molecule *m, bb_names *nm)
{
    static const char *const atom[4] = {"N", "CA", "C", "O"};
    for (int k = 0; k < 4; k++) nm->atom[k] = ms_strtab_find(m->strings, atom[k]);
    nm->oterm[0] = ms_strtab_find(m->strings, "OT1");
    nm->oterm[1] = ms_strtab_find(m->strings, "OC1");
    nm->pro = ms_strtab_find(m->strings, "PRO");
}

/* Residue r's N CA C O into out (the first atom of each name, so the first alternate
 * location); 0 when all four are there with finite coordinates. */
static int residue_backbone(const ms_molecule *m, const bb_names *nm, const float *pos,
                            size_t r, float out[12])
{
    long at[5] = {-1, -1, -1, -1, -1};   /* N CA C O, and a terminal O */
    for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++) {
        ms_str name = m->atoms.name[i];
        for (int k = 0; k < 4; k++)
            if (name == nm->atom[k] && at[k] < 0) at[k] = i;
        if ((name == nm->oterm[0] || name == nm->oterm[1]) && at[4] < 0) at[4] = i;
    }
    if (at[3] < 0) at[3] = at[4];
    for (int k = 0; k < 4; k++) {
        if (at[k] < 0) return -1;
        for (int d = 0; d < 3; d++) {
            out[3 * k + d] = pos[3 * (size_t)at[k] + (size_t)d];
            if (!isfinite(out[3 * k + d])) return -1;
        }
    }
    return 0;
}

static void backbone_free(backbone *b)
{
    free(b->bb);
    free(b->seg);
    free(b->residue);
    free(b->proline);
}

/* Protein residues with a whole backbone, in the molecule's order; seg counts changes of
 * chain or segment name between consecutive ones. */
static int gather(const ms_molecule *m, const float *pos, backbone *b, ms_error *err)
{
    size_t cap = m->nresidues ? m->nresidues : 1;
    b->n = 0;
    b->bb = ms_alloc_array(cap, 12 * sizeof *b->bb);
    b->seg = ms_alloc_array(cap, sizeof *b->seg);
    b->residue = ms_alloc_array(cap, sizeof *b->residue);
    b->proline = malloc(cap);
    if (!b->bb || !b->seg || !b->residue || !b->proline) {
        ms_error_set(err, "out of memory for the backbone of %zu residues", m->nresidues);
        return -1;
    }
    bb_names nm;
    find_names(m, &nm);
    const ms_atoms *a = &m->atoms;
    uint32_t seg = 0, prev = 0;
    for (size_t r = 0; r < m->nresidues; r++) {
        uint32_t first = m->res_start[r];
        if (!(a->flags[first] & MS_AF_PROTEIN)) continue;
        if (residue_backbone(m, &nm, pos, r, b->bb + 12 * b->n)) continue;
        int same = a->chain[first] == a->chain[prev] && a->segname[first] == a->segname[prev];
        if (b->n > 0 && !same) seg++;
        b->seg[b->n] = seg;
        b->residue[b->n] = (uint32_t)r;
        b->proline[b->n] = a->resname[first] == nm.pro;
        prev = first;
        b->n++;
    }
    return 0;
}

/* ---------------------------------------------------------------- public */

int ms_ss_compute(ms_molecule *m, long frame, ms_error *err)
{
    if (frame < 0) frame = m->frame >= 0 ? m->frame : (long)m->nframes - 1;
    if (m->nframes == 0 || frame < 0) {
        ms_error_set(err, "molecule %d has no coordinates", m->id);
        return -1;
    }
    if ((size_t)frame >= m->nframes) {
        ms_error_set(err, "molecule %d has no frame %ld (it has %zu)", m->id, frame, m->nframes);
        return -1;
    }
    backbone b = {0, NULL, NULL, NULL, NULL};
    char *codes = NULL;
    const float *pos = ms_mol_frame_pos(m, (size_t)frame, err);
    int rc = pos ? gather(m, pos, &b, err) : -1;
    if (rc == 0 && !(codes = malloc(b.n ? b.n : 1))) {
        ms_error_set(err, "out of memory for the secondary structure of %zu residues", b.n);
        rc = -1;
    }
    if (rc == 0) rc = ms_ss_dssp(b.n, b.bb, b.seg, b.proline, codes, err);
    if (rc == 0) {
        if (m->atoms.n) memset(m->atoms.ss, MS_SS_COIL_CODE, m->atoms.n);
        for (size_t k = 0; k < b.n; k++) {
            uint32_t r = b.residue[k];
            memset(m->atoms.ss + m->res_start[r], codes[k], m->res_start[r + 1] - m->res_start[r]);
        }
        m->ss_known = 1;
    }
    free(codes);
    backbone_free(&b);
    return rc;
}

int ms_ss_ensure(ms_molecule *m, long frame, ms_error *err)
{
    if (m->ss_known || m->nframes == 0 || m->atoms.n == 0) return 0;
    return ms_ss_compute(m, frame, err);
}
