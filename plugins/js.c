/* js.c: VMD's "js" binary structure and trajectory format (version 2), for the largest
 * systems: the structure as tables (a few distinct strings, 16-bit indices per atom, one
 * array per field) and frames as raw float coordinates, each block padded so that frames
 * start on page boundaries and are read straight into the frame's memory with one pread.
 * The layout is written down in doc/js-format.md. Read: atoms, optional fields, bonds (with
 * orders), frames with cells, either byte order; angles, dihedrals, impropers and
 * cross-terms are skipped. Written: native byte order, 4096-byte blocks, every field, bonds
 * with their orders. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <errno.h>
#include <limits.h>
#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define JS_MAGIC_TEXT "JS Binary Structure and Trajectory File Format"
#define JS_TEXT_LEN 46
#define JS_MAGIC 0x31337
#define JS_ENDIAN 0x12345678
#define JS_NFRAMES_AT (JS_TEXT_LEN + 20)
#define JS_HEADER (JS_TEXT_LEN + 24)     /* through nframes */
#define JS_PI 3.14159265358979323846

enum {
    JS_STRUCTURE = 0x1, JS_BONDS = 0x2, JS_BONDORDERS = 0x4, JS_ANGLES = 0x8, JS_CTERMS = 0x10,
    JS_OCCUPANCY = 0x100, JS_BFACTOR = 0x200, JS_MASS = 0x400, JS_CHARGE = 0x800,
    JS_RADIUS = 0x1000, JS_ATOMICNUMBER = 0x2000, JS_BLOCKIO = 0x10000000
};

/* The string tables: entry width and which atom field each names. */
enum { T_NAME, T_TYPE, T_RESNAME, T_SEGID, T_CHAIN, T_N };
static const int js_width[T_N] = {16, 16, 8, 8, 2};
static const int js_strf[T_N] = {MS_STRF_NAME, MS_STRF_TYPE, MS_STRF_RESNAME, MS_STRF_SEGNAME,
                                 MS_STRF_CHAIN};   /* the sink's field of each table */
static const char *const js_table_name[T_N] = {"atom name", "atom type", "residue name",
                                               "segment name", "chain"};
/* The optional float fields, in file order, and their flags. */
enum { F_OCC, F_BETA, F_MASS, F_CHARGE, F_RADIUS, F_N };
static const unsigned js_fflag[F_N] = {JS_OCCUPANCY, JS_BFACTOR, JS_MASS, JS_CHARGE, JS_RADIUS};

#define JS_CHUNK 65536

typedef struct js_reader {
    int fd;
    long long size;
    int swap;
    long natoms;
    unsigned opt;
    long long block;
    int count[T_N];              /* string table sizes */
    long long tables_at, index_at, resid_at, float_at[F_N], anum_at, bonds_at;
    long nbonds;
    long long ts_at, crd_pad, cell_pad;
    long frame;
} js_reader;

/* ---------------------------------------------------------------- byte order */

static uint32_t js_swap32(uint32_t v)
{
    return (v >> 24) | ((v >> 8) & 0xff00u) | ((v << 8) & 0xff0000u) | (v << 24);
}

static void js_swap_words(void *p, size_t n, size_t width)
{
    unsigned char *b = p;
    for (size_t i = 0; i < n; i++, b += width)
        for (size_t k = 0; k < width / 2; k++) {
            unsigned char t = b[k];
            b[k] = b[width - 1 - k];
            b[width - 1 - k] = t;
        }
}

/* Read n bytes at off; an error names what was read. */
static int js_pread(js_reader *r, void *dst, size_t n, long long off, const char *what,
                    ms_perr *err)
{
    size_t got = 0;
    while (got < n) {
        ssize_t k = pread(r->fd, (char *)dst + got, n - got, (off_t)(off + (long long)got));
        if (k < 0 && errno == EINTR) continue;
        if (k < 0) return ms_perr_set(err, "reading the %s: %s", what, strerror(errno));
        if (k == 0)
            return ms_perr_set(err, "the file ends in the %s (byte %lld of %lld)", what,
                               off + (long long)got, r->size);
        got += (size_t)k;
    }
    return MS_PLUGIN_OK;
}

static int js_int(js_reader *r, long long off, const char *what, int32_t *v, ms_perr *err)
{
    uint32_t u;
    if (js_pread(r, &u, 4, off, what, err)) return MS_PLUGIN_ERROR;
    if (r->swap) u = js_swap32(u);
    memcpy(v, &u, 4);
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- layout */

/* A count read from the file: within [0, max]. */
static int js_count(js_reader *r, long long off, const char *what, long max, long *v,
                    ms_perr *err)
{
    int32_t c;
    if (js_int(r, off, what, &c, err)) return MS_PLUGIN_ERROR;
    if (c < 0 || c > max) return ms_perr_set(err, "bad %s %d (at byte %lld)", what, c, off);
    *v = c;
    return MS_PLUGIN_OK;
}

/* Where the structure's tables and arrays lie (after the option flags at `at`). */
static int js_structure_layout(js_reader *r, long long at, ms_perr *err)
{
    long n = r->natoms;
    for (int t = 0; t < T_N; t++) {
        long c = 0;
        if (js_count(r, at + 4 * t, "string table size", 32768, &c, err)) return MS_PLUGIN_ERROR;
        if (c == 0) return ms_perr_set(err, "the %s table is empty", js_table_name[t]);
        r->count[t] = (int)c;
    }
    r->tables_at = at + 4 * T_N;
    long long p = r->tables_at;
    for (int t = 0; t < T_N; t++) p += (long long)r->count[t] * js_width[t];
    r->index_at = p;
    r->resid_at = p + 2LL * T_N * n;
    p = r->resid_at + 4LL * n;
    for (int f = 0; f < F_N; f++) {
        r->float_at[f] = r->opt & js_fflag[f] ? p : -1;
        if (r->opt & js_fflag[f]) p += 4LL * n;
    }
    r->anum_at = r->opt & JS_ATOMICNUMBER ? p : -1;
    if (r->opt & JS_ATOMICNUMBER) p += 4LL * n;
    if (p > r->size)
        return ms_perr_set(err, "the structure of %ld atoms needs %lld bytes, the file has %lld",
                           n, p, r->size);
    r->bonds_at = p;
    return MS_PLUGIN_OK;
}

/* Skip a block of `count` records of `ints` int32 each, preceded by its count. */
static int js_skip_block(js_reader *r, long long *p, int ints, const char *what, ms_perr *err)
{
    long c = 0;
    if (js_count(r, *p, what, 0x7fffffffL, &c, err)) return MS_PLUGIN_ERROR;
    *p += 4 + 4LL * ints * c;
    if (*p > r->size) return ms_perr_set(err, "the file ends in the %s", what);
    return MS_PLUGIN_OK;
}

/* The bonds, angles and cross-terms after the atom arrays, then the first frame's offset. */
static int js_tail_layout(js_reader *r, ms_perr *err)
{
    long long p = r->bonds_at;
    if (r->opt & JS_BONDS) {
        if (js_count(r, p, "bond count", 0x7fffffffL, &r->nbonds, err)) return MS_PLUGIN_ERROR;
        p += 4 + 8LL * r->nbonds + (r->opt & JS_BONDORDERS ? 4LL * r->nbonds : 0);
        if (p > r->size)
            return ms_perr_set(err, "the file ends in its %ld bonds", r->nbonds);
    }
    if (r->opt & JS_ANGLES)
        if (js_skip_block(r, &p, 3, "angles", err) || js_skip_block(r, &p, 4, "dihedrals", err) ||
            js_skip_block(r, &p, 4, "impropers", err))
            return MS_PLUGIN_ERROR;
    if ((r->opt & JS_CTERMS) && js_skip_block(r, &p, 8, "cross-terms", err))
        return MS_PLUGIN_ERROR;
    long long mask = r->block - 1;
    r->ts_at = (p + mask) & ~mask;
    r->crd_pad = (12LL * r->natoms + mask) & ~mask;
    r->cell_pad = (48 + mask) & ~mask;
    return MS_PLUGIN_OK;
}

/* The fixed header: magic text, numbers, byte order, version, atom count, option flags. */
static int js_header(js_reader *r, ms_perr *err)
{
    unsigned char h[JS_HEADER + 8];
    if (r->size < JS_HEADER + 4 || js_pread(r, h, JS_HEADER + 4, 0, "header", err))
        return ms_perr_set(err, "not a js file: shorter than its %d-byte header", JS_HEADER + 4);
    if (memcmp(h, JS_MAGIC_TEXT, JS_TEXT_LEN) != 0)
        return ms_perr_set(err, "not a js file: it does not start with '%s'", JS_MAGIC_TEXT);
    uint32_t w[6];
    memcpy(w, h + JS_TEXT_LEN, sizeof w);
    if (w[0] != JS_MAGIC || w[1] != JS_ENDIAN) {
        js_swap_words(w, 6, 4);
        r->swap = 1;
        if (w[0] != JS_MAGIC || w[1] != JS_ENDIAN)
            return ms_perr_set(err, "bad js header: magic number or byte-order mark is wrong");
    }
    if (w[2] != 2) return ms_perr_set(err, "js version %u is not supported (only 2)", w[2]);
    if ((int32_t)w[4] < 1) return ms_perr_set(err, "bad atom count %d", (int32_t)w[4]);
    r->natoms = (int32_t)w[4];
    int32_t opt;
    if (js_int(r, JS_HEADER, "option flags", &opt, err)) return MS_PLUGIN_ERROR;
    r->opt = (unsigned)opt;
    r->block = 1;
    long long at = JS_HEADER + 4;
    if (r->opt & JS_BLOCKIO) {
        int32_t b;
        if (js_int(r, at, "block size", &b, err)) return MS_PLUGIN_ERROR;
        if (b < 1 || b > (1 << 24) || (b & (b - 1)))
            return ms_perr_set(err, "bad block size %d (a power of 2 up to 16 MiB)", b);
        r->block = b;
        at += 4;
    }
    if (!(r->opt & JS_STRUCTURE)) {
        /* only frames vouch for the atom count: the file must hold one */
        r->bonds_at = at;
        r->opt &= ~(unsigned)(JS_BONDS | JS_ANGLES | JS_CTERMS);
        if (js_tail_layout(r, err)) return MS_PLUGIN_ERROR;
        if (r->ts_at + 12LL * r->natoms + 48 > r->size)
            return ms_perr_set(err, "a js file without structure must hold a frame: %ld atoms "
                               "need %lld bytes, the file has %lld", r->natoms,
                               r->ts_at + 12LL * r->natoms + 48, r->size);
        return MS_PLUGIN_OK;
    }
    return js_structure_layout(r, at, err) || js_tail_layout(r, err) ? MS_PLUGIN_ERROR
                                                                      : MS_PLUGIN_OK;
}

static void js_close_read(void *h)
{
    js_reader *r = h;
    if (r->fd >= 0) close(r->fd);
    free(r);
}

static void *js_open_read(const char *path, long *natoms, ms_perr *err)
{
    js_reader *r = calloc(1, sizeof *r);
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    FILE *fp = ms_open_sized(path, &r->size, err);
    r->fd = fp ? dup(fileno(fp)) : -1;
    if (fp) fclose(fp);
    if (r->fd < 0 || js_header(r, err)) {
        if (r->fd < 0 && fp) ms_perr_set(err, "%s", strerror(errno));
        js_close_read(r);
        return NULL;
    }
    *natoms = r->natoms;
    return r;
}

/* ---------------------------------------------------------------- structure */

typedef struct js_tables {
    char *text[T_N];            /* count[t] entries of js_width[t] bytes, NUL-terminated */
    const char **entry[T_N];    /* each entry's address, for the sink's set_strings */
} js_tables;

static void js_tables_free(js_tables *t)
{
    for (int k = 0; k < T_N; k++) free(t->text[k]), free(t->entry[k]);
}

static int js_read_tables(js_reader *r, js_tables *t, ms_perr *err)
{
    long long p = r->tables_at;
    for (int k = 0; k < T_N; k++) {
        size_t bytes = (size_t)r->count[k] * (size_t)js_width[k];
        if (!(t->text[k] = malloc(bytes)) ||
            !(t->entry[k] = malloc((size_t)r->count[k] * sizeof *t->entry[k])))
            return ms_perr_set(err, "out of memory");
        if (js_pread(r, t->text[k], bytes, p, js_table_name[k], err)) return MS_PLUGIN_ERROR;
        for (int i = 0; i < r->count[k]; i++) {
            t->text[k][(size_t)(i + 1) * js_width[k] - 1] = 0;
            t->entry[k][i] = t->text[k] + (size_t)i * js_width[k];
        }
        p += (long long)bytes;
    }
    return MS_PLUGIN_OK;
}

/* One chunk of every per-atom array. */
typedef struct js_chunk {
    int16_t *idx[T_N];
    uint32_t *str[T_N];          /* idx checked and widened, for the sink's add_atoms */
    int32_t *resid, *anum;
    float *f[F_N];
    char *block;                 /* the arrays above, for at most n atoms each */
} js_chunk;

/* Room for n atoms (no more than a file's atom count: small files stay cheap). */
static int js_chunk_alloc(js_chunk *c, long n)
{
    size_t per = 6 * T_N + 8 + 4 * F_N, un = (size_t)n;
    if (!(c->block = malloc(per * un))) return -1;
    char *p = c->block;
    for (int t = 0; t < T_N; t++) c->str[t] = (uint32_t *)p, p += 4 * un;
    c->resid = (int32_t *)p, p += 4 * un;
    c->anum = (int32_t *)p, p += 4 * un;
    for (int f = 0; f < F_N; f++) c->f[f] = (float *)p, p += 4 * un;
    for (int t = 0; t < T_N; t++) c->idx[t] = (int16_t *)p, p += 2 * un;
    return 0;
}

static int js_read_chunk(js_reader *r, js_chunk *c, long first, long n, ms_perr *err)
{
    for (int t = 0; t < T_N; t++) {
        long long at = r->index_at + 2LL * (t * (long long)r->natoms + first);
        if (js_pread(r, c->idx[t], 2 * (size_t)n, at, "atom indices", err)) return MS_PLUGIN_ERROR;
        if (r->swap) js_swap_words(c->idx[t], (size_t)n, 2);
    }
    if (js_pread(r, c->resid, 4 * (size_t)n, r->resid_at + 4LL * first, "resids", err))
        return MS_PLUGIN_ERROR;
    if (r->swap) js_swap_words(c->resid, (size_t)n, 4);
    for (int f = 0; f < F_N; f++) {
        if (r->float_at[f] < 0) continue;
        if (js_pread(r, c->f[f], 4 * (size_t)n, r->float_at[f] + 4LL * first, "atom fields", err))
            return MS_PLUGIN_ERROR;
        if (r->swap) js_swap_words(c->f[f], (size_t)n, 4);
    }
    if (r->anum_at >= 0) {
        if (js_pread(r, c->anum, 4 * (size_t)n, r->anum_at + 4LL * first, "atomic numbers", err))
            return MS_PLUGIN_ERROR;
        if (r->swap) js_swap_words(c->anum, (size_t)n, 4);
    }
    return MS_PLUGIN_OK;
}

/* The string indices of a chunk's n atoms (the first is atom `first` of the file), checked
 * and widened one column at a time; an error names the first bad atom, and its first bad
 * field. */
static int js_chunk_strings(const js_reader *r, const js_chunk *c, long first, long n,
                            ms_perr *err)
{
    long bad = n;
    int bad_field = 0;
    for (int f = 0; f < T_N; f++) {
        const int16_t *x = c->idx[f];
        uint32_t *dst = c->str[f], most = 0;
        for (long k = 0; k < n; k++) {
            uint32_t v = (uint32_t)(int32_t)x[k];   /* a negative index becomes huge */
            dst[k] = v;
            most = v > most ? v : most;
        }
        if (most < (uint32_t)r->count[f]) continue;
        long k = 0;
        while (k < n && dst[k] < (uint32_t)r->count[f]) k++;
        if (k < bad) bad = k, bad_field = f;
    }
    if (bad == n) return MS_PLUGIN_OK;
    return ms_perr_set(err, "atom %ld: %s index %d is outside its table of %d", first + bad + 1,
                       js_table_name[bad_field], c->idx[bad_field][bad], r->count[bad_field]);
}

/* Atom k of a chunk as a record pointing into the tables (the one-atom-a-call path). */
static void js_atom(const js_reader *r, const js_tables *t, const js_chunk *c, long k,
                    ms_atom_in *a)
{
    const char *s[T_N];
    for (int f = 0; f < T_N; f++) s[f] = t->text[f] + (size_t)c->str[f][k] * js_width[f];
    memset(a, 0, sizeof *a);
    a->name = s[T_NAME];
    a->type = s[T_TYPE];
    a->resname = s[T_RESNAME];
    a->segname = s[T_SEGID];
    a->chain = s[T_CHAIN];
    a->resid = c->resid[k];
    static const unsigned has[F_N] = {MS_HAS_OCCUPANCY, MS_HAS_BETA, MS_HAS_MASS, MS_HAS_CHARGE,
                                      MS_HAS_RADIUS};
    float *dst[F_N] = {&a->occupancy, &a->beta, &a->mass, &a->charge, &a->radius};
    for (int f = 0; f < F_N; f++)
        if (r->float_at[f] >= 0) {
            *dst[f] = c->f[f][k];
            a->has |= has[f];
        }
    if (r->anum_at >= 0 && c->anum[k] > 0) {
        a->atomicnumber = c->anum[k];
        a->has |= MS_HAS_ATOMICNUMBER;
    }
}

/* A chunk of n atoms as columns (ABI 4). */
static void js_chunk_columns(const js_reader *r, const js_chunk *c, long n, ms_atom_columns *col)
{
    memset(col, 0, sizeof *col);
    col->n = (size_t)n;
    for (int f = 0; f < T_N; f++) col->str[js_strf[f]] = c->str[f];
    col->resid = c->resid;
    const float **dst[F_N] = {&col->occupancy, &col->beta, &col->mass, &col->charge,
                              &col->radius};
    for (int f = 0; f < F_N; f++)
        if (r->float_at[f] >= 0) *dst[f] = c->f[f];
    if (r->anum_at >= 0) col->atomicnumber = c->anum;
}

/* The bulk path: whether to take it (MOLSCOPE_JS_PER_ATOM=1 asks for one add_atom a call,
 * which tests compare it with), and the tables given to the sink. */
static int js_bulk(const ms_struct_sink *sink)
{
    const char *v = getenv("MOLSCOPE_JS_PER_ATOM");
    return sink->add_atoms && !(v && *v && strcmp(v, "0") != 0);
}

static int js_set_strings(const js_reader *r, const js_tables *t, ms_struct_sink *sink,
                          ms_perr *err)
{
    for (int f = 0; f < T_N; f++)
        if (sink->set_strings(sink, js_strf[f], (size_t)r->count[f], t->entry[f]))
            return ms_perr_set(err, "out of memory for the %s table", js_table_name[f]);
    return MS_PLUGIN_OK;
}

/* Hand a chunk of n atoms (the first is atom `first`) to the sink. */
static int js_give_chunk(js_reader *r, const js_tables *t, const js_chunk *c, long first,
                         long n, int bulk, ms_struct_sink *sink, ms_perr *err)
{
    if (js_chunk_strings(r, c, first, n, err)) return MS_PLUGIN_ERROR;
    if (bulk) {
        ms_atom_columns col;
        js_chunk_columns(r, c, n, &col);
        if (sink->add_atoms(sink, &col))
            return ms_perr_set(err, "out of memory at atom %ld", first + 1);
        return MS_PLUGIN_OK;
    }
    for (long k = 0; k < n; k++) {
        ms_atom_in a;
        js_atom(r, t, c, k, &a);
        if (sink->add_atom(sink, &a))
            return ms_perr_set(err, "out of memory at atom %ld", first + k + 1);
    }
    return MS_PLUGIN_OK;
}

static int js_read_atoms(js_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    js_tables t;
    memset(&t, 0, sizeof t);
    js_chunk chunk, *c = &chunk;
    memset(c, 0, sizeof *c);
    int bulk = js_bulk(sink);
    int rc = js_chunk_alloc(c, r->natoms < JS_CHUNK ? r->natoms : JS_CHUNK) == 0
                 ? js_read_tables(r, &t, err)
                 : ms_perr_set(err, "out of memory");
    if (rc == MS_PLUGIN_OK && bulk) rc = js_set_strings(r, &t, sink, err);
    for (long first = 0; rc == MS_PLUGIN_OK && first < r->natoms; first += JS_CHUNK) {
        long n = r->natoms - first < JS_CHUNK ? r->natoms - first : JS_CHUNK;
        rc = js_read_chunk(r, c, first, n, err);
        if (rc == MS_PLUGIN_OK) rc = js_give_chunk(r, &t, c, first, n, bulk, sink, err);
    }
    free(c->block);
    js_tables_free(&t);
    return rc;
}

/* One batch of k bonds (the first is bond `first`): checked, 0-based, orders defaulted. */
static int js_give_bonds(js_reader *r, long long first, size_t k, int32_t *from, int32_t *to,
                         float *ord, ms_struct_sink *sink, ms_perr *err)
{
    int orders = (r->opt & JS_BONDORDERS) != 0;
    for (size_t b = 0; b < k; b++) {
        if (from[b] < 1 || from[b] > r->natoms || to[b] < 1 || to[b] > r->natoms)
            return ms_perr_set(err, "bond %lld joins atoms %d and %d of %ld",
                               first + (long long)b + 1, from[b], to[b], r->natoms);
        from[b]--, to[b]--;
        ord[b] = orders && isfinite(ord[b]) ? ord[b] : 1.0f;
    }
    int bulk = js_bulk(sink), bad = 0;
    if (bulk) bad = sink->add_bonds(sink, k, (const uint32_t *)from, (const uint32_t *)to, ord);
    for (size_t b = 0; !bulk && !bad && b < k; b++)
        bad = sink->add_bond(sink, (size_t)from[b], (size_t)to[b], ord[b]);
    return bad ? ms_perr_set(err, "out of memory for bonds") : MS_PLUGIN_OK;
}

/* Bonds: from and to arrays (1-based), then orders. */
static int js_read_bonds(js_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    enum { B = 16384 };
    int32_t from[B], to[B];
    float ord[B];
    long long at = r->bonds_at + 4, n = r->nbonds;
    for (long long first = 0; first < n; first += B) {
        size_t k = (size_t)(n - first < B ? n - first : B);
        if (js_pread(r, from, 4 * k, at + 4 * first, "bonds", err) ||
            js_pread(r, to, 4 * k, at + 4 * (n + first), "bonds", err) ||
            ((r->opt & JS_BONDORDERS) &&
             js_pread(r, ord, 4 * k, at + 4 * (2 * n + first), "bond orders", err)))
            return MS_PLUGIN_ERROR;
        if (r->swap) js_swap_words(from, k, 4), js_swap_words(to, k, 4), js_swap_words(ord, k, 4);
        if (js_give_bonds(r, first, k, from, to, ord, sink, err)) return MS_PLUGIN_ERROR;
    }
    sink->bonds_complete(sink);
    return MS_PLUGIN_OK;
}

/* A file without a structure: blank atoms, as a trajectory. */
static int js_blank_atoms(js_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    ms_atom_columns col;
    memset(&col, 0, sizeof col);
    col.n = (size_t)r->natoms;
    if (js_bulk(sink)) {
        if (sink->add_atoms(sink, &col)) return ms_perr_set(err, "out of memory for atoms");
        return MS_PLUGIN_OK;
    }
    ms_atom_in a;
    memset(&a, 0, sizeof a);
    for (long i = 0; i < r->natoms; i++)
        if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory at atom %ld", i + 1);
    return MS_PLUGIN_OK;
}

static int js_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    js_reader *r = h;
    if (sink->reserve(sink, (size_t)r->natoms))
        return ms_perr_set(err, "out of memory for %ld atoms", r->natoms);
    if (!(r->opt & JS_STRUCTURE)) return js_blank_atoms(r, sink, err);
    if (js_read_atoms(r, sink, err)) return MS_PLUGIN_ERROR;
    return (r->opt & JS_BONDS) ? js_read_bonds(r, sink, err) : MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- frames */

static int js_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    js_reader *r = h;
    long long at = r->ts_at + r->frame * (r->crd_pad + r->cell_pad);
    if (at >= r->size) return MS_PLUGIN_EOF;
    if (natoms != r->natoms) return ms_perr_set(err, "the file has %ld atoms, not %ld", r->natoms, natoms);
    if (at + r->crd_pad + 48 > r->size)
        return ms_perr_set(err, "frame %ld is truncated: the file ends %lld bytes into it",
                           r->frame + 1, r->size - at);
    r->frame++;
    double cell[6];
    if (js_pread(r, cell, sizeof cell, at + r->crd_pad, "unit cell", err)) return MS_PLUGIN_ERROR;
    if (fr->pos) {
        if (js_pread(r, fr->pos, 12 * (size_t)natoms, at, "coordinates", err))
            return MS_PLUGIN_ERROR;
        if (r->swap) js_swap_words(fr->pos, 3 * (size_t)natoms, 4);
    }
    if (r->swap) js_swap_words(cell, 6, 8);
    for (int k = 0; k < 3; k++) {
        double s = cell[3 + k] > 1 ? 1 : cell[3 + k] < -1 ? -1 : cell[3 + k];
        fr->cell[k] = isfinite(cell[k]) ? (float)cell[k] : 0.0f;
        fr->cell[3 + k] = isfinite(s) ? (float)(90.0 - asin(s) * 180.0 / JS_PI) : 90.0f;
    }
    fr->has_cell = 1;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

#define JS_BLOCK 4096

typedef struct js_writer {
    ms_out out;
    long natoms;
    long long bytes;       /* written so far */
    int frames;
} js_writer;

static void *js_open_write(const char *path, long natoms, ms_perr *err)
{
    if (natoms < 1 || natoms > 0x7fffffffL) {
        ms_perr_set(err, "cannot write %ld atoms to a js file", natoms);
        return NULL;
    }
    js_writer *w = ms_out_create(sizeof *w, path, err);
    if (w) w->natoms = natoms;
    return w;
}

static void js_put(js_writer *w, const void *p, size_t n)
{
    ms_out_write(&w->out, p, n);
    w->bytes += (long long)n;
}

static void js_put_int(js_writer *w, int32_t v) { js_put(w, &v, 4); }

/* Zeros up to the next block boundary. */
static void js_pad(js_writer *w)
{
    static const char zero[JS_BLOCK];
    size_t n = (size_t)((JS_BLOCK - w->bytes % JS_BLOCK) % JS_BLOCK);
    js_put(w, zero, n);
}

/* A string table being built: distinct strings of one field, found by hashing. */
typedef struct js_table {
    int width, n;
    char *text;                  /* n entries of width bytes */
    int32_t *slot;               /* hash slots: entry + 1, 0 empty */
    uint32_t mask;               /* slots - 1: at least twice the entries there can be */
} js_table;

/* A table for the distinct strings of n atoms (at most 32767). */
static js_table *js_table_new(int width, size_t n)
{
    js_table *t = calloc(1, sizeof *t);
    size_t most = n < 32767 ? n : 32767, slots = 16;
    while (slots < 2 * most) slots *= 2;
    if (t && (t->text = malloc(most * (size_t)width + 1)) &&
        (t->slot = calloc(slots, sizeof *t->slot))) {
        t->width = width;
        t->mask = (uint32_t)(slots - 1);
        return t;
    }
    if (t) free(t->text), free(t);
    return NULL;
}

static void js_table_free(js_table *t)
{
    if (t) free(t->text), free(t->slot), free(t);
}

static uint32_t js_hash(const char *s, int width)
{
    uint32_t h = 2166136261u;
    for (int k = 0; k < width && s[k]; k++) h = (h ^ (unsigned char)s[k]) * 16777619u;
    return h;
}

/* The index of s (truncated to the table's width) in t, added when new; -1 when full. */
static int js_table_index(js_table *t, const char *s)
{
    char key[16] = {0};
    for (int k = 0; s && k < t->width - 1 && s[k]; k++) key[k] = s[k];
    for (uint32_t h = js_hash(key, t->width) & t->mask;; h = (h + 1) & t->mask) {
        int32_t e = t->slot[h];
        if (!e) break;
        if (memcmp(t->text + (size_t)(e - 1) * t->width, key, (size_t)t->width) == 0) return e - 1;
    }
    if (t->n >= 32767 || 2 * (uint32_t)t->n >= t->mask) return -1;
    uint32_t h = js_hash(key, t->width) & t->mask;
    while (t->slot[h]) h = (h + 1) & t->mask;
    t->slot[h] = ++t->n;
    memcpy(t->text + (size_t)(t->n - 1) * t->width, key, (size_t)t->width);
    return t->n - 1;
}

/* The string of field f of an atom. */
static const char *js_field(const ms_atom_in *a, int f)
{
    const char *s[T_N] = {a->name, a->type, a->resname, a->segname, a->chain};
    return s[f];
}

/* The per-atom arrays in file order: T_N arrays of int16 indices, then 7 arrays of 32-bit
 * numbers (resid, occupancy, beta, mass, charge, radius, atomic number). */
typedef struct js_columns {
    int16_t *idx;
    uint32_t *num;
} js_columns;

/* One pass over the atoms: the five tables, every atom's indices and numbers. */
static int js_build_columns(const ms_struct_view *v, js_table **tab, js_columns *c,
                            ms_perr *err)
{
    size_t n = v->natoms;
    for (size_t i = 0; i < n; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        for (int f = 0; f < T_N; f++) {
            int k = js_table_index(tab[f], js_field(&a, f));
            if (k < 0)
                return ms_perr_set(err, "more than 32767 distinct %ss: the js format cannot "
                                   "hold them", js_table_name[f]);
            c->idx[(size_t)f * n + i] = (int16_t)k;
        }
        const float fv[F_N] = {a.occupancy, a.beta, a.mass, a.charge, a.radius};
        const int32_t iv[2] = {a.resid, a.atomicnumber};
        memcpy(&c->num[i], &iv[0], 4);
        for (int f = 0; f < F_N; f++) memcpy(&c->num[(size_t)(1 + f) * n + i], &fv[f], 4);
        memcpy(&c->num[(size_t)(1 + F_N) * n + i], &iv[1], 4);
    }
    return MS_PLUGIN_OK;
}

/* Bonds i < j: the count, all from (1-based), all to, then every order (the view's orders,
 * when the host gives them). */
static void js_write_bonds(js_writer *w, const ms_struct_view *v)
{
    int32_t n = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const unsigned *to;
        size_t k = v->get_bonds(v, i, &to);
        for (size_t b = 0; b < k; b++) n += to[b] > i;
    }
    js_put_int(w, n);
    for (int pass = 0; pass < 3; pass++)
        for (size_t i = 0; i < v->natoms; i++) {
            const unsigned *to;
            size_t k = v->get_bonds(v, i, &to);
            for (size_t b = 0; b < k; b++) {
                if (to[b] <= i) continue;
                if (pass < 2) {
                    js_put_int(w, (int32_t)(pass ? to[b] + 1 : i + 1));
                    continue;
                }
                float order = 1.0f;
                const char *type;
                if (v->get_bond_info) v->get_bond_info(v, i, b, &order, &type);
                js_put(w, &order, sizeof order);
            }
        }
}

static int js_write_structure(void *h, const ms_struct_view *v, ms_perr *err)
{
    js_writer *w = h;
    js_table *tab[T_N] = {0};
    size_t n = v->natoms;
    js_columns c = {malloc(2 * T_N * n + 1), malloc(4 * (F_N + 2) * n + 1)};
    int rc = c.idx && c.num ? MS_PLUGIN_OK : ms_perr_set(err, "out of memory for %zu atoms", n);
    for (int f = 0; rc == MS_PLUGIN_OK && f < T_N; f++)
        if (!(tab[f] = js_table_new(js_width[f], n))) rc = ms_perr_set(err, "out of memory");
    if (rc == MS_PLUGIN_OK) rc = js_build_columns(v, tab, &c, err);
    if (rc == MS_PLUGIN_OK) {
        const int32_t head[6] = {JS_MAGIC, JS_ENDIAN, 2, 9, (int32_t)n, 0};
        js_put(w, JS_MAGIC_TEXT, JS_TEXT_LEN);
        js_put(w, head, sizeof head);
        js_put_int(w, JS_STRUCTURE | JS_BONDS | JS_BONDORDERS | JS_OCCUPANCY | JS_BFACTOR | JS_MASS | JS_CHARGE |
                          JS_RADIUS | JS_ATOMICNUMBER | JS_BLOCKIO);
        js_put_int(w, JS_BLOCK);
        for (int f = 0; f < T_N; f++) js_put_int(w, tab[f]->n);
        for (int f = 0; f < T_N; f++) js_put(w, tab[f]->text, (size_t)tab[f]->n * js_width[f]);
        js_put(w, c.idx, 2 * T_N * n);
        js_put(w, c.num, 4 * (F_N + 2) * n);
        js_write_bonds(w, v);
        js_pad(w);
        if (w->out.failed) rc = ms_perr_set(err, "write failed");
    }
    for (int f = 0; f < T_N; f++) js_table_free(tab[f]);
    free(c.idx);
    free(c.num);
    return rc;
}

static int js_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    js_writer *w = h;
    (void)v;
    double cell[6];
    for (int k = 0; k < 3; k++) {
        cell[k] = f->cell[k];
        cell[3 + k] = sin((90.0 - f->cell[3 + k]) * JS_PI / 180.0);
    }
    js_put(w, f->pos, 12 * (size_t)w->natoms);
    js_pad(w);
    js_put(w, cell, sizeof cell);
    js_pad(w);
    w->frames++;
    return w->out.failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

/* The frame count in the header; a stream that cannot seek keeps 0 (readers count frames
 * from the file's size). */
static int js_close_write(void *h, ms_perr *err)
{
    js_writer *w = h;
    if (!w->out.failed && fflush(w->out.fp) == 0 && fseek(w->out.fp, JS_NFRAMES_AT, SEEK_SET) == 0) {
        int32_t n = w->frames;
        if (fwrite(&n, 4, 1, w->out.fp) != 1) w->out.failed = 1;
    }
    return ms_out_destroy(w, err);
}

/* Frames are found by number: the token is one. */
static int js_tell_frame(void *h, long long *token, ms_perr *err)
{
    (void)err;
    *token = ((js_reader *)h)->frame;
    return MS_PLUGIN_OK;
}

static int js_seek_frame(void *h, long long token, ms_perr *err)
{
    if (token < 0 || token > LONG_MAX) return ms_perr_set(err, "no frame %lld", token);
    ((js_reader *)h)->frame = (long)token;
    return MS_PLUGIN_OK;
}

static const ms_plugin js_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "js",
    .description = "VMD js binary structure and trajectory",
    .extensions = "js",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_STRUCTURE |
            MS_CAN_WRITE_FRAMES,
    .open_read = js_open_read,
    .read_structure = js_read_structure,
    .read_frame = js_read_frame,
    .close_read = js_close_read,
    .tell_frame = js_tell_frame,
    .seek_frame = js_seek_frame,
    .open_write = js_open_write,
    .write_structure = js_write_structure,
    .write_frame = js_write_frame,
    .close_write = js_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &js_plugin; }
