/* test_formats.c: unit tests of the PSF, DCD, XYZ and GRO plugins through the loader, with
 * every plugin linked in. Expected values come from the files' makers (tests/data/make/:
 * each frame is helix_amber.pdb moved by a known rule), from hand-written records in this
 * file, or from the text of the source files; never from output this test just wrote,
 * except in round trips, which compare against the original molecule. */
#include "config.h"
#include "builtin/builtin.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "fileio/write.h"

#include <math.h>
#include <string.h>
#include <unistd.h>

static ms_registry reg;
static char scratch[4096];

static const char *data_path(const char *name)
{
    static char buf[4][4096];
    static int k;
    k = (k + 1) % 4;
    snprintf(buf[k], sizeof buf[k], "%s/%s", t_data(), name);
    return buf[k];
}

/* A scratch file holding text, named with the extension the loader picks the plugin by. */
static const char *write_text(const char *ext, const char *text)
{
    const char *dir = getenv("MS_TEST_OUT");
    snprintf(scratch, sizeof scratch, "%s/formats_%ld.%s", dir ? dir : "/tmp", (long)getpid(), ext);
    FILE *f = fopen(scratch, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    return scratch;
}

static ms_molecule *load(const char *path, ms_error *err)
{
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    return ms_load_new(&reg, path, &o, err);
}

static int add(ms_molecule *m, const char *path, long first, long last, long step, ms_error *err)
{
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    o.first = first;
    o.last = last;
    o.step = step;
    return ms_load_add(&reg, m, path, &o, err);
}

static const char *str(const ms_molecule *m, ms_str id) { return ms_mol_str(m, id); }

static size_t nbonds(const ms_molecule *m)
{
    return m->has_bonds ? m->bonds.start[m->atoms.n] / 2 : 0;
}

/* The largest difference between a frame and PDB + k * step over all atoms. */
static double max_shift_error(const float *pos, const float *pdb, size_t n, int k,
                              const double step[3])
{
    double worst = 0;
    for (size_t i = 0; i < 3 * n; i++) {
        double want = (double)pdb[i] + k * step[i % 3];
        worst = fmax(worst, fabs((double)pos[i] - want));
    }
    return worst;
}

/* make_helix.py's frame k: rotate by 12 k degrees about z, move by (0.5, -0.25, 0.1) k. */
static double max_rotation_error(const float *pos, const float *pdb, size_t n, int k)
{
    double a = 12.0 * k * M_PI / 180.0, c = cos(a), s = sin(a), worst = 0;
    for (size_t i = 0; i < n; i++) {
        const float *p = pdb + 3 * i;
        double want[3] = {c * p[0] - s * p[1] + 0.5 * k, s * p[0] + c * p[1] - 0.25 * k,
                          p[2] + 0.1 * k};
        for (int d = 0; d < 3; d++) worst = fmax(worst, fabs(pos[3 * i + d] - want[d]));
    }
    return worst;
}

static int cell_near(const float *cell, const double want[6], double tol)
{
    for (int k = 0; k < 6; k++)
        if (fabs(cell[k] - want[k]) > tol) return 0;
    return 1;
}

/* ---------------------------------------------------------------- PSF */

static void test_psf_helix(void)
{
    t_suite = "psf";
    ms_error err = {{0}};
    ms_molecule *m = load(data_path("helix.psf"), &err);
    if (!t_ok(m != NULL, "load helix.psf (%s)", err.msg)) return;
    t_ok(m->atoms.n == 392 && m->nframes == 0, "392 atoms, no frames (%zu, %zu)", m->atoms.n,
         m->nframes);
    t_ok(nbonds(m) == 399 && !m->autobonds_pending,
         "the 399 bonds ParmEd wrote, no distance search (%zu)", nbonds(m));
    const ms_atoms *a = &m->atoms;
    t_ok(!strcmp(str(m, a->name[0]), "HH31") && !strcmp(str(m, a->type[0]), "HH31") &&
             !strcmp(str(m, a->resname[0]), "ACE") && a->resid[0] == 1 &&
             !strcmp(str(m, a->segname[0]), "HLXA"),
         "atom 1: HH31 HH31 ACE 1 HLXA");
    t_ok(fabsf(a->charge[0] - 0.09f) < 1e-6f && fabsf(a->charge[1] + 0.179f) < 1e-6f &&
             fabsf(a->charge[391] - 0.096f) < 1e-6f,
         "charges as make_helix.py set them (%g %g %g)", a->charge[0], a->charge[1],
         a->charge[391]);
    t_ok(fabsf(a->mass[0] - 1.0079f) < 1e-5f && fabsf(a->mass[1] - 12.0107f) < 1e-4f,
         "masses from the file (%g %g)", a->mass[0], a->mass[1]);
    t_ok(!strcmp(str(m, a->segname[391]), "HLXB") && !strcmp(str(m, a->resname[391]), "NME") &&
             a->resid[391] == 3,
         "last atom: NME 3 in HLXB");
    t_ok(a->atomicnumber[1] == 6 && a->atomicnumber[0] == 1, "elements guessed from names");
    ms_mol_free(m);
}

static void test_psf_variants(void)
{
    t_suite = "psf";
    ms_error err = {{0}};
    ms_molecule *m = load(data_path("../fuzz/corpus/psf/helix2_charmm.psf"), &err);
    if (t_ok(m != NULL, "CHARMM standard columns with integer types (%s)", err.msg)) {
        t_ok(m->atoms.n == 16 && !strcmp(str(m, m->atoms.type[1]), "16") &&
                 !strcmp(str(m, m->atoms.name[1]), "CH3") &&
                 fabsf(m->atoms.charge[1] + 0.1f) < 1e-6f,
             "atom 2: CH3, type 16, charge -0.1");
        ms_mol_free(m);
    }
    m = load(data_path("../fuzz/corpus/psf/namd.psf"), &err);
    if (t_ok(m != NULL, "NAMD space-separated layout (%s)", err.msg)) {
        const ms_atoms *a = &m->atoms;
        t_ok(!strcmp(str(m, a->segname[0]), "PROTEINA") &&
                 !strcmp(str(m, a->segname[3]), "WATERLONGNAME"),
             "long segment names");
        t_ok(a->resid[0] == 12 && a->insertion[0] == 'A' && a->resid[3] == 13 &&
                 a->insertion[3] == '\0',
             "resid 12A gives resid 12, insertion A");
        t_ok(!strcmp(str(m, a->type[0]), "NH3") && fabsf(a->charge[3] + 0.834f) < 1e-6f,
             "X-PLOR type names and charges");
        t_ok(nbonds(m) == 3, "three bonds (%zu)", nbonds(m));
        ms_mol_free(m);
    }
    /* CHEQ columns after the mass, a blank segment, a resid with an insertion letter. */
    const char *cheq =
        "PSF CHEQ\n\n       1 !NTITLE\n REMARKS hand-written\n\n       2 !NATOM\n"
        "       1      7A   ALA  N    NH1    -0.470000       14.0070           0   0.00000      -0.00000\n"
        "       2 P1   8    GLY  CA   CT2    -0.020000       12.0110           0   0.00000      -0.00000\n"
        "\n       1 !NBOND: bonds\n       1       2\n";
    m = load(write_text("psf", cheq), &err);
    if (t_ok(m != NULL, "CHEQ columns (%s)", err.msg)) {
        const ms_atoms *a = &m->atoms;
        t_ok(!strcmp(str(m, a->segname[0]), "") && !strcmp(str(m, a->segname[1]), "P1") &&
                 a->resid[0] == 7 && a->insertion[0] == 'A' && fabsf(a->mass[1] - 12.011f) < 1e-4f,
             "blank segment, resid 7A, mass before the CHEQ columns");
        t_ok(m->remarks && strstr(m->remarks, "hand-written"), "title kept as a remark");
        ms_mol_free(m);
    }
}

static void psf_error(const char *name, const char *text, const char *want)
{
    ms_error err = {{0}};
    ms_molecule *m = load(write_text("psf", text), &err);
    t_ok(!m && strstr(err.msg, want), "%s: error says '%s' (%s)", name, want, err.msg);
    ms_mol_free(m);
}

static void test_psf_errors(void)
{
    t_suite = "psf";
    const char *head = "PSF\n\n       1 !NTITLE\n REMARKS x\n\n";
    char buf[2048];
    snprintf(buf, sizeof buf, "%s       3 !NATOM\n"
             "       1 A    1    ALA  N    NH1    -0.470000       14.0070           0\n"
             "       2 A    1    ALA  CA   CT1     0.070000       12.0110           0\n"
             "\n       0 !NBOND: bonds\n", head);
    psf_error("too few atoms", buf, "line 9: !NATOM says 3, found 2");
    snprintf(buf, sizeof buf, "%s       2 !NATOM\n"
             "       1 A    1    ALA  N    NH1    -0.470000       14.0070           0\n"
             "       2 A    1    ALA  CA   CT1     0.07x000       12.0110           0\n", head);
    psf_error("bad charge", buf, "line 8: bad charge '0.07x000'");
    snprintf(buf, sizeof buf, "%s       2 !NATOM\n"
             "       1 A    1    ALA  N    NH1    -0.470000       14.0070           0\n"
             "       2 A    1    ALA  CA   CT1     0.070000       12.0110           0\n"
             "\n       2 !NBOND: bonds\n       1       2       1       9\n", head);
    psf_error("bond out of range", buf, "line 11: bond names atom 9, but there are 2 atoms");
    snprintf(buf, sizeof buf, "%s       2 !NATOM\n"
             "       1 A    1    ALA  N    NH1    -0.470000       14.0070           0\n"
             "       2 A    1    ALA  CA   CT1     0.070000       12.0110           0\n"
             "\n       2 !NBOND: bonds\n       1       2\n\n       0 !NTHETA: angles\n", head);
    psf_error("too few bonds", buf, "line 12: !NBOND says 2, found 1");
    psf_error("not a PSF", "ATOM  garbage\n", "line 1: not a PSF file");
    snprintf(buf, sizeof buf, "%s       2 !NATOM\n"
             "       1 A    1    ALA  N    NH1    -0.470000       14.0070           0\n", head);
    psf_error("file ends in the atoms", buf, "!NATOM says 2, found 1 at the end of the file");
}

/* ---------------------------------------------------------------- DCD */

static ms_molecule *psf_with(const char *dcd, ms_error *err)
{
    ms_molecule *m = load(data_path("helix.psf"), err);
    if (m && add(m, data_path(dcd), 0, -1, 1, err)) {
        ms_mol_free(m);
        return NULL;
    }
    return m;
}

static void test_dcd_variants(const float *pdb)
{
    t_suite = "dcd";
    ms_error err = {{0}};
    ms_molecule *m = psf_with("helix_be.dcd", &err);
    if (t_ok(m != NULL, "big-endian DCD (%s)", err.msg)) {
        double step[3] = {1.0, 2.0, -0.5}, worst = 0;
        int cells = 1;
        for (int k = 0; k < 3 && m->nframes == 3; k++) {
            worst = fmax(worst, max_shift_error(m->frames[k].pos, pdb, 392, k, step));
            double want[6] = {40.0 + k, 41, 42, 70, 80, 100};
            cells &= cell_near(m->frames[k].cell, want, 1e-4);
        }
        t_ok(m->nframes == 3 && worst < 1e-5, "3 frames at PDB + k (1, 2, -0.5) (worst %g)", worst);
        t_ok(cells, "cell from cosines: A 40+k, B 41, C 42, angles 70 80 100");
        ms_mol_free(m);
    }
    m = psf_with("helix_fixed.dcd", &err);
    if (t_ok(m != NULL, "fixed-atom DCD (%s)", err.msg)) {
        double step[3] = {0.25, -0.5, 1.0}, zero[3] = {0, 0, 0}, worst = 0;
        for (int k = 0; k < 4 && m->nframes == 4; k++)
            for (size_t i = 0; i < 392; i++) {
                int fixed = (i + 1) % 3 == 0;
                worst = fmax(worst, max_shift_error(m->frames[k].pos + 3 * i, pdb + 3 * i, 1,
                                                    fixed ? 0 : k, fixed ? zero : step));
            }
        t_ok(m->nframes == 4 && worst < 1e-5,
             "4 frames: free atoms move by k (0.25, -0.5, 1), fixed ones stay (worst %g)", worst);
        ms_mol_free(m);
    }
    m = psf_with("helix_4d64.dcd", &err);
    if (t_ok(m != NULL, "64-bit markers, 4D (%s)", err.msg)) {
        double step[3] = {-1, 0, 1}, want[6] = {50, 60, 70, 90, 90, 90};
        t_ok(m->nframes == 2 && max_shift_error(m->frames[1].pos, pdb, 392, 1, step) < 1e-5 &&
                 cell_near(m->frames[1].cell, want, 1e-5),
             "2 frames, the fourth dimension skipped, cell in degrees");
        ms_mol_free(m);
    }
    m = psf_with("helix_xplor.dcd", &err);
    if (t_ok(m != NULL, "X-PLOR DCD (%s)", err.msg)) {
        double step[3] = {0, 0, 3}, zero[6] = {0};
        t_ok(m->nframes == 2 && max_shift_error(m->frames[1].pos, pdb, 392, 1, step) < 1e-5 &&
                 cell_near(m->frames[1].cell, zero, 0),
             "2 frames, no cell");
        ms_mol_free(m);
    }
}

/* Write a molecule's frames as DCD, read them back, compare exactly. */
static void test_dcd_round_trip(ms_molecule *m)
{
    ms_error err = {{0}};
    const char *dir = getenv("MS_TEST_OUT");
    char out[4096];
    snprintf(out, sizeof out, "%s/rt_%ld.dcd", dir ? dir : "/tmp", (long)getpid());
    ms_write_opts wo;
    ms_write_opts_default(&wo);
    long n = ms_write_file(&reg, m, out, &wo, &err);
    t_ok(n == 10, "write 10 frames (%ld: %s)", n, n < 0 ? err.msg : "");
    ms_molecule *r = load(data_path("helix.psf"), &err);
    if (r && !add(r, out, 0, -1, 1, &err) && r->nframes == 10) {
        int same = 1, cells2 = 1;
        for (int k = 0; k < 10; k++) {
            same &= !memcmp(r->frames[k].pos, m->frames[k].pos, 392 * 3 * sizeof(float));
            double want[6];
            for (int c = 0; c < 6; c++) want[c] = m->frames[k].cell[c];
            cells2 &= cell_near(r->frames[k].cell, want, 1e-4);
        }
        t_ok(same, "coordinates read back bit for bit");
        t_ok(cells2, "cells read back (angles through cosines)");
    } else {
        t_ok(0, "read the written DCD back (%s)", err.msg);
    }
    FILE *f = fopen(out, "rb");
    int32_t head[6] = {0};
    if (f) {
        if (fread(head, 4, 6, f) != 6) head[0] = 0;
        fclose(f);
    }
    t_ok(head[0] == 84 && !memcmp(&head[1], "CORD", 4) && head[2] == 10,
         "header: 84-byte record, CORD, NSET 10");
    unlink(out);
    ms_mol_free(r);
}

static void test_dcd_mdanalysis(const float *pdb)
{
    t_suite = "dcd";
    ms_error err = {{0}};
    ms_molecule *m = psf_with("helix.dcd", &err);
    if (!t_ok(m != NULL, "helix.psf + helix.dcd (%s)", err.msg)) return;
    double worst = 0;
    int cells = 1;
    for (int k = 0; k < 10 && m->nframes == 10; k++) {
        worst = fmax(worst, max_rotation_error(m->frames[k].pos, pdb, 392, k));
        double want[6] = {30.0 + k, 32, 34 + 0.5 * k, 80, 95, 100.0 + k};
        cells &= cell_near(m->frames[k].cell, want, 1e-4);
    }
    t_ok(m->nframes == 10 && worst < 2e-5, "10 frames as make_helix.py rotated them (worst %g)",
         worst);
    t_ok(cells, "cells in degrees as MDAnalysis wrote them");

    /* first/last/step: file frames 2, 5, 8. */
    ms_molecule *s = load(data_path("helix.psf"), &err);
    if (s && !add(s, data_path("helix.dcd"), 2, 8, 3, &err))
        t_ok(s->nframes == 3 && max_rotation_error(s->frames[1].pos, pdb, 392, 5) < 2e-5,
             "first 2 last 8 step 3 keeps frames 2 5 8");
    else
        t_ok(0, "first/last/step load (%s)", err.msg);
    ms_mol_free(s);

    test_dcd_round_trip(m);
    ms_mol_free(m);
}

/* Copy the first `keep` bytes of a file (all but -keep bytes when keep < 0) to dst. */
static void copy_prefix(const char *src, const char *dst, long keep)
{
    static unsigned char buf[1 << 16];
    FILE *in = fopen(src, "rb");
    size_t n = in ? fread(buf, 1, sizeof buf, in) : 0;
    if (in) fclose(in);
    size_t k = keep < 0 ? n - (size_t)-keep : (size_t)keep;
    FILE *out = fopen(dst, "wb");
    if (out) {
        fwrite(buf, 1, k < n ? k : n, out);
        fclose(out);
    }
}

static void test_dcd_errors(void)
{
    t_suite = "dcd";
    ms_error err = {{0}};
    ms_molecule *m = load(data_path("pept.pdb"), &err);
    if (m) {
        int rc = add(m, data_path("helix.dcd"), 0, -1, 1, &err);
        t_ok(rc != 0 && strstr(err.msg, "has 392 atoms but molecule") && strstr(err.msg, "has 107"),
             "atom count mismatch names both counts (%s)", err.msg);
        t_ok(m->nframes == 1, "the molecule keeps its frame");
    }
    ms_mol_free(m);
    const char *dir = getenv("MS_TEST_OUT");
    char path[4096];
    snprintf(path, sizeof path, "%s/trunc_%ld.dcd", dir ? dir : "/tmp", (long)getpid());
    copy_prefix(data_path("helix.dcd"), path, -100);
    m = load(data_path("helix.psf"), &err);
    if (m) {
        int rc = add(m, path, 0, -1, 1, &err);
        t_ok(rc != 0 && strstr(err.msg, "frame 9: truncated"),
             "truncated last frame names frame 9 (%s)", err.msg);
        t_ok(m->nframes == 0, "a failed addfile leaves no frames (%zu)", m->nframes);
    }
    ms_mol_free(m);
    copy_prefix(data_path("helix.dcd"), path, 356 + 200); /* 356-byte header, 4784-byte frames */
    m = load(path, &err);
    t_ok(!m && strstr(err.msg, "frame 0: truncated"), "truncated first frame (%s)", err.msg);
    ms_mol_free(m);
    copy_prefix(data_path("helix.dcd"), path, 356);
    m = load(path, &err);
    t_ok(m && m->atoms.n == 392 && m->nframes == 0, "a header without frames: 392 atoms, no "
         "frames (%s)", m ? "" : err.msg);
    ms_mol_free(m);
    copy_prefix(data_path("helix.dcd"), path, 50);
    m = load(path, &err);
    t_ok(!m && strstr(err.msg, "header"), "truncated header (%s)", err.msg);
    ms_mol_free(m);
    unlink(path);
}

/* ---------------------------------------------------------------- XYZ and GRO */

static void test_xyz(const float *pdb)
{
    t_suite = "xyz";
    ms_error err = {{0}};
    ms_molecule *m = load(data_path("helix.xyz"), &err);
    if (t_ok(m != NULL, "helix.xyz (%s)", err.msg)) {
        double worst = 0;
        for (int k = 0; k < 3 && m->nframes == 3; k++)
            worst = fmax(worst, max_rotation_error(m->frames[k].pos, pdb, 392, k));
        t_ok(m->atoms.n == 392 && m->nframes == 3 && worst < 1e-5,
             "392 atoms, 3 frames as written (5 decimals; worst %g)", worst);
        size_t ca = 0, ca_carbon = 0;
        for (size_t i = 0; i < m->atoms.n; i++)
            if (!strcmp(str(m, m->atoms.name[i]), "CA")) {
                ca++;
                ca_carbon += m->atoms.atomicnumber[i] == 6;
            }
        t_ok(!strcmp(str(m, m->atoms.name[0]), "HH31") && ca > 0 && ca == ca_carbon,
             "names from the first column; CA is carbon, not calcium (%zu of %zu)", ca_carbon, ca);
        ms_mol_free(m);
    }
    m = load(data_path("../fuzz/corpus/xyz/numbers.xyz"), &err);
    if (t_ok(m != NULL, "atomic numbers as names (%s)", err.msg)) {
        t_ok(!strcmp(str(m, m->atoms.name[0]), "O") && m->atoms.atomicnumber[0] == 8 &&
                 !strcmp(str(m, m->atoms.name[1]), "H") && m->atoms.atomicnumber[2] == 1,
             "8 -> O, 1 -> H");
        ms_mol_free(m);
    }
    m = load(write_text("xyz", "3\ncomment\nO 0.000 0.000 0.000\nH 1.000 0.000 0.000\n"), &err);
    t_ok(!m && strstr(err.msg, "line 4: the file ends after 2 of 3 atoms"), "truncated (%s)",
         err.msg);
    ms_mol_free(m);
    m = load(write_text("xyz", "2\nc\nO 0 0 0\nH 1 0 0\n3\nc\nO 0 0 0\nH 1 0 0\nH 2 0 0\n"), &err);
    t_ok(!m && strstr(err.msg, "line 5: frame has 3 atoms, expected 2"), "count change (%s)",
         err.msg);
    ms_mol_free(m);
}

static void test_gro(const float *pdb)
{
    t_suite = "gro";
    ms_error err = {{0}};
    ms_molecule *m = load(data_path("spc216.gro"), &err);
    if (t_ok(m != NULL, "spc216.gro (%s)", err.msg)) {
        const ms_atoms *a = &m->atoms;
        /* "    1SOL     OW    1    .230    .628    .113" and box 1.86206 */
        t_ok(m->atoms.n == 648 && !strcmp(str(m, a->name[0]), "OW") &&
                 !strcmp(str(m, a->resname[0]), "SOL") && a->resid[0] == 1 && a->resid[647] == 216,
             "648 atoms, OW SOL 1 ... resid 216");
        const float *p = m->frames[0].pos;
        double want[6] = {18.6206, 18.6206, 18.6206, 90, 90, 90};
        t_ok(fabsf(p[0] - 2.30f) < 1e-5f && fabsf(p[1] - 6.28f) < 1e-5f &&
                 fabsf(p[2] - 1.13f) < 1e-5f && cell_near(m->frames[0].cell, want, 1e-4),
             "nm to Angstrom: 2.30 6.28 1.13, box 18.6206");
        ms_mol_free(m);
    }
    m = load(data_path("helix.gro"), &err);
    if (t_ok(m != NULL, "helix.gro (%s)", err.msg)) {
        double want[6] = {33, 32, 35.5, 80, 95, 103};
        double worst = max_rotation_error(m->frames[0].pos, pdb, 392, 3);
        t_ok(worst < 0.0051, "frame 3 of make_helix.py to GRO's 0.01 A (worst %g)", worst);
        t_ok(cell_near(m->frames[0].cell, want, 2e-3), "triclinic box vectors give %g %g %g %g %g %g",
             m->frames[0].cell[0], m->frames[0].cell[1], m->frames[0].cell[2],
             m->frames[0].cell[3], m->frames[0].cell[4], m->frames[0].cell[5]);
        ms_mol_free(m);
    }
    m = load(data_path("../fuzz/corpus/gro/helix16_vel.gro"), &err);
    if (t_ok(m != NULL, "velocities (%s)", err.msg)) {
        const float *v = m->frames[0].vel;
        t_ok(v && fabsf(v[0] - 1.0f) < 1e-5f && fabsf(v[1] + 2.0f) < 1e-5f &&
                 fabsf(v[47] - 3.0f) < 1e-5f,
             "0.1 -0.2 0.3 nm/ps read as 1 -2 3 A/ps");
        ms_mol_free(m);
    }
    m = load(data_path("../fuzz/corpus/gro/spc6x2.gro"), &err);
    if (t_ok(m != NULL, "two concatenated frames (%s)", err.msg)) {
        t_ok(m->nframes == 2 && fabs(m->frames[1].time - 2.0) < 1e-9, "2 frames, t= 2.0 read");
        ms_mol_free(m);
    }
    m = load(write_text("gro", "t\n    2\n    1SOL     OW    1   0.230   0.628   0.113\n"
                               "    1SOL    HW1    2   0.137   0.626\n   1.0 1.0 1.0\n"), &err);
    t_ok(!m && strstr(err.msg, "line 4: atom line too short"), "short atom line (%s)", err.msg);
    ms_mol_free(m);
    m = load(write_text("gro", "t\n    1\n    1SOL     OW    1   0.230   0.628   0.113\n"), &err);
    t_ok(!m && strstr(err.msg, "line 3: the file ends before the box line"), "no box (%s)",
         err.msg);
    ms_mol_free(m);
}

/* Write a molecule through a plugin and read it back. */
static ms_molecule *round_trip(ms_molecule *m, const char *ext, ms_error *err)
{
    const char *dir = getenv("MS_TEST_OUT");
    char out[4096];
    snprintf(out, sizeof out, "%s/rt_%ld.%s", dir ? dir : "/tmp", (long)getpid(), ext);
    ms_write_opts wo;
    ms_write_opts_default(&wo);
    if (ms_write_file(&reg, m, out, &wo, err) < 0) return NULL;
    ms_molecule *r = load(out, err);
    unlink(out);
    return r;
}

/* A PSF with every connectivity section: five atoms in a chain. */
static const char psf_terms_text[] =
    "PSF\n\n       1 !NTITLE\n REMARKS terms\n\n       5 !NATOM\n"
    "       1 A    1    ALA  C1   C1     0.000000       12.0110           0\n"
    "       2 A    1    ALA  C2   C1     0.000000       12.0110           0\n"
    "       3 A    1    ALA  C3   C1     0.000000       12.0110           0\n"
    "       4 A    1    ALA  C4   C1     0.000000       12.0110           0\n"
    "       5 A    1    ALA  C5   C1     0.000000       12.0110           0\n\n"
    "       4 !NBOND: bonds\n       1       2       2       3       3       4       4       5\n\n"
    "       3 !NTHETA: angles\n       1       2       3       2       3       4       3       4"
    "       5\n\n"
    "       2 !NPHI: dihedrals\n       1       2       3       4       2       3       4       5\n\n"
    "       1 !NIMPHI: impropers\n       3       1       2       4\n\n"
    "       0 !NDON: donors\n\n\n";

static int terms_are(const ms_molecule *m, int kind, size_t n, const uint32_t *want)
{
    const ms_terms *t = &m->terms[kind];
    return t->n == n && !memcmp(t->atoms, want, n * ms_term_width(kind) * sizeof *want);
}

static void test_psf_terms(void)
{
    t_suite = "psf";
    ms_error err = {{0}};
    ms_molecule *m = load(write_text("psf", psf_terms_text), &err);
    if (!t_ok(m != NULL, "load a PSF with angles (%s)", err.msg)) return;
    static const uint32_t ang[] = {0, 1, 2, 1, 2, 3, 2, 3, 4}, dih[] = {0, 1, 2, 3, 1, 2, 3, 4},
                          imp[] = {2, 0, 1, 3};
    t_ok(nbonds(m) == 4, "4 bonds");
    t_ok(terms_are(m, MS_TERM_ANGLE, 3, ang), "3 angles, as listed");
    t_ok(terms_are(m, MS_TERM_DIHEDRAL, 2, dih), "2 dihedrals, as listed");
    t_ok(terms_are(m, MS_TERM_IMPROPER, 1, imp), "1 improper, as listed");
    ms_molecule *r = round_trip(m, "psf", &err);
    t_ok(r && terms_are(r, MS_TERM_ANGLE, 3, ang) && terms_are(r, MS_TERM_DIHEDRAL, 2, dih) &&
             terms_are(r, MS_TERM_IMPROPER, 1, imp),
         "angles, dihedrals and impropers written and read back (%s)", r ? "" : err.msg);
    ms_mol_free(r);
    /* A selection of atoms 1-4 keeps the terms wholly inside it, renumbered. */
    static const uint32_t sel[] = {1, 2, 3, 4}, ang2[] = {0, 1, 2, 1, 2, 3}, dih2[] = {0, 1, 2, 3};
    const char *dir = getenv("MS_TEST_OUT");
    char out[4096];
    snprintf(out, sizeof out, "%s/terms_%ld.psf", dir ? dir : "/tmp", (long)getpid());
    ms_write_opts wo;
    ms_write_opts_default(&wo);
    wo.atoms = sel;
    wo.natoms = 4;
    r = ms_write_file(&reg, m, out, &wo, &err) < 0 ? NULL : load(out, &err);
    unlink(out);
    t_ok(r && terms_are(r, MS_TERM_ANGLE, 2, ang2) && terms_are(r, MS_TERM_DIHEDRAL, 1, dih2) &&
             r->terms[MS_TERM_IMPROPER].n == 0,
         "a selection writes the terms inside it, renumbered (%s)", r ? "" : err.msg);
    ms_mol_free(r);
    ms_mol_free(m);
    char bad[sizeof psf_terms_text + 16];
    snprintf(bad, sizeof bad, "%s", psf_terms_text);
    memcpy(strstr(bad, "       3       4       5\n\n       2 !NPHI") + 16, "       9", 8);
    m = load(write_text("psf", bad), &err);
    t_ok(!m && strstr(err.msg, "angle names atom 9, but there are 5 atoms"),
         "an angle out of range is refused: %s", err.msg);
    ms_mol_free(m);
}

static void test_round_trips(void)
{
    t_suite = "roundtrip";
    ms_error err = {{0}};
    ms_molecule *m = psf_with("helix.dcd", &err);
    if (!m) return;
    ms_molecule *r = round_trip(m, "psf", &err);
    if (t_ok(r != NULL, "PSF written and read (%s)", err.msg)) {
        int same = r->atoms.n == m->atoms.n && nbonds(r) == nbonds(m);
        for (size_t i = 0; same && i < m->atoms.n; i++)
            same = !strcmp(str(r, r->atoms.name[i]), str(m, m->atoms.name[i])) &&
                   !strcmp(str(r, r->atoms.type[i]), str(m, m->atoms.type[i])) &&
                   !strcmp(str(r, r->atoms.segname[i]), str(m, m->atoms.segname[i])) &&
                   r->atoms.resid[i] == m->atoms.resid[i] &&
                   fabsf(r->atoms.charge[i] - m->atoms.charge[i]) < 1e-6f &&
                   fabsf(r->atoms.mass[i] - m->atoms.mass[i]) < 1e-4f &&
                   r->bonds.start[i] == m->bonds.start[i];
        t_ok(same, "names, types, segments, resids, charges, masses and bonds survive");
        ms_mol_free(r);
    }
    r = round_trip(m, "gro", &err);
    if (t_ok(r != NULL, "GRO written and read (%s)", err.msg)) {
        double worst = 0, cellerr = 0;
        for (size_t k = 0; k < m->nframes && r->nframes == m->nframes; k++) {
            for (size_t i = 0; i < 3 * m->atoms.n; i++)
                worst = fmax(worst, fabs(r->frames[k].pos[i] - m->frames[k].pos[i]));
            for (int c = 0; c < 6; c++)
                cellerr = fmax(cellerr, fabs(r->frames[k].cell[c] - m->frames[k].cell[c]));
        }
        t_ok(r->nframes == 10 && worst <= 0.0051 && cellerr < 2e-3,
             "10 frames, coordinates to 0.005 A (%g), triclinic cells (%g)", worst, cellerr);
        ms_mol_free(r);
    }
    ms_mol_free(m);
    m = load(data_path("../fuzz/corpus/psf/namd.psf"), &err);
    r = m ? round_trip(m, "psf", &err) : NULL;
    if (t_ok(r != NULL, "long names written as a NAMD PSF (%s)", err.msg)) {
        t_ok(!strcmp(str(r, r->atoms.segname[3]), "WATERLONGNAME") && r->atoms.insertion[0] == 'A' &&
                 r->atoms.resid[0] == 12 && nbonds(r) == 3,
             "segment names, insertion codes and bonds survive");
        ms_mol_free(r);
    }
    ms_mol_free(m);
}

int main(void)
{
    ms_registry_init(&reg);
    if (ms_test_add_builtin(&reg)) return 1;
    ms_error err = {{0}};
    ms_molecule *pdb = load(data_path("helix_amber.pdb"), &err);
    if (!pdb || pdb->atoms.n != 392) {
        printf("FAIL: formats: helix_amber.pdb: %s\n", err.msg);
        return 1;
    }
    const float *xyz = pdb->frames[0].pos;
    test_psf_helix();
    test_psf_variants();
    test_psf_errors();
    test_psf_terms();
    test_dcd_variants(xyz);
    test_dcd_mdanalysis(xyz);
    test_dcd_errors();
    test_xyz(xyz);
    test_gro(xyz);
    test_round_trips();
    unlink(scratch);
    ms_mol_free(pdb);
    ms_registry_free(&reg);
    return t_done();
}
