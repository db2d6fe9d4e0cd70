/* oclrt.h: TachyonLOpenCLInternal, the OpenCL ray tracer (doc/ocl.md). It renders what
 * TachyonInternal renders (rt/rt.h), with the same shading, samples and options, on any
 * OpenCL device: a GPU, or the CPU through PoCL. The host builds a binary BVH over the
 * scene's primitives (Embree's rtcBuildBVH, or its own SAH builder without Embree) and
 * uploads it with the primitives as structure-of-arrays buffers; each sample pass is one
 * kernel launch, with the sums and the pixels' random states kept on the device between
 * launches.
 *
 * The device is the first GPU (else any device), or the one MOLSCOPE_OPENCL_DEVICE names by
 * index or by part of its name; MOLSCOPE_NOOPENCL set to anything but 0 turns OpenCL off.
 * Its context and queue are the process's one OpenCL engine (cl/cl.h), shared with QuickSurf.
 * Built programs are cached (MOLSCOPE_OPENCL_CACHE, else $XDG_CACHE_HOME/molscope or
 * ~/.cache/molscope). When OpenCL cannot render (no device, a kernel that does not build,
 * device memory exhausted), ms_oclrt_write says why on stderr in one line and renders with
 * TachyonInternal instead. */
#ifndef MS_OCLRT_H
#define MS_OCLRT_H

#include "rt/rt.h"

/* After each pass: the passes so far and their average as an image (owned by the tracer,
 * valid during the call); return nonzero to stop the render after this pass. It runs while
 * the tracer holds the OpenCL engine: it must not start another OpenCL render. */
typedef int (*ms_oclrt_pass_fn)(void *user, int passes, const ms_image *img);

/* What ms_oclrt_render reports besides 0: a problem of the request (bad options or sizes,
 * bad input: TachyonInternal would refuse it too) or of OpenCL (fall back). */
enum { MS_OCLRT_EINPUT = -1, MS_OCLRT_EDEVICE = -2 };

/* Whether this build has the OpenCL tracer (OpenCL found at configure time). */
int ms_oclrt_available(void);
/* Render s into img (allocated here) on the OpenCL device; cb (may be NULL) sees every pass.
 * 0, MS_OCLRT_EINPUT or MS_OCLRT_EDEVICE with err set and img empty. No fallback. */
int ms_oclrt_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                    ms_oclrt_pass_fn cb, void *user, ms_error *err);
/* Render and write path as ms_rt_write does; on an OpenCL failure, a line on stderr
 * ("TachyonLOpenCLInternal: <reason>; rendering with TachyonInternal") and TachyonInternal
 * renders instead. *fell_back (may be NULL) says whether it did. */
int ms_oclrt_write(const ms_scene *s, const ms_rt_options *o, const char *path, ms_rt_stats *st,
                   int *fell_back, ms_error *err);
/* The render devices: TachyonLOpenCLInternal, and TachyonLOptiXInternal (VMD's name for its GPU
 * tracer, which scripts use) drawing the same way. */
extern const ms_render_device ms_render_tachyon_ocl, ms_render_tachyon_optix;
/* The name of the device the tracer uses ("" before the first render or without one). */
const char *ms_oclrt_device_name(void);

/* Fault injection for the tests: the next renders fail as if the device ran out of memory
 * (MS_OCLRT_FAIL_ALLOC) or the kernels did not build (MS_OCLRT_FAIL_BUILD). */
enum { MS_OCLRT_FAIL_NONE, MS_OCLRT_FAIL_ALLOC, MS_OCLRT_FAIL_BUILD };
extern int ms_oclrt_fail;
/* For the tests: build the BVH with molscope's own SAH builder even when Embree's is there. */
extern int ms_oclrt_own_bvh;

#endif
