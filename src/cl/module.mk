# src/cl: what QuickSurf and the OpenCL tracer share (error names, the one engine: device,
# context and queue; cache folders, program build with its binary cache). Only built with OpenCL.
if HAVE_OPENCL
src_libmscore_la_SOURCES += src/cl/cl.h src/cl/cl.c src/cl/engine.c
endif
