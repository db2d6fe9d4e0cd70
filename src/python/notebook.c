/* notebook.c: what the molscope package's notebook additions (molscope.render, molscope.live)
 * need from C. render_image renders the scene with one of molscope's image devices into
 * memory through the same code as `render` (assemble/devices.h) and hands Python its RGB
 * pixels and their PNG encoding, optionally writing the file as `render` writes it; pump
 * runs Tcl's event loop for a while (the live server, its passes and timers live there),
 * letting other Python threads run between events. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "config.h"
#include "assemble/devices.h"
#include "python/pyint.h"

#include <string.h>
#include <time.h>
#include <unistd.h>

/* ms_render_write_image's maker for an image already rendered: a copy of it. */
static int copy_image(void *user, ms_image *img, ms_error *err)
{
    const ms_image *src = user;
    if (ms_image_alloc(img, src->width, src->height, err)) return -1;
    memcpy(img->rgb, src->rgb, (size_t)3 * src->width * src->height);
    return 0;
}

/* The result tuple (width, height, rgb bytes, png bytes); NULL with an exception set. */
static PyObject *image_result(const ms_image *img, PyObject *tclerror, const char *method)
{
    unsigned char *png;
    size_t len;
    ms_error err = {{0}};
    if (ms_image_png_mem(img, &png, &len, &err)) {
        PyErr_Format(tclerror, "render %s: %s", method, err.msg);
        return NULL;
    }
    PyObject *r = Py_BuildValue("iiy#y#", img->width, img->height, (const char *)img->rgb,
                                (Py_ssize_t)3 * img->width * img->height, (const char *)png,
                                (Py_ssize_t)len);
    free(png);
    return r;
}

PyObject *ms_py_render_image(PyObject *self, PyObject *args)
{
    const char *method, *path = NULL;
    ms_app *app = ms_py_app();
    if (!app || !PyArg_ParseTuple(args, "s|z:render_image", &method, &path)) return NULL;
    PyObject *tclerror = PyObject_GetAttrString(self, "TclError");
    if (!tclerror) return NULL;
    const ms_render_device *dev = ms_render_find(method);
    if (!dev) dev = ms_render_find_alias(method);
    if (!dev) {
        PyErr_Format(tclerror, "render: no render method '%s' (see render list)", method);
        Py_DECREF(tclerror);
        return NULL;
    }
    ms_image img;
    ms_error err = {{0}};
    PyObject *r = NULL;
    if (ms_render_image(&app->world, dev, &img, &err) == 0) {
        if (!path || ms_render_write_image(path, copy_image, &img, &err) == 0)
            r = image_result(&img, tclerror, dev->name);
        ms_image_free(&img);
    }
    if (!r && !PyErr_Occurred()) PyErr_Format(tclerror, "render %s: %s", dev->name, err.msg);
    Py_DECREF(tclerror);
    return r;
}

static double now_s(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + ts.tv_nsec * 1e-9;
}

/* The events pending now, for a tenth of a second at most (a ray-traced pass may be one). */
static void run_pending(void)
{
    double stop = now_s() + 0.1;
    while (now_s() < stop && Tcl_DoOneEvent(TCL_ALL_EVENTS | TCL_DONT_WAIT)) {
    }
}

PyObject *ms_py_pump(PyObject *self, PyObject *args)
{
    double seconds = 0;
    if (!ms_py_app() || !PyArg_ParseTuple(args, "|d:pump", &seconds)) return NULL;
    if (!(seconds >= 0 && seconds <= 86400)) {
        PyErr_SetString(PyExc_ValueError, "pump: seconds must be between 0 and 86400");
        return NULL;
    }
    double deadline = now_s() + seconds;
    for (;;) {
        run_pending();
        if (now_s() >= deadline) break;
        Py_BEGIN_ALLOW_THREADS
        usleep(2000);
        Py_END_ALLOW_THREADS
        if (PyErr_CheckSignals()) return NULL;
    }
    Py_RETURN_NONE;
}
