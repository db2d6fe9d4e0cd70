/* test_volumes.c: volumetric data and the plugin ABI: the DX, cube and CCP4 readers on grids
 * of known values (i + 10 j + 100 k, written by tests/data/make/make_seeds2.py with Python's
 * struct and text formatting, not by molscope), any CCP4 axis order, statistics and
 * interpolation, write/read round trips, a Gaussian volume written here as plain text and
 * cut by marching cubes at the analytic radius, ABI 1 plugins, and errors naming the
 * record. */
#include "config.h"
#include "builtin/builtin.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "fileio/write.h"
#include "surf/qsurf.h"

#include <math.h>
#include <stdio.h>
#include <string.h>
#include <unistd.h>

static ms_registry reg;

static const char *seed(const char *fmt, const char *name)
{
    static char buf[4][4096];
    static int k;
    k = (k + 1) % 4;
    const char *src = getenv("MS_SRCDIR");
    snprintf(buf[k], sizeof buf[k], "%s/tests/fuzz/corpus/%s/%s", src ? src : ".", fmt, name);
    return buf[k];
}

static const char *scratch(const char *name)
{
    static char buf[4096];
    const char *dir = getenv("MS_TEST_OUT");
    snprintf(buf, sizeof buf, "%s/volumes_%ld_%s", dir ? dir : "/tmp", (long)getpid(), name);
    return buf;
}

static ms_molecule *load(const char *path, ms_error *err)
{
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    return ms_load_new(&reg, path, &o, err);
}

/* Every value of a 3 x 4 x 5 grid is i + 10 j + 100 k. */
static int grid_ok(const ms_volume *v)
{
    if (v->n[0] != 3 || v->n[1] != 4 || v->n[2] != 5) return 0;
    for (int k = 0; k < 5; k++)
        for (int j = 0; j < 4; j++)
            for (int i = 0; i < 3; i++)
                if (v->data[i + 3 * (j + 4 * k)] != (float)(i + 10 * j + 100 * k)) return 0;
    return 1;
}

static void test_grids(void)
{
    t_suite = "volumes";
    ms_error err = {{0}};
    ms_molecule *m = load(seed("dx", "grid345.dx"), &err);
    if (t_ok(m && m->nvolumes == 1 && m->atoms.n == 0, "a .dx makes a molecule with no atoms "
             "and one volume (%s)", err.msg)) {
        const ms_volume *v = &m->volumes[0];
        t_ok(grid_ok(v), "DX: every value of the 3x4x5 grid, reordered from z fastest");
        t_ok(v->origin[0] == 1 && v->origin[1] == 2 && v->origin[2] == 3 &&
                 v->delta[0][0] == 0.5f && v->delta[1][1] == 1 && v->delta[2][2] == 2,
             "DX: origin and deltas");
        t_ok(v->min == 0 && v->max == 432 && fabsf(v->mean - 216.0f) < 1e-4f,
             "statistics: min 0, max 432, mean 216 (%g %g %g)", v->min, v->max, v->mean);
        float p[3] = {1 + 0.5f * 1.5f, 2 + 2.25f, 3 + 2 * 3.5f}; /* grid (1.5, 2.25, 3.5) */
        t_ok(fabsf(ms_volume_value(v, p, -1) - (1.5f + 22.5f + 350.0f)) < 1e-3f,
             "trilinear interpolation of a linear field is exact (%g)",
             ms_volume_value(v, p, -1));
        float out[3] = {0, 0, 0};
        t_ok(ms_volume_value(v, out, -7) == -7, "outside the grid: the outside value");
        /* Round trips through the writers. */
        const char *names[2] = {"rt.dx", "rt.ccp4"};
        for (int k = 0; k < 2; k++) {
            char path[4096];
            snprintf(path, sizeof path, "%s", scratch(names[k]));
            ms_molecule *b = NULL;
            if (ms_write_volume(&reg, v, path, NULL, &err) == 0) b = load(path, &err);
            t_ok(b && b->nvolumes == 1 && grid_ok(&b->volumes[0]) &&
                     fabsf(b->volumes[0].origin[2] - 3) < 1e-6f &&
                     fabsf(b->volumes[0].delta[2][2] - 2) < 1e-6f,
                 "%s written and read back: values, origin, spacing (%s)", names[k], err.msg);
            ms_mol_free(b);
            unlink(path);
        }
    }
    ms_mol_free(m);
    const char *ccp4[2] = {"grid345.ccp4", "grid345_zxy.ccp4"};
    for (int k = 0; k < 2; k++) {
        m = load(seed("ccp4", ccp4[k]), &err);
        t_ok(m && m->nvolumes == 1 && grid_ok(&m->volumes[0]) &&
                 fabsf(m->volumes[0].delta[0][0] - 0.5f) < 1e-6f &&
                 fabsf(m->volumes[0].delta[2][2] - 2.0f) < 1e-6f,
             "CCP4 %s: every value along x y z whatever the axis order, voxel 0.5 1 2 (%s)",
             ccp4[k], err.msg);
        ms_mol_free(m);
    }
    m = load(seed("cube", "grid345.cube"), &err);
    if (t_ok(m && m->nvolumes == 1 && m->atoms.n == 2, "cube: 2 atoms and a volume (%s)",
             err.msg)) {
        const double bohr = 0.529177210903;
        t_ok(grid_ok(&m->volumes[0]), "cube: every value");
        t_ok(fabs(m->volumes[0].origin[1] - 2 * bohr) < 1e-5 &&
                 fabs(m->volumes[0].delta[2][2] - 2 * bohr) < 1e-5 &&
                 fabs(m->frames[0].pos[0] - bohr) < 1e-5 && m->atoms.atomicnumber[0] == 8,
             "cube: Bohr converted to Angstrom, atom 1 is oxygen");
    }
    ms_mol_free(m);
}

/* A Gaussian exp(-r^2 / 2 s^2) written as plain DX text, read, and cut by marching cubes at
 * iso: the surface is the sphere r = s sqrt(2 ln(1 / iso)). */
static void test_gaussian_isosurface(void)
{
    t_suite = "volumes";
    const int n = 41;
    const double h = 0.25, s = 2.0, iso = 0.3, c = 5.0;
    const char *path = scratch("gauss.dx");
    FILE *f = fopen(path, "w");
    if (!t_ok(f != NULL, "write a Gaussian DX file")) return;
    fprintf(f, "object 1 class gridpositions counts %d %d %d\norigin 0 0 0\n", n, n, n);
    fprintf(f, "delta %g 0 0\ndelta 0 %g 0\ndelta 0 0 %g\n", h, h, h);
    fprintf(f, "object 3 class array type double rank 0 items %d data follows\n", n * n * n);
    for (int i = 0; i < n; i++)
        for (int j = 0; j < n; j++)
            for (int k = 0; k < n; k++) {
                double x = i * h - c, y = j * h - c, z = k * h - c;
                fprintf(f, "%.9g\n", exp(-(x * x + y * y + z * z) / (2 * s * s)));
            }
    fclose(f);
    ms_error err = {{0}};
    ms_molecule *m = load(path, &err);
    unlink(path);
    if (!t_ok(m && m->nvolumes == 1, "read the Gaussian (%s)", err.msg)) {
        ms_mol_free(m);
        return;
    }
    const ms_volume *v = &m->volumes[0];
    ms_qsurf_volume q;
    memset(&q, 0, sizeof q);
    for (int d = 0; d < 3; d++) {
        q.n[d] = v->n[d];
        q.origin[d] = v->origin[d];
        for (int e = 0; e < 3; e++) q.axis[d][e] = v->delta[d][e];
    }
    q.data = v->data;
    q.solid[0] = q.solid[1] = q.solid[2] = 1;
    ms_qsurf_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    if (t_ok(ms_qsurf_mc(&q, (float)iso, &mesh, &err) == 0 && mesh.nv > 100,
             "marching cubes on the volume read (%zu vertices) %s", mesh.nv, err.msg)) {
        double want = s * sqrt(2 * log(1 / iso)), worst = 0;
        for (size_t i = 0; i < mesh.nv; i++) {
            double x = mesh.pos[3 * i] - c, y = mesh.pos[3 * i + 1] - c, z = mesh.pos[3 * i + 2] - c;
            worst = fmax(worst, fabs(sqrt(x * x + y * y + z * z) - want));
        }
        double area = ms_qsurf_mesh_area(&mesh), sphere = 4 * M_PI * want * want;
        t_ok(worst < 0.02 * want, "every vertex at the analytic radius %.4f (worst %.4f)", want,
             worst);
        t_ok(fabs(area - sphere) < 0.02 * sphere, "area %.2f of the sphere's %.2f", area, sphere);
    }
    ms_qsurf_mesh_free(&mesh);
    ms_mol_free(m);
}

/* An ABI 1 plugin: its shorter description is padded with NULL volume members. */
/* A skewed 4 x 3 x 5 grid of the linear field f(p) = 1 + 2x - y + 0.5z (trilinear
 * interpolation reproduces it exactly): the sampler, grid-coordinate interpolation with
 * clamping, points and bounds, worked out by hand. */
static void test_sampling(void)
{
    t_suite = "volumes";
    ms_volume v;
    memset(&v, 0, sizeof v);
    const float d[3][3] = {{1, 0, 0}, {0.5f, 1, 0}, {0.25f, 0.5f, 2}};
    v.n[0] = 4, v.n[1] = 3, v.n[2] = 5;
    v.origin[0] = -1, v.origin[1] = 2, v.origin[2] = 0.5f;
    memcpy(v.delta, d, sizeof d);
    float data[60];
    v.data = data;
    for (int k = 0; k < 5; k++)
        for (int j = 0; j < 3; j++)
            for (int i = 0; i < 4; i++) {
                double g[3] = {i, j, k};
                float p[3];
                ms_volume_point(&v, g, p);
                data[i + 4 * (j + 3 * k)] = 1 + 2 * p[0] - p[1] + 0.5f * p[2];
            }
    float p[3] = {-1 + 1.5f + 0.5f * 1.25f + 0.25f * 2.5f, 2 + 1.25f + 0.5f * 2.5f, 0.5f + 2 * 2.5f};
    double want = 1 + 2.0 * p[0] - p[1] + 0.5 * p[2];
    ms_volume_sampler s;
    ms_volume_sampler_init(&s, &v);
    t_ok(s.ok && fabs(ms_volume_sample(&s, p) - want) < 1e-4 &&
             fabs(ms_volume_value(&v, p, -99) - want) < 1e-4,
         "skewed grid: the sampler and ms_volume_value give the field at grid (1.5, 1.25, 2.5) "
         "(%g %g, want %g)", ms_volume_sample(&s, p), ms_volume_value(&v, p, -99), want);
    double g[3] = {-3, 1, 9}, edge[3] = {0, 1, 4};
    float q[3], e[3];
    ms_volume_point(&v, edge, e);
    ms_volume_point(&v, g, q);
    t_ok(fabs(ms_volume_value_at(&v, g) - data[0 + 4 * (1 + 3 * 4)]) < 1e-5 &&
             fabs(ms_volume_sample(&s, q) - (1 + 2 * e[0] - e[1] + 0.5f * e[2])) < 1e-4 &&
             ms_volume_value(&v, q, -99) == -99,
         "outside: clamped to the nearest grid point (the sampler), the outside value (value)");
    float lo[3], hi[3];
    ms_volume_bounds(&v, lo, hi);
    /* corners: origin + {0,3} a + {0,2} b + {0,4} c */
    t_ok(lo[0] == -1 && fabsf(hi[0] - (-1 + 3 + 1 + 1)) < 1e-6f && lo[1] == 2 &&
             fabsf(hi[1] - (2 + 2 + 2)) < 1e-6f && lo[2] == 0.5f && fabsf(hi[2] - 8.5f) < 1e-6f,
         "bounds of the skewed box's corners (%g..%g %g..%g %g..%g)", lo[0], hi[0], lo[1],
         hi[1], lo[2], hi[2]);
    memset(v.delta, 0, sizeof v.delta);
    ms_volume_sampler_init(&s, &v);
    t_ok(!s.ok && ms_volume_sample(&s, p) == 0, "degenerate axes: the sampler says so, gives 0");
}

static void test_abi1(void)
{
    t_suite = "abi";
    unsigned char old[sizeof(ms_plugin)];
    memset(old, 0xAB, sizeof old); /* bytes past an ABI 1 struct must never be read */
    ms_plugin v1;
    memcpy(&v1, ms_plugin_entry_pdb(), sizeof v1);
    v1.abi = 1;
    memcpy(old, &v1, MS_PLUGIN_ABI1_SIZE);
    void *copy = NULL;
    const ms_plugin *p = ms_registry_upgrade((const ms_plugin *)old, &copy);
    t_ok(p && copy && p->read_volume_meta == NULL && p->write_volume == NULL &&
             p->read_structure == v1.read_structure,
         "an ABI 1 description is copied with the new members NULL");
    free(copy);
    ms_plugin v3 = v1;
    v3.abi = MS_PLUGIN_ABI + 1;
    t_ok(ms_registry_upgrade(&v3, &copy) == NULL, "an ABI newer than the host's is refused");
}

/* Errors name the record and the problem. */
static void expect_error(const char *ext, const char *text, const char *want)
{
    const char *path = scratch(ext);
    FILE *f = fopen(path, "w");
    if (f) {
        fputs(text, f);
        fclose(f);
    }
    ms_error err = {{0}};
    ms_molecule *m = load(path, &err);
    t_ok(!m && strstr(err.msg, want) != NULL, "%s: error mentions '%s' (%s)", ext, want, err.msg);
    ms_mol_free(m);
    unlink(path);
}

static void test_errors(void)
{
    t_suite = "errors";
    expect_error("e.dx", "object 1 class gridpositions counts 2 2 2\norigin 0 0 0\n"
                 "delta 1 0 0\ndelta 0 1 0\ndelta 0 0 1\n"
                 "object 3 class array type double rank 0 items 8 data follows\n1 2 3\n4 x 6\n"
                 "7 8\n",
                 "line 8: bad value 'x'");
    expect_error("t.dx", "object 1 class gridpositions counts 2 2 2\norigin 0 0 0\n"
                 "delta 1 0 0\ndelta 0 1 0\ndelta 0 0 1\n"
                 "object 3 class array type double rank 0 items 8 data follows\n"
                 "1.0000 2.0000 3.0000\n",
                 "after 3 of 8 values");
    expect_error("e.cif", "data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n_atom_site.Cartn_y\n"
                 "_atom_site.Cartn_z\n1 1.0 2.0 3.0\n2 1.0 2.x 3.0\n",
                 "atom_site row 2 (id 2): bad Cartn_y '2.x'");
    expect_error("q.cif", "data_x\n_cell.length_a 'open\n", "line 2: unterminated quoted value");
    expect_error("l.cif", "data_x\nloop_\n_atom_site.id\n_atom_site.Cartn_x\n1 2 3\n",
                 "not a multiple of its 2 columns");
    expect_error("e.pqr", "ATOM 1 N MET 1 1.0 2.0 3.0 -0.3\n", "line 1: ATOM record has 9 fields");
    expect_error("e.mol2", "@<TRIPOS>MOLECULE\nm\n2 0\nSMALL\n\n@<TRIPOS>ATOM\n"
                 "1 C 0 0 0 C.3\n2 C 1.x 0 0 C.3\n", "line 8: bad x coordinate '1.x'");
    expect_error("e.coor", "short", "not a NAMD binary file");
}

/* A truncated XTC: the frame that ends early is an error naming it. */
static void test_xtc_truncated(void)
{
    t_suite = "errors";
    const char *src = seed("xtc", "helix16.xtc");
    FILE *f = fopen(src, "rb");
    unsigned char buf[8192];
    size_t n = f ? fread(buf, 1, sizeof buf, f) : 0;
    if (f) fclose(f);
    const char *path = scratch("cut.xtc");
    f = fopen(path, "wb");
    if (f) {
        fwrite(buf, 1, n - 10, f);
        fclose(f);
    }
    ms_molecule *m = NULL;
    ms_error err = {{0}};
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    m = ms_mol_new(&err);
    for (int i = 0; i < 16; i++) ms_mol_add_blank_atom(m, &err);
    int rc = ms_load_add(&reg, m, path, &o, &err);
    t_ok(rc < 0 && strstr(err.msg, "frame 1: truncated") && m->nframes == 0,
         "a truncated second XTC frame fails the load, naming the frame (%s)", err.msg);
    ms_mol_free(m);
    unlink(path);
}

int main(void)
{
    ms_registry_init(&reg);
    if (ms_test_add_builtin(&reg)) return 1;
    test_grids();
    test_gaussian_isosurface();
    test_sampling();
    test_abi1();
    test_errors();
    test_xtc_truncated();
    ms_registry_free(&reg);
    return t_done();
}
