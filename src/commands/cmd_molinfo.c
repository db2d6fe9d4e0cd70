/* cmd_molinfo.c: the `molinfo` command.
 *
 *   molinfo num | list | top | index n
 *   molinfo <molid|top> get <keywords> ?frame n|now|first|last?   -> one value per keyword
 *   molinfo <molid|top> set <keywords> <values> ?frame n?
 *
 * Keywords name molecule properties (numatoms, filename, center, the view matrices...) and
 * per-frame ones (a b c alpha beta gamma physical_time). Other modules add keywords with
 * ms_molinfo_add_keyword. */
#include "config.h"
#include "commands/commands.h"
#include "commands/molinfo.h"

#include <limits.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MAX_EXTRA_KEYWORDS 32
static ms_molinfo_keyword extra[MAX_EXTRA_KEYWORDS];
static int nextra;

int ms_molinfo_add_keyword(const ms_molinfo_keyword *k)
{
    if (nextra >= MAX_EXTRA_KEYWORDS) return -1;
    extra[nextra++] = *k;
    return 0;
}

/* ---------------------------------------------------------------- matrices */

Tcl_Obj *ms_matrix_to_obj(const float m[16])
{
    Tcl_Obj *rows = Tcl_NewListObj(0, NULL);
    for (int r = 0; r < 4; r++) {
        Tcl_Obj *row = Tcl_NewListObj(0, NULL);
        for (int c = 0; c < 4; c++) Tcl_ListObjAppendElement(NULL, row, Tcl_NewDoubleObj(m[4 * r + c]));
        Tcl_ListObjAppendElement(NULL, rows, row);
    }
    return rows;
}

/* A matrix written without blanks between its rows ({1 0 0 0}{0 1 0 0}...), which is not a
 * Tcl list: its 16 numbers in order, braces read as blanks, as VMD reads it. 0 or -1. */
static int matrix_from_numbers(const char *text, float m[16])
{
    char *copy = ms_strdup(text), *save = NULL;
    int n = 0;
    if (!copy) return -1;
    for (char *p = copy; *p; p++)
        if (*p == '{' || *p == '}') *p = ' ';
    for (char *w = strtok_r(copy, " \t\n", &save); w; w = strtok_r(NULL, " \t\n", &save)) {
        char *end;
        double v = strtod(w, &end);
        if (*end || n == 16 || !isfinite(v)) {
            n = -1;
            break;
        }
        m[n++] = (float)v;
    }
    free(copy);
    return n == 16 ? 0 : -1;
}

int ms_matrix_from_obj(Tcl_Interp *interp, Tcl_Obj *obj, float m[16], const char *what)
{
    Tcl_Obj **rows, **cols;
    int nr, nc;
    if (Tcl_ListObjGetElements(NULL, obj, &nr, &rows) != TCL_OK) goto bad;
    /* Accept {{r0} {r1} {r2} {r3}} and its one-element wrapping {{{r0} ...}}. */
    if (nr == 1 && Tcl_ListObjGetElements(NULL, rows[0], &nr, &rows) != TCL_OK) goto bad;
    if (nr != 4) goto bad;
    for (int r = 0; r < 4; r++) {
        if (Tcl_ListObjGetElements(NULL, rows[r], &nc, &cols) != TCL_OK || nc != 4) goto bad;
        for (int c = 0; c < 4; c++) {
            double v;
            if (Tcl_GetDoubleFromObj(NULL, cols[c], &v) != TCL_OK) goto bad;
            m[4 * r + c] = (float)v;
        }
    }
    return TCL_OK;
bad:
    if (matrix_from_numbers(Tcl_GetString(obj), m) == 0) return TCL_OK;
    return ms_cmd_error(interp, "molinfo: %s: expected a 4x4 matrix {{r0} {r1} {r2} {r3}}, got '%s'",
                        what, Tcl_GetString(obj));
}

static void translation(float m[16], float x, float y, float z)
{
    static const float id[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
    memcpy(m, id, sizeof id);
    m[3] = x;
    m[7] = y;
    m[11] = z;
}

static void mat_mul(const float a[16], const float b[16], float out[16])
{
    float t[16];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            float s = 0;
            for (int k = 0; k < 4; k++) s += a[4 * r + k] * b[4 * k + c];
            t[4 * r + c] = s;
        }
    memcpy(out, t, sizeof t);
}

void ms_mol_matrices(const ms_molecule *m, float center[16], float rot[16], float scale[16],
                     float global[16], float view[16])
{
    translation(center, -m->center[0], -m->center[1], -m->center[2]);
    memcpy(rot, m->rotate, 16 * sizeof(float));
    translation(scale, 0, 0, 0);
    scale[0] = scale[5] = scale[10] = m->scale;
    translation(global, m->global[0], m->global[1], m->global[2]);
    float t[16];
    mat_mul(global, rot, t);
    mat_mul(t, scale, t);
    mat_mul(t, center, view);
}

/* ---------------------------------------------------------------- get */

static Tcl_Obj *str_list_files(const ms_molecule *m, int types)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < m->nfiles; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewStringObj(types ? m->files[i].type : m->files[i].path, -1));
    return l;
}

/* The keywords of molinfo get (and, where marked, set). */
typedef enum {
    K_ID, K_INDEX, K_NAME, K_FILENAME, K_FILETYPE, K_FILESPEC, K_DATABASE, K_ACCESSION,
    K_REMARKS, K_NUMATOMS, K_NUMFRAMES, K_FRAME, K_LAST, K_NUMVOLUMEDATA, K_ACTIVE, K_DRAWN,
    K_DISPLAYED, K_FIXED, K_TOP, K_CENTER, K_CENTER_MATRIX, K_ROTATE_MATRIX, K_SCALE_MATRIX,
    K_GLOBAL_MATRIX, K_VIEW_MATRIX, K_PHYSICAL_TIME, K_TIMESTEPS, K_A, K_B, K_C, K_ALPHA,
    K_BETA, K_GAMMA, K_BOND, K_ANGLE, K_DIHEDRAL, K_IMPROPER, K_VDW, K_ELEC, K_HBOND,
    K_KINETIC, K_POTENTIAL, K_TEMPERATURE, K_ENERGY, K_EFIELD, K_COUNT
} keyword;
static const char *const keywords[K_COUNT + 1] = {
    "id", "index", "name", "filename", "filetype", "filespec", "database", "accession",
    "remarks", "numatoms", "numframes", "frame", "last", "numvolumedata", "active", "drawn",
    "displayed", "fixed", "top", "center", "center_matrix", "rotate_matrix", "scale_matrix",
    "global_matrix", "view_matrix", "physical_time", "timesteps", "a", "b", "c", "alpha",
    "beta", "gamma", "bond", "angle", "dihedral", "improper", "vdw", "elec", "hbond", "kinetic",
    "potential", "temperature", "energy", "efield", NULL};

/* An extra keyword's handler for k, or NULL ("rep " also takes "rep 0"). */
static const ms_molinfo_keyword *find_extra(const char *k, int setting)
{
    for (int e = 0; e < nextra; e++)
        if ((!setting || extra[e].set) &&
            (ms_word_eq(k, extra[e].name) ||
             (extra[e].prefix && !strncasecmp(k, extra[e].name, strlen(extra[e].name)))))
            return &extra[e];
    return NULL;
}

/* "<where>: unknown keyword \"k\": must be ..." over the table and the extra keywords. */
static int unknown_keyword(Tcl_Interp *interp, const char *k)
{
    Tcl_Obj *msg = Tcl_ObjPrintf("%s: unknown keyword \"%s\": must be ", ms_args_where(), k);
    int total = K_COUNT + nextra;
    for (int i = 0; i < total; i++) {
        const char *name = i < K_COUNT ? keywords[i] : extra[i - K_COUNT].name;
        Tcl_AppendPrintfToObj(msg, "%s%.*s", i == 0 ? "" : i + 1 == total ? ", or " : ", ",
                              (int)strcspn(name, " "), name);
    }
    Tcl_SetObjResult(interp, msg);
    return TCL_ERROR;
}

static int get_keyword(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *k, long frame,
                       Tcl_Obj **out)
{
    const ms_frame *f = frame >= 0 && (size_t)frame < m->nframes ? &m->frames[frame] : NULL;
    float mats[5][16];
    int i = ms_args_find(keywords, sizeof *keywords, k);
    Tcl_Obj *v[3];
    switch ((keyword)i) {
    case K_ID: *out = Tcl_NewIntObj(m->id); break;
    case K_INDEX: *out = Tcl_NewIntObj(ms_molset_index_of(&app->mols, m->id)); break;
    case K_NAME: *out = Tcl_NewStringObj(m->name ? m->name : "", -1); break;
    case K_FILENAME: *out = str_list_files(m, 0); break;
    case K_FILETYPE: *out = str_list_files(m, 1); break;
    case K_FILESPEC:
        *out = Tcl_NewListObj(0, NULL);
        for (size_t j = 0; j < m->nfiles; j++) {   /* VMD's: the load options, as mol new takes them */
            const ms_molfile *fl = &m->files[j];
            Tcl_ListObjAppendElement(NULL, *out, Tcl_ObjPrintf("first %ld last %ld step %ld "
                                     "filebonds %d autobonds %d", fl->first, fl->last, fl->step,
                                     fl->filebonds, fl->autobonds));
        }
        break;
    case K_DATABASE: case K_ACCESSION: *out = Tcl_NewStringObj("", 0); break;
    case K_REMARKS: *out = Tcl_NewStringObj(m->remarks ? m->remarks : "", -1); break;
    case K_NUMATOMS: *out = Tcl_NewWideIntObj((Tcl_WideInt)m->atoms.n); break;
    case K_NUMFRAMES: case K_TIMESTEPS: *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nframes); break;
    case K_FRAME: *out = Tcl_NewIntObj(m->frame); break;
    case K_LAST: *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nframes - 1); break;
    case K_NUMVOLUMEDATA: *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nvolumes); break;
    case K_ACTIVE: *out = Tcl_NewIntObj(m->active); break;
    case K_DRAWN: case K_DISPLAYED: *out = Tcl_NewIntObj(m->displayed); break;
    case K_FIXED: *out = Tcl_NewIntObj(m->fixed); break;
    case K_TOP: *out = Tcl_NewIntObj(app->mols.top == m->id); break;
    case K_CENTER:
        for (int c = 0; c < 3; c++) v[c] = Tcl_NewDoubleObj(m->center[c]);
        *out = Tcl_NewListObj(3, v);
        break;
    case K_CENTER_MATRIX: case K_ROTATE_MATRIX: case K_SCALE_MATRIX: case K_GLOBAL_MATRIX:
    case K_VIEW_MATRIX:
        ms_mol_matrices(m, mats[0], mats[1], mats[2], mats[3], mats[4]);
        *out = ms_matrix_to_obj(mats[i - K_CENTER_MATRIX]);
        break;
    case K_PHYSICAL_TIME: *out = Tcl_NewDoubleObj(f ? f->time : 0.0); break;
    case K_A: case K_B: case K_C: case K_ALPHA: case K_BETA: case K_GAMMA:
        *out = Tcl_NewDoubleObj(f ? f->cell[i - K_A] : 0.0);
        break;
    case K_BOND: case K_ANGLE: case K_DIHEDRAL: case K_IMPROPER: case K_VDW: case K_ELEC:
    case K_HBOND: case K_KINETIC: case K_POTENTIAL: case K_TEMPERATURE: case K_ENERGY:
    case K_EFIELD:   /* the frame's energies (molecule.h: MS_EN_* in this order) */
        *out = Tcl_NewDoubleObj(f ? f->energy[i - K_BOND] : 0.0);
        break;
    default: {
        const ms_molinfo_keyword *e = find_extra(k, 0);
        if (!e) return unknown_keyword(interp, k);
        return e->get(app, interp, m, k, frame, out);
    }
    }
    return TCL_OK;
}

/* Is `k` a keyword that takes an index ("rep" of "rep 0")? */
static int takes_index(const char *k)
{
    size_t len = strlen(k);
    for (int e = 0; e < nextra; e++)
        if (extra[e].prefix && strlen(extra[e].name) == len + 1 &&
            !strncasecmp(extra[e].name, k, len) && extra[e].name[len] == ' ')
            return 1;
    return 0;
}

/* frame n|now|first|last -> index, or -2 on error. */
static long parse_frame(Tcl_Interp *interp, const ms_molecule *m, Tcl_Obj *w)
{
    static const char *const words[] = {"now", "first", "last", NULL};
    int k;
    long v;
    if (ms_arg_long_or(NULL, w, NULL, words, 0, INT_MAX, &k, &v) == TCL_OK &&
        (k >= 0 || (size_t)v < m->nframes))
        return k == 0 ? m->frame : k == 1 ? 0 : k == 2 ? (long)m->nframes - 1 : v;
    ms_cmd_error(interp, "%s: molecule %d has no frame '%s' (it has %zu)", ms_args_where(),
                 m->id, Tcl_GetString(w), m->nframes);
    return -2;
}

/* The frame of "?frame <n>?" at objv[at] (the words are there when at < objc). */
static int frame_option(Tcl_Interp *interp, const ms_molecule *m, int objc,
                        Tcl_Obj *const objv[], int at, long *frame)
{
    static const char *const frame_word[] = {"frame", NULL};
    int k;
    *frame = m->frame;
    if (at >= objc) return TCL_OK;
    if (at + 2 != objc) return ms_args_usage(interp);
    if (ms_arg_choice(interp, objv[at], frame_word, NULL, &k)) return TCL_ERROR;
    return (*frame = parse_frame(interp, m, objv[at + 1])) == -2 ? TCL_ERROR : TCL_OK;
}

/* molinfo <molid> get <keywords> ?frame <n>? */
static int molinfo_get(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "molinfo");
    long frame;
    if (!m || frame_option(interp, m, objc, objv, 4, &frame)) return TCL_ERROR;
    Tcl_Obj **keys;
    int nk;
    if (Tcl_ListObjGetElements(interp, objv[3], &nk, &keys) != TCL_OK) return TCL_ERROR;
    Tcl_Obj *res = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < nk; i++) {
        Tcl_Obj *v = NULL;
        /* "rep 0", "selection 0" ... arrive as one keyword with a space ({{rep 0}}), or
         * split in two when given as a plain string (molinfo top get "rep 0"). */
        Tcl_Obj *joined = NULL;
        if (i + 1 < nk && takes_index(Tcl_GetString(keys[i]))) {
            int idx;
            if (Tcl_GetIntFromObj(NULL, keys[i + 1], &idx) == TCL_OK) {
                joined = Tcl_ObjPrintf("%s %d", Tcl_GetString(keys[i]), idx);
                Tcl_IncrRefCount(joined);
                i++;
            }
        }
        int rc = get_keyword(app, interp, m, Tcl_GetString(joined ? joined : keys[i]), frame, &v);
        if (joined) Tcl_DecrRefCount(joined);
        if (rc != TCL_OK) {
            Tcl_DecrRefCount(res);
            return TCL_ERROR;
        }
        Tcl_ListObjAppendElement(NULL, res, v);
    }
    Tcl_SetObjResult(interp, res);
    return TCL_OK;
}

/* ---------------------------------------------------------------- set */

static int set_keyword(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *k,
                       Tcl_Obj *v, long frame)
{
    ms_frame *f = frame >= 0 && (size_t)frame < m->nframes ? &m->frames[frame] : NULL;
    float mat[16];
    double d;
    int i = ms_args_find(keywords, sizeof *keywords, k), b;
    switch ((keyword)i) {
    case K_FRAME:
        if (ms_arg_int(interp, v, k, INT_MIN, INT_MAX, &b)) return TCL_ERROR;
        ms_error err = {{0}};
        if (ms_molset_goto(&app->mols, m, b, &err))
            return ms_cmd_error(interp, "%s: %s", ms_args_where(), err.msg);
        return TCL_OK;
    case K_NAME: {
        char *n = ms_strdup(Tcl_GetString(v));
        if (!n) return ms_cmd_error(interp, "%s: out of memory", ms_args_where());
        free(m->name);
        m->name = n;
        return TCL_OK;
    }
    case K_ACTIVE: case K_DRAWN: case K_DISPLAYED: case K_FIXED: case K_TOP:
        if (ms_arg_bool(interp, v, k, &b)) return TCL_ERROR;
        if (i == K_ACTIVE) m->active = (unsigned)b;
        else if (i == K_FIXED) m->fixed = (unsigned)b;
        else if (i == K_TOP) { if (b) app->mols.top = m->id; }
        else m->displayed = (unsigned)b;
        return TCL_OK;
    case K_CENTER:
        return ms_arg_vec3(interp, v, k, m->center);
    case K_CENTER_MATRIX: case K_ROTATE_MATRIX: case K_SCALE_MATRIX: case K_GLOBAL_MATRIX:
        if (ms_matrix_from_obj(interp, v, mat, k) != TCL_OK) return TCL_ERROR;
        if (i == K_CENTER_MATRIX) for (int c = 0; c < 3; c++) m->center[c] = -mat[4 * c + 3];
        else if (i == K_ROTATE_MATRIX) memcpy(m->rotate, mat, sizeof mat);
        else if (i == K_SCALE_MATRIX) m->scale = mat[0];
        else for (int c = 0; c < 3; c++) m->global[c] = mat[4 * c + 3];
        return TCL_OK;
    case K_A: case K_B: case K_C: case K_ALPHA: case K_BETA: case K_GAMMA: case K_PHYSICAL_TIME:
        if (!f) return ms_cmd_error(interp, "%s: molecule %d has no frames", ms_args_where(), m->id);
        if (ms_arg_double(interp, v, k, &d)) return TCL_ERROR;
        if (i == K_PHYSICAL_TIME) f->time = d;
        else f->cell[i - K_A] = (float)d;
        return TCL_OK;
    default: {
        const ms_molinfo_keyword *e = find_extra(k, 1);
        if (!e) return ms_cmd_error(interp, "%s: cannot set keyword '%s'", ms_args_where(), k);
        return e->set(app, interp, m, k, v, frame);
    }
    }
}

/* molinfo <molid> set <keywords> <values> ?frame <n>? */
static int molinfo_set(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "molinfo");
    long frame;
    if (!m) return TCL_ERROR;
    app->world.scene_version++;
    if (frame_option(interp, m, objc, objv, 5, &frame)) return TCL_ERROR;
    Tcl_Obj **keys, **vals;
    int nk, nv;
    if (Tcl_ListObjGetElements(interp, objv[3], &nk, &keys) != TCL_OK ||
        Tcl_ListObjGetElements(interp, objv[4], &nv, &vals) != TCL_OK)
        return TCL_ERROR;
    /* One keyword may take its value unwrapped: molinfo top set frame 3. */
    if (nk == 1 && nv != 1) {
        nv = 1;
        vals = (Tcl_Obj **)&objv[4];
    }
    if (nk != nv)
        return ms_cmd_error(interp, "%s: %d keywords but %d values", ms_args_where(), nk, nv);
    for (int i = 0; i < nk; i++)
        if (set_keyword(app, interp, m, Tcl_GetString(keys[i]), vals[i], frame) != TCL_OK)
            return TCL_ERROR;
    return TCL_OK;
}

/* ---------------------------------------------------------------- the command */

static int molinfo_num(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewWideIntObj((Tcl_WideInt)app->mols.n));
    return TCL_OK;
}

static int molinfo_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (size_t i = 0; i < app->mols.n; i++)
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewIntObj(app->mols.mols[i]->id));
    Tcl_SetObjResult(interp, l);
    return TCL_OK;
}

/* molinfo <molid> get|set ...: the molecule first, then the operation. */
static int molinfo_mol(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    static const ms_subcmd ops[] = {
        {"get", molinfo_get, 1, 3, "<keywords> ?frame <n>?"},
        {"set", molinfo_set, 2, 4, "<keywords> <values> ?frame <n>?"},
        {NULL, NULL, 0, 0, NULL}};
    int id;
    if (Tcl_GetIntFromObj(NULL, objv[1], &id) == TCL_OK && !ms_molset_get(&app->mols, id))
        return ms_cmd_error(interp, "molinfo: %s: no molecule exists with id %d",   /* VMD's words */
                            ms_word_eq(Tcl_GetString(objv[2]), "set") ? "set" : "get", id);
    if (!ms_cmd_mol(app, interp, objv[1], "molinfo")) return TCL_ERROR;
    char where[64];
    snprintf(where, sizeof where, "molinfo %.40s", Tcl_GetString(objv[1]));
    return ms_args_dispatch(app, interp, objc, objv, 2, ops, NULL, where);
}

static int molinfo_top(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc > 2) return molinfo_mol(app, interp, objc, objv);   /* molinfo top get ... */
    Tcl_SetObjResult(interp, Tcl_NewIntObj(app->mols.top));
    return TCL_OK;
}

static int molinfo_index(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int i;
    if (ms_arg_int(interp, objv[2], NULL, INT_MIN, INT_MAX, &i)) return TCL_ERROR;
    if (i < 0 || (size_t)i >= app->mols.n) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(-1));
        return TCL_OK;
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(app->mols.mols[i]->id));
    return TCL_OK;
}

static const ms_subcmd molinfo_table[] = {
    {"num", molinfo_num, 0, 0, ""},
    {"list", molinfo_list, 0, 0, ""},
    {"top", molinfo_top, 0, 5, "?get|set <keywords> ...?"},
    {"index", molinfo_index, 1, 1, "<n>"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_molinfo_register(ms_app *app)
{
    static const ms_subcmd by_molid = {"<molid>", molinfo_mol, 2, 6,
                                       "<molid> get|set <keywords> ?<values>? ?frame <n>?"};
    ms_cmdset_create(app, "molinfo", molinfo_table);
    ms_cmdset_fallback(app, "molinfo", &by_molid);
    ms_cmdset_quiet(app, "molinfo");
}
