/* bench_system.h: the benchmarks' large system: 1tii replicated on a grid to about a
 * million atoms, with its real bonds and per-atom colours (what an element colouring would
 * give), and the VDW and Licorice display lists a representation would build from it. */
#ifndef MS_BENCH_SYSTEM_H
#define MS_BENCH_SYSTEM_H

#include "scene/displaylist.h"

typedef struct bench_sys {
    size_t n;                 /* atoms */
    float *pos, *radius;
    ms_rgba8 *color;
    uint32_t *bstart, *bto;   /* CSR bonds of the replicated system */
    float lo[3], hi[3];       /* bounding box of the positions */
    size_t n0;                /* atoms of one copy */
} bench_sys;

/* 1tii from the data folder, `copies` times; 0, or -1 after printing why. */
int bench_system_make(const char *data, int copies, bench_sys *s);
void bench_system_free(bench_sys *s);

/* VMD's VDW (a sphere per atom, its radius) and Licorice (spheres of radius 0.3 and, per
 * bond, two half cylinders coloured by their atoms) lists, filled in parallel blocks. */
int bench_vdw_list(const bench_sys *s, ms_displaylist *dl, ms_error *err);
int bench_licorice_list(const bench_sys *s, ms_displaylist *dl, ms_error *err);

#endif
