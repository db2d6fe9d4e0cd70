/* test_pbc.c: the vectorised loops of src/pbc (kernels.c) against the scalar double-precision
 * rules they replace, atom for atom and bit for bit: wrap into the parallelepiped, wrap into
 * the brick (-orthorhombic), unwrap to the image nearest the previous frame. Runs of every
 * length around the block size (tails padded), points on cell faces, far away, NaN and
 * huge; and the runs of consecutive atoms the loops are handed. */
#include "config.h"
#include "ms_test.h"
#include "pbc/internal.h"

#include <math.h>
#include <string.h>

/* The rules as the scalar code states them (fractional floor / round, then the lattice). */
static void ref_wrap(float *p, const ms_pbc_cell *c, const double o[3], int brick)
{
    double q[3] = {p[0] - o[0], p[1] - o[1], p[2] - o[2]}, n[3], t[3];
    if (brick) {
        double r[3] = {q[0], q[1], q[2]};
        for (int k = 2; k >= 0; k--) {
            double m = ms_pbc_floor(r[k] / c->v[k][k]);
            for (int d = 0; d < 3; d++) r[d] -= m * c->v[k][d];
        }
        for (int d = 0; d < 3; d++) t[d] = r[d] - q[d];
    } else {
        ms_pbc_frac(c, q, n);
        for (int k = 0; k < 3; k++) n[k] = -ms_pbc_floor(n[k]);
        ms_pbc_lattice(c, n, t);
    }
    if (t[0] != 0 || t[1] != 0 || t[2] != 0)
        for (int d = 0; d < 3; d++) p[d] = (float)(p[d] + t[d]);
}

static void ref_unwrap(float *p, const float *r, const ms_pbc_cell *c)
{
    double d[3] = {(double)p[0] - r[0], (double)p[1] - r[1], (double)p[2] - r[2]}, n[3], t[3];
    ms_pbc_frac(c, d, n);
    for (int k = 0; k < 3; k++) n[k] = ms_pbc_round(n[k]);
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) return;
    ms_pbc_lattice(c, n, t);
    for (int k = 0; k < 3; k++) p[k] = (float)(p[k] - t[k]);
}

static unsigned long long rng = 88172645463325252ull;
static double urand(void)
{
    rng ^= rng << 13, rng ^= rng >> 7, rng ^= rng << 17;
    return (double)(rng >> 11) / 9007199254740992.0;
}

/* n atoms: most spread over several cells, some exactly on lattice points and faces, a few
 * far away, NaN, huge, negative zero. */
static void fill(float *p, size_t n, const ms_pbc_cell *c)
{
    for (size_t i = 0; i < n; i++) {
        float *a = p + 3 * i;
        double s[3] = {urand() * 5 - 2, urand() * 5 - 2, urand() * 5 - 2};
        switch (i % 11) {
        case 3: s[0] = floor(s[0]), s[1] = floor(s[1]); break;     /* on faces */
        case 5: s[2] = 1; break;
        case 7: s[0] = s[1] = s[2] = 1e4 * urand(); break;
        default: break;
        }
        double t[3];
        ms_pbc_lattice(c, s, t);
        for (int d = 0; d < 3; d++) a[d] = (float)t[d];
        if (i % 97 == 13) a[1] = NAN;
        if (i % 89 == 17) a[2] = 3e30f;
        if (i % 83 == 19) a[0] = -0.0f;
    }
}

/* Same bits, except that +0 and -0 count as equal (a zero's sign is not a position). */
static int same(const float *a, const float *b, size_t n)
{
    for (size_t i = 0; i < 3 * n; i++)
        if (!(a[i] == b[i] || (isnan(a[i]) && isnan(b[i])))) return 0;
    return 1;
}

static void check_cell(const char *name, const float cellp[6])
{
    ms_pbc_cell c;
    t_ok(ms_pbc_cell_make(cellp, &c), "%s: cell", name);
    const double origin[3] = {-3.25, 1.5, 0.125};
    const size_t lens[] = {1, 2, 63, 64, 65, 127, 128, 129, 1000};
    for (size_t li = 0; li < sizeof lens / sizeof *lens; li++) {
        size_t n = lens[li];
        float *a = malloc(12 * n), *b = malloc(12 * n), *prev = malloc(12 * n);
        fill(a, n, &c);
        for (int brick = 0; brick < 2; brick++) {
            memcpy(b, a, 12 * n);
            memcpy(prev, a, 12 * n);
            for (size_t i = 0; i < n; i++) ref_wrap(a + 3 * i, &c, origin, brick);
            if (brick) ms_pbc_wrap_run_brick(b, n, &c, origin);
            else ms_pbc_wrap_run(b, n, &c, origin);
            t_ok(same(a, b, n), "%s: %s of %zu atoms as the scalar rule", name,
                 brick ? "wrap into the brick" : "wrap", n);
        }
        /* unwrap the wrapped atoms against where they were */
        memcpy(b, a, 12 * n);
        for (size_t i = 0; i < n; i++) ref_unwrap(a + 3 * i, prev + 3 * i, &c);
        ms_pbc_unwrap_run(b, prev, n, &c);
        t_ok(same(a, b, n), "%s: unwrap of %zu atoms as the scalar rule", name, n);
        free(a), free(b), free(prev);
    }
}

static void check_runs(void)
{
    const uint32_t atoms[] = {0, 1, 2, 3, 4, 7, 9, 10, 11, 12, 13, 14, 15, 16, 40};
    ms_pbc_runs r;
    t_ok(ms_pbc_runs_make(atoms, 15, 4, &r) == 0, "runs: made");
    const uint32_t want[][2] = {{0, 4}, {4, 1}, {7, 1}, {9, 4}, {13, 4}, {40, 1}};
    int ok = r.n == 6;
    for (size_t k = 0; ok && k < r.n; k++) ok = r.run[k][0] == want[k][0] && r.run[k][1] == want[k][1];
    t_ok(ok, "runs: consecutive atoms, at most 4 a run (%zu runs)", r.n);
    free(r.run);
    t_ok(ms_pbc_runs_make(atoms, 0, 4, &r) == 0 && r.n == 0, "runs: none of no atoms");
    free(r.run);
}

int main(void)
{
    t_suite = "pbc";
    check_cell("cubic", (const float[6]){31.5f, 31.5f, 31.5f, 90, 90, 90});
    check_cell("monoclinic", (const float[6]){40.1f, 35.7f, 52.3f, 80, 85, 90});
    check_cell("triclinic", (const float[6]){18.82f, 19.0f, 19.4f, 80, 85, 95});
    check_runs();
    return t_failures ? 1 : 0;
}
