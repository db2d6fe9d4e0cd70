/* shell.h: the interactive or batch read-evaluate loop on standard input. */
#ifndef MS_SHELL_H
#define MS_SHELL_H

#include "app/app.h"

/* Run until EOF or quit; returns the exit status. */
int ms_shell_run(ms_app *app);
/* Print the interpreter's error message and stack trace to stderr. */
void ms_shell_report_error(ms_app *app, const char *context);

#endif
