/* test_qsurf.c: unit tests of the QuickSurf engine against values known independently:
 * the exp2 approximation against libm, VMD's grid rules worked by hand, one atom's surface
 * against the analytic isosurface radius, the density map against a double-precision
 * brute-force sum, and on 1tii (loaded through the core with the PDB plugin): a closed,
 * consistently oriented surface, the same mesh in one pass, in many forced slabs and on
 * the OpenCL path, red vertices next to oxygens under element colours, one bead per
 * residue; plus marching cubes on an analytic field with skewed axes. */
#include "config.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "surf/qsurf_impl.h"

#include <dirent.h>
#include <float.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "builtin/builtin.h"

static ms_registry reg;

/* ---------------------------------------------------------------- mesh checks */

static int cmp_u64(const void *a, const void *b)
{
    uint64_t x = *(const uint64_t *)a, y = *(const uint64_t *)b;
    return x < y ? -1 : x > y;
}

/* Closed and consistently oriented: every directed edge once, and its reverse once, so
 * every undirected edge belongs to exactly two triangles. Also: indices in range, no
 * triangle repeating a vertex. Returns the number of violations. */
static size_t mesh_defects(const ms_qsurf_mesh *m)
{
    size_t ne = 3 * m->nt, bad = 0;
    uint64_t *e = malloc((ne ? ne : 1) * sizeof *e);
    if (!e) return SIZE_MAX;
    for (size_t t = 0; t < m->nt; t++) {
        const uint32_t *i = m->index + 3 * t;
        if (i[0] >= m->nv || i[1] >= m->nv || i[2] >= m->nv) bad++;
        if (i[0] == i[1] || i[1] == i[2] || i[0] == i[2]) bad++;
        for (int k = 0; k < 3; k++) e[3 * t + k] = (uint64_t)i[k] << 32 | i[(k + 1) % 3];
    }
    qsort(e, ne, sizeof *e, cmp_u64);
    for (size_t k = 0; k < ne; k++) {
        if (k + 1 < ne && e[k] == e[k + 1]) bad++;
        uint64_t rev = e[k] << 32 | e[k] >> 32;
        if (!bsearch(&rev, e, ne, sizeof *e, cmp_u64)) bad++;
    }
    free(e);
    return bad;
}

static double signed_volume(const ms_qsurf_mesh *m)
{
    double v = 0.0;
    for (size_t t = 0; t < m->nt; t++) {
        const ms_qsurf_pos_t *a = m->pos + 3 * m->index[3 * t];
        const ms_qsurf_pos_t *b = m->pos + 3 * m->index[3 * t + 1];
        const ms_qsurf_pos_t *c = m->pos + 3 * m->index[3 * t + 2];
        v += (a[0] * ((double)b[1] * c[2] - (double)b[2] * c[1]) +
              a[1] * ((double)b[2] * c[0] - (double)b[0] * c[2]) +
              a[2] * ((double)b[0] * c[1] - (double)b[1] * c[0])) / 6.0;
    }
    return v;
}

/* ---------------------------------------------------------------- fast exp2 */

static void test_exp2(void)
{
    t_suite = "qsurf";
    double worst = 0.0;
    for (int i = 0; i <= 1200000; i++) {
        float e = -12.0f * (float)i / 1200000.0f;
        double rel = fabs((double)ms_qsurf_exp2(e) / exp2((double)e) - 1.0);
        worst = MS_MAX(worst, rel);
    }
    t_ok(worst < 5e-6, "fast exp2 relative error %.2e over [-12, 0] (VMD's: 1.3e-3)", worst);
}

/* ---------------------------------------------------------------- quantization */

/* The 8-bit normal and colour codes against the rule computed in double precision: v = f *
 * 127.5 - 0.5 (f * 255 for colours), clamped to the codes' range, rounded half away from
 * zero; NaN gives the lowest code. */
static void test_quantize(void)
{
    t_suite = "qsurf";
    int bad_n = 0, bad_c = 0;
    for (int i = -13000; i <= 13000; i++) {
        float f = (float)i / 10000.0f;
        double v = (double)(f * 127.5f - 0.5f), u = (double)(f * 255.0f);
        v = fmin(fmax(v, -128.0), 127.0), u = fmin(fmax(u, 0.0), 255.0);
        long wn = v >= 0 ? (long)floor(v + 0.5) : -(long)floor(0.5 - v), wc = (long)floor(u + 0.5);
        bad_n += ms_qsurf_snorm(f, 127.5f) != wn;
        bad_c += ms_qsurf_unorm(f, 255.0f) != wc;
    }
    t_ok(!bad_n && !bad_c, "8-bit codes of normals and colours over [-1.3, 1.3] follow the rule "
         "(%d and %d differ)", bad_n, bad_c);
    t_ok(ms_qsurf_snorm(1.0f, 127.5f) == 127 && ms_qsurf_snorm(-1.0f, 127.5f) == -128 &&
             ms_qsurf_snorm(0.0f, 127.5f) == -1 && ms_qsurf_snorm(NAN, 127.5f) == -128 &&
             ms_qsurf_snorm(INFINITY, 127.5f) == 127 && ms_qsurf_unorm(NAN, 255.0f) == 0 &&
             ms_qsurf_unorm(INFINITY, 255.0f) == 255 && ms_qsurf_unorm(0.5f, 255.0f) == 128,
         "normal codes: 1 -> 127, -1 -> -128, 0 -> -1, NaN -> -128; colour 0.5 -> 128, NaN -> 0");
}

/* ---------------------------------------------------------------- grid rules */

static void test_grid_rules(void)
{
    t_suite = "qsurf";
    float pos[6] = {0, 0, 0, 3, 0, 0}, rad[2] = {1.0f, 1.0f};
    ms_qsurf_atoms a = {.n = 1, .pos = pos, .radius = rad};
    ms_qsurf_params p;
    ms_qsurf_grid g;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    /* p = 1.7; pad = max(1.7, 0.65 sqrt(4/3 pi 1.7^3)) = 2.94870; N = ceil(2 pad / h). */
    int rc = ms_qsurf_grid_setup(&a, &p, &g, &err);
    t_ok(rc == 0 && fabsf(g.pad - 2.94870f) < 1e-4f && fabsf(g.origin[0] + 2.94870f) < 1e-4f,
         "padding 0.65 sqrt(4/3 pi p^3) and origin (pad %g, origin %g)", g.pad, g.origin[0]);
    t_ok(g.n[0] == 6 && g.n[1] == 6 && g.n[2] == 6 && g.gausslim == 2.0f,
         "N = ceil((extent + 2 pad) / h) = 6 per axis, gausslim 2 at quality 0 (%d %d %d)",
         g.n[0], g.n[1], g.n[2]);
    a.n = 2, p.gridspacing = 0.5f, p.quality = 3;
    ms_qsurf_grid_setup(&a, &p, &g, &err);
    t_ok(g.n[0] == 18 && g.n[1] == 12 && g.gausslim == 4.0f,
         "two atoms 3 A apart at h 0.5: 18 x 12 points, gausslim 4 at quality 3 (%d %d)",
         g.n[0], g.n[1]);
    rad[0] = rad[1] = 5.0f, p.gridspacing = 1.0f;
    ms_qsurf_grid_setup(&a, &p, &g, &err);
    t_ok(g.h == 5.0f, "coarse-grained (minrad 5 > 4 A): spacing x minrad = %g", g.h);
    float all[4] = {0.0005f, 1.0f, 1.5f, 3.0f}, lo, hi;
    uint32_t sel[2] = {1, 2};
    ms_qsurf_radius_range(all, 4, sel, 2, &lo, &hi);
    t_ok(lo == 1.0f && hi == 1.5f, "minrad <= 0.001: range from the selection (%g %g)", lo, hi);
    all[0] = 0.9f;
    ms_qsurf_radius_range(all, 4, sel, 2, &lo, &hi);
    t_ok(lo == 1.0f && hi == 1.5f, "max/min > 2.5: range from the selection (%g %g)", lo, hi);
    all[3] = 2.0f;
    ms_qsurf_radius_range(all, 4, sel, 2, &lo, &hi);
    t_ok(lo == 0.9f && hi == 2.0f, "otherwise the whole molecule's range (%g %g)", lo, hi);
    p.radscale = 0.0f;
    t_ok(ms_qsurf_grid_setup(&a, &p, &g, &err) < 0 && strstr(err.msg, "radius scale"),
         "radius scale 0 is refused (%s)", err.msg);
    p.radscale = 1.0f, rad[0] = rad[1] = 0.0f;
    t_ok(ms_qsurf_grid_setup(&a, &p, &g, &err) < 0 && strstr(err.msg, "no atoms"),
         "atoms without radius are refused (%s)", err.msg);
}

/* ---------------------------------------------------------------- one atom */

static void check_sphere(float h, int quality, float radius, float iso)
{
    float pos[3] = {1.25f, -2.5f, 0.75f}, rgb[3] = {0.2f, 0.4f, 0.6f};
    ms_qsurf_atoms a = {.n = 1, .pos = pos, .radius = &radius, .rgb = rgb};
    ms_qsurf_params p;
    ms_qsurf_mesh m = {0};
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    p.gridspacing = h, p.quality = quality, p.isovalue = iso, p.backend = MS_QSURF_CPU;
    if (!t_ok(ms_qsurf_surface(&a, &p, &m, NULL, &err) == 0 && m.nt > 0,
              "one atom (h %g): surface (%s)", h, err.msg))
        return;
    /* exp(-R^2 / 2 sigma^2) = iso, sigma = radscale * r */
    double want = radius * sqrt(-2.0 * log(iso)), worst = 0.0, mean = 0.0, mindot = 1.0;
    int colors_ok = 1;
    for (size_t v = 0; v < m.nv; v++) {
        double d[3], len = 0.0, dot = 0.0;
        for (int k = 0; k < 3; k++) d[k] = m.pos[3 * v + k] - pos[k], len += d[k] * d[k];
        len = sqrt(len);
        for (int k = 0; k < 3; k++) dot += d[k] / len * ms_qsurf_unpack_normal(m.normal[3 * v + k]);
        worst = MS_MAX(worst, fabs(len - want));
        mean += len / (double)m.nv;
        mindot = MS_MIN(mindot, dot);
        for (int k = 0; k < 3; k++)
            if (abs((int)m.color[4 * v + k] - (int)lrintf(rgb[k] * 255.0f)) > 1) colors_ok = 0;
    }
    t_ok(worst <= h, "one atom (h %g, q %d): every vertex within one spacing of R = %.4f "
         "(worst %.4f, mean %.4f)", h, quality, want, worst, mean);
    t_ok(fabs(mean - want) < 0.02 * want, "one atom (h %g): mean radius within 2%% (%.4f)", h,
         mean);
    t_ok(mindot > 0.95, "one atom (h %g): normals point outwards (min cos %.3f)", h, mindot);
    double vol = signed_volume(&m), ball = 4.0 / 3.0 * M_PI * want * want * want;
    double lo = 4.0 / 3.0 * M_PI * pow(want - h, 3), hi = 4.0 / 3.0 * M_PI * pow(want + h, 3);
    t_ok(vol > lo && vol < hi && (h > 0.5f || fabs(vol - ball) < 0.02 * ball),
         "one atom (h %g): enclosed volume %.3f vs 4/3 pi R^3 %.3f", h, vol, ball);
    t_ok(mesh_defects(&m) == 0, "one atom (h %g): closed, oriented (%zu vertices)", h, m.nv);
    t_ok(colors_ok, "one atom (h %g): the atom's colour at every vertex", h);
    ms_qsurf_mesh_free(&m);
}

static void test_one_atom(void)
{
    t_suite = "qsurf";
    check_sphere(1.0f, 0, 1.5f, 0.5f);
    check_sphere(0.25f, 3, 1.5f, 0.5f);
    check_sphere(0.5f, 1, 2.0f, 0.2f);
}

/* Every CPU density loop gives the same bits where an atom's cutoff spans several vectors
 * and the grid is narrower than that span (h 0.25, gausslim 4: 49 voxels across, on a
 * grid of about 45). */
static void test_wide_atoms(void)
{
    t_suite = "qsurf";
    float pos[9] = {0.3f, 0.1f, -0.2f, 1.1f, 0.7f, 0.4f, -0.6f, 0.9f, 1.3f};
    float rad[3] = {1.5f, 1.4f, 1.6f}, rgb[9] = {1, 0, 0, 0, 1, 0, 0.2f, 0.3f, 0.9f};
    ms_qsurf_atoms a = {.n = 3, .pos = pos, .radius = rad, .rgb = rgb};
    ms_qsurf_params p;
    ms_qsurf_grid g;
    ms_qsurf_atomgrid ag;
    ms_qsurf_slab s[2];
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    p.gridspacing = 0.25f, p.quality = 3;
    if (ms_qsurf_grid_setup(&a, &p, &g, &err) < 0 || ms_qsurf_atomgrid_build(&a, &g, &ag, &err) < 0)
        return;
    size_t n = (size_t)g.n[0] * g.n[1] * g.n[2];
    for (int k = 0; k < 2; k++) {
        ms_qsurf_slab_alloc(&s[k], g.n[0], g.n[1], g.n[2], 1);
        s[k].zb = s[k].cz = 0, s[k].ze = g.n[2] - 1;
    }
    ms_qsurf_density_cpu_with(&ag, &s[0], MS_QSURF_K_GATHER);
    for (int k = 0; k < 4; k++) {
        ms_qsurf_density_cpu_with(&ag, &s[1], k);
        int same = !memcmp(s[0].dens, s[1].dens, n * sizeof(float));
        for (int c = 0; c < 3; c++) same = same && !memcmp(s[0].rgb[c], s[1].rgb[c], n * 4);
        t_ok(same, "%s: atoms 49 voxels across on a %d-voxel-wide grid, the gather's bits",
             ms_qsurf_kernel_name(k), g.n[0]);
    }
    for (int k = 0; k < 2; k++) ms_qsurf_slab_free(&s[k]);
    ms_qsurf_atomgrid_free(&ag);
}

/* Bad input gives an error or is left out, never a crash. */
static void test_bad_input(void)
{
    t_suite = "qsurf";
    float pos[9] = {0, 0, 0, NAN, 1, 2, 1.0f, 0.5f, 0}, rad[3] = {1.5f, 1.5f, 1.5f};
    ms_qsurf_atoms a = {.n = 3, .pos = pos, .radius = rad};
    ms_qsurf_params p;
    ms_qsurf_mesh m = {0}, ref = {0};
    ms_qsurf_stats st;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    p.backend = MS_QSURF_CPU;
    uint32_t valid[2] = {0, 2};
    ms_qsurf_atoms b = a;
    b.index = valid, b.n = 2;
    int rc = ms_qsurf_surface(&a, &p, &m, &st, &err);
    ms_qsurf_surface(&b, &p, &ref, NULL, &err);
    t_ok(rc == 0 && st.grid.natoms == 2 && m.nv == ref.nv && m.nv > 0,
         "an atom with a NaN coordinate is left out (%zu atoms used, %zu vertices)",
         st.grid.natoms, m.nv);
    pos[3] = 1e6f, pos[4] = -1e6f, pos[5] = 1e6f;
    p.gridspacing = 0.01f;
    t_ok(ms_qsurf_surface(&a, &p, &m, &st, &err) < 0 && m.nv == 0 && strstr(err.msg, "grid"),
         "atoms 1e6 A apart at spacing 0.01: refused (%s)", err.msg);
    a.n = 0;
    t_ok(ms_qsurf_surface(&a, &p, &m, &st, &err) < 0 && strstr(err.msg, "no atoms"),
         "no atoms: an error (%s)", err.msg);
    p.isovalue = NAN;
    a.n = 1;
    t_ok(ms_qsurf_surface(&a, &p, &m, &st, &err) < 0 && strstr(err.msg, "isovalue"),
         "a NaN isovalue is refused (%s)", err.msg);
    ms_qsurf_mesh_free(&m);
    ms_qsurf_mesh_free(&ref);
}

/* ---------------------------------------------------------------- marching cubes alone */

static void test_mc_skewed(void)
{
    t_suite = "qsurf";
    /* f = -|p - c|^2 on a grid with skewed, unequal axes: the surface f = -R^2 is the sphere
     * of radius R whatever the axes. */
    int n = 40;
    ms_qsurf_volume v = {.n = {n, n, n}, .origin = {-4.0f, -4.0f, -4.0f},
                         .axis = {{0.2f, 0, 0}, {0.05f, 0.2f, 0}, {0, 0.04f, 0.22f}},
                         .solid = {1.0f, 0.5f, 0.0f}};
    v.data = malloc((size_t)n * n * n * sizeof(float));
    if (!v.data) return;
    double c[3] = {-0.2, 0.3, 0.1}, R = 2.0, worst = 0.0, mindot = 1.0;
    for (int k = 0; k < n; k++)
        for (int j = 0; j < n; j++)
            for (int i = 0; i < n; i++) {
                double d2 = 0.0;
                for (int r = 0; r < 3; r++) {
                    double x = v.origin[r] + i * v.axis[0][r] + j * v.axis[1][r] + k * v.axis[2][r];
                    d2 += (x - c[r]) * (x - c[r]);
                }
                v.data[((size_t)k * n + j) * n + i] = (float)-d2;
            }
    ms_qsurf_mesh m = {0};
    ms_error err = {{0}};
    int rc = ms_qsurf_mc(&v, (float)(-R * R), &m, &err);
    for (size_t i = 0; rc == 0 && i < m.nv; i++) {
        double d[3], len = 0.0, dot = 0.0;
        for (int r = 0; r < 3; r++) d[r] = m.pos[3 * i + r] - c[r], len += d[r] * d[r];
        len = sqrt(len);
        for (int r = 0; r < 3; r++) dot += d[r] / len * ms_qsurf_unpack_normal(m.normal[3 * i + r]);
        worst = MS_MAX(worst, fabs(len - R));
        mindot = MS_MIN(mindot, dot);
    }
    t_ok(rc == 0 && m.nv > 0 && worst < 0.02, "marching cubes on skewed axes: sphere radius "
         "within 0.02 (worst %.4f, %zu vertices)", worst, m.nv);
    t_ok(mindot > 0.98, "skewed axes: normals along the true gradient (min cos %.4f)", mindot);
    double ball = 4.0 / 3.0 * M_PI * R * R * R;
    t_ok(mesh_defects(&m) == 0 && fabs(signed_volume(&m) / ball - 1) < 0.02,
         "skewed axes: closed, volume %.3f (4/3 pi R^3 %.3f)", signed_volume(&m), ball);
    t_ok(m.nv > 0 && m.color[0] == 255 && m.color[1] == 128 && m.color[2] == 0 && m.color[3] == 255,
         "solid colour without colour grids");
    v.n[2] = 1;
    t_ok(ms_qsurf_mc(&v, 0.0f, &m, &err) == 0 && m.nv == 0, "a single plane gives no surface");
    ms_qsurf_mesh_free(&m);
    free(v.data);
}

/* ---------------------------------------------------------------- 1tii */

typedef struct sys {
    ms_molecule *m;
    float *rgb;
    ms_qsurf_atoms a;
} sys;

/* VMD's Element colours for the elements of 1tii: C cyan, N blue, O red, S yellow. */
static void element_rgb(int z, float *c)
{
    static const float cyan[3] = {0.25f, 0.75f, 0.75f}, blue[3] = {0, 0, 1}, red[3] = {1, 0, 0},
                       yellow[3] = {1, 1, 0}, other[3] = {0.6f, 0.6f, 0.6f};
    const float *s = z == 6 ? cyan : z == 7 ? blue : z == 8 ? red : z == 16 ? yellow : other;
    memcpy(c, s, 3 * sizeof(float));
}

static int load_1tii(sys *s)
{
    char path[1024];
    ms_load_opts o;
    ms_error err = {{0}};
    memset(s, 0, sizeof *s);
    snprintf(path, sizeof path, "%s/1tii.pdb", t_data());
    ms_load_opts_default(&o);
    o.waitfor = -1;
    s->m = ms_load_new(&reg, path, &o, &err);
    if (!t_ok(s->m != NULL, "load 1tii.pdb (%s)", err.msg)) return -1;
    size_t n = s->m->atoms.n;
    s->rgb = malloc(3 * n * sizeof(float));
    for (size_t i = 0; i < n; i++) element_rgb(s->m->atoms.atomicnumber[i], s->rgb + 3 * i);
    s->a = (ms_qsurf_atoms){.n = n, .pos = ms_mol_pos(s->m), .radius = s->m->atoms.radius,
                            .rgb = s->rgb};
    ms_qsurf_radius_range(s->m->atoms.radius, n, NULL, 0, &s->a.minrad, &s->a.maxrad);
    return 0;
}

static int surface(const sys *s, int backend, ms_qsurf_mesh *m, ms_qsurf_stats *st)
{
    ms_qsurf_params p;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    p.backend = backend;
    int rc = ms_qsurf_surface(&s->a, &p, m, st, &err);
    if (rc < 0) t_ok(0, "1tii surface: %s", err.msg);
    return rc;
}

static int same_mesh(const ms_qsurf_mesh *a, const ms_qsurf_mesh *b)
{
    return a->nv == b->nv && a->nt == b->nt &&
           !memcmp(a->index, b->index, 3 * a->nt * sizeof *a->index) &&
           !memcmp(a->pos, b->pos, 3 * a->nv * sizeof *a->pos);
}

/* Compare a mesh with the reference one: the same vertex count, area within 0.1 %. */
static void compare(const char *what, const ms_qsurf_mesh *ref, const ms_qsurf_mesh *m)
{
    double a0 = ms_qsurf_mesh_area(ref), a1 = ms_qsurf_mesh_area(m);
    t_ok(m->nv == ref->nv && fabs(a1 - a0) <= 1e-3 * a0,
         "1tii %s: %zu vertices (one pass %zu), area %.2f (one pass %.2f)", what, m->nv, ref->nv,
         a1, a0);
    t_ok(mesh_defects(m) == 0, "1tii %s: closed and oriented", what);
    t_ok(same_mesh(ref, m), "1tii %s: the very same mesh", what);
}

static void test_1tii_slabs(const sys *s)
{
    ms_qsurf_mesh ref = {0}, m = {0};
    ms_qsurf_stats st;
    if (surface(s, MS_QSURF_CPU, &ref, &st) < 0) return;
    t_ok(st.nslabs == 1 && ref.nv > 10000, "1tii in one pass: %d x %d x %d grid, %zu vertices, "
         "%zu triangles", st.grid.n[0], st.grid.n[1], st.grid.n[2], ref.nv, ref.nt);
    t_ok(mesh_defects(&ref) == 0, "1tii: closed, every edge shared by two triangles, oriented");
    t_ok(signed_volume(&ref) > 0.0, "1tii: triangles face outwards (volume %.0f A^3)",
         signed_volume(&ref));
    /* A budget that holds exactly 8 layers per slab (in its half for the slabs). */
    char limit[64];
    snprintf(limit, sizeof limit, "%zu", 2 * ms_qsurf_plan_bytes(&st.grid, 1, 8));
    setenv("MOLSCOPE_QUICKSURF_MEMLIMIT", limit, 1);
    if (surface(s, MS_QSURF_CPU, &m, &st) == 0) {
        int want = (st.grid.n[2] - 1 + 7) / 8;
        t_ok(st.slab_layers == 8 && st.nslabs == want, "MOLSCOPE_QUICKSURF_MEMLIMIT=%s: %d slabs "
             "of 8 layers (%d)", limit, st.nslabs, want);
        compare("in 8-layer slabs", &ref, &m);
    }
    snprintf(limit, sizeof limit, "%zu", 2 * ms_qsurf_plan_bytes(&st.grid, 1, 8) - 2);
    setenv("MOLSCOPE_QUICKSURF_MEMLIMIT", limit, 1);
    ms_qsurf_params p;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    t_ok(ms_qsurf_surface(&s->a, &p, &m, &st, &err) < 0 && strstr(err.msg, "memory budget") &&
         m.nv == 0, "a budget below one 8-layer slab is an error (%s)", err.msg);
    unsetenv("MOLSCOPE_QUICKSURF_MEMLIMIT");
    ms_qsurf_mesh_free(&m);
    ms_qsurf_mesh_free(&ref);
}

static void note(void *ctx, const char *msg)
{
    snprintf(ctx, 512, "%s", msg);
}

/* A mesh made on the OpenCL device against the CPU's: the same vertices and triangles,
 * index for index (the density is the CPU's bit for bit and the order is the host's); the
 * vertex attributes computed in float on the device instead of double: positions within
 * 1e-3 A, normals and colours within one step of 8 bits; area within 0.1 %; closed. */
static void compare_device(const char *what, const ms_qsurf_mesh *ref, const ms_qsurf_mesh *m)
{
    double a0 = ms_qsurf_mesh_area(ref), a1 = ms_qsurf_mesh_area(m), dpos = 0.0;
    int dn = 0, dc = 0;
    int same = m->nv == ref->nv && m->nt == ref->nt &&
               !memcmp(m->index, ref->index, 3 * m->nt * sizeof *m->index);
    for (size_t i = 0; same && i < 3 * m->nv; i++) {
        dpos = MS_MAX(dpos, fabs((double)m->pos[i] - ref->pos[i]));
        dn = MS_MAX(dn, abs((int)m->normal[i] - (int)ref->normal[i]));
    }
    for (size_t i = 0; same && i < 4 * m->nv; i++)
        dc = MS_MAX(dc, abs((int)m->color[i] - (int)ref->color[i]));
    t_ok(same, "1tii %s: the CPU's %zu vertices and %zu triangles, index for index (%zu, %zu)",
         what, ref->nv, ref->nt, m->nv, m->nt);
    t_ok(same && dpos < 1e-3 && dn <= 1 && dc <= 1, "1tii %s: positions within %.1e A, normals "
         "within %d, colours within %d of the CPU's", what, dpos, dn, dc);
    t_ok(fabs(a1 - a0) <= 1e-3 * a0, "1tii %s: area %.2f (CPU %.2f)", what, a1, a0);
    t_ok(mesh_defects(m) == 0, "1tii %s: closed and oriented", what);
}

/* Slabs of 8 layers on the device, failing at the third slab at `stage`: the CPU does the
 * rest, and the mesh is the same. */
static void device_failure(const sys *s, const ms_qsurf_mesh *ref, int stage, const char *what,
                           char said[512])
{
    ms_qsurf_mesh m = {0};
    ms_qsurf_stats st;
    ms_qsurf_params p;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    ms_qsurf_grid g;
    ms_qsurf_grid_setup(&s->a, &p, &g, &err);
    p.backend = MS_QSURF_OPENCL, p.notice = note, p.notice_ctx = said;
    p.memlimit = 2 * ms_qsurf_plan_bytes(&g, 1, 8);
    ms_qsurf_cl_fail_after = 2, ms_qsurf_cl_fail_stage = stage;
    int rc = ms_qsurf_surface(&s->a, &p, &m, &st, &err);
    ms_qsurf_cl_fail_after = -1;
    t_ok(rc == 0 && st.opencl == 2 && st.nslabs > 4 && strstr(st.note, "injected"),
         "OpenCL failing in %s at slab 3 of %d: the CPU does the rest (%s)", what, st.nslabs,
         st.note);
    if (rc == 0) compare_device(what, ref, &m);
    ms_qsurf_mesh_free(&m);
}

static void test_1tii_opencl(const sys *s)
{
    ms_qsurf_mesh ref = {0}, m = {0};
    ms_qsurf_stats st;
    if (surface(s, MS_QSURF_CPU, &ref, &st) < 0) return;
    if (surface(s, MS_QSURF_OPENCL, &m, &st) < 0) return;
    if (st.opencl == 0) {
        t_skip("1tii on OpenCL", st.note);
        ms_qsurf_mesh_free(&ref);
        ms_qsurf_mesh_free(&m);
        return;
    }
    t_ok(st.nslabs == 1 && st.opencl == 1, "1tii on OpenCL: one slab on the device");
    compare_device("on OpenCL", &ref, &m);
    /* the built kernels were cached where MOLSCOPE_OPENCL_CACHE says (run-tests sets it) */
    const char *cache = getenv("MOLSCOPE_OPENCL_CACHE");
    if (cache && *cache) {
        DIR *d = opendir(cache);
        int bins = 0;
        for (struct dirent *e; d && (e = readdir(d));)
            bins += !strncmp(e->d_name, "qsurf-", 6) && strstr(e->d_name, ".bin") &&
                    !strstr(e->d_name, ".tmp");
        if (d) closedir(d);
        t_ok(bins >= 1, "QuickSurf's kernels are cached in MOLSCOPE_OPENCL_CACHE (%d files)", bins);
    }
    /* Forced slabs of 8 layers, all on the device: seamless. */
    ms_qsurf_params p;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    p.backend = MS_QSURF_OPENCL, p.memlimit = 2 * ms_qsurf_plan_bytes(&st.grid, 1, 8);
    int rc = ms_qsurf_surface(&s->a, &p, &m, &st, &err);
    if (t_ok(rc == 0 && st.nslabs > 4 && st.opencl == st.nslabs, "1tii on OpenCL in %d slabs "
             "of %d layers, all on the device (%s)", st.nslabs, st.slab_layers, err.msg))
        compare_device("on OpenCL in slabs", &ref, &m);
    /* Faults at the third slab, at each stage; the fallback said once per process. */
    char said[512] = "";
    device_failure(s, &ref, MS_QSURF_CL_FAIL_DENSITY, "the density kernel", said);
    t_ok(strstr(said, "injected") != NULL, "the fallback is said through the notice callback");
    said[0] = '\0';
    device_failure(s, &ref, MS_QSURF_CL_FAIL_ALLOC, "the mesh buffers' allocation", said);
    device_failure(s, &ref, MS_QSURF_CL_FAIL_READ, "reading the triangles back", said);
    t_ok(said[0] == '\0', "a fallback is said once per process, not at every surface");
    ms_qsurf_mesh_free(&ref);
    ms_qsurf_mesh_free(&m);
}

/* The CPU taking over marching cubes from the device: a fresh extractor resumed at a slab
 * boundary (plane state rebuilt from the density and the mesh) continues the same mesh.
 * Runs without OpenCL. */
static void test_1tii_resume(const sys *s)
{
    ms_qsurf_mesh ref = {0}, m = {0};
    ms_qsurf_stats st;
    ms_qsurf_grid g;
    ms_qsurf_atomgrid ag;
    ms_qsurf_slab sl;
    ms_qsurf_extract mc;
    ms_error err = {{0}};
    if (surface(s, MS_QSURF_CPU, &ref, &st) < 0) return;
    g = st.grid;
    int layers = 8, nz = g.n[2], rc = 0, resumed = 0;
    float axis[3][3] = {{g.h, 0, 0}, {0, g.h, 0}, {0, 0, g.h}};
    ms_qsurf_atomgrid_build(&s->a, &g, &ag, &err);
    ms_qsurf_slab_alloc(&sl, g.n[0], g.n[1], layers + 3, 1);
    rc = ms_qsurf_extract_begin(&mc, g.n, g.origin, axis, g.isovalue, 1, s->a.solid, layers, &m,
                                &err);
    for (int z0 = 0, z1; rc == 0 && z0 < nz - 1; z0 = z1) {
        z1 = MS_MIN(z0 + layers, nz - 1);
        sl.zb = sl.cz = MS_MAX(z0 - 1, 0), sl.ze = MS_MIN(z1 + 1, nz - 1);
        ms_qsurf_density_cpu(&ag, &sl);
        if (z0 == 3 * layers || z0 == 4 * layers) {
            ms_qsurf_extract_end(&mc);
            rc = ms_qsurf_extract_begin(&mc, g.n, g.origin, axis, g.isovalue, 1, s->a.solid,
                                        layers, &m, &err);
            if (rc == 0) rc = ms_qsurf_extract_resume(&mc, &sl, z0, &err);
            resumed += rc == 0;
        }
        if (rc == 0) rc = ms_qsurf_extract_slab(&mc, &sl, z0, z1, &err);
    }
    ms_qsurf_extract_end(&mc);
    t_ok(rc == 0 && resumed == 2 && same_mesh(&ref, &m) && mesh_defects(&m) == 0,
         "1tii: marching cubes resumed twice by a fresh extractor: the same mesh (%zu "
         "vertices) %s", m.nv, err.msg);
    ms_qsurf_mesh_free(&m);
    sl.zb = sl.cz = 7, sl.ze = 17;
    ms_qsurf_density_cpu(&ag, &sl);
    rc = ms_qsurf_extract_begin(&mc, g.n, g.origin, axis, g.isovalue, 1, s->a.solid, layers, &m,
                                &err);
    t_ok(rc == 0 && ms_qsurf_extract_resume(&mc, &sl, 8, &err) < 0 && strstr(err.msg, "lacks"),
         "resuming with a mesh that lacks the plane's vertices is an error (%s)", err.msg);
    ms_qsurf_extract_end(&mc);
    ms_qsurf_slab_free(&sl);
    ms_qsurf_atomgrid_free(&ag);
    ms_qsurf_mesh_free(&ref);
}

/* The density map against a double-precision sum over all atoms, at voxels near the
 * surface; and every CPU loop bit for bit alike. */
static void test_1tii_density(const sys *s)
{
    ms_qsurf_params p;
    ms_qsurf_volume v;
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    if (!t_ok(ms_qsurf_density(&s->a, &p, &v, &err) == 0, "1tii density map (%s)", err.msg)) return;
    double gl2 = 4.0, worst = 0.0;
    size_t checked = 0, nvox = (size_t)v.n[0] * v.n[1] * v.n[2];
    for (size_t i = 0; i < nvox && checked < 1500; i += 37) {
        if (v.data[i] < 0.1f || v.data[i] > 3.0f) continue;
        double x = v.origin[0] + (double)(i % v.n[0]) * v.axis[0][0];
        double y = v.origin[1] + (double)(i / v.n[0] % v.n[1]) * v.axis[1][1];
        double z = v.origin[2] + (double)(i / ((size_t)v.n[0] * v.n[1])) * v.axis[2][2];
        double sum = 0.0;
        for (size_t k = 0; k < s->a.n; k++) {
            const float *q = s->a.pos + 3 * k;
            double sg = s->a.radius[k], d2 = (x - q[0]) * (x - q[0]) + (y - q[1]) * (y - q[1]) +
                                              (z - q[2]) * (z - q[2]);
            if (d2 <= gl2 * sg * sg) sum += exp(-d2 / (2.0 * sg * sg));
        }
        worst = MS_MAX(worst, fabs(sum - v.data[i]) / sum);
        checked++;
    }
    t_ok(checked > 1000 && worst < 2e-5, "1tii density at %zu voxels matches a double-precision "
         "sum (worst relative error %.2e)", checked, worst);
    ms_qsurf_grid g;
    ms_qsurf_atomgrid ag;
    ms_qsurf_slab sl;
    ms_qsurf_grid_setup(&s->a, &p, &g, &err);
    ms_qsurf_atomgrid_build(&s->a, &g, &ag, &err);
    ms_qsurf_slab_alloc(&sl, g.n[0], g.n[1], g.n[2], 1);
    sl.zb = sl.cz = 0, sl.ze = g.n[2] - 1;
    for (int k = 0; k < 4; k++) {
        ms_qsurf_density_cpu_with(&ag, &sl, k);
        int same = !memcmp(sl.dens, v.data, nvox * sizeof(float));
        for (int c = 0; c < 3; c++)
            same = same && !memcmp(sl.rgb[c], v.rgb[c], nvox * sizeof(float));
        t_ok(same, "%s density and colour texture equal the default loop's bit for bit",
             ms_qsurf_kernel_name(k));
    }
    ms_qsurf_slab_free(&sl);
    ms_qsurf_atomgrid_free(&ag);
    ms_qsurf_volume_free(&v);
}

/* The environment switches choose the paths. */
static void test_switches(const sys *s)
{
    ms_qsurf_mesh m = {0};
    ms_qsurf_stats st;
    setenv("MOLSCOPE_NOSIMD", "1", 1);
    setenv("MOLSCOPE_QUICKSURF_KERNEL", "gather", 1);
    t_ok(!strcmp(ms_qsurf_kernel_name(ms_qsurf_cpu_kernel()), "plain-gather"),
         "MOLSCOPE_NOSIMD and MOLSCOPE_QUICKSURF_KERNEL=gather: %s",
         ms_qsurf_kernel_name(ms_qsurf_cpu_kernel()));
    unsetenv("MOLSCOPE_QUICKSURF_KERNEL");
    if (surface(s, MS_QSURF_CPU, &m, &st) == 0)
        t_ok(!strcmp(st.kernel, "plain-scatter") && mesh_defects(&m) == 0,
             "MOLSCOPE_NOSIMD: the plain loops make the surface (%s, %zu vertices)", st.kernel,
             m.nv);
    unsetenv("MOLSCOPE_NOSIMD");
    if (ms_qsurf_have_simd())
        t_ok(!strcmp(ms_qsurf_kernel_name(ms_qsurf_cpu_kernel()), "avx2-scatter"),
             "by default: the AVX2 scatter loop");
    setenv("MOLSCOPE_NOOPENCL", "1", 1);
    if (surface(s, MS_QSURF_OPENCL, &m, &st) == 0)
        t_ok(st.opencl == 0 && strstr(st.note, "MOLSCOPE_NOOPENCL"),
             "MOLSCOPE_NOOPENCL: the CPU path (%s)", st.note);
    unsetenv("MOLSCOPE_NOOPENCL");
    ms_qsurf_mesh_free(&m);
}

/* Vertices near an oxygen that no other atom comes close to (the water oxygens of 1tii)
 * are pure red; vertices where oxygens carry over 80 % of the Gaussian weight (summed here
 * in double precision) have red as their strongest channel. The second check takes the
 * vertices whose summed weight is within 10 % of the isovalue: at quality 0 the cutoff of
 * 2 sigma leaves places where the interpolated vertex is far from the true isosurface, and
 * the colour there comes from the grid point inside. */
static void test_1tii_colors(const sys *s)
{
    ms_qsurf_mesh m = {0};
    ms_qsurf_stats st;
    if (surface(s, MS_QSURF_CPU, &m, &st) < 0) return;
    size_t lone = 0, lone_red = 0, oxy = 0, oxy_red = 0;
    for (size_t v = 0; v < m.nv; v++) {
        double best = DBL_MAX, second = DBL_MAX, wo = 0.0, wall = 0.0;
        size_t who = 0;
        for (size_t k = 0; k < s->a.n; k++) {
            double d2 = 0.0, sg = s->a.radius[k];
            for (int r = 0; r < 3; r++) d2 += pow(m.pos[3 * v + r] - s->a.pos[3 * k + r], 2);
            if (d2 < best) second = best, best = d2, who = k;
            else if (d2 < second) second = d2;
            if (d2 > 4.0 * sg * sg) continue;
            double w = exp(-d2 / (2.0 * sg * sg));
            wall += w;
            if (s->m->atoms.atomicnumber[k] == 8) wo += w;
        }
        const uint8_t *c = m.color + 4 * v;
        if (fabs(wall - 0.5) < 0.05 && wo > 0.8 * wall)
            oxy++, oxy_red += c[0] > c[1] && c[0] > c[2];
        if (s->m->atoms.atomicnumber[who] == 8 && sqrt(second) - sqrt(best) > 3.0)
            lone++, lone_red += c[0] == 255 && c[1] == 0 && c[2] == 0;
    }
    t_ok(lone > 20 && lone_red == lone, "vertices around lone oxygens are pure red (%zu of %zu)",
         lone_red, lone);
    t_ok(oxy > 1000 && oxy_red == oxy, "surface vertices where oxygens weigh over 80 %% are red "
         "(red the strongest channel at %zu of %zu)", oxy_red, oxy);
    ms_qsurf_mesh_free(&m);
}

static void test_1tii_beads(const sys *s)
{
    ms_qsurf_beads b;
    ms_qsurf_atoms ba;
    ms_qsurf_mesh m = {0};
    ms_qsurf_params p;
    ms_error err = {{0}};
    if (!t_ok(ms_qsurf_beads_build(&s->a, s->m->atoms.residue, &b, &err) == 0, "beads (%s)",
              err.msg))
        return;
    t_ok(b.n == s->m->nresidues && b.n == 927, "one bead per residue (%zu beads, %zu residues)",
         b.n, s->m->nresidues);
    /* The last residue is a water: one oxygen, at its own centroid, radius 0 + 1 A, red. */
    size_t last = s->a.n - 1;
    t_ok(b.radius[b.n - 1] == 1.0f && !memcmp(b.pos + 3 * (b.n - 1), s->a.pos + 3 * last, 12) &&
         b.rgb[3 * (b.n - 1)] == 1.0f, "a one-atom residue: bead on the atom, radius 1 A");
    /* Residue 0: centroid and farthest atom, recomputed here in double. */
    uint32_t r0 = s->m->res_start[0], r1 = s->m->res_start[1];
    double c[3] = {0, 0, 0}, far = 0.0;
    for (uint32_t i = r0; i < r1; i++)
        for (int d = 0; d < 3; d++) c[d] += s->a.pos[3 * i + d] / (double)(r1 - r0);
    for (uint32_t i = r0; i < r1; i++) {
        double d2 = 0.0;
        for (int d = 0; d < 3; d++) d2 += pow(s->a.pos[3 * i + d] - c[d], 2);
        far = MS_MAX(far, sqrt(d2));
    }
    t_ok(fabs(b.pos[0] - c[0]) < 1e-4 && fabs(b.radius[0] - (far + 1.0)) < 1e-4 &&
         !memcmp(b.rgb, s->rgb + 3 * (r1 - 1), 12),
         "residue 0: centroid, farthest atom + 1 A (%.3f), last atom's colour", b.radius[0]);
    ms_qsurf_beads_atoms(&b, &ba);
    ms_qsurf_params_default(&p);
    p.backend = MS_QSURF_CPU;
    int rc = ms_qsurf_surface(&ba, &p, &m, NULL, &err);
    t_ok(rc == 0 && m.nt > 0 && mesh_defects(&m) == 0, "bead surface: closed (%zu vertices) %s",
         m.nv, err.msg);
    ms_qsurf_mesh_free(&m);
    ms_qsurf_beads_free(&b);
}

/* A size line of /proc/self/status ("VmRSS", "VmHWM") in bytes. */
static size_t status_bytes(const char *key)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    unsigned long long kb = 0;
    size_t n = strlen(key);
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, key, n) && line[n] == ':') kb = strtoull(line + n + 1, NULL, 10);
    if (f) fclose(f);
    return (size_t)kb * 1024u;
}

/* Reset VmHWM to the current resident set. */
static void reset_peak(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (f) {
        fputs("5", f);
        fclose(f);
    }
}

/* The memory budget covers the mesh too. 1tii stacked six times along z: each slab of 8
 * layers stays the size of one copy's, the mesh grows with the copies. A budget whose half
 * holds the 8-layer slabs but whose rest cannot hold the mesh fails, saying so, and leaves
 * no mesh; one that holds both makes the same mesh as no budget, and the memory the surface
 * added stays within it. */
static void test_1tii_mesh_budget(const sys *one)
{
    enum { K = 6 };
    size_t n = one->a.n;
    float *pos = malloc(3 * K * n * sizeof *pos), *rad = malloc(K * n * sizeof *rad);
    float *rgb = malloc(3 * K * n * sizeof *rgb), zlo = INFINITY, zhi = -INFINITY;
    if (!pos || !rad || !rgb) goto done;
    for (size_t i = 0; i < n; i++)
        zlo = MS_MIN(zlo, one->a.pos[3 * i + 2]), zhi = MS_MAX(zhi, one->a.pos[3 * i + 2]);
    for (size_t k = 0; k < K; k++)
        for (size_t i = 0; i < n; i++) {
            for (int d = 0; d < 3; d++) pos[3 * (k * n + i) + d] = one->a.pos[3 * i + d];
            pos[3 * (k * n + i) + 2] += (float)k * (zhi - zlo + 12.0f);
            rad[k * n + i] = one->a.radius[i];
            memcpy(rgb + 3 * (k * n + i), one->rgb + 3 * i, 3 * sizeof *rgb);
        }
    ms_qsurf_atoms a = {.n = K * n, .pos = pos, .radius = rad, .rgb = rgb,
                        .minrad = one->a.minrad, .maxrad = one->a.maxrad};
    ms_qsurf_params p;
    ms_qsurf_params_default(&p);
    p.backend = MS_QSURF_CPU;
    ms_qsurf_mesh ref = {0}, m = {0};
    ms_qsurf_stats st;
    ms_error err = {{0}};
    if (!t_ok(ms_qsurf_surface(&a, &p, &ref, &st, &err) == 0, "1tii x%d: a surface (%s)", K,
              err.msg))
        goto done;
    size_t plan8 = ms_qsurf_plan_bytes(&st.grid, 1, 8), mesh = ms_qsurf_mesh_bytes(&ref);
    t_ok(mesh > plan8, "1tii x%d: the mesh (%zu bytes) outgrows an 8-layer slab (%zu)", K, mesh,
         plan8);
    p.memlimit = 2 * plan8;
    int rc = ms_qsurf_surface(&a, &p, &m, &st, &err);
    t_ok(rc < 0 && st.slab_layers == 8 && strstr(err.msg, "the mesh needs") &&
             strstr(err.msg, "memory budget") && m.nv == 0 && m.pos == NULL,
         "a budget whose rest cannot hold the mesh fails, naming it (%s)", err.msg);
    p.memlimit = 2 * (plan8 + mesh);
    size_t base = status_bytes("VmRSS");
    reset_peak();
    rc = ms_qsurf_surface(&a, &p, &m, &st, &err);
    size_t peak = status_bytes("VmHWM"), added = peak > base ? peak - base : 0;
    t_ok(rc == 0 && same_mesh(&ref, &m), "a budget that holds slabs and mesh: the same mesh "
         "(%s)", rc ? err.msg : "");
#ifdef __SANITIZE_ADDRESS__
    (void)added;   /* AddressSanitizer's shadow memory and quarantine add to every peak */
    t_skip("the peak within the budget", "built with AddressSanitizer");
#else
    t_ok(rc == 0 && added <= p.memlimit, "the surface added %.1f MB at its peak, within the "
         "budget of %.1f MB", added / 1048576.0, p.memlimit / 1048576.0);
#endif
    ms_qsurf_mesh_free(&ref);
    ms_qsurf_mesh_free(&m);
done:
    free(pos);
    free(rad);
    free(rgb);
}

static void test_1tii(void)
{
    sys s;
    t_suite = "qsurf";
    if (load_1tii(&s) < 0) return;
    test_1tii_slabs(&s);
    test_1tii_mesh_budget(&s);
    test_1tii_opencl(&s);
    test_1tii_resume(&s);
    test_1tii_density(&s);
    test_switches(&s);
    test_1tii_colors(&s);
    test_1tii_beads(&s);
    free(s.rgb);
    ms_mol_free(s.m);
}

int main(void)
{
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    test_exp2();
    test_quantize();
    test_grid_rules();
    test_one_atom();
    test_wide_atoms();
    test_bad_input();
    test_mc_skewed();
    test_1tii();
    ms_registry_free(&reg);
    return t_done();
}
