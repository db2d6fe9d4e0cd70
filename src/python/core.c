/* core.c: the _molscope module, Python's one door into molscope. Every function of the
 * molscope package (and so of VMD's Python API) is a Tcl command evaluated here on the
 * application's interpreter: its words are handed over as a list (never re-quoted), its
 * result comes back as a string or a list of strings, and a Tcl error becomes
 * molscope.TclError carrying Tcl's message. Inside molscope this is a built-in module of the
 * embedded interpreter working on the program's application; loaded into a plain python3 as
 * an extension, start() first makes an application of its own (with every command set and
 * gopython), so Tcl runs underneath with no molscope process. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "config.h"
#include "commands/commands.h"
#include "python/pyint.h"
#include "python/python.h"

static ms_app *g_app;          /* the application Python works on */
static int g_owned;            /* made by start(): freed when Python exits */
static PyObject *g_tclerror;   /* molscope.TclError */

void ms_python_set_app(ms_app *app)
{
    g_app = app;
}

ms_app *ms_py_app(void)
{
    if (!g_app)
        PyErr_SetString(PyExc_RuntimeError, "molscope: no application (call _molscope.start first)");
    return g_app;
}

static int need_app(void)
{
    return ms_py_app() ? 0 : -1;
}

/* Raise TclError with the interpreter's result (the message a Tcl user sees). */
static PyObject *raise_tcl(void)
{
    PyErr_SetString(g_tclerror, Tcl_GetStringResult(g_app->interp));
    Tcl_ResetResult(g_app->interp);
    return NULL;
}

/* A Python object as a Tcl word: str as is, a sequence (list, tuple, numpy array) as a
 * Tcl list of its items' words, anything else as str() makes it. */
static Tcl_Obj *tcl_word(PyObject *o)
{
    if (!PyUnicode_Check(o) && !PyBytes_Check(o) && PySequence_Check(o)) {
        PyObject *seq = PySequence_Fast(o, "not a sequence");
        if (!seq) return NULL;
        Tcl_Obj *list = Tcl_NewListObj(0, NULL);
        for (Py_ssize_t i = 0; list && i < PySequence_Fast_GET_SIZE(seq); i++) {
            Tcl_Obj *w = tcl_word(PySequence_Fast_GET_ITEM(seq, i));
            if (!w) {
                Tcl_IncrRefCount(list);   /* a fresh list: this frees it */
                Tcl_DecrRefCount(list);
                list = NULL;
                break;
            }
            Tcl_ListObjAppendElement(NULL, list, w);
        }
        Py_DECREF(seq);
        return list;
    }
    PyObject *s = PyUnicode_Check(o) ? (Py_INCREF(o), o) : PyObject_Str(o);
    if (!s) return NULL;
    Py_ssize_t n;
    const char *u = PyUnicode_AsUTF8AndSize(s, &n);
    Tcl_Obj *w = u ? Tcl_NewStringObj(u, (int)n) : NULL;
    Py_DECREF(s);
    return w;
}

/* Evaluate the words of args as one command at the global level; TCL_OK or TCL_ERROR with
 * a Python exception set. */
static int eval_words(PyObject *args)
{
    Py_ssize_t n = PyTuple_GET_SIZE(args);
    if (n == 0) {
        PyErr_SetString(PyExc_TypeError, "call: no command given");
        return TCL_ERROR;
    }
    Tcl_Obj *cmd = Tcl_NewListObj(0, NULL);
    Tcl_IncrRefCount(cmd);
    for (Py_ssize_t i = 0; i < n; i++) {
        Tcl_Obj *w = tcl_word(PyTuple_GET_ITEM(args, i));
        if (!w) {
            Tcl_DecrRefCount(cmd);
            return TCL_ERROR;
        }
        Tcl_ListObjAppendElement(NULL, cmd, w);
    }
    int rc = Tcl_EvalObjEx(g_app->interp, cmd, TCL_EVAL_GLOBAL);
    Tcl_DecrRefCount(cmd);
    if (rc != TCL_OK) raise_tcl();
    return rc == TCL_OK ? TCL_OK : TCL_ERROR;
}

static PyObject *str_of(Tcl_Obj *o)
{
    int n;
    const char *s = Tcl_GetStringFromObj(o, &n);
    return PyUnicode_DecodeUTF8(s, n, "replace");
}

/* A Tcl list as a Python list of strings; NULL with TclError when it is no list. */
static PyObject *list_of(Tcl_Obj *o)
{
    int n;
    Tcl_Obj **el;
    if (Tcl_ListObjGetElements(g_app->interp, o, &n, &el) != TCL_OK) return raise_tcl();
    PyObject *list = PyList_New(n);
    for (int i = 0; list && i < n; i++) {
        PyObject *s = str_of(el[i]);
        if (!s) {
            Py_CLEAR(list);
            break;
        }
        PyList_SET_ITEM(list, i, s);
    }
    return list;
}

static PyObject *py_call(PyObject *self, PyObject *args)
{
    if (need_app() || eval_words(args) != TCL_OK) return NULL;
    PyObject *r = str_of(Tcl_GetObjResult(g_app->interp));
    Tcl_ResetResult(g_app->interp);
    return r;
}

static PyObject *py_call_list(PyObject *self, PyObject *args)
{
    if (need_app() || eval_words(args) != TCL_OK) return NULL;
    Tcl_Obj *res = Tcl_GetObjResult(g_app->interp);
    Tcl_IncrRefCount(res);
    PyObject *r = list_of(res);
    Tcl_DecrRefCount(res);
    Tcl_ResetResult(g_app->interp);
    return r;
}

static PyObject *py_split(PyObject *self, PyObject *args)
{
    PyObject *text;
    if (need_app() || !PyArg_ParseTuple(args, "U:split", &text)) return NULL;
    Tcl_Obj *o = tcl_word(text);
    if (!o) return NULL;
    Tcl_IncrRefCount(o);
    PyObject *r = list_of(o);
    Tcl_DecrRefCount(o);
    return r;
}

static PyObject *py_evaltcl(PyObject *self, PyObject *args)
{
    const char *script;
    if (need_app() || !PyArg_ParseTuple(args, "s:evaltcl", &script)) return NULL;
    if (Tcl_EvalEx(g_app->interp, script, -1, TCL_EVAL_GLOBAL) != TCL_OK) return raise_tcl();
    PyObject *r = str_of(Tcl_GetObjResult(g_app->interp));
    Tcl_ResetResult(g_app->interp);
    return r;
}

/* read_line(prompt): the interactive prompt's input, read from Tcl's standard input
 * channel (the one the Tcl shell reads, so no line is lost between the two); EOFError at
 * its end. */
static PyObject *py_read_line(PyObject *self, PyObject *args)
{
    const char *prompt = "";
    if (need_app() || !PyArg_ParseTuple(args, "|s:read_line", &prompt)) return NULL;
    PyObject *out = PySys_GetObject("stdout");   /* borrowed */
    PyObject *r = out && out != Py_None ? PyObject_CallMethod(out, "flush", NULL) : NULL;
    Py_XDECREF(r);
    PyErr_Clear();
    fputs(prompt, stdout);
    fflush(stdout);
    Tcl_Channel in = Tcl_GetStdChannel(TCL_STDIN);
    Tcl_Obj *line = Tcl_NewObj();
    Tcl_IncrRefCount(line);
    int n = in ? Tcl_GetsObj(in, line) : -1;
    PyObject *res = n < 0 ? (PyErr_SetNone(PyExc_EOFError), NULL) : str_of(line);
    Tcl_DecrRefCount(line);
    return res;
}

static void free_owned_app(void)
{
    if (!g_owned) return;
    ms_app *app = g_app;
    g_app = NULL;
    g_owned = 0;
    ms_py_frames_forget();
    ms_app_free(app);
}

/* start(anchor): make the application of a plain python3, finding the Tcl library and
 * the plugins as a molscope program at the path anchor would. Nothing when one exists. */
static PyObject *py_start(PyObject *self, PyObject *args)
{
    const char *anchor;
    if (!PyArg_ParseTuple(args, "s:start", &anchor)) return NULL;
    if (g_app) Py_RETURN_FALSE;
    ms_app *app = ms_app_new_at(anchor, anchor, ms_command_sets);
    if (!app) return PyErr_NoMemory();
    ms_python_register(app);
    if (ms_app_source_init(app) != TCL_OK) {
        PyErr_Format(PyExc_ImportError, "molscope: %s", Tcl_GetStringResult(app->interp));
        ms_app_free(app);
        return NULL;
    }
    g_app = app;
    g_owned = 1;
    Py_AtExit(free_owned_app);
    Py_RETURN_TRUE;
}

static PyMethodDef core_methods[] = {
    {"call", py_call, METH_VARARGS,
     "call(*words) -> str: run one Tcl command (each argument one word); its result"},
    {"call_list", py_call_list, METH_VARARGS,
     "call_list(*words) -> list of str: run one Tcl command; its result as a list"},
    {"split", py_split, METH_VARARGS, "split(text) -> list of str: a Tcl list's elements"},
    {"evaltcl", py_evaltcl, METH_VARARGS, "evaltcl(script) -> str: evaluate Tcl text"},
    {"frame_buffer", ms_py_frame_buffer, METH_VARARGS,
     "frame_buffer(molid, frame=-1) -> FrameBuffer: a frame's coordinates, shared"},
    {"read_line", py_read_line, METH_VARARGS,
     "read_line(prompt='') -> str: a line of standard input as Tcl reads it"},
    {"render_image", ms_py_render_image, METH_VARARGS,
     "render_image(method, path=None) -> (width, height, rgb, png): render in memory"},
    {"pump", ms_py_pump, METH_VARARGS,
     "pump(seconds=0): run Tcl's event loop (the live view's server) for that long"},
    {"start", py_start, METH_VARARGS,
     "start(anchor) -> bool: create the application (a plain python3 only)"},
    {NULL, NULL, 0, NULL}};

static struct PyModuleDef core_module = {PyModuleDef_HEAD_INIT, "_molscope",
                                         "molscope's Tcl interpreter, for the molscope package",
                                         -1, core_methods, NULL, NULL, NULL, NULL};

PyMODINIT_FUNC PyInit__molscope(void);
PyMODINIT_FUNC PyInit__molscope(void)
{
    PyObject *m = PyModule_Create(&core_module);
    if (!m) return NULL;
    if (!g_tclerror) {
        PyObject *bases = PyTuple_Pack(2, PyExc_ValueError, PyExc_RuntimeError);
        g_tclerror = bases ? PyErr_NewExceptionWithDoc(
                                 "molscope.TclError", "A molscope (Tcl) command failed; the "
                                 "message is Tcl's.", bases, NULL)
                           : NULL;
        Py_XDECREF(bases);
    }
    if (!g_tclerror || PyModule_AddObject(m, "TclError", (Py_INCREF(g_tclerror), g_tclerror))) {
        Py_DECREF(m);
        return NULL;
    }
    if (ms_py_frames_init(m) < 0) {
        Py_DECREF(m);
        return NULL;
    }
    PyModule_AddIntConstant(m, "embedded", g_app != NULL);
    return m;
}
