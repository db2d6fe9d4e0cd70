/* python.h: Python scripting (built with --with-python). Inside molscope: the gopython
 * command and `-python -e file.py`, which start the embedded interpreter on first use and
 * run Python in the same process, on the same molecules, with VMD's module names (vmd,
 * molecule, atomsel, ...) importable. For a plain python3: the _molscope extension module
 * (core.c) that the molscope package (src/python/molscope/) loads, which makes an
 * application of its own. Both reach molscope only through its Tcl commands (core.c). */
#ifndef MS_PYTHON_H
#define MS_PYTHON_H

#include "app/app.h"

/* Create the gopython command on the application's interpreter. */
void ms_python_register(ms_app *app);

/* Run a Python file in the interpreter's __main__ (started if needed), as gopython file
 * does. TCL_OK, or TCL_ERROR with the Python traceback as the interpreter's result. */
int ms_python_run_file(ms_app *app, const char *path);

/* Make app the application Python's _molscope module works on (the embedded interpreter's
 * app, or one the extension made). */
void ms_python_set_app(ms_app *app);

#endif
