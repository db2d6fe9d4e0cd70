/* dotted.c: VMD's Dotted method (radius scale, resolution): every selected atom as a sphere
 * of scale * radius drawn in dots (poles and res/2 - 1 rings of res dots), unlit. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>

#define MAX_DOTS 4096

typedef struct dot_job {
    const ms_rep_build *b;
    ms_dl_points *pt;
    size_t p0, ndots;
    float scale;
    float (*dir)[3];
} dot_job;

/* Unit directions of the dots for a resolution. */
static size_t dots(int res, float dir[][3])
{
    int around = res < 3 ? 3 : res, rings = res / 2 < 2 ? 2 : res / 2;
    while ((size_t)(rings - 1) * (size_t)around + 2 > MAX_DOTS) around--, rings = around / 2;
    size_t n = 0;
    dir[n][0] = 0, dir[n][1] = 0, dir[n][2] = 1, n++;
    for (int k = 1; k < rings; k++) {
        double th = 3.14159265358979323846 * k / rings;
        for (int a = 0; a < around; a++) {
            double ph = 2 * 3.14159265358979323846 * a / around;
            dir[n][0] = (float)(sin(th) * cos(ph));
            dir[n][1] = (float)(sin(th) * sin(ph));
            dir[n][2] = (float)cos(th);
            n++;
        }
    }
    dir[n][0] = 0, dir[n][1] = 0, dir[n][2] = -1, n++;
    return n;
}

static void fill(void *ctxp, size_t begin, size_t end, int thread)
{
    const dot_job *j = ctxp;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = j->b->idx[s];
        const float *c = ms_rep_xyz(j->b, i);
        float r = j->b->m->atoms.radius[i] * j->scale;
        ms_rgba8 col = ms_rep_rgba(j->b, i);
        for (size_t d = 0; d < j->ndots; d++) {
            size_t o = j->p0 + s * j->ndots + d;
            for (int k = 0; k < 3; k++) j->pt->xyz[3 * o + k] = c[k] + r * j->dir[d][k];
            j->pt->size[o] = 1;
            j->pt->color[o] = col;
        }
    }
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    dl->lit = 0;
    if (!(b->p[0] > 0) || b->nsel == 0) return 0;
    dot_job j = {b, NULL, 0, 0, b->p[0], NULL};
    j.dir = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA, MAX_DOTS * sizeof *j.dir, err);
    if (!j.dir) return -1;
    j.ndots = dots(ms_rep_res(b->p[1]), j.dir);
    size_t n;
    if (ms_mul_size(b->nsel, j.ndots, &n)) {
        ms_error_set(err, "too many dots");
        return -1;
    }
    long p0 = ms_dl_extend(dl, MS_DL_POINTS, n, err);
    if (p0 < 0) return -1;
    j.pt = &dl->points;
    j.p0 = (size_t)p0;
    ms_parallel_for(b->nsel, 1024, fill, &j);
    return 0;
}

const ms_rep_method ms_rep_dotted = {
    "Dotted", 2, {{"sphere scale", 1.0f}, {"sphere resolution", 12.0f}}, 0, build};
