/* trace.c: VMD's Trace method (radius, resolution): consecutive control atoms (CA, or P of
 * nucleic acids) of each chain joined by a cylinder whose halves take their colours,
 * stretched to meet at the bends; unlit lines at a resolution of 2 or less or a radius under 0.01. */
#include "config.h"
#include "rep/rep_int.h"

#include <string.h>

typedef struct trace_out {
    ms_displaylist *dl;
    float r;
    uint16_t res;
    int cyl;
} trace_out;

/* Two half lines, or one cylinder whose halves are VMD's: a to mid stretched to meet prev,
 * mid to b stretched to meet next. */
static int link(const trace_out *o, const float *prev, const float *a, const float *mid,
                const float *b, const float *next, ms_rgba8 ca, ms_rgba8 cb)
{
    if (!o->cyl)
        return ms_dl_line(o->dl, a, mid, 1, ca, MS_LINE_SOLID) ||
               ms_dl_line(o->dl, mid, b, 1, cb, MS_LINE_SOLID) ? -1 : 0;
    float s[3], j[3], unused[3], e[3];
    ms_rep_stretch(prev, a, mid, NULL, o->r, s, j);
    ms_rep_stretch(NULL, mid, b, next, o->r, unused, e);
    return ms_dl_bond(o->dl, s, j, e, o->r, ca, cb, 0, o->res);
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    ms_rep_backbone bb;
    memset(&bb, 0, sizeof bb);
    if (ms_rep_backbone_build(b->m, &bb, err)) return -1;
    int res = ms_rep_res(b->p[1]);
    trace_out o = {dl, b->p[0], (uint16_t)res, !(res <= 2 || b->p[0] < 0.01f)};
    if (!o.cyl) dl->lit = 0;
    int rc = 0;
    for (size_t c = 0; c < bb.nchains && rc == 0; c++) {
        const ms_rep_chain *ch = &bb.chains[c];
        for (size_t q = 0; q + 1 < ch->n && rc == 0; q++) {
            uint32_t i = bb.atom[ch->first + q], k = bb.atom[ch->first + q + 1];
            if (!ms_rep_on(b, i) || !ms_rep_on(b, k)) continue;
            const float *pi = ms_rep_xyz(b, i), *pk = ms_rep_xyz(b, k);
            const float *prev = q > 0 ? ms_rep_xyz(b, bb.atom[ch->first + q - 1]) : NULL;
            const float *next = q + 2 < ch->n ? ms_rep_xyz(b, bb.atom[ch->first + q + 2]) : NULL;
            float mid[3] = {0.5f * (pi[0] + pk[0]), 0.5f * (pi[1] + pk[1]), 0.5f * (pi[2] + pk[2])};
            rc = link(&o, prev, pi, mid, pk, next, ms_rep_rgba(b, i), ms_rep_rgba(b, k));
        }
    }
    ms_rep_backbone_free(&bb);
    if (rc) ms_error_set(err, "out of memory for display list");
    return rc ? -1 : 0;
}

const ms_rep_method ms_rep_trace = {
    "Trace", 2, {{"bond radius", 0.3f}, {"bond resolution", 12.0f}}, 0, build};
