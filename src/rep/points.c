/* points.c: VMD's Points method (point size): an unlit point at every selected atom. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <string.h>

typedef struct point_job {
    const ms_rep_build *b;
    ms_dl_points *pt;
    size_t p0;
    float size;
} point_job;

static void fill(void *ctxp, size_t begin, size_t end, int thread)
{
    const point_job *j = ctxp;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = j->b->idx[s];
        size_t o = j->p0 + s;
        memcpy(j->pt->xyz + 3 * o, ms_rep_xyz(j->b, i), 3 * sizeof(float));
        j->pt->size[o] = j->size;
        j->pt->color[o] = ms_rep_rgba(j->b, i);
    }
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    dl->lit = 0;
    long p0 = ms_dl_extend(dl, MS_DL_POINTS, b->nsel, err);
    if (p0 < 0) return -1;
    point_job j = {b, &dl->points, (size_t)p0, b->p[0]};
    ms_parallel_for(b->nsel, 16384, fill, &j);
    return 0;
}

const ms_rep_method ms_rep_points = {"Points", 1, {{"size", 1.0f}}, 0, build};
