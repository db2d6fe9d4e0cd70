/* test_molecule.c: unit tests of the molecule core on real structures: the distance bond
 * search against a brute-force search, the CSR table, residues, fragments, classification,
 * secondary structure from HELIX/SHEET, and transactional loading. The PDB plugin is
 * linked in directly. */
#include "config.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "molecule/analysis.h"
#include "molecule/elements.h"

#include <stdio.h>
#include <string.h>
#include <unistd.h>

#include "builtin/builtin.h"

#include "ms_testload.h"

/* Brute-force distance bonds with the same rule, as an independent reference. */
static size_t brute_bonds(const ms_molecule *m, const float *p)
{
    size_t n = m->atoms.n, count = 0;
    for (size_t i = 0; i < n; i++)
        for (size_t j = i + 1; j < n; j++) {
            if ((m->atoms.flags[i] & m->atoms.flags[j] & MS_AF_HYDROGEN)) continue;
            char a = m->atoms.altloc[i], b = m->atoms.altloc[j];
            if (a && b && a != b) continue;
            float dx = p[3 * i] - p[3 * j], dy = p[3 * i + 1] - p[3 * j + 1],
                  dz = p[3 * i + 2] - p[3 * j + 2];
            float d2 = dx * dx + dy * dy + dz * dz, c = 0.6f * (m->atoms.radius[i] + m->atoms.radius[j]);
            if (d2 < c * c && d2 > 1e-6f) count++;
        }
    return count;
}

static int bonded(const ms_molecule *m, uint32_t i, uint32_t j)
{
    for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
        if (m->bonds.to[k] == j) return 1;
    return 0;
}

static void test_1tii(void)
{
    t_suite = "molecule";
    ms_error err = {{0}};
    ms_molecule *m = load_err("1tii.pdb", &err);
    if (!t_ok(m != NULL, "load 1tii.pdb (%s)", err.msg)) return;
    t_ok(m->atoms.n == 5684, "1tii has 5684 atoms (%zu)", m->atoms.n);
    t_ok(m->nresidues == 927, "927 residues (%zu)", m->nresidues);
    t_ok(m->nframes == 1 && m->frame == 0, "one frame, current");
    size_t nb = m->bonds.start[m->atoms.n] / 2;
    size_t ref = brute_bonds(m, m->frames[0].pos);
    t_ok(nb == ref, "cell-grid bonds equal brute force (%zu vs %zu)", nb, ref);
    t_ok(nb == 5575, "5575 bonds, as MDAnalysis' guess_bonds finds (%zu)", nb);
    t_ok(m->nfragments == 222, "222 fragments (%zu)", m->nfragments);
    int sorted = 1, symmetric = 1;
    for (uint32_t i = 0; i < m->atoms.n; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            if (k > m->bonds.start[i] && m->bonds.to[k] <= m->bonds.to[k - 1]) sorted = 0;
            if (!bonded(m, m->bonds.to[k], i)) symmetric = 0;
        }
    t_ok(sorted && symmetric, "bond rows sorted, every bond listed for both atoms");
    size_t prot = 0, water = 0, bb = 0, hyd = 0, helix = 0, sheet = 0;
    for (size_t i = 0; i < m->atoms.n; i++) {
        prot += (m->atoms.flags[i] & MS_AF_PROTEIN) != 0;
        water += (m->atoms.flags[i] & MS_AF_WATER) != 0;
        bb += (m->atoms.flags[i] & MS_AF_PROT_BB) != 0;
        hyd += (m->atoms.flags[i] & MS_AF_HYDROGEN) != 0;
        helix += m->atoms.ss[i] == 'H';
        sheet += m->atoms.ss[i] == 'E';
    }
    t_ok(water == 215, "215 water atoms (%zu)", water);
    t_ok(prot == 5469, "5469 protein atoms, as by residue name (%zu)", prot);
    t_ok(bb == 4 * 711 || bb > 2800, "protein backbone atoms found (%zu)", bb);
    t_ok(hyd == 0, "no hydrogens in 1tii (%zu)", hyd);
    t_ok(helix > 0 && sheet > 0, "HELIX/SHEET records give helix (%zu) and sheet (%zu) atoms",
         helix, sheet);
    t_ok(m->frames[0].cell[0] > 105.69f && m->frames[0].cell[5] == 120.0f, "CRYST1 cell read");
    /* atom 0: N of GLN? check coordinates against the file's first ATOM line */
    const char *name0 = ms_mol_str(m, m->atoms.name[0]);
    t_ok(name0[0] != '\0' && m->atoms.atomicnumber[0] > 0, "first atom has name %s, element %s",
         name0, ms_element_symbol(m->atoms.atomicnumber[0]));
    ms_mol_free(m);
}

static void test_il2(void)
{
    t_suite = "molecule";
    ms_error err = {{0}};
    ms_molecule *m = load_err("il2.pdb", &err);
    if (!t_ok(m != NULL, "load il2.pdb (%s)", err.msg)) return;
    size_t hyd = 0, prot = 0;
    for (size_t i = 0; i < m->atoms.n; i++) {
        hyd += (m->atoms.flags[i] & MS_AF_HYDROGEN) != 0;
        prot += (m->atoms.flags[i] & MS_AF_PROTEIN) != 0;
    }
    t_ok(m->atoms.n == 2084 && hyd > 900, "il2: 2084 atoms, hydrogens flagged (%zu)", hyd);
    t_ok(prot == m->atoms.n, "il2: every atom is protein (%zu of %zu)", prot, m->atoms.n);
    size_t hh = 0;
    for (uint32_t i = 0; i < m->atoms.n; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
            if ((m->atoms.flags[i] & m->atoms.flags[m->bonds.to[k]] & MS_AF_HYDROGEN)) hh++;
    t_ok(hh == 0, "never an H-H bond");
    t_ok(m->nfragments == 1, "il2 is one fragment (%zu)", m->nfragments);
    ms_mol_free(m);
}

static void test_nucleic(void)
{
    t_suite = "molecule";
    ms_error err = {{0}};
    ms_molecule *m = load_err("names.pdb", &err);
    if (!t_ok(m != NULL, "load names.pdb (%s)", err.msg)) return;
    size_t nuc = 0, nbb = 0;
    for (size_t i = 0; i < m->atoms.n; i++) {
        nuc += (m->atoms.flags[i] & MS_AF_NUCLEIC) != 0;
        nbb += (m->atoms.flags[i] & MS_AF_NUC_BB) != 0;
    }
    t_ok(nuc == 82 && nbb > 0, "starred sugar names: 82 nucleic atoms, 4 waters not (%zu of %zu, %zu backbone)",
         nuc, m->atoms.n, nbb);
    ms_mol_free(m);
}

static void write_file(const char *path, const char *text)
{
    FILE *f = fopen(path, "w");
    fputs(text, f);
    fclose(f);
}

static void test_bad_input(void)
{
    t_suite = "load";
    char path[] = "/tmp/ms_test_XXXXXX.pdb";
    int fd = mkstemps(path, 4);
    close(fd);
    ms_error err = {{0}};
    ms_load_opts o;
    ms_load_opts_default(&o);
    write_file(path, "ATOM      1  N   SER A   4      17.166  -7.606  -4.933  1.00 44.05           N\n"
                     "ATOM      2  CA  SER A   4      17.9x8  -6.979  -3.851  1.00 44.75           C\n");
    t_ok(!ms_load_new(&reg, path, &o, &err) && strstr(err.msg, "line 2") &&
             strstr(err.msg, "x coordinate"),
         "bad coordinate names line and field (%s)", err.msg);
    write_file(path, "ATOM      1  N   SER A   4      17.166  -7.606\n");
    t_ok(!ms_load_new(&reg, path, &o, &err) && strstr(err.msg, "line 1"),
         "truncated record is an error (%s)", err.msg);
    write_file(path, "REMARK nothing here\n");
    t_ok(!ms_load_new(&reg, path, &o, &err) && strstr(err.msg, "no ATOM"),
         "a file without atoms is an error (%s)", err.msg);
    write_file(path, "MODEL 1\n"
                     "ATOM      1  N   SER A   4      17.166  -7.606  -4.933  1.00 44.05           N\n"
                     "ATOM      2  CA  SER A   4      17.918  -6.979  -3.851  1.00 44.75           C\n"
                     "ENDMDL\nMODEL 2\n"
                     "ATOM      1  N   SER A   4      17.166  -7.606  -4.933  1.00 44.05           N\n"
                     "ENDMDL\n");
    o.waitfor = -1;
    t_ok(!ms_load_new(&reg, path, &o, &err) && strstr(err.msg, "1 atoms, expected 2"),
         "a short second model is an error with waitfor all (%s)", err.msg);
    write_file(path, "ATOM  A0000  N   SER AA000      17.166  -7.606  -4.933  1.00 44.05           N\n"
                     "ATOM  A0001  CA  SER AA000      17.918  -6.979  -3.851  1.00 44.75           C\n"
                     "CONECTA0000A0001\n");
    ms_molecule *m = ms_load_new(&reg, path, &o, &err);
    t_ok(m && m->atoms.resid[0] == 10000 && bonded(m, 0, 1), "hybrid-36 serials, resids, CONECT");
    ms_mol_free(m);
    unlink(path);
    t_ok(!ms_load_new(&reg, "/nonexistent/x.pdb", &o, &err) && strstr(err.msg, "No such file"),
         "a missing file says so (%s)", err.msg);
}

/* The bond table of m as its pairs i < j, ascending (as a js file lists them); *n pairs. */
static uint32_t *ordered_pairs(const ms_molecule *m, size_t *n)
{
    size_t nb = m->bonds.start[m->atoms.n] / 2, k = 0;
    uint32_t *p = malloc(2 * nb * sizeof *p + 1);
    for (uint32_t i = 0; p && i < m->atoms.n; i++)
        for (uint32_t b = m->bonds.start[i]; b < m->bonds.start[i + 1]; b++)
            if (m->bonds.to[b] > i) {
                p[2 * k] = i;
                p[2 * k + 1] = m->bonds.to[b];
                k++;
            }
    *n = k;
    return p;
}

static int same_table(const ms_molecule *a, const uint32_t *start, const uint32_t *to,
                      const float *order)
{
    size_t n = a->atoms.n;
    if (memcmp(a->bonds.start, start, (n + 1) * sizeof *start)) return 0;
    if (memcmp(a->bonds.to, to, start[n] * sizeof *to)) return 0;
    return !order || (a->bonds.order && !memcmp(a->bonds.order, order, start[n] * sizeof *order));
}

/* The CSR table from pairs in order (no sorting pass) equals the one from the same bonds
 * reversed, shuffled and given twice, with a self pair and an atom out of range; orders
 * follow their bonds either way. */
static void test_bond_table_order(void)
{
    t_suite = "molecule";
    ms_error err = {{0}};
    ms_molecule *m = load_err("1tii.pdb", &err);
    if (!t_ok(m != NULL, "load 1tii.pdb (%s)", err.msg)) return;
    size_t np, n = m->atoms.n;
    uint32_t *p = ordered_pairs(m, &np);
    uint32_t *q = malloc((4 * np + 4) * sizeof *q), *start = malloc((n + 1) * sizeof *start);
    float *op = malloc(np * sizeof *op), *oq = malloc((2 * np + 2) * sizeof *oq);
    uint32_t *to = malloc(2 * np * sizeof *to + 1);
    float *ord = malloc(2 * np * sizeof *ord + 1);
    if (!t_ok(p && q && start && op && oq && to && ord, "memory")) return;
    for (size_t k = 0; k < np; k++) op[k] = (float)(1 + k % 3);
    t_ok(ms_bonds_build(m, p, np, op, &err) == 0, "table from pairs in order");
    memcpy(start, m->bonds.start, (n + 1) * sizeof *start);
    memcpy(to, m->bonds.to, start[n] * sizeof *to);
    memcpy(ord, m->bonds.order, start[n] * sizeof *ord);
    size_t nq = 0;
    for (size_t k = 0; k < np; k++) {   /* every bond twice, the second copy reversed */
        size_t a = (k * 7919) % np;     /* 7919 is prime and does not divide np */
        q[2 * nq] = p[2 * a + 1], q[2 * nq + 1] = p[2 * a], oq[nq++] = op[a];
        q[2 * nq] = p[2 * a], q[2 * nq + 1] = p[2 * a + 1], oq[nq++] = op[a];
    }
    q[2 * nq] = 5, q[2 * nq + 1] = 5, oq[nq++] = 9;
    q[2 * nq] = 0, q[2 * nq + 1] = (uint32_t)n, oq[nq++] = 9;
    t_ok(np % 7919 != 0 && ms_bonds_build(m, q, nq, oq, &err) == 0 &&
             same_table(m, start, to, ord),
         "the same table from %zu bonds shuffled, reversed, duplicated, with bad pairs", np);
    t_ok(ms_bonds_build(m, p, np, NULL, &err) == 0 && same_table(m, start, to, NULL) &&
             !m->bonds.order,
         "pairs in order without orders: the same partners, no orders");
    free(p), free(q), free(start), free(op), free(oq), free(to), free(ord);
    ms_mol_free(m);
}

/* Atoms added with some arrays given are zero in the others (the secondary structure coil). */
static void test_atoms_given(void)
{
    t_suite = "molecule";
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    if (!t_ok(m != NULL, "new molecule")) return;
    ms_atoms *a = &m->atoms;
    long first = ms_mol_add_blank_atoms(m, 3, &err);
    a->beta[1] = 7.0f, a->resid[2] = 4;
    void *given[] = {&a->beta, &a->ss};
    long more = ms_mol_add_atoms_given(m, 2000, given, 2, &err);
    int zero = 1;
    for (size_t i = 3; i < a->n; i++) {
        a->beta[i] = 1.0f, a->ss[i] = 'H';
        zero &= a->resid[i] == 0 && a->charge[i] == 0 && a->flags[i] == 0 && a->name[i] == 0;
    }
    t_ok(first == 0 && more == 3 && a->n == 2003 && zero && a->beta[1] == 7.0f &&
             a->resid[2] == 4 && a->ss[0] == 'C',
         "2000 atoms added to 3: the arrays not given are blank, the first atoms kept");
    ms_mol_free(m);
}

/* Resident memory of this process in bytes (VmRSS). */
static size_t rss_bytes(void)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    size_t kb = 0;
    while (f && fgets(line, sizeof line, f))
        if (sscanf(line, "VmRSS: %zu kB", &kb) == 1) break;
    if (f) fclose(f);
    return kb * 1024;
}

/* A reader's atom count is a hint: one as large as the memory available reserves address
 * space but commits no pages (a header claiming more atoms than its file holds). */
static void test_reserve_hint(void)
{
    t_suite = "molecule";
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    if (!t_ok(m != NULL, "new molecule")) return;
    size_t n = ms_mem_available() / 64, before = rss_bytes();
    if (ms_mol_reserve_atoms(m, n, &err)) {
        t_ok(err.msg[0] != 0, "a reserve that cannot be had says so");
    } else {
        size_t grew = rss_bytes() - before;
        t_ok(grew < ((size_t)64 << 20), "a hint of %zu atoms (all the memory available) "
             "commits no pages: resident memory grew by %zu bytes", n, grew);
    }
    ms_mol_free(m);
}

int main(void)
{
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    test_1tii();
    test_bond_table_order();
    test_atoms_given();
    test_reserve_hint();
    test_il2();
    test_nucleic();
    test_bad_input();
    ms_registry_free(&reg);
    return t_done();
}
