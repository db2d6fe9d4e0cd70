/* cmd_quit.c: quit and exit. They set the application's quit request (app/app.h); the shell
 * and the batch runner act on it. */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"

#include <limits.h>

/* quit ?status?: VMD schedules the exit and returns an error on purpose, so a sourcing
 * script stops right there; the shell then exits with the status. */
static int cmd_quit(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int status = 0;
    if (objc == 2 && ms_arg_int(interp, objv[1], "status", INT_MIN, INT_MAX, &status)) return TCL_ERROR;
    app->quit_requested = 1;
    app->quit_status = status;
    Tcl_SetObjResult(interp, Tcl_NewStringObj("", 0));
    return TCL_ERROR;
}

void ms_cmd_quit_register(ms_app *app)
{
    static const ms_subcmd cmds[] = {{"quit", cmd_quit, 0, 1, "?<status>?"},
                                     {"exit", cmd_quit, 0, 1, "?<status>?"}};
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
