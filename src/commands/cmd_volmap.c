/* cmd_volmap.c: the `volmap` command (VMD's volumetric map maker), the density map only:
 *
 *   volmap density <sel> ?-res r? ?-radscale s? ?-weight none|<keyword>|<list>?
 *          ?-allframes? ?-combine avg|max|min|stdev? ?-quality q? ?-o file? ?-mol molid?
 *
 * Each selected atom is a normalised Gaussian of width radscale * radius weighted by
 * -weight (mass, charge, beta, occupancy, radius, or one number per selected atom), summed
 * on QuickSurf's grid (surf/qsurf.h, ms_volmap_density). With -allframes every frame's map
 * (on one grid) is combined. -o writes the map (the type from the extension: .dx, .ccp4);
 * the map is added to molecule -mol, or to the selection's molecule when no -o is given.
 * Returns the new volume's index in that molecule, or "" when only a file was written. */
#include "config.h"
#include "commands/atomsel.h"
#include "commands/commands.h"
#include "fileio/write.h"
#include "surf/qsurf.h"

#include <math.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

typedef enum { COMBINE_AVG, COMBINE_MAX, COMBINE_MIN, COMBINE_STDEV } combine_how;
static const char *const combine_names[] = {"avg", "max", "min", "stdev", NULL};

typedef struct volmap_opts {
    ms_volmap_params p;
    Tcl_Obj *weight, *mol;
    const char *out;
    int allframes;
    int combine;              /* combine_how */
} volmap_opts;

#define VOFF(f) offsetof(volmap_opts, f)
static const ms_opt volmap_options[] = {
    {"-res", MS_OPT_FLOAT, VOFF(p.res), 0, 1e4, MS_OPT_ABOVE | MS_OPT_MAX, NULL},
    {"-radscale", MS_OPT_FLOAT, VOFF(p.radscale), 0, 1e4, MS_OPT_ABOVE | MS_OPT_MAX, NULL},
    {"-weight", MS_OPT_OBJ, VOFF(weight), 0, 0, 0, NULL},
    {"-allframes", MS_OPT_FLAG, VOFF(allframes), 0, 0, 0, NULL},
    {"-combine", MS_OPT_ENUM, VOFF(combine), 0, 0, 0, combine_names},
    {"-quality", MS_OPT_INT, VOFF(p.quality), 0, 3, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"-o", MS_OPT_STRING, VOFF(out), 0, 0, 0, NULL},
    {"-mol", MS_OPT_OBJ, VOFF(mol), 0, 0, 0, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

static int parse_opts(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], volmap_opts *o)
{
    memset(o, 0, sizeof *o);
    ms_volmap_params_default(&o->p);
    o->combine = COMBINE_AVG;
    return ms_args_options(interp, objc, objv, 3, volmap_options, o, NULL);
}

/* Per-atom weights (indexed like the molecule) from -weight; NULL for none. */
static int get_weights(Tcl_Interp *interp, const ms_molecule *m, Tcl_Obj *wobj,
                       const uint32_t *atoms, size_t n, float **out)
{
    *out = NULL;
    if (!wobj || ms_word_eq(Tcl_GetString(wobj), "none")) return TCL_OK;
    const char *w = Tcl_GetString(wobj);
    static const char *const keywords[] = {"mass", "charge", "beta", "occupancy", "radius", NULL};
    const float *const columns[] = {m->atoms.mass, m->atoms.charge, m->atoms.beta,
                                    m->atoms.occupancy, m->atoms.radius};
    int k = ms_args_find(keywords, sizeof *keywords, w);
    const float *src = k < 0 ? NULL : columns[k];
    float *v = ms_calloc_array(m->atoms.n ? m->atoms.n : 1, sizeof *v);
    if (!v) return ms_cmd_error(interp, "volmap density: out of memory");
    if (src) {
        memcpy(v, src, m->atoms.n * sizeof *v);
    } else {
        Tcl_Obj **el;
        int ne;
        if (Tcl_ListObjGetElements(NULL, wobj, &ne, &el) != TCL_OK || (size_t)ne != n) {
            free(v);
            return ms_cmd_error(interp, "volmap density: -weight: expected none, mass, charge, "
                                "beta, occupancy, radius or %zu numbers, got '%.60s'", n, w);
        }
        for (size_t k = 0; k < n; k++) {
            double d;
            if (Tcl_GetDoubleFromObj(NULL, el[k], &d) != TCL_OK) {
                free(v);
                return ms_cmd_error(interp, "volmap density: -weight: '%s' is not a number",
                                    Tcl_GetString(el[k]));
            }
            v[atoms[k]] = (float)d;
        }
    }
    *out = v;
    return TCL_OK;
}

/* The bounding box of the selected atoms over every frame (-1: a streamed frame unread). */
static int frames_box(const ms_molecule *m, const uint32_t *atoms, size_t n, float lo[3],
                      float hi[3], ms_error *err)
{
    for (int d = 0; d < 3; d++) lo[d] = INFINITY, hi[d] = -INFINITY;
    for (size_t f = 0; f < m->nframes; f++) {
        const float *pos = ms_mol_frame_pos(m, f, err);
        if (!pos) return -1;
        for (size_t k = 0; k < n; k++) {
            const float *p = pos + 3 * (size_t)atoms[k];
            for (int d = 0; d < 3; d++)
                if (isfinite(p[d])) lo[d] = fminf(lo[d], p[d]), hi[d] = fmaxf(hi[d], p[d]);
        }
    }
    return 0;
}

/* Combine one frame's map into the accumulator (sums for avg and stdev). */
static void combine_into(int how, float *acc, float *acc2, const float *v, size_t n, int first)
{
    for (size_t i = 0; i < n; i++) {
        if (first) acc[i] = v[i], acc2[i] = v[i] * v[i];
        else if (how == COMBINE_MAX) acc[i] = fmaxf(acc[i], v[i]);
        else if (how == COMBINE_MIN) acc[i] = fminf(acc[i], v[i]);
        else acc[i] += v[i], acc2[i] += v[i] * v[i];
    }
}

/* The map of one frame, or of all frames combined, into vol. */
static int compute(const ms_molecule *m, long frame, const uint32_t *atoms, size_t n,
                   const float *w, volmap_opts *o, ms_qsurf_volume *vol, ms_error *err)
{
    ms_volmap_in in = {n, NULL, m->atoms.radius, w, atoms};
    if (!o->allframes) {
        if (!(in.pos = ms_mol_frame_pos(m, (size_t)frame, err))) return -1;
        return ms_volmap_density(&in, &o->p, vol, err);
    }
    if (frames_box(m, atoms, n, o->p.box_lo, o->p.box_hi, err)) return -1;
    o->p.use_box = isfinite(o->p.box_lo[0]);
    float *acc2 = NULL;
    for (size_t f = 0; f < m->nframes; f++) {
        ms_qsurf_volume one;
        if (!(in.pos = ms_mol_frame_pos(m, f, err))) goto fail;
        if (ms_volmap_density(&in, &o->p, f ? &one : vol, err)) goto fail;
        size_t np = (size_t)vol->n[0] * (size_t)vol->n[1] * (size_t)vol->n[2];
        if (f == 0) {
            if (!(acc2 = ms_alloc_array(np, sizeof *acc2))) goto oom;
            combine_into(o->combine, vol->data, acc2, vol->data, np, 1);
            continue;
        }
        combine_into(o->combine, vol->data, acc2, one.data, np, 0);
        ms_qsurf_volume_free(&one);
    }
    size_t np = (size_t)vol->n[0] * (size_t)vol->n[1] * (size_t)vol->n[2];
    double nf = (double)m->nframes;
    for (size_t i = 0; i < np; i++) {
        if (o->combine == COMBINE_AVG) vol->data[i] = (float)(vol->data[i] / nf);
        else if (o->combine == COMBINE_STDEV) {
            double mean = vol->data[i] / nf, var = acc2[i] / nf - mean * mean;
            vol->data[i] = (float)sqrt(var > 0 ? var : 0);
        }
    }
    free(acc2);
    return 0;
oom:
    ms_error_set(err, "out of memory");
fail:
    free(acc2);
    ms_qsurf_volume_free(vol);
    return -1;
}

/* The computed map as a molecule volume: attached and/or written. */
static int deliver(ms_app *app, Tcl_Interp *interp, ms_molecule *target, ms_qsurf_volume *q,
                   const volmap_opts *o)
{
    ms_volume v;
    memset(&v, 0, sizeof v);
    v.name = ms_strdup("volmap density");
    v.data = q->data;
    q->data = NULL;
    for (int d = 0; d < 3; d++) {
        v.n[d] = q->n[d];
        v.origin[d] = q->origin[d];
        for (int e = 0; e < 3; e++) v.delta[d][e] = q->axis[d][e];
    }
    ms_error err = {{0}};
    if (!v.name) {
        ms_volume_clear(&v);
        return ms_cmd_error(interp, "volmap density: out of memory");
    }
    if (o->out && ms_write_volume(&app->plugins, &v, o->out, NULL, &err)) {
        ms_volume_clear(&v);
        return ms_cmd_error(interp, "volmap density: %s: %s", o->out, err.msg);
    }
    if (!target) {
        ms_volume_clear(&v);
        Tcl_ResetResult(interp);
        return TCL_OK;
    }
    long k = ms_mol_add_volume(target, &v, &err);
    if (k < 0) return ms_cmd_error(interp, "volmap density: %s", err.msg);
    ms_molset_emit(&app->mols, MS_EV_VOLUMES, target, NULL);
    Tcl_SetObjResult(interp, Tcl_NewLongObj(k));
    return TCL_OK;
}

static int volmap_density(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    volmap_opts o;
    if (parse_opts(interp, objc, objv, &o)) return TCL_ERROR;
    int molid;
    long frame;
    uint32_t *atoms = NULL;
    size_t n = 0;
    if (ms_atomsel_resolve(app, interp, Tcl_GetString(objv[2]), "volmap density", &molid,
                           &frame, &atoms, &n) != TCL_OK)
        return TCL_ERROR;
    ms_molecule *m = ms_molset_get(&app->mols, molid), *target = NULL;
    float *w = NULL;
    int rc = TCL_ERROR;
    if (!m || frame < 0 || (size_t)frame >= m->nframes || n == 0) {
        ms_cmd_error(interp, "volmap density: %s: %s", Tcl_GetString(objv[2]),
                     n == 0 ? "the selection is empty" : "the molecule has no coordinates");
        goto done;
    }
    if (o.mol && !(target = ms_cmd_mol(app, interp, o.mol, "volmap density"))) goto done;
    if (!o.mol && !o.out) target = m;
    if (get_weights(interp, m, o.weight, atoms, n, &w)) goto done;
    ms_qsurf_volume q;
    ms_error err = {{0}};
    if (compute(m, frame, atoms, n, w, &o, &q, &err)) {
        ms_cmd_error(interp, "volmap density: %s", err.msg);
        goto done;
    }
    rc = deliver(app, interp, target, &q, &o);
    ms_qsurf_volume_free(&q);
done:
    free(atoms);
    free(w);
    return rc;
}

static const ms_subcmd volmap_table[] = {
    {"density", volmap_density, 1, MS_ARGS_ANY,
     "<selection> ?-res <r>? ?-radscale <s>? ?-weight <w>? ?-allframes? ?-combine "
     "avg|max|min|stdev? ?-quality <0..3>? ?-o <file>? ?-mol <molid>?"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_volmap_register(ms_app *app) { ms_cmdset_create(app, "volmap", volmap_table); }
