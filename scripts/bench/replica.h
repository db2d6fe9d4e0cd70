/* replica.h: the benchmarks' large system: 1tii (tests/data) replicated on a grid to about a
 * million atoms, with its real bonds and per-atom radii, and colours by element as a
 * colouring method would give them. */
#ifndef MS_BENCH_REPLICA_H
#define MS_BENCH_REPLICA_H

#include <stddef.h>
#include <stdint.h>

#include "scene/displaylist.h"

typedef struct bench_sys {
    size_t n;                 /* atoms */
    float *pos, *radius;
    ms_rgba8 *color;
    uint32_t *bstart, *bto;   /* CSR bonds of the replicated system */
    size_t n0;                /* atoms of one copy */
} bench_sys;

/* copies of 1tii from data/1tii.pdb, 120 x 120 x 180 A apart. 0, or -1 with a message. */
int bench_sys_make(const char *data, int copies, bench_sys *s);
void bench_sys_free(bench_sys *s);

#endif
