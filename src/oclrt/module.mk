# src/oclrt: TachyonLOpenCLInternal, the OpenCL ray tracer (doc/ocl.md). It needs OpenCL and
# Embree (for the BVH builder); without either, only the render device is built and every
# render falls back to TachyonInternal.
src_libmscore_la_SOURCES += src/oclrt/oclrt.h src/oclrt/tachyon_ocl.c
if HAVE_OPENCL
if HAVE_EMBREE
src_libmscore_la_SOURCES += \
	src/oclrt/oclrt_impl.h src/oclrt/params.h src/oclrt/flatten.c src/oclrt/bvh.c \
	src/oclrt/sah.c src/oclrt/device.c src/oclrt/frame.c
endif
endif

# The kernels, params.h then kernels.cl, become a C string for device.c.
src/oclrt/kernels.inc: src/oclrt/params.h src/oclrt/kernels.cl
	$(AM_V_GEN)$(MKDIR_P) src/oclrt && \
	cat $(srcdir)/src/oclrt/params.h $(srcdir)/src/oclrt/kernels.cl | \
	sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/"/' -e 's/$$/\\n"/' > $@-t && mv $@-t $@
BUILT_SOURCES += src/oclrt/kernels.inc
CLEANFILES += src/oclrt/kernels.inc
EXTRA_DIST += src/oclrt/kernels.cl
