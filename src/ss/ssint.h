/* ssint.h: the secondary structure module's internals, shared by its files and no one else:
 * the backbone chain the DSSP steps work on and its hydrogen bonds. Residues are numbered
 * 0..n-1 in the order of the molecule; the public API is ss.h. */
#ifndef MS_SSINT_H
#define MS_SSINT_H

#include "ss/ss.h"

/* DSSP's constants (Kabsch & Sander 1983). */
#define MS_SS_HBOND_MAX (-0.5f)     /* a hydrogen bond has E below this, kcal/mol */
#define MS_SS_ENERGY_MIN (-9.9f)    /* energies are clamped here */
#define MS_SS_PEPTIDE_MAX 2.5f      /* C(i-1)-N(i) longer than this is a chain break */
#define MS_SS_CA_CUTOFF 9.0f        /* hydrogen bonds are looked for between CA this close */

/* The backbone of nres residues and what the steps derive from it. */
typedef struct ms_ss_chain {
    size_t n;
    const float *bb;          /* N CA C O of residue k at bb[12k ..] */
    const uint32_t *seg;      /* chain of each residue */
    const uint8_t *proline;
    float *h;                 /* amide hydrogen, 3 per residue */
    uint8_t *donor;           /* has an amide H: peptide-bonded to k-1, not proline */
    uint32_t *piece;          /* unbroken runs: k and l are joined by peptide bonds only
                               * when piece[k] == piece[l] */
    int32_t *acc;             /* the two best acceptors of k's N-H (-1: none), 2 per residue */
    float *energy;            /* their energies, kcal/mol (0 when none) */
} ms_ss_chain;

static inline const float *ms_ss_atom(const ms_ss_chain *c, size_t k, int which)
{
    return c->bb + 12 * k + 3 * (size_t)which;   /* which: 0 N, 1 CA, 2 C, 3 O */
}

/* Chain breaks, amide hydrogens (H = N + unit vector C(k-1)->O(k-1) reversed, as DSSP
 * places them), and for every donor its two lowest-energy acceptors (hbond.c). */
int ms_ss_hbonds(ms_ss_chain *c, ms_error *err);

/* Does the N-H of residue d bond to the C=O of residue a (one of d's two best acceptors,
 * with E < -0.5 kcal/mol)? */
static inline int ms_ss_bonded(const ms_ss_chain *c, size_t d, size_t a)
{
    const int32_t *p = c->acc + 2 * d;
    const float *e = c->energy + 2 * d;
    return (p[0] == (int32_t)a && e[0] < MS_SS_HBOND_MAX) ||
           (p[1] == (int32_t)a && e[1] < MS_SS_HBOND_MAX);
}

/* The patterns: ladders and bridges (E, B), then helices (H, G, I), then turns (T), each
 * kept only where a higher-priority code is not already assigned (patterns.c). ss has n
 * codes, all coil on entry. */
int ms_ss_patterns(const ms_ss_chain *c, char *ss, ms_error *err);

#endif
