/* pyint.h: what the files of the _molscope module share (Python.h first, then this). */
#ifndef MS_PYINT_H
#define MS_PYINT_H

#include "app/app.h"

/* The application Python works on, or NULL with RuntimeError set. */
ms_app *ms_py_app(void);

/* frame_buffer(molid, frame): the coordinates of a frame as a writable float32 buffer of
 * shape (natoms, 3), no copy (frames.c). */
PyObject *ms_py_frame_buffer(PyObject *self, PyObject *args);
/* Make the FrameBuffer type ready and add it to the module; 0, or -1 with an exception. */
int ms_py_frames_init(PyObject *module);
/* Python has ended: molecules freed from now on free their coordinates themselves (the
 * buffers Python leaked are not to be touched). */
void ms_py_frames_forget(void);

/* render_image(method, path=None) -> (width, height, rgb, png): the scene rendered in memory
 * by an image device, optionally written to path as `render` writes it (notebook.c). */
PyObject *ms_py_render_image(PyObject *self, PyObject *args);
/* pump(seconds=0): run Tcl's events (the live server's) for that long, letting other
 * Python threads run meanwhile (notebook.c). */
PyObject *ms_py_pump(PyObject *self, PyObject *args);

#endif
