/* derived.c: selection values computed from the whole structure rather than read from one
 * atom: phi and psi of protein residues (dihedrals through the bonded neighbours' C and N)
 * and VMD's `sidechain`: from each protein CA, the non-backbone neighbour that starts the
 * side chain, then everything bonded to it short of the backbone. */
#include "config.h"
#include "select/selint.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* First atom of residue r named `name`, or -1. */
static long atom_named(const ms_molecule *m, size_t r, ms_str name)
{
    if (name == MS_STR_NONE) return -1;
    for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++)
        if (m->atoms.name[i] == name) return (long)i;
    return -1;
}

/* A bond partner of atom i named `name` in another residue, or -1. */
static long partner_named(const ms_molecule *m, long i, ms_str name)
{
    if (i < 0 || !m->has_bonds) return -1;
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
        uint32_t j = m->bonds.to[k];
        if (m->atoms.name[j] == name && m->atoms.residue[j] != m->atoms.residue[i]) return j;
    }
    return -1;
}

/* The dihedral p0-p1-p2-p3 in degrees, IUPAC sign convention. */
static double dihedral(const float *pos, long i0, long i1, long i2, long i3)
{
    double b[3][3], n1[3], n2[3], m1[3];
    long idx[4] = {i0, i1, i2, i3};
    for (int s = 0; s < 3; s++)
        for (int k = 0; k < 3; k++)
            b[s][k] = (double)pos[3 * idx[s + 1] + k] - (double)pos[3 * idx[s] + k];
    n1[0] = b[0][1] * b[1][2] - b[0][2] * b[1][1];
    n1[1] = b[0][2] * b[1][0] - b[0][0] * b[1][2];
    n1[2] = b[0][0] * b[1][1] - b[0][1] * b[1][0];
    n2[0] = b[1][1] * b[2][2] - b[1][2] * b[2][1];
    n2[1] = b[1][2] * b[2][0] - b[1][0] * b[2][2];
    n2[2] = b[1][0] * b[2][1] - b[1][1] * b[2][0];
    double len = sqrt(b[1][0] * b[1][0] + b[1][1] * b[1][1] + b[1][2] * b[1][2]);
    /* m1 = n1 x (b2/|b2|) */
    m1[0] = (n1[1] * b[1][2] - n1[2] * b[1][1]) / (len > 0 ? len : 1);
    m1[1] = (n1[2] * b[1][0] - n1[0] * b[1][2]) / (len > 0 ? len : 1);
    m1[2] = (n1[0] * b[1][1] - n1[1] * b[1][0]) / (len > 0 ? len : 1);
    double x = n1[0] * n2[0] + n1[1] * n2[1] + n1[2] * n2[2];
    double y = m1[0] * n2[0] + m1[1] * n2[1] + m1[2] * n2[2];
    return -atan2(y, x) * 180.0 / M_PI;
}

int ms_sel_phipsi(ms_selctx *c)
{
    if (c->phi) return 0;
    const ms_molecule *m = c->m;
    c->phi = ms_calloc_array(m->nresidues + 1, sizeof *c->phi);
    c->psi = ms_calloc_array(m->nresidues + 1, sizeof *c->psi);
    if (!c->phi || !c->psi) {
        ms_error_set(c->err, "out of memory computing phi and psi");
        return -1;
    }
    if (!c->pos || !m->res_start) return 0;
    ms_str N = ms_strtab_find(m->strings, "N"), CA = ms_strtab_find(m->strings, "CA"),
           C = ms_strtab_find(m->strings, "C");
    for (size_t r = 0; r < m->nresidues; r++) {
        if (!(m->atoms.flags[m->res_start[r]] & MS_AF_PROTEIN)) continue;
        long n = atom_named(m, r, N), ca = atom_named(m, r, CA), cc = atom_named(m, r, C);
        if (n < 0 || ca < 0 || cc < 0) continue;
        long prev = partner_named(m, n, C), next = partner_named(m, cc, N);
        if (prev >= 0) c->phi[r] = dihedral(c->pos, prev, n, ca, cc);
        if (next >= 0) c->psi[r] = dihedral(c->pos, n, ca, cc, next);
    }
    return 0;
}

static int is_backbone(const ms_molecule *m, uint32_t i)
{
    return (m->atoms.flags[i] & (MS_AF_PROT_BB | MS_AF_NUC_BB)) != 0;
}

static uint32_t nbonds(const ms_molecule *m, uint32_t i)
{
    return m->bonds.start[i + 1] - m->bonds.start[i];
}

/* Of two non-backbone neighbours of a CA, the one that starts the side chain: the one with
 * more bonds; between two lone atoms the heavier (above 2.3 amu); else the first by name. */
static uint32_t pick_seed(const ms_molecule *m, uint32_t b1, uint32_t b2)
{
    uint32_t c1 = nbonds(m, b1), c2 = nbonds(m, b2);
    if (c1 == 1 && c2 > 1) return b2;
    if (c1 != 1 || c2 != 1) return b1;
    float m1 = m->atoms.mass[b1], m2 = m->atoms.mass[b2];
    if (m1 > 2.3f && m2 <= 2.3f) return b2;
    if (m2 > 2.3f && m1 <= 2.3f) return b1;
    return strcmp(ms_mol_str(m, m->atoms.name[b1]), ms_mol_str(m, m->atoms.name[b2])) > 0 ? b2
                                                                                        : b1;
}

/* Mark seeds: one per protein residue with a CA and a non-backbone neighbour. */
static void sidechain_seeds(const ms_molecule *m, uint8_t *mark)
{
    ms_str CA = ms_strtab_find(m->strings, "CA");
    for (size_t r = 0; r < m->nresidues; r++) {
        if (!(m->atoms.flags[m->res_start[r]] & MS_AF_PROTEIN)) continue;
        long ca = atom_named(m, r, CA);
        if (ca < 0) continue;
        long b1 = -1, b2 = -1;
        for (uint32_t k = m->bonds.start[ca]; k < m->bonds.start[ca + 1]; k++) {
            uint32_t j = m->bonds.to[k];
            if (is_backbone(m, j)) continue;
            if (b1 < 0) b1 = j;
            else if (b2 < 0) b2 = j;
        }
        if (b1 >= 0) mark[b2 < 0 ? (uint32_t)b1 : pick_seed(m, (uint32_t)b1, (uint32_t)b2)] = 1;
    }
}

int ms_sel_sidechain(ms_selctx *c)
{
    if (c->sidechain) return 0;
    const ms_molecule *m = c->m;
    size_t n = c->n;
    uint8_t *mark = ms_calloc_array(n, 1);
    uint32_t *stack = ms_alloc_array(n, sizeof *stack);
    if (!mark || !stack) {
        free(mark);
        free(stack);
        ms_error_set(c->err, "out of memory finding side chains");
        return -1;
    }
    if (m->has_bonds && m->res_start) sidechain_seeds(m, mark);
    /* Grow from the seeds through bonds, stopping at backbone atoms. */
    size_t sp = 0;
    for (size_t i = 0; i < n; i++)
        if (mark[i]) stack[sp++] = (uint32_t)i;
    while (sp) {
        uint32_t i = stack[--sp];
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            uint32_t j = m->bonds.to[k];
            if (mark[j] || is_backbone(m, j)) continue;
            mark[j] = 1;
            stack[sp++] = j;
        }
    }
    free(stack);
    c->sidechain = mark;
    return 0;
}
