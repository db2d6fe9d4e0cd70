# src/python: Python scripting (doc/python.md), built when configure finds Python 3
# embedding. libmspython holds the _molscope module (core.c) and the embedded interpreter
# with gopython (embed.c); the program links it with libpython, and the extension module
# _molscope.so (for a plain python3) links it with the core, without libpython: the host
# python3 provides it. The molscope package (src/python/molscope/*.py) is installed beside
# the extension in $(pymoddir); in the build tree src/python/ holds both (PYTHONPATH).
EXTRA_DIST += src/python/python.h src/python/pyint.h src/python/core.c src/python/embed.c \
	src/python/frames.c src/python/notebook.c $(MS_PYPKG)
MS_PYPKG = src/python/molscope/__init__.py src/python/molscope/_tcl.py \
	src/python/molscope/_atomsel.py src/python/molscope/_vmdnames.py \
	src/python/molscope/molecule.py src/python/molscope/molrep.py \
	src/python/molscope/display.py src/python/molscope/render.py \
	src/python/molscope/trans.py src/python/molscope/animate.py \
	src/python/molscope/color.py src/python/molscope/material.py \
	src/python/molscope/graphics.py src/python/molscope/label.py \
	src/python/molscope/vmdnumpy.py src/python/molscope/measure.py \
	src/python/molscope/topology.py src/python/molscope/selection.py \
	src/python/molscope/axes.py src/python/molscope/_image.py src/python/molscope/_live.py
if HAVE_PYTHON
noinst_LTLIBRARIES += src/python/libmspython.la
src_python_libmspython_la_SOURCES = src/python/python.h src/python/pyint.h src/python/core.c \
	src/python/embed.c src/python/frames.c src/python/notebook.c
src_python_libmspython_la_CFLAGS = $(AM_CFLAGS) $(PYTHON_CFLAGS)
src_python_libmspython_la_CPPFLAGS = $(AM_CPPFLAGS) -DMS_PYTHON3='"$(PYTHON3)"' \
	-DMS_PYMODDIR='"$(pymoddir)"'
src_molscope_LDADD += src/python/libmspython.la $(PYTHON_LIBS)

pymod_LTLIBRARIES = src/python/_molscope.la
src_python__molscope_la_SOURCES =
src_python__molscope_la_LIBADD = src/python/libmspython.la src/libmscore.la $(TCL_LIBS) \
	$(PNG_LIBS) $(PTHREAD_LIBS) $(MPI_LIBS)
src_python__molscope_la_LDFLAGS = -module -avoid-version -shared
pymolscopedir = $(pymoddir)/molscope
pymolscope_DATA = $(MS_PYPKG)

# The build tree's src/python is a folder python3 imports from (the package beside the
# extension), and `make install` says where the module went.
all-local: ms-python-link
ms-python-link: src/python/_molscope.la
	$(AM_V_at)ln -sf .libs/_molscope.so $(builddir)/src/python/_molscope.so
	$(AM_V_at)test -f $(builddir)/src/python/molscope/__init__.py || \
	  ln -sfn $(abs_srcdir)/src/python/molscope $(builddir)/src/python/molscope
install-data-hook:
	@echo "molscope: the Python module is installed in $(DESTDIR)$(pymoddir)"
	@echo "molscope: python3 finds it there for prefix /usr/local; else set PYTHONPATH=$(pymoddir)"
CLEANFILES += src/python/_molscope.so
clean-local: clean-local-python
clean-local-python:
	-test ! -L $(builddir)/src/python/molscope || rm -f $(builddir)/src/python/molscope
.PHONY: ms-python-link clean-local-python
endif
