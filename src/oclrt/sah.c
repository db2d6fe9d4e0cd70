/* sah.c: molscope's own BVH builder for the OpenCL tracer, used when Embree's rtcBuildBVH is
 * not there (and by the tests, to check the two trees give the same images): top-down,
 * binned surface area heuristic. At each node the primitives' centroids are sorted into 16
 * bins along each axis; the split between bins with the least (area x count) of the two sides
 * wins; equal centroids split in halves. Leaves hold at most max_leaf primitives, except at
 * the depth limit. O(n log n); nodes and leaf references come from an arena of large blocks. */
#include "config.h"
#include "oclrt/oclrt_impl.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#define BINS 16
#define BLOCK (1u << 20)

typedef struct block {
    struct block *next;
    size_t used, cap;
    max_align_t data[];
} block;

typedef struct sah {
    block *blocks;
    int max_leaf, max_depth, failed;
} sah;

static void *arena_alloc(sah *S, size_t bytes)
{
    bytes = (bytes + sizeof(max_align_t) - 1) / sizeof(max_align_t) * sizeof(max_align_t);
    block *b = S->blocks;
    if (!b || b->used + bytes > b->cap) {
        size_t cap = bytes > BLOCK ? bytes : BLOCK;
        b = malloc(sizeof *b + cap);
        if (!b) {
            S->failed = 1;
            return NULL;
        }
        b->next = S->blocks, b->used = 0, b->cap = cap;
        S->blocks = b;
    }
    void *p = (char *)b->data + b->used;
    b->used += bytes;
    return p;
}

void orc_sah_free(void *arena)
{
    for (block *b = arena, *next; b; b = next) {
        next = b->next;
        free(b);
    }
}

static void box_empty(orc_box *b)
{
    for (int k = 0; k < 3; k++) b->lo[k] = INFINITY, b->hi[k] = -INFINITY;
}

static void box_grow(orc_box *b, const orc_box *o)
{
    for (int k = 0; k < 3; k++) {
        b->lo[k] = fminf(b->lo[k], o->lo[k]);
        b->hi[k] = fmaxf(b->hi[k], o->hi[k]);
    }
}

static float box_area(const orc_box *b)
{
    float d[3];
    for (int k = 0; k < 3; k++) d[k] = b->hi[k] > b->lo[k] ? b->hi[k] - b->lo[k] : 0.0f;
    return d[0] * d[1] + d[1] * d[2] + d[2] * d[0];
}

static float centroid(const orc_bprim *p, int k)
{
    return 0.5f * (p->box.lo[k] + p->box.hi[k]);
}

static orc_bnode *make_leaf(sah *S, const orc_bprim *p, size_t n)
{
    orc_bnode *l = arena_alloc(S, sizeof *l + n * sizeof(uint32_t));
    if (!l) return NULL;
    memset(l, 0, sizeof *l);
    l->leaf = 1;
    l->n = (uint32_t)n;
    l->refs = (uint32_t *)(l + 1);
    for (size_t i = 0; i < n; i++) l->refs[i] = p[i].ref;
    return l;
}

/* The bin of a centroid c along an axis starting at lo, BINS / extent per unit. */
static int bin_of(float c, float lo, float scale)
{
    int b = (int)((c - lo) * scale);
    return b < 0 ? 0 : b >= BINS ? BINS - 1 : b;
}

/* The best split: its axis (-1: none) and first right bin. */
static int best_split(const orc_bprim *p, size_t n, const orc_box *cb, int *split)
{
    float best = INFINITY;
    int axis = -1;
    for (int k = 0; k < 3; k++) {
        float ext = cb->hi[k] - cb->lo[k];
        if (!(ext > 0.0f)) continue;
        float scale = (float)BINS / ext;
        orc_box box[BINS], acc;
        size_t count[BINS] = {0}, right[BINS] = {0};
        float rarea[BINS];
        for (int b = 0; b < BINS; b++) box_empty(&box[b]);
        for (size_t i = 0; i < n; i++) {
            int b = bin_of(centroid(&p[i], k), cb->lo[k], scale);
            count[b]++;
            box_grow(&box[b], &p[i].box);
        }
        box_empty(&acc);
        for (int b = BINS - 1; b > 0; b--) {
            box_grow(&acc, &box[b]);
            right[b] = count[b] + (b < BINS - 1 ? right[b + 1] : 0);
            rarea[b] = box_area(&acc);
        }
        box_empty(&acc);
        size_t left = 0;
        for (int b = 1; b < BINS; b++) {
            box_grow(&acc, &box[b - 1]);
            left += count[b - 1];
            if (!left || !right[b]) continue;
            float cost = box_area(&acc) * (float)left + rarea[b] * (float)right[b];
            if (cost < best) best = cost, axis = k, *split = b;
        }
    }
    return axis;
}

static orc_bnode *build(sah *S, orc_bprim *p, size_t n, int depth)
{
    if (n <= (size_t)S->max_leaf || depth >= S->max_depth - 1) return make_leaf(S, p, n);
    orc_box cb;
    box_empty(&cb);
    for (size_t i = 0; i < n; i++)
        for (int k = 0; k < 3; k++) {
            float c = centroid(&p[i], k);
            cb.lo[k] = fminf(cb.lo[k], c);
            cb.hi[k] = fmaxf(cb.hi[k], c);
        }
    int split = 0, axis = best_split(p, n, &cb, &split);
    size_t mid = n / 2;
    if (axis >= 0) {            /* partition: bins below split to the left */
        float scale = (float)BINS / (cb.hi[axis] - cb.lo[axis]);
        size_t i = 0, j = n;
        while (i < j) {
            if (bin_of(centroid(&p[i], axis), cb.lo[axis], scale) < split) {
                i++;
            } else {
                orc_bprim t = p[i];
                p[i] = p[--j];
                p[j] = t;
            }
        }
        if (i > 0 && i < n) mid = i;
    }
    orc_bnode *node = arena_alloc(S, sizeof *node);
    if (!node) return NULL;
    memset(node, 0, sizeof *node);
    for (int c = 0; c < 2; c++) {
        orc_bprim *q = c ? p + mid : p;
        size_t m = c ? n - mid : mid;
        box_empty(&node->box[c]);
        for (size_t i = 0; i < m; i++) box_grow(&node->box[c], &q[i].box);
        node->kid[c] = build(S, q, m, depth + 1);
        if (!node->kid[c]) return NULL;
    }
    return node;
}

orc_bnode *orc_sah_build(orc_bprim *p, size_t n, int max_leaf, int max_depth, void **arena,
                         ms_error *err)
{
    sah S = {NULL, max_leaf < 1 ? 1 : max_leaf, max_depth < 2 ? 2 : max_depth, 0};
    orc_bnode *root = n ? build(&S, p, n, 0) : NULL;
    *arena = S.blocks;
    if (S.failed || (n && !root)) {
        orc_sah_free(S.blocks);
        *arena = NULL;
        ms_error_set(err, "out of memory for the BVH of %zu primitives", n);
        return NULL;
    }
    return root;
}
