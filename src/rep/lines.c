/* lines.c: VMD's Lines method (line thickness, bond cutoff): each bond as one line when its
 * atoms share a colour and as two half lines in their colours otherwise, a point for a
 * selected atom with no bond drawn; unlit. Licorice with radius 0 draws this too. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <string.h>

typedef struct line_job {
    const ms_rep_build *b;
    const ms_rep_bondlist *bl;
    ms_displaylist *dl;
    size_t *lfirst, *pfirst;    /* per selected position: first line, first point */
    size_t l0, p0;
    float width;
} line_job;

/* Does atom i draw a line towards partner j? Whole lines are drawn by the lower index. */
static int draws(const ms_rep_build *b, uint32_t i, uint32_t j)
{
    return b->color[i] != b->color[j] || j > i;
}

static void count_lines(void *ctxp, size_t begin, size_t end, int thread)
{
    const line_job *j = ctxp;
    const ms_rep_build *b = j->b;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = b->idx[s];
        size_t lines = 0, bonds = 0;
        for (uint32_t k = j->bl->start[i]; k < j->bl->start[i + 1]; k++) {
            uint32_t o = j->bl->to[k];
            if (!ms_rep_on(b, o)) continue;
            bonds++;
            lines += (size_t)draws(b, i, o);
        }
        j->lfirst[s] = lines;
        j->pfirst[s] = bonds == 0;
    }
}

static void fill_lines(void *ctxp, size_t begin, size_t end, int thread)
{
    const line_job *j = ctxp;
    const ms_rep_build *b = j->b;
    ms_dl_lines *ln = &j->dl->lines;
    ms_dl_points *pt = &j->dl->points;
    for (size_t s = begin; s < end; s++) {
        uint32_t i = b->idx[s];
        const float *p = ms_rep_xyz(b, i);
        ms_rgba8 col = ms_rep_rgba(b, i);
        size_t c = j->l0 + j->lfirst[s];
        int bonds = 0;
        for (uint32_t k = j->bl->start[i]; k < j->bl->start[i + 1]; k++) {
            uint32_t o = j->bl->to[k];
            if (!ms_rep_on(b, o)) continue;
            bonds = 1;
            if (!draws(b, i, o)) continue;
            const float *q = ms_rep_xyz(b, o);
            int whole = b->color[i] == b->color[o];
            for (int d = 0; d < 3; d++) {
                ln->a[3 * c + d] = p[d];
                ln->b[3 * c + d] = whole ? q[d] : 0.5f * (p[d] + q[d]);
            }
            ln->width[c] = j->width;
            ln->color[c] = col;
            ln->style[c] = MS_LINE_SOLID;
            c++;
        }
        if (!bonds) {
            size_t o = j->p0 + j->pfirst[s];
            memcpy(pt->xyz + 3 * o, p, 3 * sizeof(float));
            pt->size[o] = j->width;
            pt->color[o] = col;
        }
    }
}

int ms_rep_bond_lines(const ms_rep_build *b, const ms_rep_bondlist *bl, float width,
                      ms_displaylist *dl, ms_error *err)
{
    dl->lit = 0;
    if (b->nsel == 0) return 0;
    line_job j = {b, bl, dl, NULL, NULL, 0, 0, width < 1 ? 1 : (float)(int)width};
    j.lfirst = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (b->nsel + 1) * sizeof(size_t), err);
    j.pfirst = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA, (b->nsel + 1) * sizeof(size_t), err);
    if (!j.lfirst || !j.pfirst) return -1;
    ms_parallel_for(b->nsel, 16384, count_lines, &j);
    size_t nl = ms_rep_scan(j.lfirst, b->nsel), np = ms_rep_scan(j.pfirst, b->nsel);
    long l0 = ms_dl_extend(dl, MS_DL_LINES, nl, err);
    long p0 = l0 < 0 ? -1 : ms_dl_extend(dl, MS_DL_POINTS, np, err);
    if (p0 < 0) return -1;
    j.l0 = (size_t)l0;
    j.p0 = (size_t)p0;
    ms_parallel_for(b->nsel, 16384, fill_lines, &j);
    return 0;
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    ms_rep_bondlist bl;
    if (ms_rep_bonds_get(b, b->p[1], &bl, err)) return -1;
    return ms_rep_bond_lines(b, &bl, b->p[0], dl, err);
}

const ms_rep_method ms_rep_lines = {
    "Lines", 2, {{"thickness", 1.0f}, {"bond cutoff", 0.0f}}, 0, build};
