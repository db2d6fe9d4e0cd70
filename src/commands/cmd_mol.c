/* cmd_mol.c: the `mol` command (alias `molecule`): loading and managing molecules. The
 * representation subcommands (addrep, modstyle, ...) are added by the rep module, ssrecalc by
 * cmd_ss.c.
 *
 *   mol new [file [options]] | mol new atoms N       -> molid
 *   mol addfile file [options] [molid]                -> molid
 *   mol load type file [type file ...]                -> molid   (obsolescent form)
 *   mol delete molid|all; mol top molid; mol list [molid]; mol rename molid name
 *   mol on|off|fix|free|unfix|active|inactive molspec
 *   mol cancel molid; mol reanalyze molid; mol bondsrecalc molid
 *   mol voldelete volid molid
 * Load options include VMD's and molscope's `assembly id` (build a biological assembly).
 * molscope adds the load option `bcast on` to new and addfile: under MPI, rank 0 reads the
 * file and every rank receives the molecule (see commands.h). */
#include "config.h"
#include "commands/commands.h"
#include "fileio/load.h"
#include "molecule/analysis.h"
#include "rep/rep.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static int mol_new_atoms(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    long n;
    if (ms_arg_long(interp, objv[3], "count", 0, 0x7fffffffL, &n)) return TCL_ERROR;
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    if (!m || !(m->name = ms_strdup("molecule")) || ms_mol_reserve_atoms(m, (size_t)n, &err))
        goto fail;
    for (long i = 0; i < n; i++)
        if (ms_mol_add_blank_atom(m, &err) < 0) goto fail;
    for (long i = 0; i < n; i++) ms_analysis_atom_defaults(m, (size_t)i, 0, 0, 0);
    if (ms_bonds_build(m, NULL, 0, NULL, &err) || ms_analysis_classify(m, &err) ||
        ms_molset_add(&app->mols, m, &err))
        goto fail;
    Tcl_SetObjResult(interp, Tcl_NewIntObj(m->id));
    return TCL_OK;
fail:
    ms_mol_free(m);
    return ms_cmd_error(interp, "mol new atoms: %s", err.msg[0] ? err.msg : "out of memory");
}

static int mol_new(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 2) {
        ms_error err = {{0}};
        ms_molecule *m = ms_mol_new(&err);
        if (!m || !(m->name = ms_strdup("molecule")) || ms_molset_add(&app->mols, m, &err)) {
            ms_mol_free(m);
            return ms_cmd_error(interp, "mol new: out of memory");
        }
        Tcl_SetObjResult(interp, Tcl_NewIntObj(m->id));
        return TCL_OK;
    }
    if (objc == 4 && ms_word_eq(Tcl_GetString(objv[2]), "atoms"))
        return mol_new_atoms(app, interp, objc, objv);
    ms_load_opts o;
    ms_load_opts_default(&o);
    if (ms_cmd_parse_load_opts(interp, "mol new", objc, objv, 3, &o, NULL)) return TCL_ERROR;
    return ms_cmd_load(app, interp, "mol new", Tcl_GetString(objv[2]), &o, NULL);
}

static int mol_addfile(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_load_opts o;
    ms_load_opts_default(&o);
    Tcl_Obj *molword;
    if (ms_cmd_parse_load_opts(interp, "mol addfile", objc, objv, 3, &o, &molword))
        return TCL_ERROR;
    ms_molecule *m;
    if (molword) m = ms_cmd_mol(app, interp, molword, "mol addfile");
    else if (!(m = ms_molset_top(&app->mols)))
        /* VMD: with no molecule loaded, addfile makes a new one. */
        return ms_cmd_load(app, interp, "mol addfile", Tcl_GetString(objv[2]), &o, NULL);
    if (!m) return TCL_ERROR;
    return ms_cmd_load(app, interp, "mol addfile", Tcl_GetString(objv[2]), &o, m);
}

static int mol_load(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if ((objc - 2) % 2) return ms_args_usage(interp);
    ms_molecule *m = NULL;
    for (int i = 2; i < objc; i += 2) {
        ms_load_opts o;
        ms_load_opts_default(&o);
        o.type = Tcl_GetString(objv[i]);
        o.waitfor = -1;
        if (ms_cmd_load(app, interp, "mol load", Tcl_GetString(objv[i + 1]), &o, m)) {
            if (m && i > 2) ms_molset_delete(&app->mols, m->id); /* all or nothing */
            return TCL_ERROR;
        }
        if (!m) m = ms_molset_top(&app->mols);
    }
    Tcl_SetObjResult(interp, Tcl_NewIntObj(m->id));
    return TCL_OK;
}

static int mol_delete(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int *ids, n;
    if (ms_cmd_molspec(app, interp, Tcl_GetString(objv[2]), "mol delete", &ids, &n))
        return TCL_ERROR;
    for (int i = 0; i < n; i++) ms_molset_delete(&app->mols, ids[i]);
    free(ids);
    return TCL_OK;
}

static int mol_top(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], "mol top");
    if (!m) return TCL_ERROR;
    app->mols.top = m->id;
    return TCL_OK;
}

static int mol_rename(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], "mol rename");
    if (!m) return TCL_ERROR;
    char *name = ms_strdup(Tcl_GetString(objv[3]));
    if (!name) return ms_cmd_error(interp, "mol rename: out of memory");
    free(m->name);
    m->name = name;
    return TCL_OK;
}

/* mol list, in VMD's words: one line per molecule ("<name>  Atoms:<n>  Frames (C): <n>(<c>)
 * Status:ADFT", lower case for a flag that is off), and for one molecule its reps too. */
static void list_summary(Tcl_Obj *out, const ms_molecule *m, int top)
{
    Tcl_AppendPrintfToObj(out, "%s  Atoms:%ld  Frames (C): %ld(%d)  Status:%c%c%c%c\n",
                          m->name ? m->name : "", (long)m->atoms.n, (long)m->nframes, m->frame,
                          m->active ? 'A' : 'a', m->displayed ? 'D' : 'd', m->fixed ? 'F' : 'f',
                          m->id == top ? 'T' : 't');
}

static void list_reps(ms_app *app, Tcl_Obj *out, ms_molecule *m)
{
    size_t n = ms_rep_count(app->world.reps, m);
    Tcl_AppendPrintfToObj(out, "Atom representations: %ld\n", (long)n);
    for (size_t i = 0; i < n; i++) {
        ms_rep *r = ms_rep_get(app->world.reps, m, (long)i);
        ms_error err = {{0}};
        size_t nsel = 0;
        if (m->nframes == 0 || ms_rep_update_data(app->world.reps, m, r, &err) == 0)
            ms_rep_atoms(r, &nsel);
        Tcl_AppendPrintfToObj(out, "%ld: %s, %ld atoms selected.\n  Coloring method: %s\n"
                              "   Representation: %s\n        Selection: %s\n", (long)i,
                              r->shown ? " on" : "off", (long)nsel,
                              ms_rep_text(app->world.reps, r, MS_REP_COLOR),
                              ms_rep_text(app->world.reps, r, MS_REP_STYLE),
                              ms_rep_text(app->world.reps, r, MS_REP_SELECTION));
    }
}

static int mol_list(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int *ids, n;
    if (app->mols.n == 0) {   /* VMD answers, and does not fail */
        Tcl_SetObjResult(interp, Tcl_NewStringObj("ERROR) No molecules loaded.", -1));
        return TCL_OK;
    }
    if (ms_cmd_molspec(app, interp, objc == 3 ? Tcl_GetString(objv[2]) : "all", "mol list",
                       &ids, &n))
        return TCL_ERROR;
    Tcl_Obj *out = Tcl_NewObj();
    if (n > 1) Tcl_AppendToObj(out, "Molecule Status Overview:\n-------------------------\n", -1);
    for (int i = 0; i < n; i++) {
        ms_molecule *m = ms_molset_get(&app->mols, ids[i]);
        if (n == 1) Tcl_AppendPrintfToObj(out, "Status of molecule %s:\n", m->name ? m->name : "");
        list_summary(out, m, app->mols.top);
        if (n == 1) list_reps(app, out, m);
    }
    free(ids);
    /* VMD's console prints the text; returning it lets scripts capture it too */
    int len;
    const char *t = Tcl_GetStringFromObj(out, &len);
    if (len && t[len - 1] == '\n') Tcl_SetObjLength(out, len - 1);
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

/* mol on|off|fix|free|unfix|active|inactive <molspec>: the flag each word sets. */
static const struct {
    const char *name;
    enum { F_DISPLAYED, F_FIXED, F_ACTIVE } flag;
    unsigned value;
} flag_words[] = {{"on", F_DISPLAYED, 1}, {"off", F_DISPLAYED, 0}, {"fix", F_FIXED, 1},
                  {"free", F_FIXED, 0},   {"unfix", F_FIXED, 0},  {"active", F_ACTIVE, 1},
                  {"inactive", F_ACTIVE, 0}, {NULL, F_DISPLAYED, 0}};

static int mol_flag(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int k = ms_args_find(flag_words, sizeof *flag_words, Tcl_GetString(objv[1])), *ids, n;
    if (ms_cmd_molspec(app, interp, Tcl_GetString(objv[2]), ms_args_where(), &ids, &n))
        return TCL_ERROR;
    for (int i = 0; i < n; i++) {
        ms_molecule *m = ms_molset_get(&app->mols, ids[i]);
        unsigned v = flag_words[k].value;
        if (flag_words[k].flag == F_DISPLAYED) m->displayed = v;
        else if (flag_words[k].flag == F_FIXED) m->fixed = v;
        else m->active = v;
    }
    free(ids);
    return TCL_OK;
}

static int mol_cancel(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], "mol cancel");
    if (!m) return TCL_ERROR;
    ms_loader_cancel(m);
    return TCL_OK;
}

/* mol reanalyze / bondsrecalc: redo the structure analysis (bondsrecalc also redoes the
 * distance bonds from the current frame). */
static int mol_reanalyze(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    const char *cmd = ms_args_where();
    int bonds = ms_word_eq(Tcl_GetString(objv[1]), "bondsrecalc");
    ms_molecule *m = ms_cmd_mol(app, interp, objv[2], cmd);
    if (!m) return TCL_ERROR;
    ms_error err = {{0}};
    const float *pos = ms_mol_pos(m);
    if (bonds && pos) {
        uint32_t *pairs = NULL;
        size_t np = 0, cap = 0;
        int rc = ms_bond_search(m, pos, &pairs, &np, &cap, &err) ||
                 ms_mol_set_bonds(m, np, pairs, NULL, &err);
        free(pairs);
        if (rc) return ms_cmd_error(interp, "%s: %s", cmd, err.msg);
    } else if (ms_analysis_classify(m, &err)) {
        return ms_cmd_error(interp, "%s: %s", cmd, err.msg);
    }
    ms_molset_emit(&app->mols, MS_EV_STRUCTURE, m, NULL);
    return TCL_OK;
}

/* mol voldelete <volid> <molid>: delete one volumetric data set. */
static int mol_voldelete(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_molecule *m = ms_cmd_mol(app, interp, objv[3], "mol voldelete");
    if (!m) return TCL_ERROR;
    int k;
    if (Tcl_GetIntFromObj(NULL, objv[2], &k) != TCL_OK || k < 0 || (size_t)k >= m->nvolumes)
        return ms_cmd_error(interp, "mol voldelete: molecule %d has no volume '%s' (it has %zu)",
                            m->id, Tcl_GetString(objv[2]), m->nvolumes);
    ms_mol_delete_volume(m, (size_t)k);
    ms_molset_emit(&app->mols, MS_EV_VOLUMES, m, NULL);
    return TCL_OK;
}

static const ms_subcmd mol_table[] = {
    {"new", mol_new, 0, MS_ARGS_ANY, "?<file> ?<option> <value> ...?? | atoms <count>"},
    {"addfile", mol_addfile, 1, MS_ARGS_ANY, "<file> ?<option> <value> ...? ?<molid>?"},
    {"load", mol_load, 2, MS_ARGS_ANY, "<type> <file> ?<type> <file> ...?"},
    {"delete", mol_delete, 1, 1, "<molid|all>"},
    {"top", mol_top, 1, 1, "<molid>"},
    {"rename", mol_rename, 2, 2, "<molid> <name>"},
    {"list", mol_list, 0, 1, "?<molid>?"},
    {"on", mol_flag, 1, 1, "<molspec>"},
    {"off", mol_flag, 1, 1, "<molspec>"},
    {"fix", mol_flag, 1, 1, "<molspec>"},
    {"free", mol_flag, 1, 1, "<molspec>"},
    {"unfix", mol_flag, 1, 1, "<molspec>"},
    {"active", mol_flag, 1, 1, "<molspec>"},
    {"inactive", mol_flag, 1, 1, "<molspec>"},
    {"cancel", mol_cancel, 1, 1, "<molid>"},
    {"reanalyze", mol_reanalyze, 1, 1, "<molid>"},
    {"bondsrecalc", mol_reanalyze, 1, 1, "<molid>"},
    {"voldelete", mol_voldelete, 2, 2, "<volid> <molid>"},
    {NULL, NULL, 0, 0, NULL}};

void ms_cmd_mol_register(ms_app *app)
{
    ms_cmdset_create(app, "mol", mol_table);
    /* VMD accepts `molecule` as a synonym. */
    Tcl_Eval(app->interp, "interp alias {} molecule {} mol");
}
