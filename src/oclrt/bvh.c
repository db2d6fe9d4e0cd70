/* bvh.c: the OpenCL tracer's BVH, built on the host over the bounds of the flat world's
 * primitives by Embree's BVH builder (rtcBuildBVH: binned SAH, in parallel), or by our own
 * (sah.c) without Embree, then flattened depth first into the structure-of-arrays node
 * buffers the kernels walk: per node the boxes of its two children (float4 each) and their
 * references (int4). Primitives that Embree's own geometries would leave out (a radius that
 * is not positive, a non-finite coordinate) get no leaf. */
#include "config.h"
#include "oclrt/oclrt_impl.h"
#ifdef MS_HAVE_EMBREE
#include "rt/rt_internal.h"
#endif

#include <math.h>
#include <stdint.h>
#include <stdlib.h>
#include <string.h>

#define LEAF_MAX 4
#define DEPTH_MAX 60            /* below the kernels' stack of 64 */

#ifdef MS_HAVE_EMBREE
/* Embree's builder makes our tree through these callbacks. */
static void *create_node(RTCThreadLocalAllocator a, unsigned int count, void *user)
{
    orc_bnode *n = rtcThreadLocalAlloc(a, sizeof *n, 16);
    if (n) memset(n, 0, sizeof *n);
    return n;
}

static void set_children(void *node, void **kids, unsigned int count, void *user)
{
    orc_bnode *n = node;
    for (unsigned i = 0; n && i < count && i < 2; i++) n->kid[i] = kids[i];
}

static void set_bounds(void *node, const struct RTCBounds **b, unsigned int count, void *user)
{
    orc_bnode *n = node;
    for (unsigned i = 0; n && i < count && i < 2; i++) {
        n->box[i].lo[0] = b[i]->lower_x, n->box[i].lo[1] = b[i]->lower_y, n->box[i].lo[2] = b[i]->lower_z;
        n->box[i].hi[0] = b[i]->upper_x, n->box[i].hi[1] = b[i]->upper_y, n->box[i].hi[2] = b[i]->upper_z;
    }
}

static void *create_leaf(RTCThreadLocalAllocator a, const struct RTCBuildPrimitive *p, size_t count,
                         void *user)
{
    orc_bnode *n = rtcThreadLocalAlloc(a, sizeof *n + count * sizeof(uint32_t), 16);
    if (!n) return NULL;
    memset(n, 0, sizeof *n);
    n->leaf = 1;
    n->n = (uint32_t)count;
    n->refs = (uint32_t *)(n + 1);
    for (size_t i = 0; i < count; i++) n->refs[i] = p[i].primID;
    return n;
}
#endif

/* ---------------------------------------------------------------- primitive bounds */

static int box_ok(const float lo[3], const float hi[3])
{
    for (int k = 0; k < 3; k++)
        if (!isfinite(lo[k]) || !isfinite(hi[k]) || lo[k] > hi[k]) return 0;
    return 1;
}

/* The bounds of axis (a to b) with radius ra at a and rb at b: rt/cylinder.c's and
 * rt/cone.c's. 0 when degenerate. */
static int tube_box(const float a[3], const float b[3], float ra, float rb, float lo[3], float hi[3])
{
    float w[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]}, len2 = ms_v3f_dot(w, w);
    if (!(ra >= 0) || !(rb >= 0) || !(ra + rb > 0) || !(len2 > 0) || !isfinite(len2) || !isfinite(ra + rb))
        return 0;
    for (int k = 0; k < 3; k++) {
        float s = sqrtf(fmaxf(0.0f, 1.0f - w[k] * w[k] / len2));
        lo[k] = fminf(a[k] - ra * s, b[k] - rb * s);
        hi[k] = fmaxf(a[k] + ra * s, b[k] + rb * s);
    }
    return 1;
}

static int quadric_box(const orc_world *w, size_t i, float lo[3], float hi[3])
{
    const float *a = w->qa + 4 * i, *b = w->qb + 4 * i;
    float e[3], end[3];
    switch (w->qkind[i]) {
    case ORC_SPHERE:
        if (!(a[3] > 0)) return 0;
        for (int k = 0; k < 3; k++) lo[k] = a[k] - a[3], hi[k] = a[k] + a[3];
        return box_ok(lo, hi);
    case ORC_CYLINDER:
        if (!(a[3] > 0) || !(b[3] > 0)) return 0;
        for (int k = 0; k < 3; k++) end[k] = a[k] + b[3] * b[k];
        return tube_box(a, end, a[3], a[3], lo, hi) && box_ok(lo, hi);
    case ORC_CONE:
        return tube_box(a, b, a[3], b[3], lo, hi) && box_ok(lo, hi);
    default: {
        float n2 = ms_v3f_dot(b, b);
        if (!(a[3] > 0) || !(n2 > 0) || !isfinite(n2)) return 0;
        for (int k = 0; k < 3; k++) e[k] = a[3] * sqrtf(fmaxf(0.0f, 1.0f - b[k] * b[k] / n2));
        for (int k = 0; k < 3; k++) lo[k] = a[k] - e[k], hi[k] = a[k] + e[k];
        return box_ok(lo, hi);
    }
    }
}

static int triangle_box(const orc_world *w, size_t i, float lo[3], float hi[3])
{
    const uint32_t *t = w->tri + 4 * i;
    for (int k = 0; k < 3; k++) lo[k] = INFINITY, hi[k] = -INFINITY;
    for (int v = 0; v < 3; v++)
        for (int k = 0; k < 3; k++) {
            float c = w->vxyz[4 * (size_t)t[v] + k];
            lo[k] = fminf(lo[k], c);
            hi[k] = fmaxf(hi[k], c);
        }
    return box_ok(lo, hi);
}

/* The builders' input: one box per valid primitive, with its reference. */
static orc_bprim *build_prims(const orc_world *w, size_t *n, ms_error *err)
{
    orc_bprim *p = ms_alloc_array(w->nq + w->ntri + 1, sizeof *p);
    if (!p) {
        ms_error_set(err, "out of memory for the BVH of %zu primitives", w->nq + w->ntri);
        return NULL;
    }
    *n = 0;
    for (size_t i = 0; i < w->nq + w->ntri; i++) {
        int tri = i >= w->nq;
        size_t j = tri ? i - w->nq : i;
        orc_bprim *q = &p[*n];
        if (!(tri ? triangle_box(w, j, q->box.lo, q->box.hi) : quadric_box(w, j, q->box.lo, q->box.hi))) continue;
        q->ref = (tri ? ORC_TRIANGLE : w->qkind[j]) << ORC_KIND_SHIFT | (uint32_t)j;
        (*n)++;
    }
    return p;
}

/* ---------------------------------------------------------------- flattening */

static void count_tree(const orc_bnode *n, size_t *nodes, size_t *refs)
{
    if (n->leaf) {
        *refs += n->n;
        return;
    }
    (*nodes)++;
    for (int k = 0; k < 2; k++)
        if (n->kid[k]) count_tree(n->kid[k], nodes, refs);
}

typedef struct flat {
    orc_world *w;
    size_t node, ref;
} flat;

static void put_box(float *dst, const orc_box *b, int upper)
{
    const float *v = upper ? b->hi : b->lo;
    dst[0] = v[0], dst[1] = v[1], dst[2] = v[2], dst[3] = 0;
}

/* Node n at index f->node (an inner node), its subtrees after it. */
static void flatten_node(flat *f, const orc_bnode *n)
{
    orc_world *w = f->w;
    size_t me = f->node++;
    for (int k = 0; k < 2; k++) {
        const orc_bnode *c = n->kid[k];
        float *lo = k ? w->lo1 : w->lo0, *hi = k ? w->hi1 : w->hi0;
        put_box(lo + 4 * me, &n->box[k], 0);
        put_box(hi + 4 * me, &n->box[k], 1);
        int32_t *ch = w->child + 4 * me;
        if (!c) {
            ch[k] = -1, ch[2 + k] = 0;
        } else if (c->leaf) {
            ch[k] = (int32_t)f->ref, ch[2 + k] = (int32_t)c->n;
            memcpy(w->leaf + f->ref, c->refs, c->n * sizeof(uint32_t));
            f->ref += c->n;
            if (!c->n) ch[k] = -1;
        } else {
            ch[k] = (int32_t)f->node, ch[2 + k] = 0;
            flatten_node(f, c);
        }
    }
}

static int flatten(orc_world *w, const orc_bnode *root, ms_error *err)
{
    orc_bnode top;              /* a leaf root goes under an inner node of its own */
    if (root->leaf) {
        memset(&top, 0, sizeof top);
        top.kid[0] = (orc_bnode *)root;
        for (int k = 0; k < 3; k++) top.box[0].lo[k] = -INFINITY, top.box[0].hi[k] = INFINITY;
        root = &top;
    }
    size_t nodes = 0, refs = 0;
    count_tree(root, &nodes, &refs);
    w->lo0 = ms_alloc_array(nodes, 4 * sizeof(float));
    w->hi0 = ms_alloc_array(nodes, 4 * sizeof(float));
    w->lo1 = ms_alloc_array(nodes, 4 * sizeof(float));
    w->hi1 = ms_alloc_array(nodes, 4 * sizeof(float));
    w->child = ms_alloc_array(nodes, 4 * sizeof(int32_t));
    w->leaf = ms_alloc_array(refs + 1, sizeof(uint32_t));
    if (!w->lo0 || !w->hi0 || !w->lo1 || !w->hi1 || !w->child || !w->leaf) {
        ms_error_set(err, "out of memory for a BVH of %zu nodes", nodes);
        return -1;
    }
    flat f = {w, 0, 0};
    flatten_node(&f, root);
    w->nnodes = f.node;
    w->nleaf = f.ref;
    return 0;
}

#ifdef MS_HAVE_EMBREE
/* Embree's RTCBuildPrimitive is declared 32-byte aligned, and the builder reads it with
 * aligned loads: an array of n of them aligned so (aligned_alloc wants a size that is a
 * multiple of the alignment); NULL when out of memory or too large. */
static struct RTCBuildPrimitive *build_prims_alloc(size_t n)
{
    size_t bytes, align = 32;
    if (ms_mul_size(n ? n : 1, sizeof(struct RTCBuildPrimitive), &bytes) ||
        bytes > SIZE_MAX - align)
        return NULL;
    return aligned_alloc(align, (bytes + align - 1) / align * align);
}

/* Embree's builder over p[0..n), flattened into w. */
static int embree_build(orc_world *w, const orc_bprim *p, size_t n, ms_error *err)
{
    RTCDevice dev = rt_device(err);
    if (!dev) return -1;
    struct RTCBuildPrimitive *prims = build_prims_alloc(n);
    RTCBVH bvh = prims ? rtcNewBVH(dev) : NULL;
    if (!bvh) {
        free(prims);
        if (!prims || !rt_device_check(dev, "BVH", err)) ms_error_set(err, "out of memory for the BVH");
        return -1;
    }
    for (size_t i = 0; i < n; i++) {
        struct RTCBuildPrimitive *q = &prims[i];
        q->lower_x = p[i].box.lo[0], q->lower_y = p[i].box.lo[1], q->lower_z = p[i].box.lo[2];
        q->upper_x = p[i].box.hi[0], q->upper_y = p[i].box.hi[1], q->upper_z = p[i].box.hi[2];
        q->geomID = 0;
        q->primID = p[i].ref;
    }
    struct RTCBuildArguments a = rtcDefaultBuildArguments();
    a.buildQuality = RTC_BUILD_QUALITY_MEDIUM;
    a.maxBranchingFactor = 2;
    a.maxDepth = DEPTH_MAX;
    a.minLeafSize = 1;
    a.maxLeafSize = LEAF_MAX;
    a.traversalCost = 1.0f;
    a.intersectionCost = 2.0f;
    a.bvh = bvh;
    a.primitives = prims;
    a.primitiveCount = n;
    a.primitiveArrayCapacity = n;
    a.createNode = create_node;
    a.setNodeChildren = set_children;
    a.setNodeBounds = set_bounds;
    a.createLeaf = create_leaf;
    const orc_bnode *root = rtcBuildBVH(&a);
    int rc = -1;
    if (rt_device_check(dev, "BVH build", err) == 0) {
        if (!root) ms_error_set(err, "BVH build failed");
    } else {
        root = NULL;            /* memory was refused: the tree may be incomplete */
    }
    if (root) rc = flatten(w, root, err);
    rtcReleaseBVH(bvh);
    free(prims);
    return rc;
}
#endif

int orc_bvh_build(orc_world *w, ms_error *err)
{
    size_t n;
    w->nnodes = w->nleaf = 0;
    orc_bprim *p = build_prims(w, &n, err);
    if (!p) return -1;
    int rc = 0;
    if (n) {
#ifdef MS_HAVE_EMBREE
        if (!ms_oclrt_own_bvh) {
            rc = embree_build(w, p, n, err);
            free(p);
            return rc;
        }
#endif
        void *arena = NULL;
        orc_bnode *root = orc_sah_build(p, n, LEAF_MAX, DEPTH_MAX, &arena, err);
        rc = root ? flatten(w, root, err) : -1;
        orc_sah_free(arena);
    }
    free(p);
    return rc;
}
