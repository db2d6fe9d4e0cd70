/* embed.c: Python inside molscope. The interpreter starts on first use (gopython, -python)
 * as Debian's python3 would (its program name, so its own library and dist-packages), with
 * _molscope built in and molscope's package on sys.path; VMD's module names (vmd,
 * vmd.molecule, molecule, atomsel, ...) then name the molscope package's modules and
 * __main__ has VMD's top-level names. Code runs in __main__; a Python exception becomes the
 * Tcl error, its traceback the message. Inside a plain python3 (the extension) the host's
 * interpreter is used as it is. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "config.h"
#include "commands/args.h"
#include "commands/commands.h"
#include "python/pyint.h"
#include "python/python.h"

#include <limits.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

PyMODINIT_FUNC PyInit__molscope(void);

static int g_started;   /* this program started the interpreter (and finalizes it) */

/* The folder holding molscope's Python package: MOLSCOPE_PYTHONPATH, else src/python
 * beside the program in the build tree, else <prefix>/lib/python3.X/dist-packages beside
 * <prefix>/bin (a relocated install), else the configured one. */
static void find_pydir(const ms_app *app, char *dir, size_t n)
{
    const char *env = getenv("MOLSCOPE_PYTHONPATH");
    if (env && *env) {
        snprintf(dir, n, "%s", env);
        return;
    }
    char exe_dir[PATH_MAX], cand[PATH_MAX + 64], real[PATH_MAX];
    struct stat sb;
    snprintf(exe_dir, sizeof exe_dir, "%s", app->exe_path);
    char *slash = strrchr(exe_dir, '/');
    if (slash) *slash = '\0';
    const char *rel[] = {"python", "../lib/python" Py_STRINGIFY(PY_MAJOR_VERSION) "."
                                   Py_STRINGIFY(PY_MINOR_VERSION) "/dist-packages"};
    for (size_t i = 0; i < sizeof rel / sizeof rel[0]; i++) {
        snprintf(cand, sizeof cand, "%s/%s/molscope/__init__.py", exe_dir, rel[i]);
        if (stat(cand, &sb) == 0 && realpath(cand, real)) {
            *strrchr(real, '/') = '\0';
            *strrchr(real, '/') = '\0';
            snprintf(dir, n, "%s", real);
            return;
        }
    }
    snprintf(dir, n, "%s", MS_PYMODDIR);
}

/* Set the Tcl result to the Python exception pending (its traceback); TCL_ERROR. A
 * SystemExit becomes molscope's quit with its status. */
static int python_error(Tcl_Interp *interp)
{
    PyObject *type, *exc, *tbk;
    PyErr_Fetch(&type, &exc, &tbk);
    PyErr_NormalizeException(&type, &exc, &tbk);
    if (tbk) PyException_SetTraceback(exc, tbk);
    Py_XDECREF(type);
    Py_XDECREF(tbk);
    if (!exc) return ms_cmd_error(interp, "Python error (no exception)");
    if (PyErr_GivenExceptionMatches(exc, PyExc_SystemExit)) {
        PyObject *code = PyObject_GetAttrString(exc, "code");
        long status = code && PyLong_Check(code) ? PyLong_AsLong(code) : code != Py_None;
        Py_XDECREF(code);
        Py_DECREF(exc);
        PyErr_Clear();
        char cmd[64];
        snprintf(cmd, sizeof cmd, "quit %ld", status);
        return Tcl_EvalEx(interp, cmd, -1, TCL_EVAL_GLOBAL);
    }
    PyObject *tb = PyImport_ImportModule("traceback");
    PyObject *lines = tb ? PyObject_CallMethod(tb, "format_exception", "O", exc) : NULL;
    PyObject *empty = PyUnicode_FromString("");
    PyObject *text = lines && empty ? PyUnicode_Join(empty, lines) : NULL;
    const char *s = text ? PyUnicode_AsUTF8(text) : NULL;
    Tcl_SetObjResult(interp, Tcl_NewStringObj(s ? s : "Python error (no traceback)", -1));
    int n = s ? (int)strlen(s) : 0;
    if (n > 0 && s[n - 1] == '\n') Tcl_SetObjLength(Tcl_GetObjResult(interp), n - 1);
    Py_XDECREF(text);
    Py_XDECREF(empty);
    Py_XDECREF(lines);
    Py_XDECREF(tb);
    Py_DECREF(exc);
    PyErr_Clear();
    return TCL_ERROR;
}

/* Python's output goes out in order with molscope's own. */
static void flush_both(void)
{
    PyObject *r = PyRun_String("import sys\nfor _f in (sys.stdout, sys.stderr):\n"
                               "    _f is not None and _f.flush()\n",
                               Py_file_input, PyModule_GetDict(PyImport_AddModule("__main__")),
                               NULL);
    if (r) Py_DECREF(r);
    else PyErr_Clear();
    fflush(stdout);
}

static int start_interpreter(ms_app *app, Tcl_Interp *interp)
{
    if (PyImport_AppendInittab("_molscope", PyInit__molscope) != 0)
        return ms_cmd_error(interp, "gopython: cannot register the _molscope module");
    PyConfig config;
    PyConfig_InitPythonConfig(&config);
    config.install_signal_handlers = 0;   /* Ctrl-C stays molscope's */
    config.parse_argv = 0;
    PyStatus st = PyConfig_SetBytesString(&config, &config.program_name, MS_PYTHON3);
    if (!PyStatus_Exception(st)) st = Py_InitializeFromConfig(&config);
    PyConfig_Clear(&config);
    if (PyStatus_Exception(st))
        return ms_cmd_error(interp, "gopython: cannot start Python: %s",
                            st.err_msg ? st.err_msg : "unknown error");
    g_started = 1;
    ms_python_set_app(app);
    return TCL_OK;
}

/* Start Python if needed and make VMD's names importable. */
static int ensure_python(ms_app *app, Tcl_Interp *interp)
{
    static int ready;
    if (ready) return TCL_OK;
    if (!Py_IsInitialized() && start_interpreter(app, interp) != TCL_OK) return TCL_ERROR;
    char dir[PATH_MAX];
    find_pydir(app, dir, sizeof dir);
    PyObject *sys_path = PySys_GetObject("path");   /* borrowed */
    PyObject *d = PyUnicode_FromString(dir);
    if (sys_path && d && !PySequence_Contains(sys_path, d)) PyList_Insert(sys_path, 0, d);
    Py_XDECREF(d);
    PyObject *main = PyImport_AddModule("__main__");   /* borrowed */
    PyObject *r = PyRun_String("import molscope._vmdnames\nmolscope._vmdnames.install(globals())\n",
                               Py_file_input, PyModule_GetDict(main), NULL);
    if (!r) return python_error(interp);
    Py_DECREF(r);
    ready = 1;
    return TCL_OK;
}

/* Run code (already compiled, stolen) in __main__, with __file__ set for a file. */
static int run_code(Tcl_Interp *interp, PyObject *code, const char *file)
{
    if (!code) return python_error(interp);
    PyObject *globals = PyModule_GetDict(PyImport_AddModule("__main__"));
    if (file) {
        PyObject *f = PyUnicode_DecodeFSDefault(file);
        if (f) PyDict_SetItemString(globals, "__file__", f);
        Py_XDECREF(f);
    }
    PyObject *r = PyEval_EvalCode(code, globals, globals);
    Py_DECREF(code);
    int rc = r ? TCL_OK : python_error(interp);
    Py_XDECREF(r);
    if (file && PyDict_DelItemString(globals, "__file__") != 0) PyErr_Clear();
    flush_both();
    if (rc == TCL_OK) Tcl_ResetResult(interp);
    return rc;
}

/* The whole of a file; NULL with the Tcl error set. */
static char *read_file(Tcl_Interp *interp, const char *what, const char *path)
{
    Tcl_Channel in = Tcl_OpenFileChannel(interp, path, "r", 0);
    if (!in) return ms_cmd_error(interp, "%s: cannot open '%s': %s", what, path,
                                 Tcl_PosixError(interp)), NULL;
    Tcl_Obj *text = Tcl_NewObj();
    Tcl_IncrRefCount(text);
    int n = Tcl_ReadChars(in, text, -1, 0);
    Tcl_Close(NULL, in);
    char *s = n < 0 ? NULL : strdup(Tcl_GetString(text));
    Tcl_DecrRefCount(text);
    if (!s) ms_cmd_error(interp, "%s: cannot read '%s'", what, path);
    return s;
}

static int run_file(ms_app *app, Tcl_Interp *interp, const char *what, const char *path)
{
    char *text = read_file(interp, what, path);
    if (!text) return TCL_ERROR;
    fflush(stdout);
    int rc = run_code(interp, Py_CompileString(text, path, Py_file_input), path);
    free(text);
    return rc;
}

int ms_python_run_file(ms_app *app, const char *path)
{
    if (ensure_python(app, app->interp) != TCL_OK) return TCL_ERROR;
    return run_file(app, app->interp, "-python", path);
}

/* The interactive prompt on standard input (read as the Tcl shell reads it), back to Tcl
 * at its end. */
static int interactive(Tcl_Interp *interp)
{
    fflush(stdout);
    PyObject *main = PyImport_AddModule("__main__");   /* borrowed */
    PyObject *r = PyRun_String("import code as _code, _molscope as _ms\n"
                               "_code.interact(banner='', readfunc=_ms.read_line, "
                               "local=globals(), exitmsg='')\n"
                               "del _code, _ms\n",
                               Py_file_input, PyModule_GetDict(main), NULL);
    if (!r) return python_error(interp);
    Py_DECREF(r);
    flush_both();
    Tcl_ResetResult(interp);
    return TCL_OK;
}

/* gopython | gopython <file.py> | gopython -command <code> */
static int cmd_gopython(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 3 && !ms_word_eq(Tcl_GetString(objv[1]), "-command")) return ms_args_usage(interp);
    if (objc == 2 && ms_word_eq(Tcl_GetString(objv[1]), "-command")) return ms_args_usage(interp);
    if (ensure_python(app, interp) != TCL_OK) return TCL_ERROR;
    if (objc == 1) return interactive(interp);
    if (objc == 2) return run_file(app, interp, "gopython", Tcl_GetString(objv[1]));
    fflush(stdout);
    return run_code(interp, Py_CompileString(Tcl_GetString(objv[2]), "<gopython -command>",
                                             Py_file_input), NULL);
}

/* The program's interpreter ends before the application it works on. */
static void finish(ClientData cd, Tcl_Interp *interp)
{
    if (!g_started) return;
    g_started = 0;
    flush_both();
    Py_FinalizeEx();
    ms_py_frames_forget();
}

void ms_python_register(ms_app *app)
{
    static const ms_subcmd cmd = {"gopython", cmd_gopython, 0, 2,
                                  "?<file.py>? | gopython -command <code>"};
    ms_cmd_create(app, &cmd);
    Tcl_CallWhenDeleted(app->interp, finish, app);
}
