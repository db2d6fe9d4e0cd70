/* rt_floor.c: the floor of a TachyonInternal render. Reads a ray dump (MOLSCOPE_RT_RAYDUMP,
 * src/rt/raydump.c: the scene's spheres in world coordinates, its meshes, and every ray the
 * render cast, by kind) and traces the same rays with Embree alone: camera and transmission
 * rays with rtcIntersect1, shadow and occlusion rays with rtcOccluded1, no sampling, no
 * shading, no image. As the render does, the opaque geometries are one scene and the
 * transparent meshes another: a camera or transmission ray walks the opaque scene and then
 * the transparent one up to the opaque hit; a shadow or occlusion ray that the opaque scene
 * lets through walks the transparent one to its end, an occlusion filter taking off each
 * crossing's share of the light (the mesh's opacity). Meshes are built as the render built
 * them (compact leaves, a Morton-code tree: the dump's flags). Prints, per ray kind, the
 * rays, wall and CPU seconds (the least of the repeats, each) and Mrays/s (from the wall
 * time), and the total: the time the render could not go below with these rays on these
 * trees. Variants (-v), for the experiments of doc/BENCHMARKS.md:
 *   builtin   Embree's sphere geometry (RTC_GEOMETRY_TYPE_SPHERE_POINT) and the meshes moved
 *             to world coordinates, flat scenes
 *   placed    as TachyonInternal places them: spheres as builtin, meshes under an instance
 *             of their transform (one for the meshes that share it)
 *   coherent  placed, the camera rays in packets of 8 (half a tile's row) and the shadow
 *             rays in packets of 8 of one direction (a light's, from neighbouring points),
 *             by rtcIntersect8 and rtcOccluded8 with Embree's coherent flag: what tracing a
 *             tile's rays of these kinds together would be worth
 *   reuse     placed, each transmission ray walking the transparent scene alone, up to the
 *             opaque hit its parent found (found before the timing): what carrying the
 *             parent's opaque hit down a straight transmission would be worth
 *   instance  builtin's spheres under one instance (as TachyonInternal placed every
 *             transform before it moved spheres to world space)
 *   user      a user geometry over Embree's tree, with a compact sphere test
 *   packet    builtin, the occlusion rays sharing an origin (a hit's AO rays) traced
 *             together by rtcOccluded4/8/16
 *   cache     builtin, each thread testing the sphere that blocked its last occlusion ray
 *             (recorded by an occlusion filter) before walking the tree
 *   camera8   builtin, the camera rays in packets of 8 (half a tile's row: neighbouring
 *             pixels) by rtcIntersect8 with Embree's coherent flag
 *   nbr       builtin, each shadow and occlusion ray first tested against the RTFLOOR_K
 *             (default 8) spheres nearest the sphere it leaves (by the gap between their
 *             surfaces; found with a grid before the timing, as is the sphere each ray
 *             leaves, which a render knows from its hit)
 *   own       a tree of our own over the spheres instead of Embree's (rt_floor_own.inc):
 *             Embree's builder, our node layout and traversal, 16 children a node with
 *             AVX-512 or 8 with AVX2 (RTFLOOR_WIDTH=8|16 asks for one)
 *
 *   rt_floor [-t threads] [-v variant] [-r repeats] [-shuffle | -mixed | -sort W] [-c embree-config] [-ab] dump
 *
 * -shuffle traces each kind's rays in a random order instead of the render's (tile by tile,
 * a hit's occlusion rays together): what the coherence of the render's order is worth.
 *
 * -mixed traces all the rays in the render's order, the kinds interleaved as the render casts
 * them, instead of each kind's in turn: what grouping the rays by kind would be worth (the
 * builtin and placed variants only).
 * -sort W sorts the shadow, occlusion and transmission rays within each window of W rays of
 * their kind (W divides 4096) by direction (its octant, then the cube-map face and a 4 x 4
 * cell of it) and then by origin (a Morton code in the window's box); RTFLOOR_SORT picks
 * another key (octant, face, cell, origin): what an integrator that gathers a tile's
 * secondary rays and orders them before tracing would gain (the pictures would not move:
 * each ray's answer is its own). With -ab the sorted rays are the variant's side and builtin
 * traces them in the render's order.
 * The rays are read into arrays on huge pages (ray_array): the two sides of -ab read
 * different arrays when sorted, and arrays on 4 KB pages made one side up to 16% faster than
 * the other with the same rays in the same order.
 * -c adds to Embree's device configuration (e.g. max_isa=avx2).
 * -ab compares the variant with builtin in one process on one thread: each chunk of rays is
 * traced by both in turn (which goes first alternating), each timed by the thread's CPU
 * clock, so the host's drifting speed (other machines' load) moves both alike; it prints
 * each kind's two times and their ratio, per repeat. (The two share the caches, which
 * favours the smaller tree a little: own against builtin read 0.96 here, 0.95-1.00 apart.)
 *
 * Only spheres and meshes are in the dump's geometry: a dump whose scene had other primitives
 * (cylinders, cones, discs) is traced without them, and the program says so. The variants
 * after reuse (instance to own) are for scenes of spheres alone, and say so. */
#include "rt_floor_own.h"

#include <embree3/rtcore.h>
#include <math.h>
#include <pthread.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/mman.h>
#include <sys/resource.h>
#include <time.h>

enum { PRIMARY, SHADOW, AO, SECONDARY, NKINDS, MIXED = NKINDS };
static const char *const kind_names[NKINDS + 1] = {"camera", "shadow", "occlusion", "transmission", "mixed"};

typedef struct rayrec {
    float org[3], tnear, dir[3];
    uint32_t info;
} rayrec;

/* A mesh of the dump: how the render built it, its transform and its own coordinates. */
enum { MESH_TRANSPARENT = 1, MESH_MORTON = 2, MESH_COMPACT = 4 };
typedef struct mesh {
    uint32_t flags;
    float opacity;
    uint64_t nverts, ntris;
    float xf[12];               /* list to world, 3 x 4 row-major */
    float *xyz;                 /* nverts x 3 and a spare vertex (Embree reads 16 bytes) */
    uint32_t *tri;
} mesh;

typedef struct dump {
    uint64_t nspheres, nother, nmeshes;
    float *spheres;             /* x y z r */
    mesh *meshes;
    rayrec *rays[NKINDS + 1];   /* by kind; [MIXED]: all, in the file's order (-mixed) */
    rayrec *sorted[NKINDS];     /* -sort with -ab: the variant's copy, sorted by windows */
    size_t nrays[NKINDS + 1];
} dump;

typedef enum variant { V_BUILTIN, V_PLACED, V_COHERENT, V_REUSE, V_INSTANCE, V_USER, V_PACKET, V_CACHE, V_CAMERA8, V_NBR, V_OWN, NVARIANTS } variant;
static const char *const variant_names[] = {"builtin", "placed", "coherent", "reuse", "instance", "user", "packet", "cache", "camera8", "nbr", "own"};

/* The nbr variant: each sphere's K nearest neighbours (by the gap between the surfaces),
 * and each shadow and occlusion ray's sphere (the one its origin lies on). */
static int nbr_k = 8;
static uint64_t nbr_caught;     /* rays a neighbour blocked (summed after each kind) */
static uint32_t *nbr;
static uint32_t *ray_sphere[4];

/* The context of a query: Embree's, then the sphere that blocked the thread's last
 * occlusion ray (the cache variant). */
typedef struct query {
    struct RTCIntersectContext ec;
    float light;                /* a shadow or occlusion ray's light through transparent meshes */
    unsigned last;
    uint64_t caught;            /* nbr: rays a neighbour blocked */
} query;

/* ---------------------------------------------------------------- reading the dump */

static void die(const char *fmt, const char *arg)
{
    fprintf(stderr, "rt_floor: ");
    fprintf(stderr, fmt, arg);
    fputc('\n', stderr);
    exit(1);
}

/* An array of rays on huge pages where the kernel gives them (madvise), so that reading the
 * rays costs no TLB misses and runs do not depend on where their 4 KB pages fell: moved
 * into such an array, the same rays in the same order traced up to 16% faster, within one
 * process, than from the array the file was read into (doc/BENCHMARKS.md). */
static rayrec *ray_array(size_t n)
{
    size_t huge = (size_t)2 << 20, bytes = (n * sizeof(rayrec) + huge - 1) / huge * huge;
    rayrec *r = aligned_alloc(huge, bytes ? bytes : huge);
    if (!r) die("%s", "out of memory");
    if (getenv("RTFLOOR_NOHUGE") == NULL) madvise(r, bytes, MADV_HUGEPAGE);
    return r;
}

static rayrec *ray_copy(const rayrec *src, size_t n)
{
    rayrec *r = ray_array(n);
    memcpy(r, src, n * sizeof *r);
    return r;
}

static void read_rays(FILE *f, dump *d, const char *path, int mixed)
{
    rayrec r;
    size_t cap[NKINDS + 1] = {0};
    while (fread(&r, sizeof r, 1, f) == 1) {
        unsigned k = r.info & 0xffu;
        if (k >= NKINDS) die("%s: a ray of an unknown kind", path);
        if (mixed) k = MIXED;
        if (d->nrays[k] == cap[k]) {
            cap[k] = cap[k] ? 2 * cap[k] : 1 << 16;
            d->rays[k] = realloc(d->rays[k], cap[k] * sizeof r);
            if (!d->rays[k]) die("%s: out of memory", path);
        }
        d->rays[k][d->nrays[k]++] = r;
    }
    if (ferror(f) || !feof(f)) die("%s: read error", path);
    for (int k = 0; k <= NKINDS; k++)
        if (d->nrays[k]) {
            rayrec *r = ray_copy(d->rays[k], d->nrays[k]);
            free(d->rays[k]);
            d->rays[k] = r;
        }
}

static void read_exact(FILE *f, void *p, size_t size, size_t n, const char *path)
{
    if (fread(p, size, n, f) != n) die("%s: truncated", path);
}

static void read_meshes(FILE *f, dump *d, const char *path)
{
    read_exact(f, &d->nmeshes, 8, 1, path);
    if (d->nmeshes > 1u << 24) die("%s: too many meshes", path);
    d->meshes = calloc(d->nmeshes + 1, sizeof *d->meshes);
    if (!d->meshes) die("%s: out of memory", path);
    for (uint64_t i = 0; i < d->nmeshes; i++) {
        mesh *m = &d->meshes[i];
        unsigned char h[72];
        read_exact(f, h, sizeof h, 1, path);
        memcpy(&m->flags, h, 4);
        memcpy(&m->opacity, h + 4, 4);
        memcpy(&m->nverts, h + 8, 8);
        memcpy(&m->ntris, h + 16, 8);
        memcpy(m->xf, h + 24, sizeof m->xf);
        if (m->nverts > 0xffffffffu || m->ntris > 0xffffffffu) die("%s: a mesh too large", path);
        m->xyz = malloc(3 * (m->nverts + 1) * sizeof(float));
        m->tri = malloc(3 * m->ntris * sizeof(uint32_t) + 1);
        if (!m->xyz || !m->tri) die("%s: out of memory", path);
        read_exact(f, m->xyz, 3 * sizeof(float), m->nverts, path);
        read_exact(f, m->tri, 3 * sizeof(uint32_t), m->ntris, path);
        for (uint64_t t = 0; t < 3 * m->ntris; t++)
            if (m->tri[t] >= m->nverts) die("%s: a triangle's vertex out of range", path);
    }
}

static void read_dump(const char *path, dump *d, int mixed)
{
    FILE *f = fopen(path, "rb");
    unsigned char h[32];
    uint32_t v[2];
    memset(d, 0, sizeof *d);
    if (!f) die("%s: cannot open", path);
    if (fread(h, 1, sizeof h, f) != sizeof h || memcmp(h, "MSRAYS01", 8)) die("%s: not a ray dump", path);
    memcpy(v, h + 8, sizeof v);
    memcpy(&d->nspheres, h + 16, 8);
    memcpy(&d->nother, h + 24, 8);
    if ((v[0] != 1 && v[0] != 2) || v[1] != NKINDS) die("%s: a ray dump of another version", path);
    if (d->nspheres > ((uint64_t)1 << 32)) die("%s: too many spheres", path);
    d->spheres = malloc(d->nspheres * 16 + 16);
    if (!d->spheres) die("%s: out of memory", path);
    read_exact(f, d->spheres, 16, d->nspheres, path);
    if (v[0] >= 2) read_meshes(f, d, path);
    read_rays(f, d, path, mixed);
    fclose(f);
}

/* Each kind's rays in a random order (a fixed seed). */
static void shuffle(dump *d)
{
    uint64_t x = 88172645463325252ull;
    for (int k = 0; k < NKINDS; k++)
        for (size_t i = d->nrays[k]; i > 1; i--) {
            x ^= x << 13, x ^= x >> 7, x ^= x << 17;
            size_t j = (size_t)(x % i);
            rayrec t = d->rays[k][i - 1];
            d->rays[k][i - 1] = d->rays[k][j], d->rays[k][j] = t;
        }
}

/* -sort: the key of a ray: its direction's cell (octant, cube-map face, 4 x 4 cells of the
 * face: 10 bits) above its origin's Morton code in the window's box (3 x 10 bits). */
static uint64_t spread3(uint32_t x)
{
    uint64_t v = x & 0x3ffu;
    v = (v | v << 16) & 0x030000ffull;
    v = (v | v << 8) & 0x0300f00full;
    v = (v | v << 4) & 0x030c30c3ull;
    v = (v | v << 2) & 0x09249249ull;
    return v;
}

static uint64_t dir_cell(const float *d)
{
    float a[3] = {fabsf(d[0]), fabsf(d[1]), fabsf(d[2])};
    int face = a[0] >= a[1] && a[0] >= a[2] ? 0 : a[1] >= a[2] ? 1 : 2;
    int u = (face + 1) % 3, w = (face + 2) % 3;
    float m = a[face] > 0.0f ? a[face] : 1.0f;
    unsigned cu = (unsigned)fminf(a[u] / m * 4.0f, 3.0f), cw = (unsigned)fminf(a[w] / m * 4.0f, 3.0f);
    unsigned oct = (d[0] < 0.0f) | (d[1] < 0.0f) << 1 | (d[2] < 0.0f) << 2;
    return (uint64_t)(oct << 7 | (unsigned)face << 4 | cu << 2 | cw);
}

typedef struct keyed {
    uint64_t key;
    uint32_t i;
} keyed;

static int by_key(const void *a, const void *b)
{
    const keyed *x = a, *y = b;
    return x->key < y->key ? -1 : x->key > y->key ? 1 : (x->i > y->i) - (x->i < y->i);
}

/* -sort's key (RTFLOOR_SORT): the direction's cell and then the origin (the default), the
 * cell alone, the octant alone, the face (octant and dominant axis) alone, or the origin
 * alone. Rays of equal key keep the render's order. */
enum { KEY_CELL_ORIGIN, KEY_CELL, KEY_OCTANT, KEY_FACE, KEY_ORIGIN, NKEYS };
static const char *const key_names[NKEYS] = {"cellorigin", "cell", "octant", "face", "origin"};
static int sort_key;

static uint64_t ray_key(const rayrec *r, uint64_t mort)
{
    uint64_t cell = dir_cell(r->dir);
    switch (sort_key) {
    case KEY_CELL: return cell;
    case KEY_OCTANT: return cell >> 7;
    case KEY_FACE: return cell >> 4;
    case KEY_ORIGIN: return mort;
    default: return cell << 30 | mort;
    }
}

/* Rays r[0..n) sorted by key within windows of w, into out. */
static void sort_windows(const rayrec *r, size_t n, size_t w, rayrec *out)
{
    keyed *k = malloc(w * sizeof *k);
    if (!k) die("%s", "out of memory");
    for (size_t b = 0; b < n; b += w) {
        size_t m = n - b < w ? n - b : w;
        float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
        for (size_t i = 0; i < m; i++)
            for (int a = 0; a < 3; a++) lo[a] = fminf(lo[a], r[b + i].org[a]), hi[a] = fmaxf(hi[a], r[b + i].org[a]);
        for (size_t i = 0; i < m; i++) {
            uint64_t mort = 0;
            for (int a = 0; a < 3; a++) {
                float ext = hi[a] - lo[a], f = ext > 0.0f ? (r[b + i].org[a] - lo[a]) / ext : 0.0f;
                mort |= spread3((uint32_t)(f * 1023.0f)) << a;
            }
            k[i].key = ray_key(&r[b + i], mort);
            k[i].i = (uint32_t)i;
        }
        qsort(k, m, sizeof *k, by_key);
        for (size_t i = 0; i < m; i++) out[b + i] = r[b + k[i].i];
    }
    free(k);
}

/* -sort w: the secondary kinds' rays sorted by windows (in place, or into d->sorted for -ab). */
static void sort_rays(dump *d, size_t w, int ab)
{
    for (int k = SHADOW; k < NKINDS; k++) {
        if (!d->nrays[k]) continue;
        rayrec *out = ray_array(d->nrays[k]);
        sort_windows(d->rays[k], d->nrays[k], w, out);
        if (ab) d->sorted[k] = out;
        else free(d->rays[k]), d->rays[k] = out;
    }
}

/* ---------------------------------------------------------------- the user sphere */

static void sphere_bounds(const struct RTCBoundsFunctionArguments *a)
{
    const float *s = (const float *)a->geometryUserPtr + 4 * a->primID;
    struct RTCBounds *b = a->bounds_o;
    b->lower_x = s[0] - s[3], b->lower_y = s[1] - s[3], b->lower_z = s[2] - s[3];
    b->upper_x = s[0] + s[3], b->upper_y = s[1] + s[3], b->upper_z = s[2] + s[3];
}

/* The nearest crossing of sphere s in (tnear, tfar) for ray i of an N-ray block; -1: none. */
static float sphere_t(const float *s, const float *ray, unsigned N, unsigned i)
{
    float o[3] = {ray[i], ray[N + i], ray[2 * N + i]}, d[3] = {ray[4 * N + i], ray[5 * N + i], ray[6 * N + i]};
    float tn = ray[3 * N + i], tf = ray[8 * N + i];
    float oc[3] = {s[0] - o[0], s[1] - o[1], s[2] - o[2]};
    float dd = d[0] * d[0] + d[1] * d[1] + d[2] * d[2], inv = 1.0f / dd;
    float tc = (oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2]) * inv;
    float q[3] = {oc[0] - tc * d[0], oc[1] - tc * d[1], oc[2] - tc * d[2]};
    float l2 = q[0] * q[0] + q[1] * q[1] + q[2] * q[2], r2 = s[3] * s[3];
    if (l2 > r2) return -1.0f;
    float td = sqrtf((r2 - l2) * inv);
    if (tc - td > tn && tc - td < tf) return tc - td;
    if (tc + td > tn && tc + td < tf) return tc + td;
    return -1.0f;
}

static void sphere_intersect(const struct RTCIntersectFunctionNArguments *a)
{
    const float *s = (const float *)a->geometryUserPtr + 4 * a->primID;
    float *ray = (float *)a->rayhit;
    unsigned N = a->N;
    for (unsigned i = 0; i < N; i++) {
        if (!a->valid[i]) continue;
        float t = sphere_t(s, ray, N, i);
        if (t < 0.0f) continue;
        ray[8 * N + i] = t;
        float *hit = ray + 12 * N;       /* Ng x y z, u, v, primID, geomID, instID */
        hit[i] = 1.0f, hit[N + i] = 0.0f, hit[2 * N + i] = 0.0f;
        ((unsigned *)hit)[5 * N + i] = a->primID;
        ((unsigned *)hit)[6 * N + i] = a->geomID;
        ((unsigned *)hit)[7 * N + i] = a->context->instID[0];
    }
}

static void sphere_occluded(const struct RTCOccludedFunctionNArguments *a)
{
    const float *s = (const float *)a->geometryUserPtr + 4 * a->primID;
    float *ray = (float *)a->ray;
    for (unsigned i = 0; i < a->N; i++)
        if (a->valid[i] && sphere_t(s, ray, a->N, i) >= 0.0f) ray[8 * a->N + i] = -INFINITY;
}

/* The cache variant's occlusion filter: the blocker is remembered (and accepted). */
static void record_blocker(const struct RTCFilterFunctionNArguments *a)
{
    ((query *)a->context)->last = ((const unsigned *)a->hit)[5 * a->N];
}

/* Does sphere s block the ray, clearly (a margin of 1e-4 of the radius inside the sphere
 * and past tnear, so that no ray Embree would let pass is called blocked)? */
static int sphere_blocks(const float *s, const float o[3], const float d[3], float tnear)
{
    float oc[3] = {s[0] - o[0], s[1] - o[1], s[2] - o[2]};
    float tc = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    float l2 = oc[0] * oc[0] + oc[1] * oc[1] + oc[2] * oc[2] - tc * tc, r2 = s[3] * s[3] * 0.9998f;
    if (!(l2 < r2)) return 0;
    float td = sqrtf(r2 - l2);
    return tc + td > tnear + 1e-4f * s[3];
}

/* ---------------------------------------------------------------- neighbours (nbr) */

typedef struct grid {
    float lo[3], cell;
    int n[3];
    uint32_t *start, *items;    /* cell c's spheres: items[start[c] .. start[c + 1]) */
} grid;

static size_t cell_of(const grid *g, const float p[3], int c[3])
{
    for (int k = 0; k < 3; k++) {
        int v = (int)((p[k] - g->lo[k]) / g->cell);
        c[k] = v < 0 ? 0 : v >= g->n[k] ? g->n[k] - 1 : v;
    }
    return ((size_t)c[2] * g->n[1] + c[1]) * g->n[0] + c[0];
}

static void grid_build(grid *g, const dump *d, float rmax)
{
    float hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (int k = 0; k < 3; k++) g->lo[k] = INFINITY;
    for (size_t i = 0; i < d->nspheres; i++)
        for (int k = 0; k < 3; k++) {
            g->lo[k] = fminf(g->lo[k], d->spheres[4 * i + k]);
            hi[k] = fmaxf(hi[k], d->spheres[4 * i + k]);
        }
    g->cell = 2.0f * rmax;
    size_t nc = 1;
    for (int k = 0; k < 3; k++) nc *= (size_t)(g->n[k] = (int)((hi[k] - g->lo[k]) / g->cell) + 1);
    g->start = calloc(nc + 1, sizeof *g->start);
    g->items = malloc(d->nspheres * sizeof *g->items);
    int c[3];
    for (size_t i = 0; i < d->nspheres; i++) g->start[cell_of(g, d->spheres + 4 * i, c) + 1]++;
    for (size_t i = 0; i < nc; i++) g->start[i + 1] += g->start[i];
    uint32_t *fill = malloc(nc * sizeof *fill);
    memcpy(fill, g->start, nc * sizeof *fill);
    for (size_t i = 0; i < d->nspheres; i++) g->items[fill[cell_of(g, d->spheres + 4 * i, c)]++] = (uint32_t)i;
    free(fill);
}

/* Visit the spheres of the cells within reach of p. */
#define GRID_EACH(g, p, reach, j, ...) do { \
    int c0[3], c1[3]; \
    float a_[3] = {(p)[0] - (reach), (p)[1] - (reach), (p)[2] - (reach)}; \
    float b_[3] = {(p)[0] + (reach), (p)[1] + (reach), (p)[2] + (reach)}; \
    cell_of(g, a_, c0); cell_of(g, b_, c1); \
    for (int z_ = c0[2]; z_ <= c1[2]; z_++) for (int y_ = c0[1]; y_ <= c1[1]; y_++) \
    for (int x_ = c0[0]; x_ <= c1[0]; x_++) { \
        size_t cc_ = ((size_t)z_ * (g)->n[1] + y_) * (g)->n[0] + x_; \
        for (uint32_t q_ = (g)->start[cc_]; q_ < (g)->start[cc_ + 1]; q_++) { \
            uint32_t j = (g)->items[q_]; __VA_ARGS__; } } } while (0)

static void nbr_build(const dump *d)
{
    float rmax = 0;
    for (size_t i = 0; i < d->nspheres; i++) rmax = fmaxf(rmax, d->spheres[4 * i + 3]);
    grid g;
    grid_build(&g, d, rmax);
    nbr = malloc(d->nspheres * nbr_k * sizeof *nbr);
    float *gap = malloc(nbr_k * sizeof *gap);
    for (size_t i = 0; i < d->nspheres; i++) {
        const float *si = d->spheres + 4 * i;
        uint32_t *ni = nbr + i * nbr_k;
        int n = 0;
        GRID_EACH(&g, si, si[3] + 2.0f * rmax, j, {
            if (j == i) continue;
            const float *sj = d->spheres + 4 * (size_t)j;
            float dx = sj[0] - si[0], dy = sj[1] - si[1], dz = sj[2] - si[2];
            float gp = sqrtf(dx * dx + dy * dy + dz * dz) - si[3] - sj[3];
            if (gp > rmax) continue;
            int at = n < nbr_k ? n++ : nbr_k;
            if (at == nbr_k && gp >= gap[nbr_k - 1]) continue;
            if (at == nbr_k) at = nbr_k - 1;
            while (at > 0 && gap[at - 1] > gp) { gap[at] = gap[at - 1]; ni[at] = ni[at - 1]; at--; }
            gap[at] = gp, ni[at] = j;
        });
        for (int k = n; k < nbr_k; k++) ni[k] = ~0u;
    }
    for (int kind = SHADOW; kind <= AO; kind++) {
        ray_sphere[kind] = malloc((d->nrays[kind] + 1) * sizeof(uint32_t));
        size_t found = 0;
        for (size_t r = 0; r < d->nrays[kind]; r++) {
            const float *o = d->rays[kind][r].org;
            float best = INFINITY;
            uint32_t bj = ~0u;
            GRID_EACH(&g, o, 2.0f * rmax, j, {
                const float *sj = d->spheres + 4 * (size_t)j;
                float dx = o[0] - sj[0], dy = o[1] - sj[1], dz = o[2] - sj[2];
                float e = fabsf(sqrtf(dx * dx + dy * dy + dz * dz) - sj[3]);
                if (e < best) best = e, bj = j;
            });
            ray_sphere[kind][r] = best < 1e-3f ? bj : ~0u;
            found += best < 1e-3f;
        }
        printf("nbr: %zu of %zu %s rays start on a sphere (K %d)\n", found, d->nrays[kind],
               kind_names[kind], nbr_k);
    }
    free(gap);
    free(g.start);
    free(g.items);
}

/* ---------------------------------------------------------------- the scene */

static RTCGeometry sphere_geometry(RTCDevice dev, const dump *d, variant v)
{
    RTCGeometry g;
    if (v == V_USER) {
        g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_USER);
        rtcSetGeometryUserPrimitiveCount(g, (unsigned)d->nspheres);
        rtcSetGeometryUserData(g, d->spheres);
        rtcSetGeometryBoundsFunction(g, sphere_bounds, NULL);
        rtcSetGeometryIntersectFunction(g, sphere_intersect);
        rtcSetGeometryOccludedFunction(g, sphere_occluded);
    } else {
        g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_SPHERE_POINT);
        rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, d->spheres, 0,
                                   16, (size_t)d->nspheres);
    }
    if (v == V_CACHE) rtcSetGeometryOccludedFilterFunction(g, record_blocker);
    rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_MEDIUM);
    rtcCommitGeometry(g);
    return g;
}

/* Whether variant v places meshes under instances of their transforms, as the render does. */
static int placed(variant v)
{
    return v == V_PLACED || v == V_COHERENT || v == V_REUSE;
}

/* The reuse variant: each transmission ray's opaque hit distance (INFINITY: none). */
static float *reuse_tfar;

/* The transparent meshes' occlusion filter: each crossing takes its share of the light and
 * the walk goes on (an opaque one, opacity 1, blocks), as the render's does. */
static void pass_through(const struct RTCFilterFunctionNArguments *a)
{
    const mesh *m = a->geometryUserPtr;
    if (m->opacity >= 1.0f) return;
    for (unsigned i = 0; i < a->N; i++)
        if (a->valid[i]) {
            ((query *)a->context)->light *= 1.0f - m->opacity;
            a->valid[i] = 0;
        }
}

static void xf_point(const float *x, const float *p, float *out)
{
    for (int r = 0; r < 3; r++) out[r] = x[4 * r] * p[0] + x[4 * r + 1] * p[1] + x[4 * r + 2] * p[2] + x[4 * r + 3];
}

/* Mesh m as the render built it; world: its vertices moved to world coordinates. */
static RTCGeometry mesh_geometry(RTCDevice dev, mesh *m, int world)
{
    RTCGeometry g = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_TRIANGLE);
    float *xyz = m->xyz;
    if (world) {
        xyz = malloc(3 * (m->nverts + 1) * sizeof(float));
        if (!xyz) die("%s", "out of memory");
        for (uint64_t i = 0; i < m->nverts; i++) xf_point(m->xf, m->xyz + 3 * i, xyz + 3 * i);
    }
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, xyz, 0, 12, m->nverts);
    rtcSetSharedGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, m->tri, 0, 12, m->ntris);
    if (m->flags & MESH_MORTON) rtcSetGeometryBuildQuality(g, RTC_BUILD_QUALITY_LOW);
    if (m->flags & MESH_TRANSPARENT) rtcSetGeometryOccludedFilterFunction(g, pass_through);
    rtcSetGeometryUserData(g, m);
    rtcCommitGeometry(g);
    return g;
}

/* A scene as the render makes them: the transparent part at low quality (Morton codes), the
 * opaque at medium; compact leaves when the render's were. */
static RTCScene new_scene(RTCDevice dev, int trans, int compact)
{
    RTCScene s = rtcNewScene(dev);
    rtcSetSceneBuildQuality(s, trans ? RTC_BUILD_QUALITY_LOW : RTC_BUILD_QUALITY_MEDIUM);
    if (compact) rtcSetSceneFlags(s, RTC_SCENE_FLAG_COMPACT);
    return s;
}

/* The meshes into the opaque (trans 0) or transparent scene top: moved to world coordinates
 * (builtin), or under an instance of each transform they share (placed). */
static void add_meshes(RTCDevice dev, const dump *d, variant v, int trans, RTCScene top)
{
    uint8_t *done = calloc(d->nmeshes + 1, 1);
    for (uint64_t i = 0; i < d->nmeshes; i++) {
        mesh *m = &d->meshes[i];
        if (done[i] || !(m->flags & MESH_TRANSPARENT) != !trans) continue;
        if (!placed(v)) {
            RTCGeometry g = mesh_geometry(dev, m, 1);
            rtcAttachGeometry(top, g);
            rtcReleaseGeometry(g);
            continue;
        }
        RTCScene sub = new_scene(dev, trans, m->flags & MESH_COMPACT);
        for (uint64_t k = i; k < d->nmeshes; k++) {
            mesh *o = &d->meshes[k];
            if (!(o->flags & MESH_TRANSPARENT) != !trans || memcmp(o->xf, m->xf, sizeof m->xf)) continue;
            RTCGeometry g = mesh_geometry(dev, o, 0);
            rtcAttachGeometry(sub, g);
            rtcReleaseGeometry(g);
            done[k] = 1;
        }
        rtcCommitScene(sub);
        RTCGeometry inst = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
        rtcSetGeometryInstancedScene(inst, sub);
        rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_ROW_MAJOR, m->xf);
        rtcCommitGeometry(inst);
        rtcAttachGeometry(top, inst);
        rtcReleaseGeometry(inst);
        rtcReleaseScene(sub);
    }
    free(done);
}

/* Whether the dump has a mesh of that transparency, and one with compact leaves. */
static int has_meshes(const dump *d, int trans, int *compact)
{
    int n = 0;
    *compact = 0;
    for (uint64_t i = 0; i < d->nmeshes; i++)
        if (!(d->meshes[i].flags & MESH_TRANSPARENT) == !trans) {
            n++;
            *compact |= (d->meshes[i].flags & MESH_COMPACT) != 0;
        }
    return n > 0;
}

/* The opaque scene, and the transparent one (NULL when the dump has no transparent mesh). */
static void build_scenes(RTCDevice dev, const dump *d, variant v, RTCScene sc[2])
{
    int compact;
    sc[1] = NULL;
    if (has_meshes(d, 1, &compact)) {
        sc[1] = new_scene(dev, 1, compact && !placed(v));
        add_meshes(dev, d, v, 1, sc[1]);
        rtcCommitScene(sc[1]);
    }
    has_meshes(d, 0, &compact);
    RTCScene s = sc[0] = new_scene(dev, 0, compact && !placed(v));
    if (d->nspheres) {
        RTCGeometry g = sphere_geometry(dev, d, v);
        rtcAttachGeometry(s, g);
        rtcReleaseGeometry(g);
    }
    add_meshes(dev, d, v, 0, s);
    rtcCommitScene(s);
    if (v != V_INSTANCE) return;
    RTCScene top = rtcNewScene(dev);
    RTCGeometry inst = rtcNewGeometry(dev, RTC_GEOMETRY_TYPE_INSTANCE);
    float id[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
    rtcSetGeometryInstancedScene(inst, s);
    rtcSetGeometryTransform(inst, 0, RTC_FORMAT_FLOAT3X4_COLUMN_MAJOR, id);
    rtcCommitGeometry(inst);
    rtcAttachGeometry(top, inst);
    rtcReleaseGeometry(inst);
    rtcReleaseScene(s);
    rtcCommitScene(top);
    sc[0] = top;
}

/* ---------------------------------------------------------------- tracing */

static const own_ops *own_op;   /* the own variant: its tree's width, and the tree */
static own_tree *own;

typedef struct job {
    RTCScene scene, trans;      /* the opaque scene and the transparent one (or NULL) */
    const float *spheres;
    variant v;
    int kind;
    const rayrec *rays;
    size_t n, next;             /* next: the first ray of the next chunk (shared) */
    pthread_mutex_t lock;
    uint64_t hits;              /* camera: rays that hit; occlusion: rays blocked */
} job;

#define CHUNK 4096

static void set_ray(struct RTCRay *r, const rayrec *q)
{
    r->org_x = q->org[0], r->org_y = q->org[1], r->org_z = q->org[2], r->tnear = q->tnear;
    r->dir_x = q->dir[0], r->dir_y = q->dir[1], r->dir_z = q->dir[2], r->time = 0.0f;
    r->tfar = INFINITY, r->mask = 0xffffffffu, r->id = 0, r->flags = 0;
}

static uint64_t trace_one(const job *j, query *qc, const rayrec *q)
{
    struct RTCIntersectContext *ctx = &qc->ec;
    int kind = j->kind == MIXED ? (int)(q->info & 0xffu) : j->kind;
    if (j->v == V_OWN) {
        if (kind == PRIMARY || kind == SECONDARY) {
            float tfar = INFINITY;
            uint32_t prim;
            return (uint64_t)own_op->intersect(own, q->org, q->dir, q->tnear, &tfar, &prim);
        }
        return (uint64_t)own_op->occluded(own, q->org, q->dir, q->tnear, INFINITY);
    }
    if (kind == PRIMARY || kind == SECONDARY) {
        struct RTCRayHit rh;
        set_ray(&rh.ray, q);
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        if (j->v == V_REUSE && kind == SECONDARY && j->trans) {
            rh.ray.tfar = reuse_tfar[q - j->rays];
            rtcIntersect1(j->trans, ctx, &rh);
            return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID || rh.ray.tfar < INFINITY;
        }
        rtcIntersect1(j->scene, ctx, &rh);
        if (j->trans) rtcIntersect1(j->trans, ctx, &rh);    /* up to the opaque hit */
        return rh.hit.geomID != RTC_INVALID_GEOMETRY_ID;
    }
    if (j->v == V_CACHE && qc->last != ~0u && sphere_blocks(j->spheres + 4 * (size_t)qc->last, q->org, q->dir, q->tnear))
        return 1;
    if (j->v == V_NBR) {
        uint32_t src = ray_sphere[j->kind][q - j->rays];
        if (src != ~0u)
            for (const uint32_t *n = nbr + (size_t)src * nbr_k, *e = n + nbr_k; n < e && *n != ~0u; n++)
                if (sphere_blocks(j->spheres + 4 * (size_t)*n, q->org, q->dir, q->tnear)) { qc->caught++; return 1; }
    }
    struct RTCRay r;
    set_ray(&r, q);
    rtcOccluded1(j->scene, ctx, &r);
    if (r.tfar < 0.0f || !j->trans) return r.tfar < 0.0f;
    r.tfar = INFINITY;
    qc->light = 1.0f;
    rtcOccluded1(j->trans, ctx, &r);
    return r.tfar < 0.0f;
}

/* Ray r into lane i of a w-wide packet f (Embree's RTCRayW layout: org, tnear, dir, time,
 * tfar, mask, id, flags, each w wide). */
static void pack_ray(float *f, int w, int i, const rayrec *r)
{
    float v[9] = {r->org[0], r->org[1], r->org[2], r->tnear, r->dir[0], r->dir[1], r->dir[2], 0.0f, INFINITY};
    for (int k = 0; k < 9; k++) f[k * w + i] = v[k];
    ((unsigned *)f)[9 * w + i] = 0xffffffffu;
    ((unsigned *)f)[10 * w + i] = 0;
    ((unsigned *)f)[11 * w + i] = 0;
}

/* Rays q[0..n) (n <= 16, one origin) as one packet of 4, 8 or 16; returns those blocked. */
static uint64_t trace_packet(const job *j, struct RTCIntersectContext *ctx, const rayrec *q, int n)
{
    int w = n <= 4 ? 4 : n <= 8 ? 8 : 16, valid[16];
    RTC_ALIGN(64) struct RTCRay16 p;
    float *f = (float *)&p;
    for (int i = 0; i < w; i++) {
        valid[i] = i < n ? -1 : 0;
        pack_ray(f, w, i, &q[i < n ? i : 0]);
    }
    if (w == 4) rtcOccluded4(valid, j->scene, ctx, (struct RTCRay4 *)&p);
    else if (w == 8) rtcOccluded8(valid, j->scene, ctx, (struct RTCRay8 *)&p);
    else rtcOccluded16(valid, j->scene, ctx, &p);
    uint64_t blocked = 0;
    for (int i = 0; i < n; i++) blocked += f[8 * w + i] < 0.0f;
    return blocked;
}

/* Camera rays q[0..n) (n <= 8) as one coherent packet of 8, through the opaque scene and
 * then the transparent one; returns those that hit. */
static uint64_t trace_camera8(const job *j, struct RTCIntersectContext *ctx, const rayrec *q, int n)
{
    RTC_ALIGN(32) int valid[8];
    RTC_ALIGN(32) struct RTCRayHit8 p;
    float *f = (float *)&p.ray;
    for (int i = 0; i < 8; i++) {
        valid[i] = i < n ? -1 : 0;
        pack_ray(f, 8, i, &q[i < n ? i : 0]);
        p.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
        p.hit.instID[0][i] = RTC_INVALID_GEOMETRY_ID;
    }
    enum RTCIntersectContextFlags old = ctx->flags;
    ctx->flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcIntersect8(valid, j->scene, ctx, &p);
    if (j->trans) rtcIntersect8(valid, j->trans, ctx, &p);
    ctx->flags = old;
    uint64_t hits = 0;
    for (int i = 0; i < n; i++) hits += p.hit.geomID[i] != RTC_INVALID_GEOMETRY_ID;
    return hits;
}

/* Shadow rays *q[0..n) (n <= 8, one direction) as one coherent packet of 8: the opaque
 * scene, then the transparent one for those it let through; returns those blocked. */
static uint64_t trace_shadow8(const job *j, query *qc, const rayrec *const *q, int n)
{
    RTC_ALIGN(32) int valid[8];
    RTC_ALIGN(32) struct RTCRay8 p;
    float *f = (float *)&p;
    for (int i = 0; i < 8; i++) {
        valid[i] = i < n ? -1 : 0;
        pack_ray(f, 8, i, q[i < n ? i : 0]);
    }
    struct RTCIntersectContext *ctx = &qc->ec;
    enum RTCIntersectContextFlags old = ctx->flags;
    ctx->flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
    rtcOccluded8(valid, j->scene, ctx, &p);
    uint64_t blocked = 0;
    for (int i = 0; i < 8; i++)
        if (valid[i] && p.tfar[i] < 0.0f) blocked++, valid[i] = 0;
    if (j->trans && blocked < (uint64_t)n) {
        qc->light = 1.0f;
        rtcOccluded8(valid, j->trans, ctx, &p);
        for (int i = 0; i < 8; i++) blocked += valid[i] && p.tfar[i] < 0.0f;
    }
    ctx->flags = old;
    return blocked;
}

/* The shadow rays of [b, e) gathered by direction (a light's) into packets of 8, up to 4
 * packets open at a time. */
#define OPEN 4
static uint64_t trace_shadows(const job *j, query *qc, size_t b, size_t e)
{
    const rayrec *open[OPEN][8];
    int n[OPEN] = {0}, next = 0;
    uint64_t blocked = 0;
    for (size_t i = b; i < e; i++) {
        const rayrec *r = &j->rays[i];
        int k = 0;
        while (k < OPEN && !(n[k] && !memcmp(open[k][0]->dir, r->dir, sizeof r->dir))) k++;
        if (k == OPEN) {
            for (k = 0; k < OPEN && n[k]; k++) {}
            if (k == OPEN) {                    /* all open: trace the oldest's */
                k = next, next = (next + 1) % OPEN;
                blocked += trace_shadow8(j, qc, open[k], n[k]);
                n[k] = 0;
            }
        }
        open[k][n[k]++] = r;
        if (n[k] == 8) {
            blocked += trace_shadow8(j, qc, open[k], 8);
            n[k] = 0;
        }
    }
    for (int k = 0; k < OPEN; k++)
        if (n[k]) blocked += trace_shadow8(j, qc, open[k], n[k]);
    return blocked;
}

static int same_origin(const rayrec *a, const rayrec *b)
{
    return !memcmp(a->org, b->org, sizeof a->org);
}

static uint64_t trace_range(const job *j, query *ctx, size_t b, size_t e)
{
    uint64_t hits = 0;
    int packets = j->v == V_PACKET && (j->kind == AO || j->kind == SHADOW);
    if (j->v == V_COHERENT && j->kind == SHADOW) return trace_shadows(j, ctx, b, e);
    if ((j->v == V_CAMERA8 || j->v == V_COHERENT) && j->kind == PRIMARY) {
        for (size_t i = b; i < e; i += 8) hits += trace_camera8(j, &ctx->ec, &j->rays[i], (int)(e - i < 8 ? e - i : 8));
        return hits;
    }
    for (size_t i = b; i < e;) {
        size_t k = i + 1;
        while (packets && k < e && k - i < 16 && same_origin(&j->rays[i], &j->rays[k])) k++;
        if (k - i > 1) hits += trace_packet(j, &ctx->ec, &j->rays[i], (int)(k - i));
        else hits += trace_one(j, ctx, &j->rays[i]);
        i = k;
    }
    return hits;
}

static void *worker(void *arg)
{
    job *j = arg;
    query ctx;
    uint64_t hits = 0;
    rtcInitIntersectContext(&ctx.ec);
    ctx.last = ~0u;
    ctx.caught = 0;
    for (;;) {
        pthread_mutex_lock(&j->lock);
        size_t b = j->next;
        j->next = b + CHUNK < j->n ? b + CHUNK : j->n;
        pthread_mutex_unlock(&j->lock);
        if (b >= j->n) break;
        hits += trace_range(j, &ctx, b, b + CHUNK < j->n ? b + CHUNK : j->n);
    }
    pthread_mutex_lock(&j->lock);
    j->hits += hits;
    nbr_caught += ctx.caught;
    pthread_mutex_unlock(&j->lock);
    return NULL;
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

static double cpu(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
           1e-6 * (double)(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

/* Trace every ray of one kind on nthreads threads: wall and CPU seconds, and the hits. */
static uint64_t trace_kind(RTCScene s[2], variant v, const dump *d, int kind, int nthreads,
                           double *wall, double *cpu_s)
{
    job j = {s[0], s[1], d->spheres, v, kind, d->rays[kind], d->nrays[kind], 0, PTHREAD_MUTEX_INITIALIZER, 0};
    pthread_t th[256];
    double t0 = now(), c0 = cpu();
    for (int t = 1; t < nthreads; t++)
        if (pthread_create(&th[t], NULL, worker, &j)) die("%s", "cannot start a thread");
    worker(&j);
    for (int t = 1; t < nthreads; t++) pthread_join(th[t], NULL);
    *wall = now() - t0;
    *cpu_s = cpu() - c0;
    return j.hits;
}

static double thread_cpu(void)
{
    struct timespec t;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
    return (double)t.tv_sec + 1e-9 * (double)t.tv_nsec;
}

/* -ab: each kind's rays chunk by chunk on one thread, each chunk by the builtin variant and
 * by variant v in turn (which goes first alternating), each timed by the thread's CPU clock:
 * a comparison that the host's drifting speed moves alike. */
static void trace_ab(RTCScene a[2], RTCScene b[2], variant v, const dump *d)
{
    double ta[NKINDS] = {0}, tb[NKINDS] = {0};
    for (int k = 0; k < NKINDS; k++) {
        if (!d->nrays[k]) continue;
        job ja = {a[0], a[1], d->spheres, V_BUILTIN, k, d->rays[k], d->nrays[k], 0, PTHREAD_MUTEX_INITIALIZER, 0};
        job jb = ja;
        jb.scene = b[0], jb.trans = b[1], jb.v = v;
        if (d->sorted[k]) jb.rays = d->sorted[k];
        query q;
        rtcInitIntersectContext(&q.ec);
        q.last = ~0u, q.caught = 0;
        uint64_t ha = 0, hb = 0;
        size_t c = 0;
        for (size_t i = 0; i < d->nrays[k]; i += CHUNK, c++) {
            size_t e = i + CHUNK < d->nrays[k] ? i + CHUNK : d->nrays[k];
            for (int side = 0; side < 2; side++) {
                int first_a = (c & 1) == 0, use_a = side == 0 ? first_a : !first_a;
                double t0 = thread_cpu();
                if (use_a) ha += trace_range(&ja, &q, i, e);
                else hb += trace_range(&jb, &q, i, e);
                (use_a ? ta : tb)[k] += thread_cpu() - t0;
            }
        }
        printf("ab kind=%s rays=%zu builtin=%.3f %s%s=%.3f ratio=%.3f hits=%llu/%llu\n", kind_names[k], d->nrays[k],
               ta[k], variant_names[v], d->sorted[k] ? " sorted" : "", tb[k], tb[k] / ta[k],
               (unsigned long long)ha, (unsigned long long)hb);
    }
    double sa = 0, sb = 0;
    for (int k = 0; k < NKINDS; k++) sa += ta[k], sb += tb[k];
    int sorted = d->sorted[SHADOW] || d->sorted[AO] || d->sorted[SECONDARY];
    printf("ab total builtin=%.3f %s%s=%.3f ratio=%.3f\n", sa, variant_names[v], sorted ? " sorted" : "", sb, sb / sa);
}

/* The own variant's tree: the widest this CPU runs (RTFLOOR_WIDTH=8|16 asks for one). */
static const own_ops *pick_own(void)
{
    const char *w = getenv("RTFLOOR_WIDTH");
    int want = w ? atoi(w) : 0;
    if (w && want != 8 && want != 16) die("RTFLOOR_WIDTH is 8 or 16, not %s", w);
    const own_ops *op = own_pick(want);
    if (!op) die("%s", "this CPU cannot run the own tree (it wants AVX2 and FMA, or AVX-512 for 16)");
    return op;
}

static void usage(void)
{
    die("%s", "usage: rt_floor [-t threads] [-v builtin|placed|coherent|reuse|instance|user|packet|cache|camera8|nbr|own] [-r repeats] [-shuffle | -mixed | -sort W] [-c embree-config] [-ab] dump");
}

int main(int argc, char **argv)
{
    int nthreads = 1, repeats = 1, shuffled = 0, mixed = 0, ab = 0, sortw = 0;
    variant v = V_BUILTIN;
    const char *path = NULL, *extra = "";
    for (int i = 1; i < argc; i++) {
        if (!strcmp(argv[i], "-c") && i + 1 < argc) extra = argv[++i];
        else if (!strcmp(argv[i], "-t") && i + 1 < argc) nthreads = atoi(argv[++i]);
        else if (!strcmp(argv[i], "-r") && i + 1 < argc) repeats = atoi(argv[++i]);
        else if (!strcmp(argv[i], "-shuffle")) shuffled = 1;
        else if (!strcmp(argv[i], "-mixed")) mixed = 1;
        else if (!strcmp(argv[i], "-sort") && i + 1 < argc) sortw = atoi(argv[++i]);
        else if (!strcmp(argv[i], "-ab")) ab = 1;
        else if (!strcmp(argv[i], "-v") && i + 1 < argc) {
            const char *name = argv[++i];
            for (v = 0; v < NVARIANTS && strcmp(name, variant_names[v]); v++) {}
            if (v == NVARIANTS) usage();
        } else if (argv[i][0] != '-' && !path) path = argv[i];
        else usage();
    }
    if (!path || nthreads < 1 || nthreads > 256 || repeats < 1) usage();
    if (sortw && (sortw < 1 || CHUNK % sortw || shuffled || mixed || v == V_REUSE || v == V_NBR)) usage();
    const char *key = getenv("RTFLOOR_SORT");
    if (sortw && key && *key) {     /* checked before the dump, which may take a while to read */
        for (sort_key = 0; sort_key < NKEYS && strcmp(key, key_names[sort_key]); sort_key++) {}
        if (sort_key == NKEYS) die("RTFLOOR_SORT is cellorigin, cell, octant, face or origin, not %s", key);
    }
    dump d;
    read_dump(path, &d, mixed);
    if (mixed && (shuffled || ab || v > V_PLACED)) usage();
    if (shuffled) shuffle(&d);
    if (sortw) sort_rays(&d, (size_t)sortw, ab);
    if (v == V_NBR) {
        if (getenv("RTFLOOR_K")) nbr_k = atoi(getenv("RTFLOOR_K"));
        if (nbr_k < 1 || nbr_k > 64) usage();
        nbr_build(&d);
    }
    if (d.nother)
        printf("note: the scene's %llu other primitives are not in the dump; spheres and meshes only\n",
               (unsigned long long)d.nother);
    if (d.nmeshes && v > V_REUSE) die("the %s variant is for scenes of spheres alone", variant_names[v]);
    char cfg[256];
    snprintf(cfg, sizeof cfg, "threads=%d%s%s", nthreads, *extra ? "," : "", extra);
    RTCDevice dev = rtcNewDevice(cfg);
    if (!dev) die("%s", "Embree did not start");
    double b0 = now(), bc0 = cpu();
    RTCScene s[2];
    if (v == V_OWN) {
        own_op = pick_own();
        own = own_op->build(dev, d.spheres, (size_t)d.nspheres);
        if (!own) die("%s", "out of memory for the own tree");
        s[0] = rtcNewScene(dev), s[1] = NULL;
        rtcCommitScene(s[0]);
    } else {
        build_scenes(dev, &d, v, s);
    }
    uint64_t ntris = 0;
    for (uint64_t i = 0; i < d.nmeshes; i++) ntris += d.meshes[i].ntris;
    printf("floor variant=%s%s%s threads=%d spheres=%llu meshes=%llu triangles=%llu build=%.3f build_cpu=%.3f\n",
           variant_names[v], v == V_OWN ? (own_op->width == 16 ? " (16 wide)" : " (8 wide)") : "",
           shuffled ? " (shuffled)" : sortw ? " (sorted)" : "", nthreads, (unsigned long long)d.nspheres,
           (unsigned long long)d.nmeshes, (unsigned long long)ntris, now() - b0, cpu() - bc0);
    if (v == V_REUSE && d.nrays[SECONDARY]) {
        reuse_tfar = malloc(d.nrays[SECONDARY] * sizeof *reuse_tfar);
        if (!reuse_tfar) die("%s", "out of memory");
        struct RTCIntersectContext ec;
        rtcInitIntersectContext(&ec);
        for (size_t i = 0; i < d.nrays[SECONDARY]; i++) {
            struct RTCRayHit rh;
            set_ray(&rh.ray, &d.rays[SECONDARY][i]);
            rh.hit.geomID = rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            rtcIntersect1(s[0], &ec, &rh);
            reuse_tfar[i] = rh.ray.tfar;
        }
    }
    if (ab) {
        RTCScene base[2];
        build_scenes(dev, &d, V_BUILTIN, base);
        for (int r = 0; r < repeats; r++) trace_ab(base, s, v, &d);
        rtcReleaseScene(base[0]);
        if (base[1]) rtcReleaseScene(base[1]);
    }
    double total = 0, total_cpu = 0;
    uint64_t nall = 0;
    for (int k = 0; k <= NKINDS && !ab; k++) {
        if (!d.nrays[k]) continue;
        double best = INFINITY, best_cpu = INFINITY, wall, c;
        uint64_t hits = 0;
        for (int r = 0; r < repeats; r++) {     /* the least wall and the least CPU time */
            hits = trace_kind(s, v, &d, k, nthreads, &wall, &c);
            best = fmin(best, wall), best_cpu = fmin(best_cpu, c);
        }
        printf("kind=%s rays=%zu hits=%llu wall=%.3f cpu=%.3f mrays=%.2f\n", kind_names[k], d.nrays[k],
               (unsigned long long)hits, best, best_cpu, (double)d.nrays[k] / best / 1e6);
        total += best, total_cpu += best_cpu, nall += d.nrays[k];
    }
    if (v == V_NBR)
        printf("nbr: %llu shadow and occlusion rays blocked by a neighbour (all repeats)\n",
               (unsigned long long)nbr_caught);
    if (!ab)
        printf("total rays=%llu wall=%.3f cpu=%.3f mrays=%.2f\n", (unsigned long long)nall, total, total_cpu,
           (double)nall / total / 1e6);
    rtcReleaseScene(s[0]);
    if (s[1]) rtcReleaseScene(s[1]);
    if (own) own_op->release(own);
    rtcReleaseDevice(dev);
    return 0;
}
