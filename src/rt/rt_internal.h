/* rt_internal.h: what the files of the ray tracer share, and only they include: the traced
 * world (two Embree scenes, the opaque and the transparent geometries of every placed
 * display list: spheres, cylinders, cones and discs moved to world space, meshes under an
 * instance of their transform; per list, one Embree geometry per primitive kind), the
 * primitive method tables (one file per primitive, as Tachyon has them), the camera, the
 * shading settings and the per-thread state of the integrator. */
#ifndef MS_RT_INTERNAL_H
#define MS_RT_INTERNAL_H

#include <embree3/rtcore.h>
#include <stddef.h>
#include <stdint.h>

#include "rt/rt.h"
#include "rt/rt_common.h"
#include "scene/displaylist.h"
#include "scene/scene.h"

/* ---------------------------------------------------------------- device (device.c) */

/* The process's Embree device, made on first use with ms_threads_count() threads. NULL with
 * err set when Embree cannot start. */
RTCDevice rt_device(ms_error *err);
/* Bytes Embree may hold from now on (allocations past it fail, and the build reports that
 * the scene does not fit in memory); 0 lifts the limit. */
void rt_device_set_budget(size_t bytes);
/* Bytes Embree may still take under the budget; 0 when there is no budget. */
size_t rt_device_room(void);
/* Bytes Embree holds now, and the most it held since rt_device_peak_reset. */
size_t rt_device_held(void);
size_t rt_device_peak(void);
void rt_device_peak_reset(void);
/* After an Embree call: 0 when no error is pending, else -1 with err saying what failed. */
int rt_device_check(RTCDevice dev, const char *what, ms_error *err);
/* Flush-to-zero and denormals-are-zero on for the calling thread; returns the old state for
 * rt_fpu_restore. */
unsigned rt_fpu_fast(void);
void rt_fpu_restore(unsigned state);

/* ---------------------------------------------------------------- world (world.c) */

typedef enum rt_kind { RT_SPHERE, RT_CYLINDER, RT_CONE, RT_RING, RT_MESH, RT_NKINDS } rt_kind;

/* The primitives of one kind of one placed list: in world coordinates (place.c), but a
 * mesh's in the list's (its instance places it). The arrays are the display list's where
 * its layout serves, else arrays the world made. */
typedef struct rt_geom {
    rt_kind kind;
    size_t n;
    rt_material mat;
    int transparent;            /* its material or a colour lets light through: it is in the
                                 * transparent instance */
    int alpha;                  /* some primitive's colour has alpha < 255 */
    int user;                   /* spheres as a user geometry (sharing the tree of cylinders) */
    const float *a, *b;         /* centres; base and apex; ring centre and normal */
    const float *ra, *rb;       /* radius (base radius); cone apex radius; ring inner radius */
    const ms_rgba8 *color;      /* per primitive, or per vertex for meshes */
    const float *xyz;           /* mesh vertices, normals (quantized), triangles */
    const int8_t *normal;
    const uint32_t *tri;
    size_t nverts, vcap;        /* mesh vertices, and room in xyz (Embree reads past the end) */
    const float *aux;           /* per-primitive data a primitive file made (cylinder axes) */
    const ms_rgba8 *color2;     /* cylinders: the colour beyond the joint (a bond's second) */
    const float *joint;         /* cylinders: the joint, 3 floats each */
    const float *join;          /* cylinders: the joint's distance along the axis (cylinder.c) */
    /* Cylinders: the list's spheres centred on their ends are tested with them, as one
     * primitive (cylinder.c): 8 floats a cylinder (centre and radius of the sphere at the
     * base, then at the far end; radius 0: none) and 2 colours; NULL when none. */
    const float *ends;
    const ms_rgba8 *endcol;
    const ms_dl_spheres *spheres;  /* the spheres the cylinders may take (world.c sets it) */
    uint8_t *taken;             /* per sphere: 1 when a cylinder took it (cylinder.c sets it) */
    const ms_scene_item *item;  /* the scene item (its clip planes, in world coordinates) */
    const float *xf, *nm;       /* meshes: their instance's list-to-world transform and its
                                 * normal matrix; NULL for the others (world space) */
    uint8_t morton;             /* meshes: its tree built by Morton codes (low quality) */
    uint8_t compact;            /* meshes: its instance's scene has compact leaves */
} rt_geom;

/* A source's list with its spheres, cylinders, cones and discs in world space (place.c):
 * the list's arrays, or copies moved by its transform; its mesh is the list's. */
typedef struct rt_placed {
    ms_displaylist dl;          /* a shallow copy: positions and radii replaced when moved */
    rt_discs discs;
    rt_xform x;
    int skip;                   /* a singular transform: nothing to see */
    size_t group;               /* the sources sharing its transform (its meshes' instance) */
} rt_placed;

/* The placed list of src into p; 0, 1 when its transform is singular (nothing to trace), or
 * -1 with err set when memory runs out. */
int rt_place(struct rt_world *w, const rt_source *src, rt_placed *p, ms_error *err);
/* An upper bound of the bytes the placed copies of a scene's lists take. */
size_t rt_place_bytes(const ms_scene *s);

/* The scenes of the world: the opaque geometries, and the transparent ones (walked by a
 * shadow or occlusion ray only when the opaque ones let it through). Each holds the
 * world-space geometries and, per transform with meshes, an instance of a scene of them. */
enum { RT_OPAQUE, RT_TRANS };

typedef struct rt_world {
    RTCDevice dev;
    RTCScene scene[2];          /* RT_OPAQUE, RT_TRANS; scene[RT_TRANS] NULL when empty */
    rt_geom **part[2];          /* by Embree geometry id in each scene: the geometry, or for an
                                 * instance the first of its scene's (by their ids there) */
    size_t npart[2];
    rt_geom *geoms;             /* every geometry (made in one block: Embree keeps pointers) */
    size_t ngeoms;
    rt_placed *placed;          /* per source */
    int has_trans;              /* some geometry is transparent */
    int compact;                /* large meshes get compact leaves (world.c, new_scene) */
    double samples;             /* camera rays to trace (0: unknown) */
    float eps;                  /* secondary ray offset, from the scene's size */
    void **owned;               /* arrays made for the build */
    size_t nowned, capowned;
    size_t owned_bytes;         /* their sizes together */
    rt_sources set;             /* the scene's lists, their strokes and cap discs */
} rt_world;

/* Build the world of a scene (Embree scenes committed) for about samples camera rays (pixels
 * times passes) and rays rays in all (0, 0: unknown, as for a session, which may trace many
 * passes), its large meshes' leaves as leaves says (MS_RT_LEAVES_*). 0, or -1 with err set
 * and w freed. */
int rt_world_build(rt_world *w, const ms_scene *s, double samples, double rays, int leaves,
                   ms_error *err);
/* The rays a camera sample casts where it hits: itself, a shadow ray per light and the
 * occlusion rays, as the shader will, twice over when a material is transparent (an
 * estimate: reflection, and transmission past one surface, not counted). */
double rt_rays_per_sample(const ms_scene *s, int aosamples);
/* A lower bound of the bytes Embree will hold for s (its triangles, and its other
 * primitives), to refuse a scene that cannot fit before building it. */
size_t rt_world_estimate(const ms_scene *s, size_t *ntris, size_t *nother);
void rt_world_free(rt_world *w);
/* Memory the world owns: the helper of the primitive files. NULL with err set. */
void *rt_world_alloc(rt_world *w, size_t n, size_t elsize, ms_error *err);

/* ---------------------------------------------------------------- primitives */

/* What each primitive file provides (sphere.c, cylinder.c, cone.c, ring.c, mesh.c). */
typedef struct rt_prim {
    const char *name;
    /* The Embree geometry of g (not committed; it may add data to g); NULL with err set. */
    RTCGeometry (*geometry)(rt_world *w, rt_geom *g, ms_error *err);
    /* At a hit (p: the hit point): the shading normal n and the geometric normal ng (both in
     * world coordinates, any length) and the colour. */
    void (*surface)(const rt_geom *g, const struct RTCHit *h, const float p[3], float n[3],
                    float ng[3], ms_rgba8 *c);
} rt_prim;

extern const rt_prim rt_sphere_prim, rt_cylinder_prim, rt_cone_prim, rt_ring_prim, rt_mesh_prim;
extern const rt_prim *const rt_prims[RT_NKINDS];

/* ---------------------------------------------------------------- occlusion and transparency */

/* The context of every ray query: Embree's, and for occlusion queries the light each ray
 * (by its id) still carries through the transparent surfaces it crossed. A shadow or
 * occlusion ray walks the opaque scene (a hit ends it), then the transparent one, where
 * each crossing filters it (Tachyon counts each: a sphere's two, a triangle's one) and lets
 * it pass, unless the primitive is opaque after all. */
typedef struct rt_ctx {
    struct RTCIntersectContext ec;   /* first: Embree hands &ec back to the callbacks */
    float *filter;
} rt_ctx;

/* Opacity of primitive prim at a hit (u, v: a mesh's barycentric coordinates). */
float rt_geom_opacity(const rt_geom *g, unsigned prim, float u, float v);
/* Does one of g's clip planes cut away the point at t along the ray o + t d (in g's
 * coordinates: world space, or a mesh's list)? */
int rt_geom_clipped(const rt_geom *g, const float o[3], const float d[3], float t);
/* The occlusion filter of built-in geometries (spheres, meshes) that are transparent or
 * clipped: a crossing a clip plane cut away is passed, as is a transparent one (filtering
 * the light); anything else blocks. */
void rt_occlusion_filter(const struct RTCFilterFunctionNArguments *args);

/* ---------------------------------------------------------------- user geometries (user.c) */

/* Cylinders, cones and discs are Embree user geometries: a bounds function and an exact
 * hit test per primitive. Ray i of an N-ray call, read out: */
typedef struct rt_uray {
    float o[3], d[3], tnear, tfar;
    unsigned id;
} rt_uray;
/* The test: the hits of primitive prim in (tnear, tfar), nearest first, in t; returns how
 * many (0, 1 or 2). */
typedef int (*rt_user_test)(const rt_geom *g, unsigned prim, const rt_uray *r, float t[2]);

/* A user geometry of g with its bounds function and hit callbacks; NULL with err set. */
RTCGeometry rt_user_geometry(rt_world *w, const rt_geom *g, RTCBoundsFunction bounds,
                             RTCIntersectFunctionN isect, RTCOccludedFunctionN occluded,
                             ms_error *err);
/* Ray i of an N-ray call; Embree's RTCRayN layout: twelve fields of N lanes each (origin,
 * tnear, direction, time, tfar, mask, id, flags), then the hit. */
static inline void rt_user_ray(const float *ray, unsigned N, unsigned i, rt_uray *r)
{
    r->o[0] = ray[i], r->o[1] = ray[N + i], r->o[2] = ray[2 * N + i];
    r->tnear = ray[3 * N + i];
    r->d[0] = ray[4 * N + i], r->d[1] = ray[5 * N + i], r->d[2] = ray[6 * N + i];
    r->tfar = ray[8 * N + i];
    r->id = ((const unsigned *)ray)[10 * N + i];
}
void rt_user_hit(const struct RTCIntersectFunctionNArguments *args, unsigned i, float t);
/* The same, with which part of a composite primitive was hit in the hit's u. */
void rt_user_hit_part(const struct RTCIntersectFunctionNArguments *args, unsigned i, float t,
                      float part);
/* An occlusion call's crossings (nhits of them, at t[]): those a clip plane cut away are
 * passed; of the others an opaque one blocks the ray, transparent ones filter it,
 * (1 - opacity) a crossing. */
void rt_user_block(const struct RTCOccludedFunctionNArguments *args, unsigned i, int nhits,
                   const float *t, const rt_uray *r);
/* Roots t0 <= t1 of a t^2 + 2 b t + c = 0 (a != 0), computed stably; 0 when none. */
int rt_quadratic(float a, float b, float c, float *t0, float *t1);
/* A sphere's crossings in (tnear, tfar), nearest first (sphere.c). */
int rt_sphere_hits(const float c[3], float rad, const rt_uray *r, float t[2]);
/* Empty bounds (Embree leaves such a primitive out). */
void rt_bounds_empty(struct RTCBounds *b);

/* The callbacks' bodies, inlined into each primitive's callbacks with its test. */
static inline void rt_user_intersect(const struct RTCIntersectFunctionNArguments *args,
                                     rt_user_test test)
{
    const rt_geom *g = args->geometryUserPtr;
    for (unsigned i = 0; i < args->N; i++) {
        rt_uray r;
        float t[2];
        if (!args->valid[i]) continue;
        rt_user_ray((const float *)args->rayhit, args->N, i, &r);
        if (test(g, args->primID, &r, t)) rt_user_hit(args, i, t[0]);
    }
}

static inline void rt_user_occluded(const struct RTCOccludedFunctionNArguments *args,
                                    rt_user_test test)
{
    const rt_geom *g = args->geometryUserPtr;
    for (unsigned i = 0; i < args->N; i++) {
        rt_uray r;
        float t[2];
        if (!args->valid[i]) continue;
        rt_user_ray((const float *)args->ray, args->N, i, &r);
        int n = test(g, args->primID, &r, t);
        if (n) rt_user_block(args, i, n, t, &r);
    }
}

/* ---------------------------------------------------------------- ray dump (raydump.c) */

/* One ray of the dump: origin, tnear, direction, kind | mask << 8 (32 bytes). */
typedef struct rt_rayrec {
    float org[3], tnear, dir[3];
    uint32_t info;
} rt_rayrec;
/* A rendering thread's rays of the current pass. */
typedef struct rt_raybuf {
    rt_rayrec *r;
    size_t n, cap;
    int oom;
} rt_raybuf;
typedef struct rt_raydump rt_raydump;

/* Open the dump file at path and write the header and the world's spheres; NULL with err
 * set when it cannot be written. */
rt_raydump *rt_raydump_open(const char *path, const rt_world *w, ms_error *err);
/* The buffer of thread t (NULL when d is NULL: no dump). */
rt_raybuf *rt_raydump_buf(rt_raydump *d, int thread);
void rt_raybuf_add(rt_raybuf *b, int kind, unsigned mask, const float org[3], const float dir[3],
                   float tnear);
/* Write the threads' buffers (after a pass, in the calling thread) and empty them. */
void rt_raydump_flush(rt_raydump *d);
/* Finish the file (ok: keep it; else remove it) and free d; -1 with err set when ok and a
 * write failed. NULL is allowed. */
int rt_raydump_close(rt_raydump *d, int ok, ms_error *err);

/* ---------------------------------------------------------------- tracing (shade.c) */

/* Per rendering thread. */
typedef struct rt_thread {
    rt_ctx ctx;
    uint32_t rng;               /* the pixel's random state while it is traced */
    uint64_t rays[MS_RT_NRAYKINDS];
    rt_raybuf *dump;            /* the ray dump's buffer; NULL when off */
} rt_thread;

/* The colour seen along a ray (dir unit length), with depth levels of reflection and
 * transmission left; primary: a camera ray (its fog coordinate is the planar depth). */
void rt_trace(const rt_shader *sh, rt_thread *th, const float org[3], const float dir[3],
              int depth, int primary, float out[3]);

/* ---------------------------------------------------------------- frames (frame.c) */

/* The frame's buffers against the memory allowed (o->memory, else what is available): an
 * error when they do not fit, else what is left becomes Embree's budget (lifted by
 * rt_device_set_budget(0) after the render). */
int rt_plan_memory(const ms_scene *s, const ms_rt_options *o, ms_error *err);

/* ---------------------------------------------------------------- sampling (sample.c) */

/* PCG's 32-bit output permutation on an LCG state: a uniform word per call. */
static inline uint32_t rt_rand(uint32_t *s)
{
    uint32_t x = *s = *s * 747796405u + 2891336453u;
    x = ((x >> ((x >> 28) + 4u)) ^ x) * 277803737u;
    return (x >> 22) ^ x;
}
/* Uniform in [0, 1). */
static inline float rt_randf(uint32_t *s)
{
    return (float)(rt_rand(s) >> 8) * (1.0f / 16777216.0f);
}
/* A well-mixed word from two (pixel and pass seeds). */
static inline uint32_t rt_hash2(uint32_t a, uint32_t b)
{
    uint32_t h = a * 0x9e3779b9u ^ (b + 0x7f4a7c15u + (a << 6) + (a >> 2));
    h ^= h >> 16;
    h *= 0x85ebca6bu;
    h ^= h >> 13;
    h *= 0xc2b2ae35u;
    return h ^ (h >> 16);
}

/* The position of pass k's sample in pixel idx, in [0, 1)^2 (pass 0: the centre). */
void rt_sample_pixel(uint32_t idx, int k, float *x, float *y);
/* A uniform point of the unit disc. */
void rt_sample_disc(uint32_t *rng, float p[2]);
/* A stratified set of count directions of the hemisphere around unit normal n. */
typedef struct rt_hemisphere {
    float n[3], t[3], b[3], r1;
    float cs, sn;               /* the azimuth of the next direction */
    int count, i;
} rt_hemisphere;
void rt_hemisphere_init(rt_hemisphere *h, const float n[3], int count, uint32_t *rng);
/* The next direction (count of them, in order) in d; returns its cosine with the normal. */
float rt_hemisphere_next(rt_hemisphere *h, float d[3]);

#endif
