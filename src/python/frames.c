/* frames.c: vmdnumpy's views of molscope's coordinates. A FrameBuffer exports one frame's
 * float32 x y z array through the buffer protocol (shape natoms x 3, writable), so numpy
 * arrays made from it are the molecule's memory: writing them moves the atoms. Views stay
 * safe when the molecule or the frame goes: the molecule asks its keeper before freeing a
 * frame's coordinates (molecule.h keep_pos), and a live buffer of them takes the array
 * over; the numpy array then holds detached data, which no longer moves any atom, and is
 * freed with the last reference. One FrameBuffer exists per array (a second request gets
 * the same object), so only one can own it. */
#define PY_SSIZE_T_CLEAN
#include <Python.h>

#include "config.h"
#include "app/app.h"
#include "python/pyint.h"

typedef struct frame_buffer {
    PyObject_HEAD
    float *pos;
    Py_ssize_t natoms;
    Py_ssize_t shape[2], strides[2];
    int owned;                       /* the molecule let go: pos is ours to free */
    struct frame_buffer *next;       /* the live buffers */
} frame_buffer;

static frame_buffer *g_live;

static int keep_pos(void *ud, float *pos)
{
    int taken = 0;
    for (frame_buffer *b = g_live; b; b = b->next)
        if (b->pos == pos && !b->owned) b->owned = taken = 1;
    return taken;
}

static void fb_dealloc(PyObject *self)
{
    frame_buffer *b = (frame_buffer *)self;
    for (frame_buffer **p = &g_live; *p; p = &(*p)->next)
        if (*p == b) {
            *p = b->next;
            break;
        }
    if (b->owned) free(b->pos);
    Py_TYPE(self)->tp_free(self);
}

static int fb_getbuffer(PyObject *self, Py_buffer *view, int flags)
{
    frame_buffer *b = (frame_buffer *)self;
    view->obj = self;
    Py_INCREF(self);
    view->buf = b->pos;
    view->len = b->natoms * 3 * (Py_ssize_t)sizeof(float);
    view->readonly = 0;
    view->itemsize = sizeof(float);
    view->format = (flags & PyBUF_FORMAT) ? "f" : NULL;
    view->ndim = 2;
    view->shape = (flags & PyBUF_ND) ? b->shape : NULL;
    view->strides = (flags & PyBUF_STRIDES) == PyBUF_STRIDES ? b->strides : NULL;
    view->suboffsets = NULL;
    view->internal = NULL;
    return 0;
}

static PyObject *fb_detached(PyObject *self, void *closure)
{
    return PyBool_FromLong(((frame_buffer *)self)->owned);
}

static PyBufferProcs fb_as_buffer = {fb_getbuffer, NULL};
static PyGetSetDef fb_getset[] = {
    {"detached", fb_detached, NULL, "True once the molecule or frame was deleted", NULL},
    {NULL, NULL, NULL, NULL, NULL}};

static PyTypeObject frame_buffer_type = {
    PyVarObject_HEAD_INIT(NULL, 0).tp_name = "_molscope.FrameBuffer",
    .tp_basicsize = sizeof(frame_buffer),
    .tp_dealloc = fb_dealloc,
    .tp_as_buffer = &fb_as_buffer,
    .tp_flags = Py_TPFLAGS_DEFAULT,
    .tp_doc = "One frame's coordinates (float32, natoms x 3), shared with the molecule",
    .tp_getset = fb_getset,
};

/* The molecule and its frame's coordinates; NULL with ValueError. */
static float *frame_pos(ms_app *app, int molid, long frame, ms_molecule **out)
{
    ms_molecule *m = molid < 0 ? ms_molset_top(&app->mols) : ms_molset_get(&app->mols, molid);
    if (!m) return PyErr_Format(PyExc_ValueError, "vmdnumpy: no molecule with id %d", molid), NULL;
    if (m->pending && ms_app_finish_molecule(app, m) != 0)
        return PyErr_Format(PyExc_ValueError, "vmdnumpy: molecule %d was deleted", molid), NULL;
    if (frame < 0) frame = m->frame;
    if (frame < 0 || (size_t)frame >= m->nframes)
        return PyErr_Format(PyExc_ValueError, "vmdnumpy: molecule %d has no frame %ld (it has %zu)",
                            m->id, frame, m->nframes), NULL;
    ms_error err = {{0}};   /* numpy keeps a view of it: a streamed frame is pinned */
    ms_frame *fr = ms_mol_frame_pin(m, (size_t)frame, &err);
    if (!fr) return PyErr_Format(PyExc_ValueError, "vmdnumpy: %s", err.msg), NULL;
    *out = m;
    return fr->pos;
}

PyObject *ms_py_frame_buffer(PyObject *self, PyObject *args)
{
    int molid;
    long frame = -1;
    ms_app *app = ms_py_app();
    if (!app || !PyArg_ParseTuple(args, "i|l:frame_buffer", &molid, &frame)) return NULL;
    ms_molecule *m;
    float *pos = frame_pos(app, molid, frame, &m);
    if (!pos) return NULL;
    for (frame_buffer *b = g_live; b; b = b->next)
        if (b->pos == pos && !b->owned) return Py_NewRef((PyObject *)b);
    frame_buffer *b = PyObject_New(frame_buffer, &frame_buffer_type);
    if (!b) return NULL;
    b->pos = pos;
    b->natoms = (Py_ssize_t)m->atoms.n;
    b->shape[0] = b->natoms;
    b->shape[1] = 3;
    b->strides[0] = 3 * sizeof(float);
    b->strides[1] = sizeof(float);
    b->owned = 0;
    b->next = g_live;
    g_live = b;
    m->keep_pos = keep_pos;
    return (PyObject *)b;
}

void ms_py_frames_forget(void)
{
    g_live = NULL;
}

int ms_py_frames_init(PyObject *module)
{
    if (PyType_Ready(&frame_buffer_type) < 0) return -1;
    Py_INCREF(&frame_buffer_type);
    return PyModule_AddObject(module, "FrameBuffer", (PyObject *)&frame_buffer_type);
}
