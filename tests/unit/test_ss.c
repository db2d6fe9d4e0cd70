/* test_ss.c: unit tests of the secondary structure module (src/ss). The assignments are
 * compared with mkdssp 4.2.2 (Debian's `dssp`, an independent DSSP) on real structures: the
 * reference strings below were printed by tests/python/dssp_refs.py, which says how the
 * files were prepared for mkdssp (tests/python/test_ss_dssp.py repeats the comparison live
 * where mkdssp is installed). The hydrogen bonds found through the cell grid are compared
 * with a brute-force search over all pairs written here with its own energy formula;
 * breaks, the on-demand rule and molecules without protein are checked on structures
 * changed in known ways. */
#include "config.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "molecule/analysis.h"
#include "select/select.h"
#include "ss/ssint.h"

#include <math.h>
#include <string.h>

#include "ms_testload.h"

/* ---------------------------------------------------------------- mkdssp's assignments */

/* Runs of consecutive residue numbers of one chain and mkdssp's codes for them. */
typedef struct ref_run {
    const char *chain;
    int resid;
    const char *codes;
} ref_run;

/* tests/python/dssp_refs.py (mkdssp 4.2.2 on the ATOM records, HELIX/SHEET left out). */
static const ref_run ref_1tii[] = {
    {"D", 1, "CCCHHHHHHHTTCCCEEEEEECEEEEEEECCTTTCEEEEEETTCCEEEECCCCCTTHHHH"},
    {"D", 61, "HHHHHHHHHHHHHHCCCEEEEEECCCCCEEEEEEEEEC"},
    {"E", 1, "CCCHHHHHHHTTCCCEEEEEECEEEEEEECCTTTCEEEEEETTCCEEEECCCCCTTHHHH"},
    {"E", 61, "HHHHHHHHHHHHHHCCCEEEEEETTCCCEEEEEEEEEC"},
    {"F", 1, "CCCHHHHHHHHTCCCEEEEEECEEEEEEECCTTTCEEEEEETTCCEEEECCCCCTTHHHH"},
    {"F", 61, "HHHHHHHHHHHHHHTCCEEEEEECCCCCEEEEEEEEEC"},
    {"G", 1, "CCCHHHHHHHTTCCCEEEEEECEEEEEEECCTTTCEEEEEETTCCEEEECCCCCTTHHHH"},
    {"G", 61, "HHHHHHHHHHHHHHTCCEEEEEETTCCCEEEEEEEEEC"},
    {"H", 1, "CCCHHHHHHHHTCCCEEEEEECEEEEEEECCCCCCEEEEEETTCCEEECCCCCCTTHHHH"},
    {"H", 61, "HHHHHHHHHHHHHHCCCEEEEEETTCCCEEEEEEEEEC"},
    {"A", 1, "CEEEEEECCCHHHHHHHTEECCTTCCCCTTTCCCCCCCHHHHHHCC"},
    {"A", 48, "CCCCCCCTTEECCBCCHHHHHHHHHHHCTTCCEEEEEEEECCTTEEEHHHHHGGGCCCGG"},
    {"A", 108, "GCCEEEETCEEGGGEEEEEEEETTEECCCCEECTTCCHHHHTTCCCBCHHHHHTTCCCCT"},
    {"A", 168, "TCGGGGCTTGGGTCCGGGCC"},
    {"C", 195, "CCHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHHCC"},
    {NULL, 0, NULL}};
static const ref_run ref_il2[] = {
    {"", 4, "CHHHHHHHHHHHHHHHHHHHHHHHHHTCCCTTHHHHHTCCBCCBCCCCCGGGGHHHHHTH"},
    {"", 64, "HHHHHHHHHHHTTTC"},
    {"", 83, "CCHHHHHHHHHHHHHCCCCCCCCCBCCCCBCHHHHHHHHHHHHHHHHHHCC"},
    {NULL, 0, NULL}};
static const ref_run ref_pept[] = {{"E", 1, "CEEEETTEEEEEC"}, {NULL, 0, NULL}};
static const ref_run ref_helix_amber[] = {
    {"", 2, "CHHHHHHHHHHHHHHHHHHHHC"}, {"B", 2, "C"}, {NULL, 0, NULL}};

/* The residue of chain/resid (no insertion code), or -1. */
static long find_residue(const ms_molecule *m, const char *chain, int resid)
{
    for (size_t r = 0; r < m->nresidues; r++) {
        uint32_t a = m->res_start[r];
        if (m->atoms.resid[a] == resid && !m->atoms.insertion[a] &&
            !strcmp(ms_mol_str(m, m->atoms.chain[a]), chain))
            return (long)r;
    }
    return -1;
}

static char three_state(char s) { return strchr("HGI", s) ? 'H' : strchr("EB", s) ? 'E' : 'C'; }

/* Every atom of each residue carries one code; count residues agreeing with the reference
 * (8 and 3 states). Returns the number of reference residues. */
static size_t agreement(const ms_molecule *m, const ref_run *ref, size_t *same8, size_t *same3)
{
    size_t n = 0;
    *same8 = *same3 = 0;
    for (const ref_run *run = ref; run->chain; run++)
        for (size_t k = 0; run->codes[k]; k++, n++) {
            long r = find_residue(m, run->chain, run->resid + (int)k);
            if (r < 0) continue;
            uint32_t a0 = m->res_start[r], a1 = m->res_start[r + 1];
            char s = m->atoms.ss[a0];
            int uniform = 1;
            for (uint32_t a = a0; a < a1; a++) uniform &= m->atoms.ss[a] == s;
            if (!uniform) continue;
            *same8 += s == run->codes[k];
            *same3 += three_state(s) == three_state(run->codes[k]);
        }
    return n;
}

static void test_reference(const char *file, const ref_run *ref, size_t *tot, size_t *agree)
{
    ms_molecule *m = load(file);
    if (!m) return;
    ms_error err = {{0}};
    int rc = ms_ss_compute(m, -1, &err);
    t_ok(rc == 0 && m->ss_known, "%s: computed (%s)", file, rc ? err.msg : "ok");
    size_t s8, s3, n = agreement(m, ref, &s8, &s3);
    t_ok(n > 0 && s8 * 100 >= n * 95, "%s: 8-state agreement with mkdssp %zu/%zu (>= 95%%)",
         file, s8, n);
    t_ok(n > 0 && s3 * 100 >= n * 95, "%s: 3-state agreement with mkdssp %zu/%zu (>= 95%%)",
         file, s3, n);
    *tot += n;
    *agree += s8;
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- shapes */

static char code_of(const ms_molecule *m, const char *chain, int resid)
{
    long r = find_residue(m, chain, resid);
    return r < 0 ? '?' : m->atoms.ss[m->res_start[r]];
}

/* Do residues from..to of chain all carry code? */
static int run_is(const ms_molecule *m, const char *chain, int from, int to, char code)
{
    for (int r = from; r <= to; r++)
        if (code_of(m, chain, r) != code) return 0;
    return 1;
}

/* An ideal helix is helix all along but for its ends (no bond reaches past them). */
static void test_ideal_helix(void)
{
    ms_molecule *m = load("helix_amber.pdb");
    if (!m) return;
    ms_error err = {{0}};
    t_ok(ms_ss_compute(m, -1, &err) == 0, "helix_amber: computed");
    t_ok(run_is(m, "", 3, 22, 'H'), "helix_amber: residues 3-22 are alpha helix");
    t_ok(code_of(m, "", 2) == 'C' && code_of(m, "", 23) == 'C',
         "helix_amber: the end residues 2 and 23 are coil (got %c %c)", code_of(m, "", 2),
         code_of(m, "", 23));
    ms_mol_free(m);
}

/* Moving residues 12.. of the helix 40 A away breaks the chain between 11 and 12: 4-turns
 * then end at 7 and start at 12 again, so H covers 3-10 and 13-22 and no pattern spans the
 * break. */
static void test_chain_break(void)
{
    ms_molecule *m = load("helix_amber.pdb");
    if (!m) return;
    long r12 = find_residue(m, "", 12);
    float *pos = m->frames[m->frame].pos;
    for (uint32_t a = m->res_start[r12]; a < m->atoms.n; a++) pos[3 * a] += 40.0f;
    ms_error err = {{0}};
    t_ok(ms_ss_compute(m, -1, &err) == 0, "broken helix: computed");
    t_ok(run_is(m, "", 3, 10, 'H') && run_is(m, "", 13, 22, 'H'),
         "broken helix: 3-10 and 13-22 stay helix");
    t_ok(code_of(m, "", 11) != 'H' && code_of(m, "", 12) != 'H',
         "broken helix: 11 and 12 at the break are not (got %c %c)", code_of(m, "", 11),
         code_of(m, "", 12));
    ms_mol_free(m);
}

/* 1tii's own HELIX/SHEET records and the computed structure cover mostly the same
 * residues (authors' records differ from DSSP at the ends of elements). */
static void test_records_overlap(void)
{
    ms_molecule *m = load("1tii.pdb");
    if (!m) return;
    char *rec = malloc(m->atoms.n);
    memcpy(rec, m->atoms.ss, m->atoms.n);
    ms_error err = {{0}};
    t_ok(ms_ss_compute(m, -1, &err) == 0, "1tii: computed over its records");
    size_t nh = 0, hh = 0, ne = 0, ee = 0, nhelix_any = 0;
    for (size_t r = 0; r < m->nresidues; r++) {
        uint32_t a = m->res_start[r];
        char f = three_state(rec[a]), c = three_state(m->atoms.ss[a]);
        if (!(m->atoms.flags[a] & MS_AF_PROTEIN)) continue;
        if (f == 'H') nh++, hh += c == 'H';
        if (f == 'E') ne++, ee += c == 'E';
        nhelix_any += c == 'H';
    }
    t_ok(nh > 0 && hh * 100 >= nh * 95,
         "1tii: %zu of the %zu residues of HELIX records are computed helix (>= 95%%)", hh, nh);
    t_ok(ne > 0 && ee * 100 >= ne * 95,
         "1tii: %zu of the %zu residues of SHEET records are computed strand (>= 95%%)", ee, ne);
    t_ok(nhelix_any > 0 && hh * 100 >= nhelix_any * 95,
         "1tii: %zu of the %zu computed helix residues lie in HELIX records (>= 95%%)", hh,
         nhelix_any);
    free(rec);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- molecules without protein */

static void test_no_protein(const char *file)
{
    ms_molecule *m = load(file);
    if (!m) return;
    memset(m->atoms.ss, 'H', m->atoms.n);   /* so that coil must be written */
    ms_error err = {{0}};
    int rc = ms_ss_compute(m, -1, &err);
    size_t coil = 0;
    for (size_t i = 0; i < m->atoms.n; i++) coil += m->atoms.ss[i] == 'C';
    t_ok(rc == 0 && m->ss_known && coil == m->atoms.n,
         "%s (no protein): all %zu atoms coil (got %zu)", file, m->atoms.n, coil);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- on demand */

/* pept.pdb has no HELIX/SHEET records: the first selection of a structure word computes
 * its structure (mkdssp: strands 2-5 and 8-12, turn 6-7). */
static void test_selection_computes(void)
{
    ms_molecule *m = load("pept.pdb");
    if (!m) return;
    t_ok(!m->ss_known, "pept: no structure from the file");
    long plain = count(m, "resid 2 to 5 8 to 12");
    t_ok(count(m, "resid 2 to 12") > 0 && !m->ss_known, "other keywords do not compute it");
    long sheet = count(m, "sheet");
    t_ok(m->ss_known && sheet == plain && plain > 0,
         "pept: 'sheet' computes the structure: %ld atoms, those of resid 2-5 8-12 (%ld)",
         sheet, plain);
    t_ok(count(m, "turn") == count(m, "resid 6 7"), "pept: 'turn' is resid 6 7");
    t_ok(count(m, "structure E") == plain && count(m, "helix") == 0,
         "pept: 'structure E' the same, no helix");
    ms_mol_free(m);

    /* il2: the number of helix residues is mkdssp's count of H, G and I */
    m = load("il2.pdb");
    if (!m) return;
    long want = 0;
    for (const ref_run *run = ref_il2; run->chain; run++)
        for (const char *s = run->codes; *s; s++) want += strchr("HGI", *s) != NULL;
    long got = count(m, "helix and name CA");
    t_ok(got == want, "il2: 'helix and name CA' gives mkdssp's %ld helix residues (got %ld)",
         want, got);
    ms_mol_free(m);
}

static void test_ensure(void)
{
    ms_molecule *m = load("pept.pdb");
    if (!m) return;
    ms_error err = {{0}};
    t_ok(ms_ss_ensure(m, -1, &err) == 0 && m->ss_known, "ensure computes when unknown");
    long r3 = find_residue(m, "E", 3);
    m->atoms.ss[m->res_start[r3]] = 'T';   /* as `$sel set structure` would */
    t_ok(ms_ss_ensure(m, -1, &err) == 0 && m->atoms.ss[m->res_start[r3]] == 'T',
         "ensure keeps a known structure");
    t_ok(ms_ss_compute(m, 5, &err) < 0 && strstr(err.msg, "no frame 5"),
         "compute on a frame that does not exist fails (%s)", err.msg);
    ms_mol_free(m);

    m = ms_mol_new(&err);   /* atoms without coordinates */
    for (int i = 0; i < 4; i++) ms_mol_add_blank_atom(m, &err);
    ms_bonds_build(m, NULL, 0, NULL, &err);
    ms_analysis_classify(m, &err);
    err.msg[0] = '\0';
    t_ok(ms_ss_ensure(m, -1, &err) == 0 && !m->ss_known,
         "ensure without coordinates waits for them");
    t_ok(ms_ss_compute(m, -1, &err) < 0 && strstr(err.msg, "no coordinates"),
         "compute without coordinates fails (%s)", err.msg);
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- patterns by hand */

/* A chain of 20 residues in one piece whose hydrogen bonds are set by hand (bond: the N-H
 * of d to the C=O of a, -2 kcal/mol); the expected codes follow from the definitions. */
#define HAND_N 20
typedef struct hand {
    uint32_t seg[HAND_N], piece[HAND_N];
    int32_t acc[2 * HAND_N];
    float energy[2 * HAND_N];
    ms_ss_chain c;
} hand;

static void hand_init(hand *h)
{
    memset(h, 0, sizeof *h);
    for (int k = 0; k < 2 * HAND_N; k++) h->acc[k] = -1;
    h->c = (ms_ss_chain){HAND_N, NULL, h->seg, NULL, NULL, NULL, h->piece, h->acc, h->energy};
}

static void bond(hand *h, int d, int a)
{
    int k = h->acc[2 * d] < 0 ? 0 : 1;
    h->acc[2 * d + k] = a;
    h->energy[2 * d + k] = -2.0f;
}

static void expect_codes(hand *h, const char *want, const char *what)
{
    char ss[HAND_N + 1];
    memset(ss, 'C', HAND_N);
    ss[HAND_N] = '\0';
    ms_error err = {{0}};
    int rc = ms_ss_patterns(&h->c, ss, &err);
    t_ok(rc == 0 && !strcmp(ss, want), "%s: %s (got %s)", what, want, ss);
}

static void test_patterns(void)
{
    hand h;
    /* antiparallel: mutual bonds 2-12 and 4-10 make bridges (2,12), (3,11), (4,10) */
    hand_init(&h);
    bond(&h, 12, 2), bond(&h, 2, 12), bond(&h, 10, 4), bond(&h, 4, 10);
    expect_codes(&h, "CCEEECCCCCEEECCCCCCC", "antiparallel ladder of three bridges");
    /* one pair of mutual bonds: a lone bridge */
    hand_init(&h);
    bond(&h, 12, 2), bond(&h, 2, 12);
    expect_codes(&h, "CCBCCCCCCCCCBCCCCCCC", "isolated bridge");
    /* parallel (i,j): bonds j -> i-1 and i+1 -> j; ladders (3,13)(4,14) and (7,15)(8,16)
     * are joined across a bulge of two residues on one strand and none on the other */
    hand_init(&h);
    bond(&h, 13, 2), bond(&h, 4, 13), bond(&h, 14, 3), bond(&h, 5, 14);
    bond(&h, 15, 6), bond(&h, 8, 15), bond(&h, 16, 7), bond(&h, 9, 16);
    expect_codes(&h, "CCCEEEEEECCCCEEEECCC", "parallel ladders joined across a bulge");
    /* a lone bridge (2,5) before a ladder (5..7, 16..18) whose partner strand runs the
     * other way: no bulge (the gap would be negative); 2-5 is also a 3-turn */
    hand_init(&h);
    bond(&h, 5, 2), bond(&h, 2, 5), bond(&h, 18, 5), bond(&h, 5, 18), bond(&h, 16, 7),
        bond(&h, 7, 16);
    expect_codes(&h, "CCBTTEEECCCCCCCCEEEC", "no bulge across a strand running back");
    /* 4-turns at 2, 3 (H 3-6) and 5-turns at 1, 2 (a pi helix 2-6 would overlap): alpha
     * has priority, as Kabsch & Sander define it; 3-turns at 10, 11 make G 11-13 */
    hand_init(&h);
    bond(&h, 6, 2), bond(&h, 7, 3), bond(&h, 6, 1), bond(&h, 7, 2);
    bond(&h, 13, 10), bond(&h, 14, 11);
    expect_codes(&h, "CCTHHHHCCCCGGGCCCCCC", "alpha before pi; 3-10 helix");
    /* the same turns across a chain break between 4 and 5 are no turns at all */
    for (int k = 5; k < HAND_N; k++) h.piece[k] = 1;
    expect_codes(&h, "CCCCCCCCCCCGGGCCCCCC", "no turn across a break");
}

/* ---------------------------------------------------------------- hydrogen bonds */

typedef struct test_bb {
    size_t n;
    float *bb;
    uint32_t *seg;
    uint8_t *pro;
} test_bb;

/* The backbone of every protein residue with N, CA, C and O, gathered here by name. */
static void gather(const ms_molecule *m, test_bb *b)
{
    static const char *const names[4] = {"N", "CA", "C", "O"};
    const float *pos = m->frames[m->frame].pos;
    b->bb = malloc(m->nresidues * 12 * sizeof *b->bb);
    b->seg = malloc(m->nresidues * sizeof *b->seg);
    b->pro = malloc(m->nresidues);
    b->n = 0;
    for (size_t r = 0; r < m->nresidues; r++) {
        uint32_t a0 = m->res_start[r];
        if (!(m->atoms.flags[a0] & MS_AF_PROTEIN)) continue;
        int found = 0;
        for (int k = 0; k < 4; k++)
            for (uint32_t a = a0; a < m->res_start[r + 1]; a++)
                if (!strcmp(ms_mol_str(m, m->atoms.name[a]), names[k])) {
                    memcpy(b->bb + 12 * b->n + 3 * k, pos + 3 * a, 3 * sizeof(float));
                    found++;
                    break;
                }
        if (found < 4) continue;
        b->seg[b->n] = (uint32_t)m->atoms.chain[a0];
        b->pro[b->n] = !strcmp(ms_mol_str(m, m->atoms.resname[a0]), "PRO");
        b->n++;
    }
}

static double dd(const float *a, const float *b)
{
    return sqrt((double)(a[0] - b[0]) * (a[0] - b[0]) + (double)(a[1] - b[1]) * (a[1] - b[1]) +
                (double)(a[2] - b[2]) * (a[2] - b[2]));
}

/* Kabsch & Sander's energy, written again: q1 q2 f = 0.42 * 0.20 * 332. */
static double ks_energy(const float *n, const float *h, const float *c, const float *o)
{
    double e = 0.42 * 0.20 * 332.0 * (1 / dd(o, n) + 1 / dd(c, h) - 1 / dd(o, h) - 1 / dd(c, n));
    return e < -9.9 ? -9.9 : e;
}

/* The grid's bonds against all pairs: for every donor, the two lowest energies among all
 * acceptors with CA closer than 9 A must be the ones found. */
static void test_hbonds_brute_force(void)
{
    ms_molecule *m = load("1tii.pdb");
    if (!m) return;
    test_bb b;
    gather(m, &b);
    ms_ss_chain c = {b.n, b.bb, b.seg, b.pro, malloc(b.n * 3 * sizeof(float)), malloc(b.n),
                     malloc(b.n * sizeof(uint32_t)), malloc(b.n * 2 * sizeof(int32_t)),
                     malloc(b.n * 2 * sizeof(float))};
    ms_error err = {{0}};
    t_ok(ms_ss_hbonds(&c, &err) == 0, "1tii: hydrogen bonds of %zu residues", b.n);
    size_t bad_h = 0, bad = 0, bonds = 0, donors = 0;
    for (size_t d = 0; d < b.n; d++) {
        const float *n = b.bb + 12 * d, *h = c.h + 3 * d;
        if (!c.donor[d]) continue;
        donors++;
        const float *pc = b.bb + 12 * (d - 1) + 6, *po = pc + 3;   /* previous C, O */
        double dot = 0;
        for (int k = 0; k < 3; k++) dot += (h[k] - n[k]) * (pc[k] - po[k]) / dd(pc, po);
        bad_h += fabs(dd(h, n) - 1.0) > 1e-4 || dot < 1.0 - 1e-4;
        double best[2] = {0, 0};
        for (size_t a = 0; a < b.n; a++) {
            if (a == d || a + 1 == d || dd(b.bb + 12 * d + 3, b.bb + 12 * a + 3) >= 9.0) continue;
            double e = ks_energy(n, h, b.bb + 12 * a + 6, b.bb + 12 * a + 9);
            if (e < best[0]) best[1] = best[0], best[0] = e;
            else if (e < best[1]) best[1] = e;
        }
        for (int k = 0; k < 2; k++) {
            bad += fabs(best[k] - c.energy[2 * d + k]) > 1.5e-3;
            bonds += c.energy[2 * d + k] < -0.5;
        }
    }
    t_ok(bad_h == 0, "1tii: amide H 1 A from N along C=O of the residue before (%zu off)",
         bad_h);
    t_ok(bad == 0 && bonds > 0,
         "1tii: the grid finds the best two acceptors of all %zu donors (%zu bonds; %zu off)",
         donors, bonds, bad);
    free(c.h), free(c.donor), free(c.piece), free(c.acc), free(c.energy);
    free(b.bb), free(b.seg), free(b.pro);
    ms_mol_free(m);
}

int main(void)
{
    t_suite = "ss";
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    size_t tot = 0, agree = 0;
    test_reference("1tii.pdb", ref_1tii, &tot, &agree);
    test_reference("il2.pdb", ref_il2, &tot, &agree);
    test_reference("pept.pdb", ref_pept, &tot, &agree);
    test_reference("helix_amber.pdb", ref_helix_amber, &tot, &agree);
    t_ok(agree * 1000 >= tot * 995, "all four: %zu of %zu residues as mkdssp (>= 99.5%%)", agree,
         tot);
    test_patterns();
    test_ideal_helix();
    test_chain_break();
    test_records_overlap();
    test_no_protein("water648.pdb");
    test_no_protein("names.pdb");
    test_selection_computes();
    test_ensure();
    test_hbonds_brute_force();
    ms_registry_free(&reg);
    return t_done();
}
