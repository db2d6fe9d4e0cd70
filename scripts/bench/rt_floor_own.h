/* rt_floor_own.h: rt_floor's own tree over spheres (rt_floor_own.inc), in two widths for
 * the CPU's vector units. */
#ifndef RT_FLOOR_OWN_H
#define RT_FLOOR_OWN_H

#include <embree3/rtcore.h>
#include <stddef.h>
#include <stdint.h>

typedef struct own_tree own_tree;
typedef struct own_ops {
    int width;                  /* children a node */
    /* The tree over spheres[0..n) (x y z r each; those without a positive radius and finite
     * numbers left out), built on dev's threads; NULL when out of memory or none is left. */
    own_tree *(*build)(RTCDevice dev, const float *spheres, size_t n);
    void (*release)(own_tree *t);
    /* Whether a sphere crosses the ray o + t d within [tnear, tfar]. */
    int (*occluded)(const own_tree *t, const float o[3], const float d[3], float tnear, float tfar);
    /* The nearest crossing within [tnear, *tfar]: 1 with *tfar and *sphere (its index in
     * spheres) set, or 0. */
    int (*intersect)(const own_tree *t, const float o[3], const float d[3], float tnear, float *tfar,
                     uint32_t *sphere);
} own_ops;

/* The two widths; build is NULL where the compiler cannot make them (not x86-64). */
extern const own_ops own_ops8;    /* AVX2 and FMA */
extern const own_ops own_ops16;   /* AVX-512 (F and VL) */

/* The tree this CPU runs best: want 16 or 8 asks for that width, 0 the widest it has.
 * NULL when the CPU lacks what the width needs. */
const own_ops *own_pick(int want);

#endif
