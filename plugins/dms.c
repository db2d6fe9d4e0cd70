/* dms.c: the Desmond DMS plugin: an SQLite database (read through libsqlite3) whose table
 * `particle` holds one row per atom (id, name, resname, resid, chain, segid, insertion,
 * anum, mass, charge, x y z, vx vy vz; every column but id and x y z may be absent), `bond`
 * the bonds (p0, p1: particle ids, "order"), and `global_cell` three rows, the box vectors.
 * Atoms come in the order of their ids; one frame. Writes the same tables, building the
 * database in memory and writing it out whole (so the output may be any file). Angles and
 * the force-field tables are not read or written. */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "gmx_util.h"

#include <sqlite3.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

typedef struct dms_reader {
    sqlite3 *db;
    long natoms;
    int64_t *ids;         /* particle ids in order: an atom's index is its rank */
} dms_reader;

static void dms_close_read(void *h)
{
    dms_reader *r = h;
    sqlite3_close(r->db);
    free(r->ids);
    free(r);
}

/* An error from SQLite, naming what was being done. */
static int dms_error(sqlite3 *db, const char *what, ms_perr *err)
{
    return ms_perr_set(err, "%s: %s", what, db ? sqlite3_errmsg(db) : "out of memory");
}

/* One integer from a query; MS_PLUGIN_ERROR with err set. */
static int dms_scalar(sqlite3 *db, const char *sql, long long *v, ms_perr *err)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK)
        return dms_error(db, "not a DMS file", err);
    int rc = sqlite3_step(st);
    if (rc == SQLITE_ROW) *v = sqlite3_column_int64(st, 0);
    sqlite3_finalize(st);
    return rc == SQLITE_ROW ? MS_PLUGIN_OK : dms_error(db, "not a DMS file", err);
}

static void *dms_open_read(const char *path, long *natoms, ms_perr *err)
{
    dms_reader *r = calloc(1, sizeof *r);
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    long long n = 0;
    if (sqlite3_open_v2(path, &r->db, SQLITE_OPEN_READONLY, NULL) != SQLITE_OK) {
        dms_error(r->db, "cannot open", err);
        goto fail;
    }
    sqlite3_limit(r->db, SQLITE_LIMIT_LENGTH, 1 << 20);
    if (dms_scalar(r->db, "SELECT COUNT(*) FROM particle", &n, err)) goto fail;
    if (n < 1 || n > 0x7fffffffLL) {
        ms_perr_set(err, "the particle table has %lld rows", n);
        goto fail;
    }
    r->natoms = *natoms = (long)n;
    return r;
fail:
    dms_close_read(r);
    return NULL;
}

/* Does table t have column c? */
static int dms_has_column(sqlite3 *db, const char *t, const char *c)
{
    sqlite3_stmt *st;
    char sql[128];
    snprintf(sql, sizeof sql, "PRAGMA table_info(%s)", t);
    if (sqlite3_prepare_v2(db, sql, -1, &st, NULL) != SQLITE_OK) return 0;
    int found = 0;
    while (!found && sqlite3_step(st) == SQLITE_ROW) {
        const char *name = (const char *)sqlite3_column_text(st, 1);
        found = name && strcmp(name, c) == 0;
    }
    sqlite3_finalize(st);
    return found;
}

/* The particle query: every column the atom record can use, NULL for absent ones. */
enum { C_ID, C_X, C_Y, C_Z, C_NAME, C_RESNAME, C_RESID, C_CHAIN, C_SEGID, C_INS, C_ANUM, C_MASS,
       C_CHARGE, C_VX, C_VY, C_VZ, C_N };
static const char *const dms_cols[C_N] = {"id", "x", "y", "z", "name", "resname", "resid",
                                          "chain", "segid", "insertion", "anum", "mass",
                                          "charge", "vx", "vy", "vz"};

static int dms_query(sqlite3 *db, sqlite3_stmt **st, ms_perr *err)
{
    char sql[512] = "SELECT ";
    for (int c = 0; c < C_N; c++) {
        size_t len = strlen(sql);
        int have = dms_has_column(db, "particle", dms_cols[c]);
        if (c <= C_Z && !have)
            return ms_perr_set(err, "the particle table has no column '%s'", dms_cols[c]);
        if (have) snprintf(sql + len, sizeof sql - len, "%s\"%s\"", c ? ", " : "", dms_cols[c]);
        else snprintf(sql + len, sizeof sql - len, "%sNULL", c ? ", " : "");
    }
    size_t len = strlen(sql);
    snprintf(sql + len, sizeof sql - len, " FROM particle ORDER BY id");
    if (sqlite3_prepare_v2(db, sql, -1, st, NULL) != SQLITE_OK)
        return dms_error(db, "reading the particle table", err);
    return MS_PLUGIN_OK;
}

/* A text column ("" for NULL), at most 63 characters, into buf. */
static const char *dms_text(sqlite3_stmt *st, int c, char buf[64])
{
    const unsigned char *t = sqlite3_column_text(st, c);
    snprintf(buf, 64, "%s", t ? (const char *)t : "");
    return buf;
}

/* The atom record of the current row. */
static void dms_atom(sqlite3_stmt *st, ms_atom_in *a, char buf[6][64])
{
    memset(a, 0, sizeof *a);
    a->name = a->type = dms_text(st, C_NAME, buf[0]);
    a->resname = dms_text(st, C_RESNAME, buf[1]);
    a->chain = dms_text(st, C_CHAIN, buf[2]);
    a->segname = dms_text(st, C_SEGID, buf[3]);
    a->insertion = dms_text(st, C_INS, buf[4])[0];
    a->resid = sqlite3_column_int(st, C_RESID);
    a->x = (float)sqlite3_column_double(st, C_X);
    a->y = (float)sqlite3_column_double(st, C_Y);
    a->z = (float)sqlite3_column_double(st, C_Z);
    a->has = MS_HAS_POS;
    if (sqlite3_column_type(st, C_ANUM) != SQLITE_NULL && sqlite3_column_int(st, C_ANUM) > 0) {
        a->atomicnumber = sqlite3_column_int(st, C_ANUM);
        a->has |= MS_HAS_ATOMICNUMBER;
    }
    if (sqlite3_column_type(st, C_MASS) != SQLITE_NULL) {
        a->mass = (float)sqlite3_column_double(st, C_MASS);
        a->has |= MS_HAS_MASS;
    }
    if (sqlite3_column_type(st, C_CHARGE) != SQLITE_NULL) {
        a->charge = (float)sqlite3_column_double(st, C_CHARGE);
        a->has |= MS_HAS_CHARGE;
    }
    if (sqlite3_column_type(st, C_VX) != SQLITE_NULL) {
        a->vx = (float)sqlite3_column_double(st, C_VX);
        a->vy = (float)sqlite3_column_double(st, C_VY);
        a->vz = (float)sqlite3_column_double(st, C_VZ);
        a->has |= MS_HAS_VEL;
    }
}

static int dms_read_particles(dms_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    sqlite3_stmt *st;
    if (dms_query(r->db, &st, err)) return MS_PLUGIN_ERROR;
    if (!(r->ids = malloc((size_t)r->natoms * sizeof *r->ids))) {
        sqlite3_finalize(st);
        return ms_perr_set(err, "out of memory for %ld atoms", r->natoms);
    }
    sink->reserve(sink, (size_t)r->natoms);
    long k = 0;
    int rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW && k < r->natoms) {
        ms_atom_in a;
        char buf[6][64];
        r->ids[k] = sqlite3_column_int64(st, C_ID);
        if (k > 0 && r->ids[k] == r->ids[k - 1]) {
            sqlite3_finalize(st);
            return ms_perr_set(err, "particle id %lld appears twice", (long long)r->ids[k]);
        }
        dms_atom(st, &a, buf);
        if (sink->add_atom(sink, &a)) {
            sqlite3_finalize(st);
            return ms_perr_set(err, "out of memory at particle %ld", k + 1);
        }
        k++;
    }
    sqlite3_finalize(st);
    if (rc != SQLITE_DONE && rc != SQLITE_ROW) return dms_error(r->db, "reading the particle table", err);
    if (k != r->natoms) return ms_perr_set(err, "the particle table has %ld rows, not %ld", k, r->natoms);
    return MS_PLUGIN_OK;
}

/* The index of particle id, or -1. */
static long dms_index(const dms_reader *r, int64_t id)
{
    long lo = 0, hi = r->natoms - 1;
    while (lo <= hi) {
        long mid = lo + (hi - lo) / 2;
        if (r->ids[mid] == id) return mid;
        if (r->ids[mid] < id) lo = mid + 1;
        else hi = mid - 1;
    }
    return -1;
}

static int dms_read_bonds(dms_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    if (!dms_has_column(r->db, "bond", "p0")) return MS_PLUGIN_OK; /* no bond table */
    int orders = dms_has_column(r->db, "bond", "order");
    sqlite3_stmt *st;
    const char *sql = orders ? "SELECT p0, p1, \"order\" FROM bond" : "SELECT p0, p1, 1 FROM bond";
    if (sqlite3_prepare_v2(r->db, sql, -1, &st, NULL) != SQLITE_OK)
        return dms_error(r->db, "reading the bond table", err);
    int rc;
    long nb = 0;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW) {
        long i = dms_index(r, sqlite3_column_int64(st, 0)),
             j = dms_index(r, sqlite3_column_int64(st, 1));
        nb++;
        if (i < 0 || j < 0) {
            ms_perr_set(err, "bond %ld names particle %lld, which does not exist", nb,
                        (long long)sqlite3_column_int64(st, i < 0 ? 0 : 1));
            break;
        }
        double o = sqlite3_column_type(st, 2) == SQLITE_NULL ? 1.0 : sqlite3_column_double(st, 2);
        if (sink->add_bond(sink, (size_t)i, (size_t)j, (float)o)) {
            ms_perr_set(err, "out of memory for bonds");
            break;
        }
    }
    sqlite3_finalize(st);
    if (rc == SQLITE_ROW) return MS_PLUGIN_ERROR;
    if (rc != SQLITE_DONE) return dms_error(r->db, "reading the bond table", err);
    sink->bonds_complete(sink);
    return MS_PLUGIN_OK;
}

/* global_cell: three rows, the box vectors; absent or empty: no cell. */
static int dms_read_cell(dms_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    if (!dms_has_column(r->db, "global_cell", "x")) return MS_PLUGIN_OK;
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(r->db, "SELECT x, y, z FROM global_cell ORDER BY id", -1, &st,
                           NULL) != SQLITE_OK)
        return dms_error(r->db, "reading the global_cell table", err);
    double v[9];
    int n = 0, rc;
    while ((rc = sqlite3_step(st)) == SQLITE_ROW && n < 3) {
        for (int d = 0; d < 3; d++) v[3 * n + d] = sqlite3_column_double(st, d) / 10.0;
        n++;
    }
    sqlite3_finalize(st);
    if (n == 0) return MS_PLUGIN_OK;
    if (n != 3 || rc == SQLITE_ROW)
        return ms_perr_set(err, "the global_cell table must have 3 rows (the box vectors)");
    float cell[6];
    ms_gmx_box_to_cell(v, cell);
    sink->set_cell(sink, cell);
    return MS_PLUGIN_OK;
}

static int dms_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    dms_reader *r = h;
    if (dms_read_particles(r, sink, err) || dms_read_bonds(r, sink, err) ||
        dms_read_cell(r, sink, err))
        return MS_PLUGIN_ERROR;
    return MS_PLUGIN_OK;
}

static int dms_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    (void)h, (void)natoms, (void)fr, (void)err;
    return MS_PLUGIN_EOF; /* one frame, given with the structure */
}

/* ---------------------------------------------------------------- writing */

typedef struct dms_writer {
    ms_out out;
    sqlite3 *db;
    int frames;
} dms_writer;

static const char dms_schema[] =
    "PRAGMA journal_mode=OFF;"
    "CREATE TABLE particle (id INTEGER PRIMARY KEY, anum INTEGER, name TEXT NOT NULL, "
    "x FLOAT, y FLOAT, z FLOAT, vx FLOAT, vy FLOAT, vz FLOAT, resname TEXT NOT NULL, "
    "resid INTEGER, chain TEXT NOT NULL, segid TEXT NOT NULL, mass FLOAT, charge FLOAT, "
    "insertion TEXT NOT NULL);"
    "CREATE TABLE bond (p0 INTEGER, p1 INTEGER, \"order\" INTEGER);"
    "CREATE TABLE global_cell (id INTEGER PRIMARY KEY, x FLOAT, y FLOAT, z FLOAT);";

static void *dms_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    dms_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    if (sqlite3_open(":memory:", &w->db) != SQLITE_OK ||
        sqlite3_exec(w->db, dms_schema, NULL, NULL, NULL) != SQLITE_OK) {
        dms_error(w->db, "creating the database", err);
        sqlite3_close(w->db);
        w->db = NULL;
        ms_perr e2;
        ms_out_destroy(w, &e2);
        return NULL;
    }
    return w;
}

static const char *or_blank(const char *s) { return s ? s : ""; }

/* Insert the atoms of a view with the frame's positions and velocities. */
static int dms_insert_particles(dms_writer *w, const ms_struct_view *v, const ms_frame_in *f,
                                ms_perr *err)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(w->db, "INSERT INTO particle VALUES (?,?,?,?,?,?,?,?,?,?,?,?,?,?,?,?)",
                           -1, &st, NULL) != SQLITE_OK)
        return dms_error(w->db, "writing the particle table", err);
    int rc = SQLITE_DONE;
    for (size_t i = 0; i < v->natoms && rc == SQLITE_DONE; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        const float *p = f->pos + 3 * i, *u = f->vel ? f->vel + 3 * i : NULL;
        char ins[2] = {a.insertion && a.insertion != ' ' ? a.insertion : '\0', '\0'};
        sqlite3_bind_int64(st, 1, (sqlite3_int64)i);
        sqlite3_bind_int(st, 2, a.atomicnumber);
        sqlite3_bind_text(st, 3, or_blank(a.name), -1, SQLITE_TRANSIENT);
        for (int d = 0; d < 3; d++) {
            sqlite3_bind_double(st, 4 + d, p[d]);
            sqlite3_bind_double(st, 7 + d, u ? u[d] : 0.0);
        }
        sqlite3_bind_text(st, 10, or_blank(a.resname), -1, SQLITE_TRANSIENT);
        sqlite3_bind_int(st, 11, a.resid);
        sqlite3_bind_text(st, 12, or_blank(a.chain), -1, SQLITE_TRANSIENT);
        sqlite3_bind_text(st, 13, or_blank(a.segname), -1, SQLITE_TRANSIENT);
        sqlite3_bind_double(st, 14, a.mass);
        sqlite3_bind_double(st, 15, a.charge);
        sqlite3_bind_text(st, 16, ins, -1, SQLITE_TRANSIENT);
        rc = sqlite3_step(st);
        sqlite3_reset(st);
    }
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? MS_PLUGIN_OK : dms_error(w->db, "writing the particle table", err);
}

static int dms_insert_bonds(dms_writer *w, const ms_struct_view *v, ms_perr *err)
{
    sqlite3_stmt *st;
    if (sqlite3_prepare_v2(w->db, "INSERT INTO bond VALUES (?,?,?)", -1, &st, NULL) != SQLITE_OK)
        return dms_error(w->db, "writing the bond table", err);
    int rc = SQLITE_DONE;
    for (size_t i = 0; i < v->natoms && rc == SQLITE_DONE; i++) {
        const unsigned *to;
        size_t n = v->get_bonds(v, i, &to);
        for (size_t b = 0; b < n && rc == SQLITE_DONE; b++) {
            if (to[b] <= i) continue;
            sqlite3_bind_int64(st, 1, (sqlite3_int64)i);
            sqlite3_bind_int64(st, 2, (sqlite3_int64)to[b]);
            float order = 1.0f;
            const char *type;
            if (v->get_bond_info) v->get_bond_info(v, i, b, &order, &type);
            sqlite3_bind_int64(st, 3, (sqlite3_int64)lrintf(order)); /* DMS orders are integers */
            rc = sqlite3_step(st);
            sqlite3_reset(st);
        }
    }
    sqlite3_finalize(st);
    return rc == SQLITE_DONE ? MS_PLUGIN_OK : dms_error(w->db, "writing the bond table", err);
}

/* The cell as three box vectors (a along x, b in the xy plane). */
static int dms_insert_cell(dms_writer *w, const float cell[6], ms_perr *err)
{
    if (!(cell[0] > 0 && cell[1] > 0 && cell[2] > 0)) return MS_PLUGIN_OK;
    float box[9];
    ms_gmx_cell_to_box(cell, box);
    char sql[256];
    for (int k = 0; k < 3; k++) {
        snprintf(sql, sizeof sql, "INSERT INTO global_cell VALUES (%d, %.9g, %.9g, %.9g)", k + 1,
                 10.0 * box[3 * k], 10.0 * box[3 * k + 1], 10.0 * box[3 * k + 2]);
        if (sqlite3_exec(w->db, sql, NULL, NULL, NULL) != SQLITE_OK)
            return dms_error(w->db, "writing the global_cell table", err);
    }
    return MS_PLUGIN_OK;
}

static int dms_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    dms_writer *w = h;
    if (w->frames++) return ms_perr_set(err, "a DMS file holds one frame: write one");
    if (sqlite3_exec(w->db, "BEGIN", NULL, NULL, NULL) != SQLITE_OK)
        return dms_error(w->db, "writing", err);
    if (dms_insert_particles(w, v, f, err) || dms_insert_bonds(w, v, err) ||
        dms_insert_cell(w, f->cell, err))
        return MS_PLUGIN_ERROR;
    if (sqlite3_exec(w->db, "COMMIT", NULL, NULL, NULL) != SQLITE_OK)
        return dms_error(w->db, "writing", err);
    return MS_PLUGIN_OK;
}

/* The database, serialized, is the file. */
static int dms_close_write(void *h, ms_perr *err)
{
    dms_writer *w = h;
    sqlite3_int64 n = 0;
    unsigned char *bytes = w->frames ? sqlite3_serialize(w->db, "main", &n, 0) : NULL;
    if (w->frames && !bytes) w->out.failed = 1;
    if (bytes) ms_out_write(&w->out, bytes, (size_t)n);
    sqlite3_free(bytes);
    sqlite3_close(w->db);
    int rc = ms_out_destroy(w, err);
    if (rc == MS_PLUGIN_OK && !bytes) return ms_perr_set(err, "nothing was written");
    return rc;
}

static const ms_plugin dms_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "dms",
    .description = "Desmond DMS structure (SQLite)",
    .extensions = "dms",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = dms_open_read,
    .read_structure = dms_read_structure,
    .read_frame = dms_read_frame,
    .close_read = dms_close_read,
    .open_write = dms_open_write,
    .write_frame = dms_write_frame,
    .close_write = dms_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &dms_plugin; }
