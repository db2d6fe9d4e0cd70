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

#endif
