/* test_base.c: unit tests of the base utilities: interned strings, array growth, the
 * worker pool, the neighbour cell grid (against brute force), hybrid-36 numbers and field
 * parsing of the plugin helpers. */
#include "config.h"
#include "ms_test.h"
#include "base/base.h"
#include "base/strtab.h"
#include "base/threads.h"
#include "base/grid.h"
#include "plugin_util.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

static void test_strtab(void)
{
    t_suite = "strtab";
    ms_strtab *t = ms_strtab_new();
    t_ok(t && ms_strtab_intern_cstr(t, "") == 0, "empty string is id 0");
    ms_str ca = ms_strtab_intern_cstr(t, "CA");
    ms_str cb = ms_strtab_intern_cstr(t, "CB");
    t_ok(ca != cb && ms_strtab_intern_cstr(t, "CA") == ca, "same string, same id");
    t_ok(strcmp(ms_strtab_get(t, cb), "CB") == 0, "id gives the string back");
    t_ok(ms_strtab_find(t, "CG") == MS_STR_NONE, "find does not add");
    /* Many strings force rehashing; every one must still be found. */
    char buf[32];
    int ok = 1;
    for (int i = 0; i < 100000; i++) {
        snprintf(buf, sizeof buf, "s%d", i);
        ms_str id = ms_strtab_intern_cstr(t, buf);
        if (id == MS_STR_NONE || strcmp(ms_strtab_get(t, id), buf)) ok = 0;
    }
    for (int i = 0; i < 100000 && ok; i += 997) {
        snprintf(buf, sizeof buf, "s%d", i);
        ms_str id = ms_strtab_find(t, buf);
        if (id == MS_STR_NONE || strcmp(ms_strtab_get(t, id), buf)) ok = 0;
    }
    t_ok(ok && ms_strtab_count(t) == 100003, "100000 strings interned and found (count %u)",
         ms_strtab_count(t));
    t_ok(strcmp(ms_strtab_get(t, 0xfffffff0u), "") == 0, "an unknown id reads as empty");
    ms_strtab_free(t);
}

static void test_grow(void)
{
    t_suite = "base";
    int *a = NULL;
    size_t cap = 0;
    t_ok(ms_grow((void **)&a, &cap, 1000, sizeof *a) == 0 && cap >= 1000, "grow to 1000");
    size_t old = cap;
    t_ok(ms_grow((void **)&a, &cap, SIZE_MAX / 2, sizeof *a) == -1 && cap == old,
         "an overflowing size fails and leaves the array alone");
    free(a);
    size_t out;
    t_ok(ms_mul_size(SIZE_MAX / 2, 3, &out) == -1, "size multiplication detects overflow");
    t_ok(ms_word_eq("newcartoon", "NewCartoon") && !ms_word_eq("new", "NewCartoon"),
         "subcommand words compare case-insensitively");
    t_ok(ms_word_eq("ambientocclusionXYZ", "ambientocclusion"),
         "subcommand words compare over 15 characters");
}

typedef struct {
    atomic_long sum;
    atomic_int calls;
    char *seen;
} pf_ctx;

static void pf_body(void *vctx, size_t b, size_t e, int tid)
{
    pf_ctx *c = vctx;
    long s = 0;
    for (size_t i = b; i < e; i++) {
        s += (long)i;
        c->seen[i]++;
    }
    atomic_fetch_add(&c->sum, s);
    atomic_fetch_add(&c->calls, 1);
}

static void test_threads(void)
{
    t_suite = "threads";
    size_t n = 1000003;
    pf_ctx c = {.seen = calloc(n, 1)};
    atomic_init(&c.sum, 0);
    atomic_init(&c.calls, 0);
    for (int rep = 0; rep < 20; rep++) ms_parallel_for(n, 1000, pf_body, &c);
    int each = 1;
    for (size_t i = 0; i < n; i++) each &= c.seen[i] == 20;
    t_ok(each, "every index visited exactly once per loop (%d threads)", ms_threads_count());
    t_ok(atomic_load(&c.sum) == 20L * (long)(n * (n - 1) / 2), "sums agree");
    free(c.seen);
}

static atomic_int tids_used;

static void tid_body(void *vctx, size_t b, size_t e, int tid)
{
    pf_body(vctx, b, e, tid);
    atomic_fetch_or(&tids_used, 1 << (tid & 15));
    for (volatile int spin = 0; spin < 2000; spin++) {} /* give every thread a chance */
}

/* A limit below the pool's size keeps the loops to that many threads, and lifts again. */
static void test_thread_limit(void)
{
    t_suite = "threads";
    size_t n = 200000;
    pf_ctx c = {.seen = calloc(n, 1)};
    atomic_init(&c.sum, 0);
    atomic_init(&c.calls, 0);
    int pool = ms_threads_count();
    int before = ms_threads_set_limit(2);
    atomic_store(&tids_used, 0);
    for (int rep = 0; rep < 5; rep++) ms_parallel_for(n, 100, tid_body, &c);
    t_ok(before == 0 && ms_threads_count() == 2 && (atomic_load(&tids_used) & ~3) == 0,
         "limit 2 of a pool of %d: threads used 0x%x", pool, atomic_load(&tids_used));
    ms_threads_set_limit(0);
    atomic_store(&tids_used, 0);
    for (int rep = 0; rep < 5; rep++) ms_parallel_for(n, 100, tid_body, &c);
    t_ok(ms_threads_count() == pool && (atomic_load(&tids_used) & ~3) != 0,
         "no limit: the whole pool of %d works again (0x%x)", pool, atomic_load(&tids_used));
    int each = 1;
    for (size_t i = 0; i < n; i++) each &= c.seen[i] == 10;
    t_ok(each, "every index visited exactly once per loop, limited or not");
    free(c.seen);
}

/* Points in clusters with a few outliers far out, a NaN and an infinity. */
static float *grid_points(size_t n, unsigned seed)
{
    float *p = malloc(3 * n * sizeof *p);
    srand(seed);
    for (size_t i = 0; p && i < 3 * n; i++)
        p[i] = (float)(rand() % 20000) / 1000.0f + (i / 3 % 50 == 7 ? 400.0f : 0.0f);
    if (p && n > 10) p[3 * 3 + 1] = NAN, p[3 * 5 + 2] = INFINITY;
    return p;
}

static int finite_point(const float *p)
{
    return isfinite(p[0]) && isfinite(p[1]) && isfinite(p[2]);
}

static double dist2(const float *a, const float *b)
{
    double d = 0;
    for (int k = 0; k < 3; k++) d += ((double)a[k] - b[k]) * ((double)a[k] - b[k]);
    return d;
}

/* ms_grid_near's cells hold exactly the points within the cutoff of q. */
static int near_agrees(const ms_grid *g, const float *pts, size_t n, const float *q, double cut)
{
    ms_grid_run runs[9];
    int nr = ms_grid_near(g, q, runs);
    size_t found = 0, want = 0;
    for (size_t j = 0; j < n; j++) want += finite_point(pts + 3 * j) && dist2(q, pts + 3 * j) <= cut * cut;
    for (int r = 0; r < nr; r++)
        for (uint32_t k = runs[r].begin; k < runs[r].end; k++)
            found += dist2(q, pts + 3 * (size_t)g->items[k]) <= cut * cut;
    return found == want;
}

/* In double precision, then in single (the cells the representations' pair search uses). */
static void test_grid_near(int single)
{
    t_suite = single ? "grid, single precision" : "grid";
    size_t n = 3000;
    float *pts = grid_points(n, 7);
    ms_grid g;
    ms_error err = {{0}};
    ms_grid_points gp = {pts, 3, NULL, n};
    ms_grid_spec spec = {2.5, 4.0, 64.0, 1.26, single};
    t_ok(pts && ms_grid_build(&g, &gp, &spec, &err) == 0, "a grid over 3000 points builds");
    t_ok(g.n == n - 2 && g.start[g.ncells] == n - 2, "the two non-finite points are left out");
    t_ok(g.cell >= 2.5 && (double)g.ncells <= 4.0 * (double)g.n + 64.0,
         "cells at least the cutoff wide, at most 4 per point + 64 (%zu cells, %.2f wide)",
         g.ncells, g.cell);
    int ok = 1;
    for (size_t c = 0; c < g.ncells; c++)
        for (uint32_t k = g.start[c] + 1; k < g.start[c + 1]; k++) ok &= g.items[k] > g.items[k - 1];
    t_ok(ok, "items ascend inside every cell");
    ok = 1;
    for (size_t i = 0; i < n; i++) ok &= near_agrees(&g, pts, n, pts + 3 * i, 2.5);
    float outside[3] = {-3.0f, 5.0f, 5.0f}, far[3] = {-1000.0f, 5.0f, 5.0f};
    if (!single) ok &= near_agrees(&g, pts, n, outside, 2.5);   /* single: own points only */
    ms_grid_run runs[9];
    t_ok(ok, "the cells near each point hold every point within the cutoff");
    t_ok(ms_grid_near(&g, far, runs) == 0 && ms_grid_near(&g, pts + 9, runs) == 0,
         "a point far outside, or not finite, has no cells near it");
    ms_grid_free(&g);
    free(pts);
}

/* Each cell's own pairs and those with its forward half find every close pair once. */
static void test_grid_pairs(void)
{
    size_t n = 2000;
    float *pts = grid_points(n, 11);
    uint32_t *ids = malloc(n / 2 * sizeof *ids);
    for (size_t i = 0; ids && i < n / 2; i++) ids[i] = (uint32_t)(2 * i + 1);   /* odd ones */
    ms_grid g;
    ms_error err = {{0}};
    ms_grid_points gp = {pts, 3, ids, n / 2};
    ms_grid_spec spec = {1.7, 8.0, 64.0, 1.1, 0};
    t_ok(pts && ids && ms_grid_build(&g, &gp, &spec, &err) == 0, "a grid over a subset builds");
    size_t found = 0, want = 0, odd = 1;
    for (long z = 0; z < g.dim[2]; z++)
        for (long y = 0; y < g.dim[1]; y++)
            for (long x = 0; x < g.dim[0]; x++) {
                size_t c = ms_grid_index(&g, x, y, z);
                ms_grid_run runs[5];
                int nr = ms_grid_forward(&g, x, y, z, runs);
                for (uint32_t a = g.start[c]; a < g.start[c + 1]; a++) {
                    odd &= g.items[a] % 2;
                    for (uint32_t b = a + 1; b < g.start[c + 1]; b++)
                        found += dist2(pts + 3 * g.items[a], pts + 3 * g.items[b]) <= 1.7 * 1.7;
                    for (int r = 0; r < nr; r++)
                        for (uint32_t b = runs[r].begin; b < runs[r].end; b++)
                            found += dist2(pts + 3 * g.items[a], pts + 3 * g.items[b]) <= 1.7 * 1.7;
                }
            }
    for (size_t i = 1; i < n; i += 2)
        for (size_t j = i + 2; j < n; j += 2)
            want += finite_point(pts + 3 * i) && finite_point(pts + 3 * j) &&
                    dist2(pts + 3 * i, pts + 3 * j) <= 1.7 * 1.7;
    t_ok(odd, "the items are the ids given");
    t_ok(found == want && want > 0, "every pair within the cutoff is found once (%zu of %zu)",
         found, want);
    ms_grid_free(&g);
    free(ids);
    free(pts);
}

static void test_grid_edges(void)
{
    ms_grid g;
    ms_error err = {{0}};
    float one[3] = {1, 2, 3}, sparse[6] = {0, 0, 0, 1e30f, -1e30f, 1e30f};
    ms_grid_points none = {one, 3, NULL, 0}, far = {sparse, 3, NULL, 2};
    ms_grid_spec spec = {1.0, 2.0, 8.0, 1.26, 0};
    t_ok(ms_grid_build(&g, &none, &spec, &err) == 0 && g.n == 0 && g.ncells == 1,
         "no points: one empty cell");
    ms_grid_free(&g);
    int built = ms_grid_build(&g, &far, &spec, &err) == 0;
    t_ok(built && g.ncells <= 12 && g.n == 2, "two points 1e30 apart: a handful of cells (%zu)",
         g.ncells);
    ms_grid_run runs[9];
    int nr = ms_grid_near(&g, sparse + 3, runs);
    size_t held = 0;
    for (int r = 0; r < nr; r++) held += runs[r].end - runs[r].begin;
    t_ok(held >= 1, "a point's own cell is near it");
    ms_grid_free(&g);
}

static void test_hy36(void)
{
    t_suite = "hybrid36";
    struct { const char *s; long v; } cases[] = {
        {"99999", 99999}, {"A0000", 100000}, {"A0001", 100001}, {"ZZZZZ", 100000 + 26 * 1679616 - 1},
        {"a0000", 100000 + 26 * 1679616}, {"    1", 1}, {"-9999", -9999}};
    int ok = 1;
    for (size_t i = 0; i < sizeof cases / sizeof cases[0]; i++) {
        long v;
        char enc[8];
        if (ms_hy36_decode(cases[i].s, 5, &v) != 1 || v != cases[i].v) ok = 0;
        if (ms_hy36_encode(cases[i].v, 5, enc) || strcmp(enc, cases[i].s)) ok = 0;
    }
    t_ok(ok, "width 5 decodes and encodes the reference values");
    long v;
    t_ok(ms_hy36_decode("A000", 4, &v) == 1 && v == 10000, "width 4: A000 is 10000");
    t_ok(ms_hy36_decode("    ", 4, &v) == 0, "blank field is blank");
    t_ok(ms_hy36_decode("1A2", 3, &v) == -1, "mixed field is invalid");
    t_ok(ms_hy36_decode("A!00", 4, &v) == -1, "bad digit is invalid");
}

static void test_fields(void)
{
    t_suite = "fields";
    const char *line = "ATOM      1  N   SER     4      17.166  -7.606  -4.933  1.00 44.05";
    size_t n = strlen(line);
    float x = 0;
    t_ok(ms_field_float(line, n, 30, 38, &x) == 1 && x == 17.166f, "x field parses exactly");
    t_ok(ms_field_float(line, n, 70, 78, &x) == 0, "missing columns read as blank");
    t_ok(ms_field_float("  1.2.3 ", 8, 0, 8, &x) == -1, "malformed number is an error");
    t_ok(ms_field_float(" 1e3", 4, 0, 4, &x) == 1 && x == 1000.0f, "exponent form parses");
    double d;
    t_ok(ms_parse_double("-0.001", 6, &d) == 1 && d == -0.001, "fast path is exact here");
    char out[8];
    ms_field(line, n, 12, 16, out);
    t_ok(strcmp(out, "N") == 0, "field trimmed");
}

int main(void)
{
    setenv("MOLSCOPE_THREADS", "4", 1); /* a pool larger than a limit of 2, on any machine */
    test_strtab();
    test_grow();
    test_threads();
    test_thread_limit();
    test_grid_near(0);
    test_grid_near(1);
    test_grid_pairs();
    t_suite = "grid";
    test_grid_edges();
    test_hy36();
    test_fields();
    return t_done();
}
