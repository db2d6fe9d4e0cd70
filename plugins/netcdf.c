/* netcdf.c: AMBER's NetCDF trajectories and restarts, VMD's type `netcdf` (.nc .ncdf
 * .ncrst), through Debian's libnetcdf. Reads the AMBER convention (Conventions "AMBER":
 * coordinates[frame][atom][spatial], optional cell_lengths and cell_angles[frame][3],
 * time[frame] and velocities (scaled by their scale_factor to Angstrom/ps)) one frame at a
 * time, and the restart convention ("AMBERRESTART": the same variables without the frame
 * dimension, one frame). Writes trajectories in the AMBER convention (64-bit offset
 * format): coordinates, the cell when the first frame has one, time, and velocities when
 * the first frame has them. Built only when configure finds libnetcdf. */
#include "ms_plugin.h"

#include <netcdf.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

#define AMBER_VEL_SCALE 20.455

/* ---------------------------------------------------------------- reading */

typedef struct nc_reader {
    int nc;
    int restart;               /* AMBERRESTART: no frame dimension */
    size_t natoms, nframes, next;
    long long held;            /* whole frames in the file; -1 when the library knows */
    char *path;                /* for seeks: the file is checked again when its size changed */
    long long size;
    int v_coord, v_vel, v_len, v_ang, v_time;  /* -1 when absent */
    double vel_scale;
} nc_reader;

static int nc_fail(ms_perr *err, int status, const char *what)
{
    return ms_perr_set(err, "%s: %s", what, nc_strerror(status));
}

static void ncr_close(void *h)
{
    nc_reader *r = h;
    if (!r) return;
    if (r->nc >= 0) nc_close(r->nc);
    free(r->path);
    free(r);
}

/* A global text attribute into buf ("" when absent or not text). */
static void text_attr(int nc, int var, const char *name, char *buf, size_t size)
{
    size_t len;
    nc_type t;
    buf[0] = '\0';
    if (nc_inq_att(nc, var, name, &t, &len) || t != NC_CHAR || len >= size) return;
    if (nc_get_att_text(nc, var, name, buf) == NC_NOERR) buf[len] = '\0';
}

/* The length of a named dimension; -1 when absent. */
static long dim_len(int nc, const char *name)
{
    int d;
    size_t n;
    if (nc_inq_dimid(nc, name, &d) || nc_inq_dimlen(nc, d, &n)) return -1;
    return (long)n;
}

/* Variable `name` when it has the shape the convention gives: ([frame,] dim1[, dim2]) of
 * a numeric type; -1 when absent; -2 when present with another shape. */
static int conv_var(const nc_reader *r, const char *name, const char *d1, const char *d2)
{
    int v, nd, dims[NC_MAX_VAR_DIMS], want[3], nw = 0;
    nc_type t;
    if (nc_inq_varid(r->nc, name, &v)) return -1;
    if (nc_inq_var(r->nc, v, NULL, &t, &nd, NULL, NULL) || nd > 3 ||
        nc_inq_vardimid(r->nc, v, dims))
        return -2;
    if (t != NC_FLOAT && t != NC_DOUBLE && t != NC_SHORT && t != NC_INT) return -2;
    const char *names[3] = {r->restart ? NULL : "frame", d1, d2};
    for (int k = 0; k < 3; k++) {
        if (!names[k]) continue;
        if (nc_inq_dimid(r->nc, names[k], &want[nw])) return -2;
        nw++;
    }
    if (nd == 1 && nw == 0 && r->restart) {
        /* A restart's time may have a dimension of its own, of length 1. */
        size_t n;
        return nc_inq_dimlen(r->nc, dims[0], &n) == NC_NOERR && n == 1 ? v : -2;
    }
    if (nd != nw) return -2;
    for (int k = 0; k < nd; k++)
        if (dims[k] != want[k]) return -2;
    return v;
}

/* The variables, checked against the convention. */
static int find_vars(nc_reader *r, ms_perr *err)
{
    r->v_coord = conv_var(r, "coordinates", "atom", "spatial");
    r->v_vel = conv_var(r, "velocities", "atom", "spatial");
    r->v_len = conv_var(r, "cell_lengths", "cell_spatial", NULL);
    r->v_ang = conv_var(r, "cell_angles", "cell_angular", NULL);
    r->v_time = conv_var(r, "time", NULL, NULL);
    if (r->v_coord == -1) return ms_perr_set(err, "no coordinates variable");
    const char *bad = r->v_coord == -2 ? "coordinates" : r->v_vel == -2 ? "velocities"
                    : r->v_len == -2   ? "cell_lengths" : r->v_ang == -2 ? "cell_angles"
                    : r->v_time == -2  ? "time" : NULL;
    if (bad)
        return ms_perr_set(err, "the %s variable does not have the AMBER convention's "
                                "dimensions%s", bad, r->restart ? "" : " (frame first)");
    if (dim_len(r->nc, "spatial") != 3) return ms_perr_set(err, "the spatial dimension is not 3");
    if ((r->v_len >= 0 || r->v_ang >= 0) &&
        (dim_len(r->nc, "cell_spatial") != 3 || dim_len(r->nc, "cell_angular") != 3))
        return ms_perr_set(err, "the cell dimensions are not 3");
    r->vel_scale = 1.0;
    if (r->v_vel >= 0 && nc_get_att_double(r->nc, r->v_vel, "scale_factor", &r->vel_scale))
        r->vel_scale = 1.0;
    return MS_PLUGIN_OK;
}

static int check_header(nc_reader *r, long long size, ms_perr *err)
{
    char conv[256];
    text_attr(r->nc, NC_GLOBAL, "Conventions", conv, sizeof conv);
    if (!strstr(conv, "AMBER"))
        return ms_perr_set(err, "not an AMBER NetCDF file (Conventions is '%s', not AMBER)", conv);
    r->restart = strstr(conv, "AMBERRESTART") != NULL;
    long na = dim_len(r->nc, "atom");
    long nf = r->restart ? 1 : dim_len(r->nc, "frame");
    if (na < 1) return ms_perr_set(err, "no atom dimension");
    if (nf < 0) return ms_perr_set(err, "no frame dimension (a trajectory needs one)");
    r->natoms = (size_t)na;
    r->nframes = (size_t)nf;
    /* Each frame's coordinates take 6 bytes an atom at the least; allow compression 64x. */
    double need = 6.0 * (double)na * (double)(nf > 0 ? nf : 1);
    if (need > 64.0 * (double)size + 65536)
        return ms_perr_set(err, "the header declares %ld atoms in %ld frames but the file holds "
                                "only %lld bytes", na, nf, size);
    return find_vars(r, err);
}

/* ---------------------------------------------------------------- header check */

/* libnetcdf trusts a classic file's header (it has crashed on damaged ones), so the
 * header's structure is checked before the library sees it: every count, name, value and
 * dimension id within the file and consistent (the classic format specification,
 * "CDF" 1, 2 or 5). This checks, it does not read: the library reads the file. */
typedef struct cdf_hdr {
    const unsigned char *p, *end;
    int version;
    const char *bad;  /* what was wrong, NULL while all is well */
    unsigned long long numrecs;
    /* Where the data ends: fixed variables, and the record variables' extent (the first
     * record's start, the bytes of a record, the last record variable's end in it). */
    unsigned long long fixed_end, rec_begin, rec_size;
    int any_rec, unknown_size;
} cdf_hdr;

static unsigned long long cdf_uint(cdf_hdr *h, int bytes)
{
    if (h->bad || h->end - h->p < bytes) {
        if (!h->bad) h->bad = "the header ends early";
        return 0;
    }
    unsigned long long v = 0;
    for (int k = 0; k < bytes; k++) v = v << 8 | *h->p++;
    return v;
}

/* A count (4 bytes, 8 in CDF-5) no larger than max. */
static unsigned long long cdf_count(cdf_hdr *h, unsigned long long max, const char *what)
{
    unsigned long long n = cdf_uint(h, h->version == 5 ? 8 : 4);
    if (!h->bad && n > max) h->bad = what;
    return h->bad ? 0 : n;
}

static void cdf_skip(cdf_hdr *h, unsigned long long n)
{
    n = (n + 3) & ~3ull;
    if (h->bad) return;
    if ((unsigned long long)(h->end - h->p) < n) h->bad = "the header ends early";
    else h->p += n;
}

/* A name: 1..256 bytes without NUL, slash or control characters. */
static void cdf_name(cdf_hdr *h)
{
    unsigned long long n = cdf_count(h, 256, "a name longer than 256 bytes");
    if (!h->bad && n == 0) h->bad = "an empty name";
    if (!h->bad && (unsigned long long)(h->end - h->p) < n) h->bad = "the header ends early";
    for (unsigned long long k = 0; !h->bad && k < n; k++)
        if (h->p[k] < 0x20 || h->p[k] == '/' || h->p[k] == 0x7f)
            h->bad = "a bad character in a name";
    cdf_skip(h, n);
}

static int cdf_type_size(cdf_hdr *h, unsigned long long t)
{
    static const int size[] = {0, 1, 1, 2, 4, 4, 8, 1, 2, 4, 8, 8};
    if (t >= 1 && t <= (h->version == 5 ? 11u : 6u)) return size[t];
    if (!h->bad) h->bad = "an unknown value type";
    return 0;
}

/* A list's tag and count: 0 for an absent list. */
static unsigned long long cdf_list(cdf_hdr *h, unsigned tag)
{
    unsigned long long t = cdf_uint(h, 4), n = cdf_count(h, 1u << 20, "a list too long");
    if (!h->bad && t != tag && !(t == 0 && n == 0)) h->bad = "a list of the wrong kind";
    return n;
}

static void cdf_attrs(cdf_hdr *h)
{
    unsigned long long n = cdf_list(h, 0x0C);
    for (unsigned long long k = 0; k < n && !h->bad; k++) {
        cdf_name(h);
        int size = cdf_type_size(h, cdf_uint(h, 4));
        unsigned long long len = cdf_count(h, (unsigned long long)(h->end - h->p),
                                           "an attribute longer than the file");
        cdf_skip(h, len * (unsigned long long)size);
    }
}

/* Account for one variable's data: vsize bytes at begin, once or in every record. */
static void cdf_extent(cdf_hdr *h, int rec, unsigned long long vsize, unsigned long long begin)
{
    if (h->bad) return;
    if (vsize == 0xffffffffull) h->unknown_size = 1; /* over 4 GiB: the size is not stored */
    if (!rec) {
        if (begin + vsize > h->fixed_end) h->fixed_end = begin + vsize;
        return;
    }
    if (!h->any_rec || begin < h->rec_begin) h->rec_begin = begin;
    h->any_rec = 1;
    h->rec_size += (vsize + 3) & ~3ull;
}

static void cdf_vars(cdf_hdr *h, unsigned long long ndims, const int *unlimited)
{
    unsigned long long n = cdf_list(h, 0x0B);
    for (unsigned long long k = 0; k < n && !h->bad; k++) {
        cdf_name(h);
        unsigned long long nd = cdf_count(h, 1024, "a variable with too many dimensions");
        int rec = 0;
        for (unsigned long long d = 0; d < nd && !h->bad; d++) {
            unsigned long long id = cdf_count(h, ndims ? ndims - 1 : 0, "a bad dimension id");
            if (!h->bad && ndims == 0) h->bad = "a dimension id without dimensions";
            if (!h->bad && d > 0 && unlimited[id]) h->bad = "the record dimension not first";
            if (!h->bad && d == 0) rec = unlimited[id];
        }
        cdf_attrs(h);
        cdf_type_size(h, cdf_uint(h, 4));
        unsigned long long vsize = cdf_uint(h, h->version == 5 ? 8 : 4);
        unsigned long long begin = cdf_uint(h, h->version == 1 ? 4 : 8);
        cdf_extent(h, rec, vsize, begin);
    }
}

/* NULL when the classic header is sound (or the file is not classic: HDF5-based files
 * are the HDF5 library's to check), else what is wrong. *h holds what the header says. */
static const char *cdf_check(const unsigned char *data, size_t size, cdf_hdr *h)
{
    memset(h, 0, sizeof *h);
    h->p = data;
    h->end = data + size;
    if (size < 4 || memcmp(data, "CDF", 3)) return NULL;
    h->version = data[3];
    if (h->version != 1 && h->version != 2 && h->version != 5) return "an unknown CDF version";
    h->p += 4;
    h->numrecs = cdf_uint(h, h->version == 5 ? 8 : 4);
    unsigned long long nd = cdf_list(h, 0x0A), nunlim = 0;
    int *unlimited = calloc(nd ? nd : 1, sizeof *unlimited);
    if (!unlimited) return "out of memory";
    for (unsigned long long k = 0; k < nd && !h->bad; k++) {
        cdf_name(h);
        unlimited[k] = cdf_uint(h, h->version == 5 ? 8 : 4) == 0;
        nunlim += (unsigned long long)unlimited[k];
    }
    if (!h->bad && nunlim > 1) h->bad = "more than one record dimension";
    cdf_attrs(h);
    cdf_vars(h, nd, unlimited);
    free(unlimited);
    return h->bad;
}

/* How many whole records a classic file of `size` bytes holds (the header's count when
 * it cannot tell); *fixed_ok is 0 when it is too short for its fixed variables. */
static unsigned long long cdf_records_held(const cdf_hdr *h, long long size, int *fixed_ok)
{
    unsigned long long sz = size > 0 ? (unsigned long long)size : 0;
    *fixed_ok = h->unknown_size || h->fixed_end <= sz + 4;
    if (!h->any_rec || h->unknown_size || h->rec_size == 0 || h->numrecs == 0xffffffffull)
        return h->numrecs;
    if (sz + 4 < h->rec_begin + h->rec_size) return 0;
    unsigned long long held = (sz + 4 - h->rec_begin) / h->rec_size;
    return held < h->numrecs ? held : h->numrecs;
}

/* The start of the file (the header, at most 16 MiB) through cdf_check; *held: the whole
 * records the file holds (-1: not a classic file, the library knows). */
static int check_classic_header(const char *path, long long size, long long *held,
                                ms_perr *err)
{
    FILE *f = fopen(path, "rb");
    if (!f) return ms_perr_set(err, "cannot open the file");
    size_t cap = 1u << 24;
    unsigned char *buf = malloc(cap);
    size_t n = buf ? fread(buf, 1, cap, f) : 0;
    fclose(f);
    if (!buf) return ms_perr_set(err, "out of memory");
    cdf_hdr h;
    const char *bad = cdf_check(buf, n, &h);
    free(buf);
    if (bad) return ms_perr_set(err, "damaged NetCDF header: %s", bad);
    int fixed_ok = 1;
    *held = h.version ? (long long)cdf_records_held(&h, size, &fixed_ok) : -1;
    if (!fixed_ok)
        return ms_perr_set(err, "truncated: the variables end at byte %llu but the file has "
                                "%lld bytes", h.fixed_end, size);
    return MS_PLUGIN_OK;
}

static void *ncr_open(const char *path, long *natoms, ms_perr *err)
{
    nc_reader *r = calloc(1, sizeof *r);
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    struct stat sb;
    long long size = stat(path, &sb) == 0 ? (long long)sb.st_size : 0;
    int st = check_classic_header(path, size, &r->held, err)
                 ? NC_ENOTNC
                 : nc_open(path, NC_NOWRITE, &r->nc);
    if (st != NC_NOERR && err->msg[0]) {
        r->nc = -1;
        ncr_close(r);
        return NULL;
    }
    if (st != NC_NOERR) {
        r->nc = -1;
        ncr_close(r);
        nc_fail(err, st, "not a NetCDF file");
        return NULL;
    }
    if (check_header(r, size, err)) {
        ncr_close(r);
        return NULL;
    }
    r->size = size;
    if (!(r->path = strdup(path))) {
        ncr_close(r);
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    *natoms = (long)r->natoms;
    return r;
}

/* Three values of a cell variable for frame k. */
static int get_cell3(const nc_reader *r, int var, size_t k, float *out)
{
    size_t start[2] = {k, 0}, count[2] = {1, 3};
    double v[3];
    int st = r->restart ? nc_get_var_double(r->nc, var, v)
                        : nc_get_vara_double(r->nc, var, start, count, v);
    for (int c = 0; c < 3 && st == NC_NOERR; c++) out[c] = (float)v[c];
    return st;
}

/* A per-atom variable of frame k into dst (3 natoms floats). */
static int get_atoms(const nc_reader *r, int var, size_t k, float *dst)
{
    size_t start[3] = {k, 0, 0}, count[3] = {1, r->natoms, 3};
    if (r->restart) return nc_get_var_float(r->nc, var, dst);
    return nc_get_vara_float(r->nc, var, start, count, dst);
}

static int read_extras(nc_reader *r, size_t k, ms_frame_out *fr, ms_perr *err)
{
    int st;
    if (r->v_len >= 0 && r->v_ang >= 0) {
        if ((st = get_cell3(r, r->v_len, k, fr->cell)) ||
            (st = get_cell3(r, r->v_ang, k, fr->cell + 3)))
            return nc_fail(err, st, "cell");
        fr->has_cell = fr->cell[0] > 0;
    }
    if (r->v_time >= 0) {
        size_t start[1] = {k};
        float t;
        st = r->restart ? nc_get_var_float(r->nc, r->v_time, &t)
                        : nc_get_var1_float(r->nc, r->v_time, start, &t);
        if (st) return nc_fail(err, st, "time");
        fr->time = t;
        fr->has_time = 1;
    }
    if (r->v_vel >= 0 && fr->vel) {
        if ((st = get_atoms(r, r->v_vel, k, fr->vel))) return nc_fail(err, st, "velocities");
        for (size_t i = 0; i < 3 * r->natoms; i++) fr->vel[i] *= (float)r->vel_scale;
        fr->has_vel = 1;
    }
    return MS_PLUGIN_OK;
}

static int ncr_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    nc_reader *r = h;
    if (r->next >= r->nframes) return MS_PLUGIN_EOF;
    if (natoms != (long)r->natoms)
        return ms_perr_set(err, "the file has %zu atoms, the structure %ld", r->natoms, natoms);
    size_t k = r->next++;
    if (!r->restart && r->held >= 0 && (long long)k >= r->held)
        return ms_perr_set(err, "truncated: the header declares %zu frames but the file holds "
                                "only %lld whole ones", r->nframes, r->held);
    if (!fr->pos) return MS_PLUGIN_OK; /* skipped: frames are read by index */
    int st = get_atoms(r, r->v_coord, k, fr->pos);
    if (st) return nc_fail(err, st, "coordinates");
    return read_extras(r, k, fr, err);
}

/* Frames are found by number: the token is one. A classic file whose size changed since it
 * was opened has its whole records counted again (the library reads a cut record as
 * zeros), so that a frame cut off gives an error. */
static int ncr_tell_frame(void *h, long long *token, ms_perr *err)
{
    (void)err;
    *token = (long long)((nc_reader *)h)->next;
    return MS_PLUGIN_OK;
}

static int ncr_seek_frame(void *h, long long token, ms_perr *err)
{
    nc_reader *r = h;
    if (token < 0 || (unsigned long long)token > r->nframes)
        return ms_perr_set(err, "no frame %lld", token);
    struct stat sb;
    if (r->held >= 0 && stat(r->path, &sb) == 0 && (long long)sb.st_size != r->size) {
        r->size = (long long)sb.st_size;
        if (check_classic_header(r->path, r->size, &r->held, err)) return MS_PLUGIN_ERROR;
    }
    r->next = (size_t)token;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct nc_writer {
    int nc;
    long natoms;
    int defined, with_cell, with_vel;
    int v_coord, v_vel, v_len, v_ang, v_time;
    float *buf;
} nc_writer;

static void *ncw_open(const char *path, long natoms, ms_perr *err)
{
    nc_writer *w = calloc(1, sizeof *w);
    if (!w) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    w->natoms = natoms;
    int st = nc_create(path, NC_CLOBBER | NC_64BIT_OFFSET, &w->nc);
    if (st != NC_NOERR) {
        free(w);
        nc_fail(err, st, "cannot create the NetCDF file");
        return NULL;
    }
    return w;
}

static int put_text(int nc, int var, const char *name, const char *text)
{
    return nc_put_att_text(nc, var, name, strlen(text), text);
}

/* The dimension ids: frame, spatial, atom, cell_spatial, cell_angular, label. */
enum { D_FRAME, D_SPATIAL, D_ATOM, D_CSPATIAL, D_CANGULAR, D_LABEL, D_N };

static int define_dims(nc_writer *w, int *d)
{
    int st;
    if ((st = nc_def_dim(w->nc, "frame", NC_UNLIMITED, &d[D_FRAME])) ||
        (st = nc_def_dim(w->nc, "spatial", 3, &d[D_SPATIAL])) ||
        (st = nc_def_dim(w->nc, "atom", (size_t)w->natoms, &d[D_ATOM])))
        return st;
    if (!w->with_cell) return NC_NOERR;
    if ((st = nc_def_dim(w->nc, "cell_spatial", 3, &d[D_CSPATIAL])) ||
        (st = nc_def_dim(w->nc, "cell_angular", 3, &d[D_CANGULAR])) ||
        (st = nc_def_dim(w->nc, "label", 5, &d[D_LABEL])))
        return st;
    return NC_NOERR;
}

static int define_vars(nc_writer *w, const int *d)
{
    int st, v;
    int xyz[3] = {d[D_FRAME], d[D_ATOM], d[D_SPATIAL]};
    if ((st = put_text(w->nc, NC_GLOBAL, "Conventions", "AMBER")) ||
        (st = put_text(w->nc, NC_GLOBAL, "ConventionVersion", "1.0")) ||
        (st = put_text(w->nc, NC_GLOBAL, "program", "molscope")) ||
        (st = put_text(w->nc, NC_GLOBAL, "programVersion", "1.0")) ||
        (st = nc_def_var(w->nc, "spatial", NC_CHAR, 1, &d[D_SPATIAL], &v)) ||
        (st = nc_def_var(w->nc, "time", NC_FLOAT, 1, &d[D_FRAME], &w->v_time)) ||
        (st = put_text(w->nc, w->v_time, "units", "picosecond")) ||
        (st = nc_def_var(w->nc, "coordinates", NC_FLOAT, 3, xyz, &w->v_coord)) ||
        (st = put_text(w->nc, w->v_coord, "units", "angstrom")))
        return st;
    if (w->with_vel) {
        double scale = AMBER_VEL_SCALE;
        if ((st = nc_def_var(w->nc, "velocities", NC_FLOAT, 3, xyz, &w->v_vel)) ||
            (st = put_text(w->nc, w->v_vel, "units", "angstrom/picosecond")) ||
            (st = nc_put_att_double(w->nc, w->v_vel, "scale_factor", NC_DOUBLE, 1, &scale)))
            return st;
    }
    if (!w->with_cell) return NC_NOERR;
    int cl[2] = {d[D_FRAME], d[D_CSPATIAL]}, ca[2] = {d[D_FRAME], d[D_CANGULAR]};
    int lab[2] = {d[D_CANGULAR], d[D_LABEL]};
    if ((st = nc_def_var(w->nc, "cell_spatial", NC_CHAR, 1, &d[D_CSPATIAL], &v)) ||
        (st = nc_def_var(w->nc, "cell_angular", NC_CHAR, 2, lab, &v)) ||
        (st = nc_def_var(w->nc, "cell_lengths", NC_DOUBLE, 2, cl, &w->v_len)) ||
        (st = put_text(w->nc, w->v_len, "units", "angstrom")) ||
        (st = nc_def_var(w->nc, "cell_angles", NC_DOUBLE, 2, ca, &w->v_ang)) ||
        (st = put_text(w->nc, w->v_ang, "units", "degree")))
        return st;
    return NC_NOERR;
}

/* The label variables' values, once the header is written. */
static int put_labels(nc_writer *w)
{
    int v, st;
    if ((st = nc_inq_varid(w->nc, "spatial", &v)) || (st = nc_put_var_text(w->nc, v, "xyz")))
        return st;
    if (!w->with_cell) return NC_NOERR;
    static const char ang[16] = "alphabeta gamma";
    if ((st = nc_inq_varid(w->nc, "cell_spatial", &v)) || (st = nc_put_var_text(w->nc, v, "abc")) ||
        (st = nc_inq_varid(w->nc, "cell_angular", &v)))
        return st;
    return nc_put_var_text(w->nc, v, ang);
}

/* The header, from what the first frame has. */
static int define_file(nc_writer *w, const ms_frame_in *f, ms_perr *err)
{
    int d[D_N], st;
    w->with_cell = f->cell[0] > 0 && f->cell[1] > 0 && f->cell[2] > 0;
    w->with_vel = f->vel != NULL;
    if ((st = nc_set_fill(w->nc, NC_NOFILL, NULL)) || (st = define_dims(w, d)) ||
        (st = define_vars(w, d)) || (st = nc_enddef(w->nc)) || (st = put_labels(w)))
        return nc_fail(err, st, "NetCDF header");
    w->defined = 1;
    return MS_PLUGIN_OK;
}

static int ncw_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    nc_writer *w = h;
    (void)v;
    if (!w->defined && define_file(w, f, err)) return MS_PLUGIN_ERROR;
    size_t k = (size_t)f->index;
    size_t start[3] = {k, 0, 0}, count[3] = {1, (size_t)w->natoms, 3};
    size_t cs[2] = {k, 0}, cc[2] = {1, 3};
    double len[3] = {f->cell[0], f->cell[1], f->cell[2]}, ang[3] = {f->cell[3], f->cell[4],
                                                                     f->cell[5]};
    float t = (float)f->time;
    int st = nc_put_vara_float(w->nc, w->v_coord, start, count, f->pos);
    if (!st) st = nc_put_var1_float(w->nc, w->v_time, start, &t);
    if (!st && w->with_cell) st = nc_put_vara_double(w->nc, w->v_len, cs, cc, len);
    if (!st && w->with_cell) st = nc_put_vara_double(w->nc, w->v_ang, cs, cc, ang);
    if (!st && w->with_vel && f->vel) {
        size_t n = 3 * (size_t)w->natoms;
        if (!w->buf && !(w->buf = malloc(n * sizeof *w->buf)))
            return ms_perr_set(err, "out of memory");
        for (size_t i = 0; i < n; i++) w->buf[i] = (float)(f->vel[i] / AMBER_VEL_SCALE);
        st = nc_put_vara_float(w->nc, w->v_vel, start, count, w->buf);
    }
    return st ? nc_fail(err, st, "writing a frame") : MS_PLUGIN_OK;
}

static int ncw_close(void *h, ms_perr *err)
{
    nc_writer *w = h;
    int st = nc_close(w->nc);
    free(w->buf);
    free(w);
    return st ? nc_fail(err, st, "closing the NetCDF file") : MS_PLUGIN_OK;
}

static const ms_plugin netcdf_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "netcdf",
    .description = "AMBER NetCDF trajectory or restart",
    .extensions = "nc ncdf ncrst",
    .caps = MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = ncr_open,
    .read_frame = ncr_read_frame,
    .close_read = ncr_close,
    .tell_frame = ncr_tell_frame,
    .seek_frame = ncr_seek_frame,
    .open_write = ncw_open,
    .write_frame = ncw_write_frame,
    .close_write = ncw_close,
};

const ms_plugin *ms_plugin_entry(void) { return &netcdf_plugin; }
