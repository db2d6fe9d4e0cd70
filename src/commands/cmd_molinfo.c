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

static const char *cell_names[6] = {"a", "b", "c", "alpha", "beta", "gamma"};

static int get_keyword(ms_app *app, Tcl_Interp *interp, ms_molecule *m, const char *k, long frame,
                       Tcl_Obj **out)
{
    const ms_frame *f = frame >= 0 && (size_t)frame < m->nframes ? &m->frames[frame] : NULL;
    float cm[16], rm[16], sm[16], gm[16], vm[16];
    if (!strcasecmp(k, "id")) *out = Tcl_NewIntObj(m->id);
    else if (!strcasecmp(k, "index")) *out = Tcl_NewIntObj(ms_molset_index_of(&app->mols, m->id));
    else if (!strcasecmp(k, "name")) *out = Tcl_NewStringObj(m->name ? m->name : "", -1);
    else if (!strcasecmp(k, "filename")) *out = str_list_files(m, 0);
    else if (!strcasecmp(k, "filetype")) *out = str_list_files(m, 1);
    else if (!strcasecmp(k, "filespec")) {
        *out = Tcl_NewListObj(0, NULL);
        for (size_t i = 0; i < m->nfiles; i++) {
            Tcl_Obj *pair[2] = {Tcl_NewStringObj(m->files[i].type, -1),
                                Tcl_NewStringObj(m->files[i].path, -1)};
            Tcl_ListObjAppendElement(NULL, *out, Tcl_NewListObj(2, pair));
        }
    } else if (!strcasecmp(k, "database") || !strcasecmp(k, "accession"))
        *out = Tcl_NewStringObj("", 0);
    else if (!strcasecmp(k, "remarks")) *out = Tcl_NewStringObj(m->remarks ? m->remarks : "", -1);
    else if (!strcasecmp(k, "numatoms")) *out = Tcl_NewWideIntObj((Tcl_WideInt)m->atoms.n);
    else if (!strcasecmp(k, "numframes")) *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nframes);
    else if (!strcasecmp(k, "frame")) *out = Tcl_NewIntObj(m->frame);
    else if (!strcasecmp(k, "last")) *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nframes - 1);
    else if (!strcasecmp(k, "numvolumedata")) *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nvolumes);
    else if (!strcasecmp(k, "active")) *out = Tcl_NewIntObj(m->active);
    else if (!strcasecmp(k, "drawn") || !strcasecmp(k, "displayed")) *out = Tcl_NewIntObj(m->displayed);
    else if (!strcasecmp(k, "fixed")) *out = Tcl_NewIntObj(m->fixed);
    else if (!strcasecmp(k, "top")) *out = Tcl_NewIntObj(app->mols.top == m->id);
    else if (!strcasecmp(k, "center")) {
        Tcl_Obj *v[3];
        for (int i = 0; i < 3; i++) v[i] = Tcl_NewDoubleObj(m->center[i]);
        *out = Tcl_NewListObj(3, v);
    } else if (!strcasecmp(k, "center_matrix") || !strcasecmp(k, "rotate_matrix") ||
               !strcasecmp(k, "scale_matrix") || !strcasecmp(k, "global_matrix") ||
               !strcasecmp(k, "view_matrix")) {
        ms_mol_matrices(m, cm, rm, sm, gm, vm);
        const float *which = k[0] == 'c' || k[0] == 'C' ? cm : k[0] == 'r' || k[0] == 'R' ? rm
                             : k[0] == 's' || k[0] == 'S' ? sm : k[0] == 'g' || k[0] == 'G' ? gm : vm;
        *out = ms_matrix_to_obj(which);
    } else if (!strcasecmp(k, "physical_time")) {
        *out = Tcl_NewDoubleObj(f ? f->time : 0.0);
    } else if (!strcasecmp(k, "timesteps")) {
        *out = Tcl_NewWideIntObj((Tcl_WideInt)m->nframes);
    } else {
        for (int c = 0; c < 6; c++)
            if (!strcasecmp(k, cell_names[c])) {
                *out = Tcl_NewDoubleObj(f ? f->cell[c] : 0.0);
                return TCL_OK;
            }
        for (int e = 0; e < nextra; e++)
            if (!strcasecmp(k, extra[e].name) ||
                (extra[e].prefix && !strncasecmp(k, extra[e].name, strlen(extra[e].name))))
                return extra[e].get(app, interp, m, k, frame, out);
        return ms_cmd_error(interp, "molinfo: unknown keyword '%s'", k);
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
    const char *s = Tcl_GetString(w);
    if (!strcasecmp(s, "now")) return m->frame;
    if (!strcasecmp(s, "first")) return 0;
    if (!strcasecmp(s, "last")) return (long)m->nframes - 1;
    int v;
    if (Tcl_GetIntFromObj(NULL, w, &v) != TCL_OK || v < 0 || (size_t)v >= m->nframes) {
        ms_cmd_error(interp, "molinfo: molecule %d has no frame '%s' (it has %zu)", m->id, s,
                     m->nframes);
        return -2;
    }
    return v;
}

static int molinfo_get(ms_app *app, Tcl_Interp *interp, ms_molecule *m, int objc,
                       Tcl_Obj *const objv[])
{
    if (objc != 4 && objc != 6)
        return ms_cmd_error(interp, "molinfo: usage: molinfo <molid> get <keywords> ?frame <n>?");
    long frame = m->frame;
    if (objc == 6) {
        if (strcasecmp(Tcl_GetString(objv[4]), "frame"))
            return ms_cmd_error(interp, "molinfo: expected 'frame', got '%s'", Tcl_GetString(objv[4]));
        if ((frame = parse_frame(interp, m, objv[5])) == -2) return TCL_ERROR;
    }
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
    double d;
    int b;
    if (!strcasecmp(k, "frame")) {
        int f;
        if (Tcl_GetIntFromObj(NULL, v, &f) != TCL_OK)
            return ms_cmd_error(interp, "molinfo: frame: expected an integer, got '%s'", Tcl_GetString(v));
        ms_molset_set_frame(&app->mols, m, f);
        return TCL_OK;
    }
    if (!strcasecmp(k, "name")) {
        char *n = ms_strdup(Tcl_GetString(v));
        if (!n) return ms_cmd_error(interp, "molinfo: out of memory");
        free(m->name);
        m->name = n;
        return TCL_OK;
    }
    if (!strcasecmp(k, "active") || !strcasecmp(k, "drawn") || !strcasecmp(k, "displayed") ||
        !strcasecmp(k, "fixed") || !strcasecmp(k, "top")) {
        if (Tcl_GetBooleanFromObj(NULL, v, &b) != TCL_OK)
            return ms_cmd_error(interp, "molinfo: %s: expected a boolean, got '%s'", k, Tcl_GetString(v));
        if (!strcasecmp(k, "active")) m->active = (unsigned)b;
        else if (!strcasecmp(k, "fixed")) m->fixed = (unsigned)b;
        else if (!strcasecmp(k, "top")) { if (b) app->mols.top = m->id; }
        else m->displayed = (unsigned)b;
        return TCL_OK;
    }
    if (!strcasecmp(k, "center")) {
        Tcl_Obj **e;
        int n;
        double c[3];
        if (Tcl_ListObjGetElements(NULL, v, &n, &e) != TCL_OK || n != 3 ||
            Tcl_GetDoubleFromObj(NULL, e[0], &c[0]) || Tcl_GetDoubleFromObj(NULL, e[1], &c[1]) ||
            Tcl_GetDoubleFromObj(NULL, e[2], &c[2]))
            return ms_cmd_error(interp, "molinfo: center: expected {x y z}, got '%s'", Tcl_GetString(v));
        for (int i = 0; i < 3; i++) m->center[i] = (float)c[i];
        return TCL_OK;
    }
    if (!strcasecmp(k, "center_matrix") || !strcasecmp(k, "rotate_matrix") ||
        !strcasecmp(k, "scale_matrix") || !strcasecmp(k, "global_matrix")) {
        float mat[16];
        if (ms_matrix_from_obj(interp, v, mat, k) != TCL_OK) return TCL_ERROR;
        switch (k[0] | 0x20) {
        case 'c': for (int i = 0; i < 3; i++) m->center[i] = -mat[4 * i + 3]; break;
        case 'r': memcpy(m->rotate, mat, sizeof mat); break;
        case 's': m->scale = mat[0]; break;
        case 'g': for (int i = 0; i < 3; i++) m->global[i] = mat[4 * i + 3]; break;
        }
        return TCL_OK;
    }
    ms_frame *f = frame >= 0 && (size_t)frame < m->nframes ? &m->frames[frame] : NULL;
    for (int c = 0; c < 6; c++)
        if (!strcasecmp(k, cell_names[c])) {
            if (!f) return ms_cmd_error(interp, "molinfo: molecule %d has no frames", m->id);
            if (Tcl_GetDoubleFromObj(NULL, v, &d) != TCL_OK)
                return ms_cmd_error(interp, "molinfo: %s: expected a number, got '%s'", k, Tcl_GetString(v));
            f->cell[c] = (float)d;
            return TCL_OK;
        }
    if (!strcasecmp(k, "physical_time")) {
        if (!f) return ms_cmd_error(interp, "molinfo: molecule %d has no frames", m->id);
        if (Tcl_GetDoubleFromObj(NULL, v, &d) != TCL_OK)
            return ms_cmd_error(interp, "molinfo: physical_time: expected a number, got '%s'", Tcl_GetString(v));
        f->time = d;
        return TCL_OK;
    }
    for (int e = 0; e < nextra; e++)
        if (extra[e].set && (!strcasecmp(k, extra[e].name) ||
                             (extra[e].prefix && !strncasecmp(k, extra[e].name, strlen(extra[e].name)))))
            return extra[e].set(app, interp, m, k, v, frame);
    return ms_cmd_error(interp, "molinfo: cannot set keyword '%s'", k);
}

static int molinfo_set(ms_app *app, Tcl_Interp *interp, ms_molecule *m, int objc,
                       Tcl_Obj *const objv[])
{
    if (objc != 5 && objc != 7)
        return ms_cmd_error(interp, "molinfo: usage: molinfo <molid> set <keywords> <values> ?frame <n>?");
    app->world.scene_version++;
    long frame = m->frame;
    if (objc == 7) {
        if (strcasecmp(Tcl_GetString(objv[5]), "frame"))
            return ms_cmd_error(interp, "molinfo: expected 'frame', got '%s'", Tcl_GetString(objv[5]));
        if ((frame = parse_frame(interp, m, objv[6])) == -2) return TCL_ERROR;
    }
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
        return ms_cmd_error(interp, "molinfo: %d keywords but %d values", nk, nv);
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

static int molinfo_top(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc > 2) {
        /* `molinfo top get ...` */
        ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "molinfo");
        if (!m) return TCL_ERROR;
        const char *op = Tcl_GetString(objv[2]);
        if (!strcasecmp(op, "get")) return molinfo_get(app, interp, m, objc, objv);
        if (!strcasecmp(op, "set")) return molinfo_set(app, interp, m, objc, objv);
        return ms_cmd_error(interp, "molinfo: unknown operation '%s': must be get or set", op);
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(app->mols.top));
    return TCL_OK;
}

static int molinfo_index(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int i;
    if (objc != 3 || Tcl_GetIntFromObj(NULL, objv[2], &i) != TCL_OK)
        return ms_cmd_error(interp, "molinfo: usage: molinfo index <n>");
    if (i < 0 || (size_t)i >= app->mols.n) {
        Tcl_SetObjResult(interp, Tcl_NewIntObj(-1));
        return TCL_OK;
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(app->mols.mols[i]->id));
    return TCL_OK;
}

/* molinfo <molid> get|set ... */
static int molinfo_mol(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "molinfo");
    if (!m) return TCL_ERROR;
    if (objc < 3) return ms_cmd_error(interp, "molinfo: usage: molinfo <molid> get|set ...");
    const char *op = Tcl_GetString(objv[2]);
    if (!strcasecmp(op, "get")) return molinfo_get(app, interp, m, objc, objv);
    if (!strcasecmp(op, "set")) return molinfo_set(app, interp, m, objc, objv);
    return ms_cmd_error(interp, "molinfo: unknown operation '%s': must be get or set", op);
}

static const ms_subcmd molinfo_table[] = {
    {"num", molinfo_num}, {"list", molinfo_list}, {"top", molinfo_top},
    {"index", molinfo_index}, {NULL, NULL}};

void ms_cmd_molinfo_register(ms_app *app)
{
    ms_cmdset_create(app, "molinfo", molinfo_table);
    ms_cmdset_fallback(app, "molinfo", molinfo_mol);
    ms_cmdset_quiet(app, "molinfo");
}
