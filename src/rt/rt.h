/* rt.h: TachyonInternal, molscope's photorealistic CPU ray tracer. The scene (scene/scene.h) is
 * traced with Embree's BVH and ray kernels and shaded the way Tachyon shades the scenes VMD
 * gives it (doc/vmd-behaviour.md section 8, render/tachyon.c for settings): directional lights,
 * ambient, diffuse and Blinn-Phong specular terms, outlines, mirror reflection, shadows,
 * ambient occlusion, angle-modulated transparency with shadows filtered by transparent
 * surfaces, planar depth cueing, background gradients, perspective and orthographic cameras,
 * depth of field and antialiasing. Spheres, cylinders, cones and cap discs are exact
 * primitives; triangle meshes are traced from the display list's own arrays.
 *
 * Rendering is progressive. Pass k adds one camera sample to every pixel of a float
 * accumulation buffer: pass 0 at the pixel centre (a pinhole ray, as Tachyon's first
 * sample), later passes jittered in the pixel and on the lens. `render aasamples N` asks for
 * N + 1 passes, as Tachyon's antialiasing count does; a pass limit and a time budget can end
 * the render earlier (doc/rt.md). Without Embree the module still builds and every render
 * reports that molscope was built without it. */
#ifndef MS_RT_H
#define MS_RT_H

#include <stdint.h>

#include "base/base.h"
#include "image/image.h"
#include "render/render.h"
#include "scene/scene.h"

/* Limits: a request beyond them is an error, not an attempt. */
#define MS_RT_MAX_AASAMPLES 65535
#define MS_RT_MAX_AOSAMPLES 1024
#define MS_RT_MAX_DEPTH 20        /* reflection and transmission levels of one camera ray */

typedef struct ms_rt_options {
    int aasamples;        /* samples after the first: aasamples + 1 passes */
    int aosamples;        /* occlusion rays per shaded point when the scene has AO on */
    int max_passes;       /* 0: no limit beyond aasamples + 1 */
    int max_depth;        /* reflection and transmission levels (0: MS_RT_MAX_DEPTH) */
    double time_budget;   /* seconds (0: none); checked after each pass, one pass always runs */
    int progress;         /* a line per pass on stderr */
    size_t memory;        /* bytes the render may use; 0: what the system has available */
    const char *raydump;  /* a file for every ray cast (raydump.c; NULL: none); only
                           * ms_rt_render and ms_rt_write write it */
    int leaves;           /* large meshes' leaves: MS_RT_LEAVES_AUTO (by memory and rays),
                           * _COMPACT (less memory) or _FAST (faster rays) */
    int order;            /* MS_RT_ORDER_PIXELS: each pixel's passes in turn, tile by tile
                           * (the default), or _PASSES: each pass over the frame (as with a
                           * time budget); the same picture */
} ms_rt_options;

enum { MS_RT_LEAVES_AUTO, MS_RT_LEAVES_COMPACT, MS_RT_LEAVES_FAST };
enum { MS_RT_ORDER_PIXELS, MS_RT_ORDER_PASSES };

enum { MS_RT_PRIMARY, MS_RT_SHADOW, MS_RT_AO, MS_RT_SECONDARY, MS_RT_NRAYKINDS };

typedef struct ms_rt_stats {
    int passes;           /* passes rendered */
    double build_s;       /* Embree scene build, wall clock */
    double trace_s;       /* all passes, wall clock */
    double build_cpu_s;   /* the same in CPU time of the process (all threads) */
    double trace_cpu_s;
    uint64_t rays[MS_RT_NRAYKINDS];   /* camera, shadow, occlusion, reflection/transmission */
} ms_rt_stats;

/* What the last render (ms_rt_render) held at its peak, in bytes: Embree's acceleration
 * structures and the buffers it made (its memory monitor's high-water mark), the arrays the
 * world made for Embree (padded copies, spheres kept apart), the frame's accumulation and
 * random-state buffers, and the 8-bit image. */
typedef struct ms_rt_memory {
    size_t embree, world, frame, image;
} ms_rt_memory;
void ms_rt_last_memory(ms_rt_memory *out);

/* 12 antialiasing and 12 occlusion samples (VMD's defaults), no limits, no progress. */
void ms_rt_options_default(ms_rt_options *o);
/* The pass limit, time budget and ray depth from MOLSCOPE_RT_PASSES, MOLSCOPE_RT_TIME and
 * MOLSCOPE_RT_DEPTH (unset or empty: none, none, MS_RT_MAX_DEPTH), the ray dump's file from
 * MOLSCOPE_RT_RAYDUMP (the environment's string, unset or empty: none), and progress lines
 * when stderr is a terminal. 0, or -1 with err set when a value is not a positive number. */
int ms_rt_options_from_env(ms_rt_options *o, ms_error *err);
/* The options of the built-in devices for a scene: the defaults, the scene's sample counts
 * (`render aasamples|aosamples`), then the environment's limits as above. */
int ms_rt_options_for_scene(const ms_scene *s, ms_rt_options *o, ms_error *err);
/* Whether this build can trace (Embree was found at configure time). */
int ms_rt_available(void);
/* The rays of all kinds in st. */
uint64_t ms_rt_stats_rays(const ms_rt_stats *st);

/* Render s into img (allocated here, s->width x s->height). st may be NULL. 0, or -1 with err
 * set and img empty: no Embree, bad options, a scene or image too large for memory. */
int ms_rt_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                 ms_error *err);
/* Render and write path: .png .tga .ppm .bmp by extension, any other name a TGA file (as
 * VMD's TachyonInternal does). The file appears complete or not at all. */
int ms_rt_write(const ms_scene *s, const ms_rt_options *o, const char *path, ms_rt_stats *st,
                ms_error *err);

/* A progressive render one pass at a time, for callers that interleave passes with other
 * work (the live view, live/live.h): begin builds the world for s, which must stay unchanged
 * (with its display lists) until the session ends; each ms_rt_session_pass adds one sample to
 * every pixel (the same samples, in the same order, as ms_rt_render) and returns the passes
 * done; ms_rt_session_image gives their average (img allocated here). begin returns NULL
 * with err set on the errors of ms_rt_render; image returns -1 before the first pass. */
typedef struct ms_rt_session ms_rt_session;
ms_rt_session *ms_rt_session_begin(const ms_scene *s, const ms_rt_options *o, ms_error *err);
int ms_rt_session_pass(ms_rt_session *ss);
int ms_rt_session_passes(const ms_rt_session *ss);
int ms_rt_session_image(const ms_rt_session *ss, ms_image *img, ms_error *err);
void ms_rt_session_end(ms_rt_session *ss);

/* The `TachyonInternal` render device (tachyon_internal.c). */
extern const ms_render_device ms_render_tachyon_internal;

#endif
