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

static void set_hydrogen(ms_atoms *a, size_t i, int hydrogen)
{
    if (hydrogen)
        a->flags[i] |= MS_AF_HYDROGEN;
    else
        a->flags[i] &= (uint16_t)~MS_AF_HYDROGEN;
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
    set_hydrogen(a, i, g->hydrogen);
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
    /* An open-addressing table of (name, resname) pairs: a few probes find a pair already
     * seen; when its probes are all taken the home slot is reused. */
    enum { SLOTS = 4096, PROBES = 8 };
    atom_guess *cache = malloc(SLOTS * sizeof *cache);
    if (!cache) {
        for (size_t i = first; i < first + n; i++)
            ms_analysis_atom_defaults(m, i, have_mass, have_radius, m->atoms.atomicnumber[i] != 0);
        return;
    }
    for (size_t k = 0; k < SLOTS; k++) cache[k].name = MS_STR_NONE;
    ms_atoms *a = &m->atoms;
    /* An atom with its mass, radius and element given needs only its hydrogen flag, which
     * its name decides: one byte a distinct name (0 not known yet, 1 no, 2 hydrogen). */
    uint32_t nstr = ms_strtab_count(m->strings);
    uint8_t *hyd = have_mass && have_radius && nstr <= 4 * n + 65536 ? calloc(nstr, 1) : NULL;
    for (size_t i = first; i < first + n; i++) {
        ms_str name = a->name[i], res = a->resname[i];
        if (hyd && a->atomicnumber[i] && name < nstr) {
            if (!hyd[name]) hyd[name] = (uint8_t)(1 + name_is_hydrogen(ms_mol_str(m, name)));
            set_hydrogen(a, i, hyd[name] == 2);
            continue;
        }
        uint32_t home = (uint32_t)(name * 2654435761u ^ res * 40503u * 2246822519u) >> 20;
        atom_guess *g = &cache[home];
        for (uint32_t p = 0; p < PROBES; p++) {
            atom_guess *q = &cache[(home + p) & (SLOTS - 1)];
            if ((q->name == name && q->resname == res) || q->name == MS_STR_NONE) {
                g = q;
                break;
            }
        }
        if (g->name != name || g->resname != res) guess_init(m, name, res, g);
        defaults_apply(m, i, g, have_mass, have_radius, a->atomicnumber[i] != 0);
    }
    free(hyd);
    free(cache);
}

/* ---------------------------------------------------------------- residues */

static int residues_build(ms_molecule *m, ms_error *err)
{
    const ms_atoms *a = &m->atoms;
    const int32_t *resid = a->resid;
    const char *ins = a->insertion;
    const ms_str *chain = a->chain, *seg = a->segname;
    int32_t *residue = a->residue;
    size_t n = a->n, nres = 0, cap = 0;
    uint32_t *rs = NULL;   /* each residue's first atom, found in the same pass */
    for (size_t i = 0; i < n; i++) {
        if (i == 0 || resid[i] != resid[i - 1] || ins[i] != ins[i - 1] ||
            chain[i] != chain[i - 1] || seg[i] != seg[i - 1]) {
            if (ms_grow((void **)&rs, &cap, nres + 2, sizeof *rs)) {
                free(rs);
                ms_error_set(err, "out of memory for %zu residues", nres + 1);
                return -1;
            }
            rs[nres++] = (uint32_t)i;
        }
        residue[i] = (int32_t)(nres - 1);
    }
    uint32_t *fit = realloc(rs, (nres + 1) * sizeof *rs);
    if (!fit) {
        free(rs);
        ms_error_set(err, "out of memory for %zu residues", nres);
        return -1;
    }
    fit[nres] = (uint32_t)n;
    free(m->res_start);
    m->res_start = fit;
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
 * number of components. The union-find forest lives in label itself: a parent is always a
 * smaller index than its child (unions link the larger root under the smaller, and path
 * halving only moves a link further down), so one ascending pass turns each atom's parent
 * into its component's number, its parent's number being known by then. */
typedef int (*atom_pred)(const ms_molecule *m, size_t i);

static size_t components(const ms_molecule *m, atom_pred include, int32_t *label)
{
    size_t n = m->atoms.n;
    uint32_t *parent = (uint32_t *)label;
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
    size_t count = 0;
    for (size_t i = 0; i < n; i++) {
        uint32_t p = parent[i];
        if (include && !include(m, i)) label[i] = -1;
        else if (p == i) label[i] = (int32_t)count++;
        else label[i] = label[p];
    }
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

static int is_water_resname(const char *s)
{
    static const char *names[] = {"H2O", "HHO", "OHH", "HOH", "OH2", "SOL", "WAT",
                                  "TIP", "TIP2", "TIP3", "TIP4", "SPC"};
    for (size_t k = 0; k < MS_COUNTOF(names); k++)
        if (!strcmp(s, names[k])) return 1;
    return 0;
}

/* What a string means to the classification, worked out once per distinct string (the
 * molecule's string table) instead of once per atom. */
enum {
    NC_PROT_BB = 1,    /* a protein backbone name: CA C O N */
    NC_PROT_TERM = 2,  /* a protein terminal oxygen: OT1 OT2 OXT O1 O2 */
    NC_NUC_BB = 4,     /* a nucleic backbone name */
    NC_C = 8,          /* the name C */
    NC_WATER = 16      /* a water residue name */
};

typedef struct classify_ctx {
    const ms_molecule *m;
    uint8_t *cls;      /* NC_* of every string id */
    uint32_t nstr;
    uint32_t *cand, *stack;  /* scratch of the longest residue's length */
    uint8_t *best;
} classify_ctx;

static uint8_t string_class(const char *s)
{
    return (uint8_t)((is_protein_bb_name(s) ? NC_PROT_BB : 0) |
                     (is_protein_terminal_name(s) ? NC_PROT_TERM : 0) |
                     (is_nucleic_bb_name(s) ? NC_NUC_BB : 0) | (!strcmp(s, "C") ? NC_C : 0) |
                     (is_water_resname(s) ? NC_WATER : 0));
}

static uint8_t class_of(const classify_ctx *c, ms_str s)
{
    return s < c->nstr ? c->cls[s] : 0;
}

/* Is atom i a backbone candidate of the given kind (MS_AF_PROT_BB or MS_AF_NUC_BB)? A
 * terminal oxygen counts when it is bonded to an atom named C of its residue. */
static int bb_candidate(const classify_ctx *c, size_t i, int kind)
{
    const ms_molecule *m = c->m;
    uint8_t cls = class_of(c, m->atoms.name[i]);
    if (kind == MS_AF_NUC_BB) return (cls & NC_NUC_BB) != 0;
    if (cls & NC_PROT_BB) return 1;
    if (!(cls & NC_PROT_TERM) || !m->has_bonds) return 0;
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
        uint32_t j = m->bonds.to[k];
        if (m->atoms.residue[j] == m->atoms.residue[i] && (class_of(c, m->atoms.name[j]) & NC_C))
            return 1;
    }
    return 0;
}

/* Largest set of connected backbone candidates within residue r; marks its atoms in best[]
 * (indexed from the residue's first atom). Returns its size (0 with fewer than 4). */
static size_t residue_backbone(const classify_ctx *c, size_t r, int kind)
{
    const ms_molecule *m = c->m;
    uint32_t *cand = c->cand, *stack = c->stack;
    uint8_t *best = c->best;
    size_t first = m->res_start[r], last = m->res_start[r + 1], len = last - first;
    size_t ncand = 0;
    for (size_t k = 0; k < len; k++) {
        cand[k] = (uint32_t)bb_candidate(c, first + k, kind);
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

/* The scratch and string classes of one classification; -1 when memory runs out. */
static int classify_ctx_init(classify_ctx *c, const ms_molecule *m)
{
    size_t maxlen = 0;
    for (size_t r = 0; r < m->nresidues; r++)
        maxlen = MS_MAX(maxlen, (size_t)(m->res_start[r + 1] - m->res_start[r]));
    c->m = m;
    c->nstr = ms_strtab_count(m->strings);
    c->cls = malloc((size_t)c->nstr + 1);
    c->cand = ms_alloc_array(maxlen + 1, sizeof *c->cand);
    c->best = malloc(maxlen + 1);
    c->stack = ms_alloc_array(maxlen + 1, sizeof *c->stack);
    if (!c->cls || !c->cand || !c->best || !c->stack) return -1;
    for (uint32_t s = 0; s < c->nstr; s++) c->cls[s] = string_class(ms_mol_str(m, s));
    return 0;
}

static void classify_ctx_free(classify_ctx *c)
{
    free(c->cls);
    free(c->cand);
    free(c->best);
    free(c->stack);
}

static int classify_residues(ms_molecule *m, ms_error *err)
{
    ms_atoms *a = &m->atoms;
    classify_ctx c;
    if (classify_ctx_init(&c, m)) {
        classify_ctx_free(&c);
        ms_error_set(err, "out of memory classifying residues");
        return -1;
    }
    const uint16_t cleared = (uint16_t) ~(MS_AF_PROTEIN | MS_AF_NUCLEIC | MS_AF_PROT_BB |
                                          MS_AF_NUC_BB | MS_AF_WATER);
    for (size_t r = 0; r < m->nresidues; r++) {
        size_t first = m->res_start[r], last = m->res_start[r + 1];
        uint16_t whole = 0, bb = 0;   /* bb: the flag of the atoms best[] marks */
        if (class_of(&c, a->resname[first]) & NC_WATER) {
            whole = MS_AF_WATER;
        } else if (residue_backbone(&c, r, MS_AF_PROT_BB) >= 4) {
            whole = MS_AF_PROTEIN;
            bb = MS_AF_PROT_BB;
        } else if (residue_backbone(&c, r, MS_AF_NUC_BB) >= 4) {
            whole = MS_AF_NUCLEIC;
            bb = MS_AF_NUC_BB;
        }
        for (size_t i = first; i < last; i++)
            a->flags[i] = (uint16_t)((a->flags[i] & cleared) | whole |
                                     (bb && c.best[i - first] ? bb : 0));
    }
    classify_ctx_free(&c);
    return 0;
}

int ms_analysis_classify(ms_molecule *m, ms_error *err)
{
    if (residues_build(m, err)) return -1;
    m->nfragments = components(m, NULL, m->atoms.fragment);
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
    if (!p || !q) {
        free(p);
        free(q);
        ms_error_set(err, "out of memory finding polymer fragments");
        return -1;
    }
    components(m, is_protein_atom, p);
    components(m, is_nucleic_atom, q);
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
