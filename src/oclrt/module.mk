# src/oclrt: TachyonLOpenCLInternal, the OpenCL ray tracer (doc/ocl.md). It builds its BVH with
# Embree's builder when Embree is there, else with its own (sah.c). Without OpenCL only the
# render device is built and every render falls back to TachyonInternal.
src_libmscore_la_SOURCES += src/oclrt/oclrt.h src/oclrt/tachyon_ocl.c
if HAVE_OPENCL
src_libmscore_la_SOURCES += \
	src/oclrt/oclrt_impl.h src/oclrt/params.h src/oclrt/flatten.c src/oclrt/bvh.c \
	src/oclrt/sah.c src/oclrt/device.c src/oclrt/frame.c
endif

# The kernels, params.h then kernels.cl, become a C string for device.c.
src/oclrt/kernels.inc: src/oclrt/params.h src/oclrt/kernels.cl
	$(AM_V_GEN)$(MKDIR_P) src/oclrt && \
	cat $(srcdir)/src/oclrt/params.h $(srcdir)/src/oclrt/kernels.cl | \
	sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/"/' -e 's/$$/\\n"/' > $@-t && mv $@-t $@
BUILT_SOURCES += src/oclrt/kernels.inc
CLEANFILES += src/oclrt/kernels.inc
EXTRA_DIST += src/oclrt/kernels.cl
