# src/surf: QuickSurf, the Gaussian density surface engine (density map, slab planner,
# marching cubes, OpenCL path, bead reduction).
QSURF_SOURCES = \
	src/surf/qsurf.h src/surf/qsurf_impl.h src/surf/qsurf.c \
	src/surf/atomgrid.c src/surf/density.c src/surf/simd_avx2.c \
	src/surf/plan.c src/surf/mctable.c src/surf/mc.c src/surf/mesh.c \
	src/surf/opencl_impl.h src/surf/opencl.c src/surf/opencl_slab.c src/surf/beads.c \
	src/surf/volmap.c
src_libmscore_la_SOURCES += $(QSURF_SOURCES)
if HAVE_OPENCL
src_libmscore_la_LIBADD += $(OPENCL_LIBS)
endif

# The OpenCL kernels, kept as OpenCL C in kernels.cl, become a C string for opencl.c.
src/surf/kernels.inc: src/surf/kernels.cl
	$(AM_V_GEN)$(MKDIR_P) src/surf && \
	sed -e 's/\\/\\\\/g' -e 's/"/\\"/g' -e 's/^/"/' -e 's/$$/\\n"/' \
		$(srcdir)/src/surf/kernels.cl > $@-t && mv $@-t $@
BUILT_SOURCES += src/surf/kernels.inc
CLEANFILES += src/surf/kernels.inc
EXTRA_DIST += src/surf/kernels.cl
