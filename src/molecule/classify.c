/* classify.c: what VMD computes after a load: per-atom defaults (element, mass, radius,
 * hydrogen flag), residues, fragments, protein and nucleic residues from backbone names and
 * connectivity, waters, polymer fragments, and secondary structure from file records. */
#include "config.h"
#include "molecule/analysis.h"
#include "molecule/elements.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---------------------------------------------------------------- per-atom defaults */

static int name_is_hydrogen(const char *name)
{
    if (name[0] == 'H') return 1;
    return isdigit((unsigned char)name[0]) && name[1] == 'H';
}

/* What an atom's defaults take from its name and residue name. */
typedef struct atom_guess {
    ms_str name, resname;  /* MS_STR_NONE: an empty cache slot */
    int z;                 /* the atomic number guessed from them; -1 until needed */
    int hydrogen;
    float name_radius;
} atom_guess;

static void guess_init(const ms_molecule *m, ms_str name, ms_str resname, atom_guess *g)
{
    const char *s = ms_mol_str(m, name);
    g->name = name;
    g->resname = resname;
    g->z = -1;
    g->hydrogen = name_is_hydrogen(s);
    g->name_radius = ms_element_radius_from_name(s);
}

static void defaults_apply(ms_molecule *m, size_t i, atom_guess *g, int have_mass,
                           int have_radius, int have_element)
{
    ms_atoms *a = &m->atoms;
    if (!have_element) {
        if (g->z < 0) g->z = ms_element_guess(ms_mol_str(m, g->name), ms_mol_str(m, g->resname));
        a->atomicnumber[i] = (uint8_t)g->z;
    }
    if (!have_mass) a->mass[i] = ms_element_mass(a->atomicnumber[i]);
    if (!have_radius)
        a->radius[i] = have_element && a->atomicnumber[i]
                           ? ms_element_vdw_radius(a->atomicnumber[i])
                           : g->name_radius;
    if (g->hydrogen)
        a->flags[i] |= MS_AF_HYDROGEN;
    else
        a->flags[i] &= (uint16_t)~MS_AF_HYDROGEN;
}

void ms_analysis_atom_defaults(ms_molecule *m, size_t i, int have_mass, int have_radius,
                               int have_element)
{
    atom_guess g;
    guess_init(m, m->atoms.name[i], m->atoms.resname[i], &g);
    defaults_apply(m, i, &g, have_mass, have_radius, have_element);
}

void ms_analysis_atoms_defaults(ms_molecule *m, size_t first, size_t n, int have_mass,
                                int have_radius)
{
    enum { SLOTS = 1024 };
    atom_guess cache[SLOTS];
    for (size_t k = 0; k < SLOTS; k++) cache[k].name = MS_STR_NONE;
    const ms_atoms *a = &m->atoms;
    for (size_t i = first; i < first + n; i++) {
        ms_str name = a->name[i], res = a->resname[i];
        atom_guess *g = &cache[(uint32_t)(name * 2654435761u + res * 40503u) >> 22];
        if (g->name != name || g->resname != res) guess_init(m, name, res, g);
        defaults_apply(m, i, g, have_mass, have_radius, a->atomicnumber[i] != 0);
    }
}

/* ---------------------------------------------------------------- residues */

static int residues_build(ms_molecule *m, ms_error *err)
{
    ms_atoms *a = &m->atoms;
    size_t n = a->n, nres = 0;
    for (size_t i = 0; i < n; i++) {
        if (i == 0 || a->resid[i] != a->resid[i - 1] || a->insertion[i] != a->insertion[i - 1] ||
            a->chain[i] != a->chain[i - 1] || a->segname[i] != a->segname[i - 1])
            nres++;
        a->residue[i] = (int32_t)(nres - 1);
    }
    uint32_t *rs = ms_alloc_array(nres + 1, sizeof *rs);
    if (!rs) {
        ms_error_set(err, "out of memory for %zu residues", nres);
        return -1;
    }
    for (size_t i = n; i-- > 0;) rs[a->residue[i]] = (uint32_t)i;
    rs[nres] = (uint32_t)n;
    free(m->res_start);
    m->res_start = rs;
    m->nresidues = nres;
    return 0;
}

/* ---------------------------------------------------------------- fragments */

static uint32_t uf_find(uint32_t *parent, uint32_t x)
{
    while (parent[x] != x) {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    return x;
}

static void uf_union(uint32_t *parent, uint32_t x, uint32_t y)
{
    x = uf_find(parent, x);
    y = uf_find(parent, y);
    if (x == y) return;
    if (x < y) parent[y] = x; else parent[x] = y;
}

/* Label connected components of the atoms where include(i) holds, through bonds between
 * included atoms; components are numbered by their first atom; others get -1. Returns the
 * number of components, or -1 on memory exhaustion. */
typedef int (*atom_pred)(const ms_molecule *m, size_t i);

static long components(const ms_molecule *m, atom_pred include, int32_t *label)
{
    size_t n = m->atoms.n;
    uint32_t *parent = ms_alloc_array(n, sizeof *parent);
    if (!parent) return -1;
    for (size_t i = 0; i < n; i++) parent[i] = (uint32_t)i;
    if (m->has_bonds) {
        for (size_t i = 0; i < n; i++) {
            if (include && !include(m, i)) continue;
            for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
                uint32_t j = m->bonds.to[k];
                if (j > i && (!include || include(m, j))) uf_union(parent, (uint32_t)i, j);
            }
        }
    }
    long count = 0;
    for (size_t i = 0; i < n; i++) {
        if (include && !include(m, i)) {
            label[i] = -1;
            continue;
        }
        uint32_t r = uf_find(parent, (uint32_t)i);
        if (r == i) label[i] = (int32_t)count++;
        else label[i] = label[r];
    }
    free(parent);
    return count;
}

/* ---------------------------------------------------------------- polymer classification */

static int is_protein_bb_name(const char *s)
{
    return !strcmp(s, "CA") || !strcmp(s, "C") || !strcmp(s, "O") || !strcmp(s, "N");
}

static int is_protein_terminal_name(const char *s)
{
    return !strcmp(s, "OT1") || !strcmp(s, "OT2") || !strcmp(s, "OXT") || !strcmp(s, "O1") ||
           !strcmp(s, "O2");
}

static int is_nucleic_bb_name(const char *s)
{
    static const char *names[] = {"P",   "O1P", "O2P", "OP1", "OP2", "C3'", "C3*", "O3'",
                                  "O3*", "C4'", "C4*", "C5'", "C5*", "O5'", "O5*", "H5T",
                                  "H3T"};
    for (size_t k = 0; k < MS_COUNTOF(names); k++)
        if (!strcmp(s, names[k])) return 1;
    return 0;
}

/* Is atom i a backbone candidate of the given kind (MS_AF_PROT_BB or MS_AF_NUC_BB)? A
 * terminal oxygen counts when it is bonded to an atom named C of its residue. */
static int bb_candidate(const ms_molecule *m, size_t i, int kind)
{
    const char *name = ms_mol_str(m, m->atoms.name[i]);
    if (kind == MS_AF_NUC_BB) return is_nucleic_bb_name(name);
    if (is_protein_bb_name(name)) return 1;
    if (!is_protein_terminal_name(name) || !m->has_bonds) return 0;
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
        uint32_t j = m->bonds.to[k];
        if (m->atoms.residue[j] == m->atoms.residue[i] &&
            !strcmp(ms_mol_str(m, m->atoms.name[j]), "C"))
            return 1;
    }
    return 0;
}

/* Largest set of connected backbone candidates within residue r; marks its atoms in best[]
 * (indexed from the residue's first atom). Returns its size (0 with fewer than 4). */
static size_t residue_backbone(const ms_molecule *m, size_t r, int kind, uint32_t *cand,
                               uint32_t *stack, uint8_t *best)
{
    size_t first = m->res_start[r], last = m->res_start[r + 1], len = last - first;
    size_t ncand = 0;
    for (size_t k = 0; k < len; k++) {
        cand[k] = (uint32_t)bb_candidate(m, first + k, kind);
        ncand += cand[k];
        best[k] = 0;
    }
    if (ncand < 4) return 0;
    size_t best_size = 0;
    uint32_t label = 2;  /* cand[k]: 0 no, 1 unvisited, >=2 visited component */
    for (size_t k = 0; k < len; k++) {
        if (cand[k] != 1) continue;
        size_t sp = 0, size = 0;
        stack[sp++] = (uint32_t)k;
        cand[k] = label;
        while (sp) {
            uint32_t x = stack[--sp];
            size++;
            size_t ai = first + x;
            if (!m->has_bonds) continue;
            for (uint32_t b = m->bonds.start[ai]; b < m->bonds.start[ai + 1]; b++) {
                uint32_t j = m->bonds.to[b];
                if (j < first || j >= last || cand[j - first] != 1) continue;
                cand[j - first] = label;
                stack[sp++] = j - (uint32_t)first;
            }
        }
        if (size > best_size) {
            best_size = size;
            for (size_t q = 0; q < len; q++) best[q] = cand[q] == label;
        }
        label++;
    }
    return best_size;
}

static int is_water_resname(const char *s)
{
    static const char *names[] = {"H2O", "HHO", "OHH", "HOH", "OH2", "SOL", "WAT",
                                  "TIP", "TIP2", "TIP3", "TIP4", "SPC"};
    for (size_t k = 0; k < MS_COUNTOF(names); k++)
        if (!strcmp(s, names[k])) return 1;
    return 0;
}

static int classify_residues(ms_molecule *m, ms_error *err)
{
    ms_atoms *a = &m->atoms;
    size_t maxlen = 0;
    for (size_t r = 0; r < m->nresidues; r++)
        maxlen = MS_MAX(maxlen, (size_t)(m->res_start[r + 1] - m->res_start[r]));
    uint32_t *cand = ms_alloc_array(maxlen + 1, sizeof *cand);
    uint8_t *best = malloc(maxlen + 1);
    uint32_t *stack = ms_alloc_array(maxlen + 1, sizeof *stack);
    if (!cand || !best || !stack) {
        free(cand);
        free(best);
        free(stack);
        ms_error_set(err, "out of memory classifying residues");
        return -1;
    }
    const uint16_t cleared = (uint16_t) ~(MS_AF_PROTEIN | MS_AF_NUCLEIC | MS_AF_PROT_BB |
                                          MS_AF_NUC_BB | MS_AF_WATER);
    for (size_t r = 0; r < m->nresidues; r++) {
        size_t first = m->res_start[r], last = m->res_start[r + 1];
        for (size_t i = first; i < last; i++) a->flags[i] &= cleared;
        uint16_t whole = 0;
        if (is_water_resname(ms_mol_str(m, a->resname[first]))) {
            whole = MS_AF_WATER;
        } else if (residue_backbone(m, r, MS_AF_PROT_BB, cand, stack, best) >= 4) {
            whole = MS_AF_PROTEIN;
            for (size_t i = first; i < last; i++)
                if (best[i - first]) a->flags[i] |= MS_AF_PROT_BB;
        } else if (residue_backbone(m, r, MS_AF_NUC_BB, cand, stack, best) >= 4) {
            whole = MS_AF_NUCLEIC;
            for (size_t i = first; i < last; i++)
                if (best[i - first]) a->flags[i] |= MS_AF_NUC_BB;
        }
        for (size_t i = first; i < last; i++) a->flags[i] |= whole;
    }
    free(cand);
    free(best);
    free(stack);
    return 0;
}

int ms_analysis_classify(ms_molecule *m, ms_error *err)
{
    if (residues_build(m, err)) return -1;
    long nfrag = components(m, NULL, m->atoms.fragment);
    if (nfrag < 0) {
        ms_error_set(err, "out of memory finding fragments");
        return -1;
    }
    m->nfragments = (size_t)nfrag;
    if (classify_residues(m, err)) return -1;
    free(m->pfrag);
    free(m->nfrag);
    m->pfrag = m->nfrag = NULL;
    return 0;
}

static int is_protein_atom(const ms_molecule *m, size_t i)
{
    return (m->atoms.flags[i] & MS_AF_PROTEIN) != 0;
}

static int is_nucleic_atom(const ms_molecule *m, size_t i)
{
    return (m->atoms.flags[i] & MS_AF_NUCLEIC) != 0;
}

int ms_mol_polymer_fragments(ms_molecule *m, ms_error *err)
{
    if (m->pfrag && m->nfrag) return 0;
    int32_t *p = ms_alloc_array(m->atoms.n, sizeof *p);
    int32_t *q = ms_alloc_array(m->atoms.n, sizeof *q);
    if (!p || !q || components(m, is_protein_atom, p) < 0 ||
        components(m, is_nucleic_atom, q) < 0) {
        free(p);
        free(q);
        ms_error_set(err, "out of memory finding polymer fragments");
        return -1;
    }
    m->pfrag = p;
    m->nfrag = q;
    return 0;
}

/* ---------------------------------------------------------------- secondary structure */

/* Residues keyed by (chain, resid, insertion) in an open-addressing table. */
typedef struct res_key_table {
    uint32_t *slot;  /* residue + 1, 0 = empty */
    size_t mask;
} res_key_table;

static size_t res_hash(ms_str chain, int resid, char ins)
{
    uint64_t h = ((uint64_t)chain * 0x9E3779B97F4A7C15ull) ^ ((uint64_t)(uint32_t)resid << 8) ^
                 (uint8_t)ins;
    h ^= h >> 31;
    h *= 0xBF58476D1CE4E5B9ull;
    return (size_t)(h ^ (h >> 29));
}

static long res_lookup(const ms_molecule *m, const res_key_table *t, ms_str chain, int resid,
                       char ins)
{
    size_t i = res_hash(chain, resid, ins) & t->mask;
    while (t->slot[i]) {
        uint32_t r = t->slot[i] - 1, a0 = m->res_start[r];
        if (m->atoms.chain[a0] == chain && m->atoms.resid[a0] == resid &&
            m->atoms.insertion[a0] == ins)
            return r;
        i = (i + 1) & t->mask;
    }
    return -1;
}

void ms_analysis_apply_ss(ms_molecule *m, const ms_ss_range *r, size_t n)
{
    ms_atoms *a = &m->atoms;
    for (size_t i = 0; i < a->n; i++) a->ss[i] = MS_SS_COIL_CODE;
    if (n == 0 || m->nresidues == 0) return;
    res_key_table t;
    size_t nslots = 16;
    while (nslots < 2 * m->nresidues) nslots *= 2;
    t.slot = calloc(nslots, sizeof *t.slot);
    t.mask = nslots - 1;
    if (!t.slot) return;  /* structure stays coil: a cosmetic loss, never wrong data */
    for (size_t res = 0; res < m->nresidues; res++) {
        uint32_t a0 = m->res_start[res];
        if (res_lookup(m, &t, a->chain[a0], a->resid[a0], a->insertion[a0]) >= 0) continue;
        size_t i = res_hash(a->chain[a0], a->resid[a0], a->insertion[a0]) & t.mask;
        while (t.slot[i]) i = (i + 1) & t.mask;
        t.slot[i] = (uint32_t)res + 1;
    }
    for (size_t k = 0; k < n; k++) {
        long r0 = res_lookup(m, &t, r[k].chain, r[k].resid0, r[k].insertion0);
        if (r0 < 0) continue;
        for (size_t res = (size_t)r0; res < m->nresidues; res++) {
            uint32_t a0 = m->res_start[res];
            if (a->chain[a0] != r[k].chain) break;
            for (uint32_t i = a0; i < m->res_start[res + 1]; i++) a->ss[i] = r[k].code;
            if (a->resid[a0] == r[k].resid1 && a->insertion[a0] == r[k].insertion1) break;
        }
    }
    free(t.slot);
    m->ss_known = 1;
}
