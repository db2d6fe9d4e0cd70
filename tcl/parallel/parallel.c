/* parallel.c: the molscope::parallel Tcl package: VMD's `parallel` command over MPI, as a
 * loadable extension. molscope loads it at startup (init.tcl); a plain tclsh started by
 * mpirun loads it with `package require molscope::parallel` and the package then starts
 * MPI itself and ends it at exit (aborting the whole job when a rank exits non-zero, as
 * tclsh does after a script error). Without MPI every form works on one node.
 *
 *   parallel nodename | noderank | nodecount      -> this rank's host name, rank, rank count
 *   parallel barrier                              -> "" once every rank has arrived
 *   parallel allgather <value>                    -> every rank's value, in rank order
 *   parallel allreduce <proc> <value>             -> the same fold on every rank
 *   parallel for <start> <end> <proc> <userdata>  -> "" once every index is done
 *
 * allreduce gathers every value to rank 0, folds them left to right in rank order with
 * `{*}<proc> <accumulated> <next>` (each value is one argument; VMD builds the call by
 * string concatenation, which splits values that contain spaces), and broadcasts the
 * result, so a non-commutative proc gives the same value on every rank. An error in the
 * proc is every rank's error. With one node the value is returned without calling proc.
 *
 * for calls `{*}<proc> <i> <userdata>` for every i in [start, end] (rank 0's range), indices
 * handed out one at a time by rank 0, which works too (ms_par_for). An error in the proc
 * ends the whole job with its message (VMD reports it and goes on; a batch job here should
 * stop rather than produce a movie with holes). With one node it is a plain loop and the
 * error is the command's.
 *
 * The collective forms are refused inside a `parallel for` callback: the other ranks are
 * not at the same point, so they could never complete. */
#include "config.h"
#include "commands/args.h"
#include "parallel/parallel.h"

#include <limits.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <tcl.h>

#define PKG_NAME "molscope::parallel"
#define PKG_VERSION "1.0"
/* Set on the interpreter while a `parallel for` runs (also read by `mol new ... bcast`). */
#define BUSY_KEY "molscope::parallel::busy"

static int refuse_in_for(Tcl_Interp *interp, const char *sub)
{
    if (!Tcl_GetAssocData(interp, BUSY_KEY, NULL)) return TCL_OK;
    return ms_cmd_error(interp, "parallel %s: not allowed inside a parallel for callback (the "
                             "other ranks are not at the same point)", sub);
}

/* {*}prefix arg1 ?arg2?, evaluated at global level. */
static int call_prefix(Tcl_Interp *interp, Tcl_Obj *prefix, Tcl_Obj *a, Tcl_Obj *b)
{
    Tcl_Obj *cmd = Tcl_DuplicateObj(prefix);
    Tcl_IncrRefCount(cmd);
    int rc = Tcl_ListObjAppendElement(interp, cmd, a);
    if (rc == TCL_OK && b) rc = Tcl_ListObjAppendElement(interp, cmd, b);
    if (rc == TCL_OK) rc = Tcl_EvalObjEx(interp, cmd, TCL_EVAL_GLOBAL);
    Tcl_DecrRefCount(cmd);
    return rc;
}

/* ---------------------------------------------------------------- the simple forms */

static int par_allgather(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (refuse_in_for(interp, "allgather")) return TCL_ERROR;
    int len;
    const char *s = Tcl_GetStringFromObj(objv[2], &len);
    ms_error err = {{0}};
    ms_par_parts parts;
    if (ms_par_allgather(s, (size_t)len, &parts, &err))
        return ms_cmd_error(interp, "parallel allgather: %s", err.msg);
    Tcl_Obj *list = Tcl_NewListObj(0, NULL);
    for (int r = 0; r < parts.n; r++)
        Tcl_ListObjAppendElement(NULL, list,
                                 Tcl_NewStringObj(parts.data + parts.off[r], (int)parts.len[r]));
    ms_par_parts_free(&parts);
    Tcl_SetObjResult(interp, list);
    return TCL_OK;
}

/* Rank 0's fold of every rank's value; TCL_ERROR leaves the proc's error in interp. */
static int fold_on_rank0(Tcl_Interp *interp, Tcl_Obj *proc, const ms_par_parts *parts)
{
    Tcl_Obj *acc = Tcl_NewStringObj(parts->data + parts->off[0], (int)parts->len[0]);
    Tcl_IncrRefCount(acc);
    for (int r = 1; r < parts->n; r++) {
        Tcl_Obj *next = Tcl_NewStringObj(parts->data + parts->off[r], (int)parts->len[r]);
        if (call_prefix(interp, proc, acc, next) != TCL_OK) {
            Tcl_DecrRefCount(acc);
            return TCL_ERROR;
        }
        Tcl_DecrRefCount(acc);
        acc = Tcl_GetObjResult(interp);
        Tcl_IncrRefCount(acc);
    }
    Tcl_SetObjResult(interp, acc);
    Tcl_DecrRefCount(acc);
    return TCL_OK;
}

static int par_allreduce(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (refuse_in_for(interp, "allreduce")) return TCL_ERROR;
    if (ms_par_size() == 1) {
        Tcl_SetObjResult(interp, objv[3]);
        return TCL_OK;
    }
    int len;
    const char *s = Tcl_GetStringFromObj(objv[3], &len);
    ms_error err = {{0}};
    ms_par_parts parts;
    if (ms_par_gather0(s, (size_t)len, &parts, &err))
        return ms_cmd_error(interp, "parallel allreduce: %s", err.msg);
    int32_t rc = TCL_OK;
    if (ms_par_rank() == 0) rc = fold_on_rank0(interp, objv[2], &parts);
    ms_par_parts_free(&parts);
    /* Rank 0's outcome, then its result or error message, to everyone. */
    ms_par_bcast_small(&rc, sizeof rc, &err); /* the others wait while rank 0 folds */
    void *out = NULL;
    size_t n = 0;
    if (ms_par_rank() == 0) {
        int olen;
        out = (void *)Tcl_GetStringFromObj(Tcl_GetObjResult(interp), &olen);
        n = (size_t)olen;
    }
    ms_par_bcast_buffer(&out, &n, &err);
    Tcl_Obj *res = Tcl_NewStringObj(out, (int)n);
    if (ms_par_rank() != 0) free(out);
    if (rc != TCL_OK) {
        Tcl_Obj *msg = Tcl_ObjPrintf("parallel allreduce: %s: ", Tcl_GetString(objv[2]));
        Tcl_AppendObjToObj(msg, res);
        Tcl_DecrRefCount(res);
        res = msg;
    }
    Tcl_SetObjResult(interp, res);
    return rc == TCL_OK ? TCL_OK : TCL_ERROR;
}

/* ---------------------------------------------------------------- parallel for */

typedef struct for_ctx {
    Tcl_Interp *interp;
    Tcl_Obj *proc, *userdata;
} for_ctx;

static int for_item(void *ctx, long i, ms_error *err)
{
    for_ctx *c = ctx;
    if (call_prefix(c->interp, c->proc, Tcl_NewWideIntObj(i), c->userdata) == TCL_OK) return 0;
    Tcl_AppendObjToErrorInfo(c->interp, Tcl_ObjPrintf("\n    (parallel for index %ld)", i));
    const char *info = Tcl_GetVar(c->interp, "errorInfo", TCL_GLOBAL_ONLY);
    ms_error_set(err, "%s", info && *info ? info : Tcl_GetStringResult(c->interp));
    return -1;
}

static int par_for(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (refuse_in_for(interp, "for")) return TCL_ERROR;
    long first, last;
    if (ms_arg_long(interp, objv[2], "start", LONG_MIN, LONG_MAX, &first) ||
        ms_arg_long(interp, objv[3], "end", LONG_MIN, LONG_MAX, &last))
        return TCL_ERROR;
    for_ctx c = {interp, objv[4], objv[5]};
    ms_error err = {{0}};
    Tcl_SetAssocData(interp, BUSY_KEY, NULL, (ClientData)1);
    int rc = ms_par_for(first, last, for_item, &c, &err);
    Tcl_DeleteAssocData(interp, BUSY_KEY);
    if (rc) return TCL_ERROR; /* one rank: the proc's error is the result */
    Tcl_ResetResult(interp);
    return TCL_OK;
}

/* ---------------------------------------------------------------- the command */

static int par_nodename(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewStringObj(ms_par_nodename(), -1));
    return TCL_OK;
}

static int par_noderank(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(ms_par_rank()));
    return TCL_OK;
}

static int par_nodecount(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewIntObj(ms_par_size()));
    return TCL_OK;
}

static int par_barrier(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_error err = {{0}};
    if (refuse_in_for(interp, "barrier")) return TCL_ERROR;
    if (ms_par_barrier(&err)) return ms_cmd_error(interp, "parallel barrier: %s", err.msg);
    return TCL_OK;
}

static const ms_subcmd parallel_table[] = {
    {"nodename", par_nodename, 0, 0, ""},
    {"noderank", par_noderank, 0, 0, ""},
    {"nodecount", par_nodecount, 0, 0, ""},
    {"barrier", par_barrier, 0, 0, ""},
    {"allgather", par_allgather, 1, 1, "<value>"},
    {"allreduce", par_allreduce, 2, 2, "<proc> <value>"},
    {"for", par_for, 4, 4, "<start> <end> <proc> <userdata>"},
    {NULL, NULL, 0, 0, NULL}};

/* The package has no application: the handlers get none. */
static int cmd_parallel(ClientData cd, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    return ms_args_dispatch(NULL, interp, objc, objv, 1, parallel_table, NULL, "parallel");
}

/* ---------------------------------------------------------------- loading */

/* tclsh's exit when this package started MPI: finalize after status 0, abort the job after
 * any other status, then let Tcl finish exiting. */
static void par_exit_proc(ClientData cd)
{
    int status = (int)(intptr_t)cd;
    Tcl_SetExitProc(NULL);
    if (status != 0) {
        Tcl_Channel ch[2] = {Tcl_GetStdChannel(TCL_STDOUT), Tcl_GetStdChannel(TCL_STDERR)};
        for (int k = 0; k < 2; k++)
            if (ch[k]) Tcl_Flush(ch[k]);
    }
    ms_par_exit(status);
    Tcl_Exit(status);
}

int Molscope_parallel_Init(Tcl_Interp *interp);
int Parallel_Init(Tcl_Interp *interp);

int Molscope_parallel_Init(Tcl_Interp *interp)
{
#ifdef USE_TCL_STUBS
    if (!Tcl_InitStubs(interp, "8.6", 0)) return TCL_ERROR;
#endif
    static int started;
    ms_error err = {{0}};
    if (ms_par_init(NULL, NULL, &err))
        return ms_cmd_error(interp, "parallel: cannot start MPI: %s", err.msg);
    if (!started && ms_par_owner()) {
        Tcl_SetExitProc(par_exit_proc);
        if (ms_par_rank() == 0 && ms_par_size() > 1)
            fprintf(stderr, "parallel: %d ranks\n", ms_par_size());
    }
    started = 1;
    Tcl_CreateObjCommand(interp, "parallel", cmd_parallel, NULL, NULL);
    return Tcl_PkgProvide(interp, PKG_NAME, PKG_VERSION);
}

/* The name Tcl's `load` derives from the file name (parallel.so). */
int Parallel_Init(Tcl_Interp *interp) { return Molscope_parallel_Init(interp); }
