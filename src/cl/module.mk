# src/cl: what QuickSurf's OpenCL engine and the OpenCL tracer share (error names, device
# choice, cache folders, program build with its binary cache). Only built with OpenCL.
if HAVE_OPENCL
src_libmscore_la_SOURCES += src/cl/cl.h src/cl/cl.c
endif
