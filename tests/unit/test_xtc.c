/* test_xtc.c: the XTC writer (plugins/xtc.c) through the plugin interface, read back by the
 * plugin's reader. Expected values come from the format's definition, computed here: a
 * coordinate x (Angstrom) is stored as the integer k = x * 100 rounded half away from zero
 * (nm times precision 1000) and read back as (k * (1/1000 in single precision)) * 10; up to
 * 9 atoms are stored as plain floats (x / 10); the header fields are read from the file's
 * bytes here. Systems: random clouds, chains of close atoms broken by far jumps (runs of
 * small differences and full triples), spacings growing and shrinking (the adaptive size),
 * ranges past 2^24 integers (separate bit fields) and past 2^64 packed (128-bit numbers),
 * 1..10 atoms, 1M atoms, and out-of-range coordinates. */
#include "config.h"
#include "builtin/builtin.h"
#include "ms_test.h"

#include <math.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <time.h>
#include <unistd.h>

static const ms_plugin *xtc;

static const char *scratch(const char *name)
{
    static char buf[4096];
    const char *dir = getenv("MS_TEST_OUT");
    snprintf(buf, sizeof buf, "%s/xtc_%ld_%s", dir ? dir : "/tmp", (long)getpid(), name);
    return buf;
}

/* The integer a coordinate is stored as, and the coordinate read back from it. */
static int64_t stored_int(float x)
{
    double v = (double)x * 100.0;
    return (int64_t)(v < 0 ? -floor(-v + 0.5) : floor(v + 0.5));
}

static float read_back(float x) { return ((float)stored_int(x) * (float)(1.0 / 1000)) * 10.0f; }

static uint32_t be32_at(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static float bef_at(const unsigned char *p)
{
    uint32_t v = be32_at(p);
    float f;
    memcpy(&f, &v, 4);
    return f;
}

/* Write nframes frames of pos (frame k: pos moved by k * shift in x) to path; 0 or -1 with
 * the message in err. */
static int write_frames(const char *path, const float *pos, long n, int nframes, float shift,
                        const float cell[6], ms_perr *err)
{
    void *h = xtc->open_write(path, n, err);
    if (!h) return -1;
    float *p = malloc((size_t)n * 3 * sizeof *p);
    int rc = p ? MS_PLUGIN_OK : MS_PLUGIN_ERROR;
    for (int k = 0; k < nframes && rc == MS_PLUGIN_OK; k++) {
        for (long i = 0; i < 3 * n; i++) p[i] = pos[i] + (i % 3 == 0 ? (float)k * shift : 0);
        ms_frame_in f;
        memset(&f, 0, sizeof f);
        f.pos = p;
        if (cell) memcpy(f.cell, cell, sizeof f.cell);
        f.time = 0.5 * k;
        f.index = k;
        rc = xtc->write_frame(h, NULL, &f, err);
    }
    free(p);
    int rc2 = xtc->close_write(h, err);
    return rc == MS_PLUGIN_OK && rc2 == MS_PLUGIN_OK ? 0 : -1;
}

/* Read path back: every frame must hold expect(pos moved by k * shift) exactly (plain:
 * x / 10 * 10 in floats). Returns the frames read, -1 on a mismatch or an error (*why). */
static int check_frames(const char *path, const float *pos, long n, float shift, int plain,
                        char *why, size_t whylen)
{
    ms_perr err = {{0}};
    long natoms = 0;
    void *h = xtc->open_read(path, &natoms, &err);
    if (!h || natoms != n) {
        snprintf(why, whylen, "open: %.400s (atoms %ld)", err.msg, natoms);
        if (h) xtc->close_read(h);
        return -1;
    }
    float *got = malloc((size_t)n * 3 * sizeof *got);
    int k = 0, rc;
    ms_frame_out fr;
    for (;; k++) {
        memset(&fr, 0, sizeof fr);
        fr.pos = got;
        if ((rc = xtc->read_frame(h, n, &fr, &err)) != MS_PLUGIN_OK) break;
        if (fr.time != 0.5 * k) {
            snprintf(why, whylen, "frame %d: time %g", k, fr.time);
            rc = MS_PLUGIN_ERROR;
            break;
        }
        long bad = -1;
        for (long i = 0; i < 3 * n && bad < 0; i++) {
            float x = pos[i] + (i % 3 == 0 ? (float)k * shift : 0);
            float want = plain ? (x / 10.0f) * 10.0f : read_back(x);
            if (got[i] != want) bad = i;
        }
        if (bad >= 0) {
            float x = pos[bad] + (bad % 3 == 0 ? (float)k * shift : 0);
            snprintf(why, whylen, "frame %d atom %ld: wrote %.9g read %.9g", k, bad / 3,
                     (double)x, (double)got[bad]);
            rc = MS_PLUGIN_ERROR;
            break;
        }
    }
    if (rc == MS_PLUGIN_ERROR && !why[0]) snprintf(why, whylen, "frame %d: %.400s", k, err.msg);
    free(got);
    xtc->close_read(h);
    return rc == MS_PLUGIN_EOF ? k : -1;
}

static long file_size(const char *path)
{
    struct stat sb;
    return stat(path, &sb) == 0 ? (long)sb.st_size : -1;
}

/* The first 96 bytes of a file. */
static int head_of(const char *path, unsigned char b[96])
{
    FILE *f = fopen(path, "rb");
    size_t got = f ? fread(b, 1, 96, f) : 0;
    if (f) fclose(f);
    return got == 96 ? 0 : -1;
}

/* Write and read back 3 frames of a system; `name` reports it. Returns the first frame's
 * compressed bytes (from its header), -1 on failure. */
static long round_trip(const char *name, const float *pos, long n)
{
    const char *path = scratch("rt.xtc");
    ms_perr err = {{0}};
    char why[512] = "";
    if (write_frames(path, pos, n, 3, 0.37f, NULL, &err) != 0) {
        t_ok(0, "%s: write: %s", name, err.msg);
        return -1;
    }
    int frames = check_frames(path, pos, n, 0.37f, 0, why, sizeof why);
    t_ok(frames == 3, "%s: %ld atoms, 3 frames read back to the file's precision (%s)", name, n,
         why);
    unsigned char b[96];
    long bytes = head_of(path, b) == 0 ? (long)be32_at(b + 88) : -1;
    unlink(path);
    return frames == 3 ? bytes : -1;
}

static unsigned long long rng_state = 88172645463325252ull;
static double urand(void)
{
    rng_state ^= rng_state << 13;
    rng_state ^= rng_state >> 7;
    rng_state ^= rng_state << 17;
    return (double)(rng_state >> 11) / 9007199254740992.0;
}

static float *alloc_pos(long n)
{
    float *p = malloc((size_t)n * 3 * sizeof *p);
    if (!p) {
        fprintf(stderr, "out of memory\n");
        exit(1);
    }
    return p;
}

/* A header written by the plugin: magic, atoms, step, time, box, precision, integer range. */
static void test_header(void)
{
    t_suite = "xtc_header";
    long n = 50;
    float *pos = alloc_pos(n);
    for (long i = 0; i < 3 * n; i++) pos[i] = (float)(urand() * 40 - 20);
    const float cell[6] = {37, 32, 37.5f, 80, 95, 107};
    const char *path = scratch("head.xtc");
    ms_perr err = {{0}};
    unsigned char b[96];
    if (!t_ok(write_frames(path, pos, n, 2, 1.0f, cell, &err) == 0 && head_of(path, b) == 0,
              "write 2 frames of 50 atoms with a triclinic cell (%s)", err.msg))
        return;
    int64_t lo[3] = {INT64_MAX, INT64_MAX, INT64_MAX}, hi[3] = {INT64_MIN, INT64_MIN, INT64_MIN};
    for (long i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            int64_t k = stored_int(pos[3 * i + d]);
            lo[d] = k < lo[d] ? k : lo[d];
            hi[d] = k > hi[d] ? k : hi[d];
        }
    int range_ok = 1;
    for (int d = 0; d < 3; d++)
        range_ok &= (int32_t)be32_at(b + 60 + 4 * d) == lo[d] &&
                    (int32_t)be32_at(b + 72 + 4 * d) == hi[d];
    t_ok(be32_at(b) == 1995 && be32_at(b + 4) == 50 && be32_at(b + 8) == 0 &&
             bef_at(b + 12) == 0.0f && be32_at(b + 52) == 50 && bef_at(b + 56) == 1000.0f,
         "magic 1995, 50 atoms (twice), step 0, time 0, precision 1000");
    t_ok(range_ok, "the integer range in the header is the rounded coordinates' bounding box");
    /* Box rows: a = (3.7, 0, 0) nm; b = 3.2 (cos 107, sin 107, 0); c from the cell. */
    double ga = 107 * M_PI / 180, be = 95 * M_PI / 180, al = 80 * M_PI / 180;
    double cx = 3.75 * cos(be), cy = 3.75 * (cos(al) - cos(be) * cos(ga)) / sin(ga);
    double want[9] = {3.7, 0, 0, 3.2 * cos(ga), 3.2 * sin(ga), 0, cx, cy,
                      sqrt(3.75 * 3.75 - cx * cx - cy * cy)};
    double worst = 0;
    for (int k = 0; k < 9; k++) worst = fmax(worst, fabs(bef_at(b + 16 + 4 * k) - want[k]));
    t_ok(worst < 1e-6, "the box matrix (nm, lower triangular) from a b c alpha beta gamma "
         "(worst %g nm)", worst);
    long natoms = 0;
    void *h = xtc->open_read(path, &natoms, &err);
    ms_frame_out fr;
    memset(&fr, 0, sizeof fr);
    float *got = alloc_pos(n);
    fr.pos = got;
    int ok = h && xtc->read_frame(h, n, &fr, &err) == MS_PLUGIN_OK;
    memset(&fr, 0, sizeof fr);
    fr.pos = got;
    ok = ok && xtc->read_frame(h, n, &fr, &err) == MS_PLUGIN_OK;
    double cw = 0;
    for (int k = 0; k < 6; k++) cw = fmax(cw, fabs(fr.cell[k] - cell[k]));
    t_ok(ok && fr.has_cell && cw < 1e-4 && fr.time == 0.5,
         "the second frame reads back with its cell (worst %g) and time %g", cw, fr.time);
    if (h) xtc->close_read(h);
    free(got);
    free(pos);
    unlink(path);
}

/* Random clouds, chains of close atoms with far jumps, spacings growing and shrinking. */
static void test_round_trips(void)
{
    t_suite = "xtc_roundtrip";
    long n = 3000;
    float *pos = alloc_pos(n);
    for (long i = 0; i < 3 * n; i++) pos[i] = (float)(urand() * 200 - 100);
    long cloud = round_trip("random cloud in 200 A", pos, n);
    /* Chains of 1 A steps (runs of small differences, longer than a run can hold), every
     * 37th atom jumping 60 A away (full triples). */
    float at[3] = {0, 0, 0};
    for (long i = 0; i < n; i++) {
        double step = i % 37 == 0 ? 60.0 : 1.0;
        for (int d = 0; d < 3; d++) {
            at[d] += (float)(step * (urand() - 0.5) * 2 / sqrt(3.0));
            pos[3 * i + d] = at[d];
        }
    }
    long chain = round_trip("chains of close atoms broken by far jumps", pos, n);
    /* The cloud's triples take 43 bits (20000^3 > 2^42) and a run flag: few of its atoms lie
     * close enough to the one before to be coded in fewer. */
    t_ok(cloud >= n * 40 / 8 && chain > 0 && chain * 3 < cloud * 2,
         "close atoms are coded as small differences: %ld bytes against %ld for a cloud", chain,
         cloud);
    t_ok(chain > 0 && chain < n * 4, "chains take under 4 bytes an atom (%.2f)",
         (double)chain / (double)n);
    /* Water-like triples: O, H 1 A away, H 1.6 A from the first H, molecules 3 A apart. */
    for (long i = 0; i < n; i++) {
        int r = (int)(i % 3);
        for (int d = 0; d < 3; d++)
            pos[3 * i + d] = r == 0 ? (float)(urand() * 60) : pos[3 * (i - 1) + d] +
                                                                    (float)(urand() - 0.5) * 1.1f;
    }
    round_trip("water-like triples", pos, n);
    /* Spacing growing from 0.01 A to 300 A and back: the size index goes up and down. */
    for (long i = 0; i < n; i++) {
        double t = (double)i / (double)(n - 1), s = 0.01 * pow(30000.0, 1 - fabs(2 * t - 1));
        for (int d = 0; d < 3; d++) {
            at[d] = i ? at[d] + (float)(s * (urand() - 0.5)) : 0;
            pos[3 * i + d] = at[d];
        }
    }
    round_trip("spacing 0.01 A -> 300 A -> 0.01 A", pos, n);
    /* Identical atoms and atoms 0.005 A apart (differences of 0 and 1 integer). */
    for (long i = 0; i < 3 * n; i++) pos[i] = i < 3 * n / 2 ? 5.0f : 5.0f + 0.005f * (float)(i % 2);
    round_trip("identical and nearly identical atoms", pos, n);
    /* Many random scales: clouds and walks of every size. */
    int ok = 1;
    for (int trial = 0; trial < 40 && ok; trial++) {
        long m = 10 + (long)(urand() * 400);
        double scale = pow(10.0, urand() * 9 - 2), walk = pow(10.0, urand() * 6 - 3);
        for (long i = 0; i < m; i++)
            for (int d = 0; d < 3; d++)
                pos[3 * i + d] = trial % 2 ? (float)((urand() - 0.5) * scale)
                                           : (i ? pos[3 * (i - 1) + d] : 0) +
                                                 (float)((urand() - 0.5) * walk);
        char name[64];
        snprintf(name, sizeof name, "random %s, scale %.3g", trial % 2 ? "cloud" : "walk",
                 trial % 2 ? scale : walk);
        ok = round_trip(name, pos, m) > 0;
    }
    free(pos);
}

/* Ranges of more than 2^24 integers (separate bit fields) and packed triples past 64 bits. */
static void test_large(void)
{
    t_suite = "xtc_large";
    long n = 400;
    float *pos = alloc_pos(n);
    /* +-30000 A: 6e6 integers a side, 2^67 for the three: 128-bit packing. */
    for (long i = 0; i < 3 * n; i++) pos[i] = (float)((urand() - 0.5) * 60000);
    round_trip("coordinates +-30000 A (packed triples of 68 bits)", pos, n);
    /* +-1e6 A: 2e8 integers a side (past 2^24: one field per coordinate), chains inside. */
    for (long i = 0; i < n; i++)
        for (int d = 0; d < 3; d++)
            pos[3 * i + d] = i % 5 ? pos[3 * (i - 1) + d] + (float)(urand() - 0.5)
                                   : (float)((urand() - 0.5) * 2e6);
    const char *path = scratch("large.xtc");
    ms_perr err = {{0}};
    char why[512] = "";
    unsigned char b[96];
    int rc = write_frames(path, pos, n, 2, 0.37f, NULL, &err);
    t_ok(rc == 0 && check_frames(path, pos, n, 0.37f, 0, why, sizeof why) == 2,
         "coordinates +-1e6 A with close atoms among them read back (%s%s)", err.msg, why);
    int large = head_of(path, b) == 0;
    for (int d = 0; d < 3 && large; d++)
        large = (int64_t)(int32_t)be32_at(b + 72 + 4 * d) - (int32_t)be32_at(b + 60 + 4 * d) >
                0xffffff;
    t_ok(large, "their integer ranges pass 2^24 (the format's large-integer coding)");
    /* A walk of steps up to 20000 A: small differences of more than 64 bits (the size
     * index in the header, chosen from the first differences, passes 64). */
    for (long i = 0; i < 3 * n; i++)
        pos[i] = (i < 3 ? 0 : pos[i - 3]) + (float)((urand() - 0.5) * 40000);
    rc = write_frames(path, pos, n, 2, 0.37f, NULL, &err);
    why[0] = '\0';
    int wide = rc == 0 && check_frames(path, pos, n, 0.37f, 0, why, sizeof why) == 2 &&
               head_of(path, b) == 0;
    t_ok(wide && (int32_t)be32_at(b + 84) > 64,
         "a walk of 20000 A steps reads back, coded with a size index past 64 (%d; %s%s)",
         (int)(int32_t)be32_at(b + 84), err.msg, why);
    /* The extremes: +-2e7 A (2e9 integers, 32-bit fields). */
    for (long i = 0; i < 3 * n; i++) pos[i] = (float)((urand() - 0.5) * 4e7);
    pos[0] = 2.0e7f;
    pos[4] = -2.0e7f;
    round_trip("coordinates up to +-2e7 A", pos, n);
    /* Out of range or not a number: an error naming the atom. */
    pos[3 * 17 + 1] = 3e7f;
    rc = write_frames(path, pos, n, 1, 0, NULL, &err);
    t_ok(rc != 0 && strstr(err.msg, "atom 17") && strstr(err.msg, "out of the XTC range"),
         "a coordinate of 3e7 A is an error naming the atom (%s)", err.msg);
    pos[3 * 17 + 1] = NAN;
    memset(&err, 0, sizeof err);
    rc = write_frames(path, pos, n, 1, 0, NULL, &err);
    t_ok(rc != 0 && strstr(err.msg, "atom 17"), "NaN is an error naming the atom (%s)", err.msg);
    unlink(path);
    free(pos);
}

/* 1..9 atoms as plain floats, 10 compressed. */
static void test_small(void)
{
    t_suite = "xtc_small";
    float pos[30];
    for (int i = 0; i < 30; i++) pos[i] = (float)(urand() * 50 - 25) + 0.123456f;
    const char *path = scratch("small.xtc");
    for (long n = 1; n <= 10; n++) {
        ms_perr err = {{0}};
        char why[512] = "";
        unsigned char b[96] = {0};
        int rc = write_frames(path, pos, n, 2, 0.5f, NULL, &err);
        int frames = rc == 0 ? check_frames(path, pos, n, 0.5f, n <= 9, why, sizeof why) : -1;
        long size = file_size(path);
        FILE *f = fopen(path, "rb");
        size_t got = f ? fread(b, 1, 96, f) : 0;
        if (f) fclose(f);
        if (n <= 9) {
            int plain = got >= 60 && size == 2 * (56 + 12 * n) && be32_at(b + 52) == (uint32_t)n &&
                        bef_at(b + 56) == pos[0] / 10.0f;
            t_ok(frames == 2 && plain, "%ld atoms: 2 frames of %ld bytes, plain floats (nm), "
                 "read back (%s%s; %ld bytes)", n, 56 + 12 * n, err.msg, why, size);
        } else {
            t_ok(frames == 2 && got == 96 && bef_at(b + 56) == 1000.0f,
                 "10 atoms: compressed at precision 1000 and read back (%s%s)", err.msg, why);
        }
    }
    unlink(path);
}

/* A million atoms (a replicated chain system): exact, and the time one frame takes. */
static void test_million(void)
{
    t_suite = "xtc_1m";
    long n = 1000000;
    float *pos = alloc_pos(n);
    float at[3] = {0, 0, 0};
    for (long i = 0; i < n; i++)
        for (int d = 0; d < 3; d++) {
            at[d] = i % 1000 ? at[d] + (float)(urand() - 0.5) * 2.5f : (float)(urand() * 1000);
            pos[3 * i + d] = at[d];
        }
    const char *path = scratch("1m.xtc");
    ms_perr err = {{0}};
    void *h = xtc->open_write(path, n, &err);
    ms_frame_in f;
    memset(&f, 0, sizeof f);
    f.pos = pos;
    struct timespec t0, t1;
    clock_gettime(CLOCK_MONOTONIC, &t0);
    int rc = h ? xtc->write_frame(h, NULL, &f, &err) : -1;
    clock_gettime(CLOCK_MONOTONIC, &t1);
    if (h && xtc->close_write(h, &err) != MS_PLUGIN_OK) rc = -1;
    double s = (double)(t1.tv_sec - t0.tv_sec) + 1e-9 * (double)(t1.tv_nsec - t0.tv_nsec);
    char why[512] = "";
    int frames = rc == 0 ? check_frames(path, pos, n, 0, 0, why, sizeof why) : -1;
    t_ok(frames == 1, "1M atoms: one frame written in %.3f s (%.1f bytes an atom), read back "
         "exactly (%s%s)", s, (double)file_size(path) / (double)n, err.msg, why);
    unlink(path);
    free(pos);
}

int main(void)
{
    xtc = ms_plugin_entry_xtc();
    if (!t_ok(xtc && xtc->open_write && xtc->write_frame && xtc->close_write &&
                  (xtc->caps & MS_CAN_WRITE_FRAMES),
              "the xtc plugin writes frames"))
        return t_done();
    test_header();
    test_round_trips();
    test_large();
    test_small();
    test_million();
    return t_done();
}
