/* tube.c: VMD's Tube method (radius, resolution): a spline (VMD's modified Catmull-Rom)
 * through each chain's control atoms (CA; P for nucleic acids), drawn as six cylinders
 * between consecutive control points, the first three in the first atom's colour and the
 * rest in the second's, stretched to join; unlit lines at a resolution of 2 or less or a
 * radius under 0.01. */
#include "config.h"
#include "rep/rep_int.h"

#include <string.h>

#define STEPS 6                 /* cylinders between two control points, as VMD */

/* Point k (0 .. STEPS (n - 1)) of the chain's spline. */
static void point(const ms_rep_build *b, const ms_rep_backbone *bb, const ms_rep_chain *ch,
                  const float basis[4][4], long k, float out[3])
{
    long n = (long)ch->n, seg = k / STEPS, j = k % STEPS;
    if (seg >= n - 1) seg = n - 2, j = STEPS;
    const float *p[4];
    for (int i = 0; i < 4; i++) {
        long c = seg - 1 + i;
        c = c < 0 ? 0 : c >= n ? n - 1 : c;
        p[i] = ms_rep_xyz(b, bb->atom[ch->first + (size_t)c]);
    }
    ms_rep_spline_eval(basis, p[0], p[1], p[2], p[3], (float)j / STEPS, out);
}

static int chain_tube(const ms_rep_build *b, const ms_rep_backbone *bb, const ms_rep_chain *ch,
                      const float basis[4][4], float r, int res, int cyl, ms_displaylist *dl)
{
    long last = STEPS * (long)(ch->n - 1);
    for (long s = 0; s < last; s++) {
        size_t owner = ch->first + (size_t)(s / STEPS) + (s % STEPS >= STEPS / 2);
        uint32_t atom = bb->atom[owner];
        if (!ms_rep_on(b, atom)) continue;
        float a[3], e[3], prev[3], next[3], s0[3], s1[3];
        point(b, bb, ch, basis, s, a);
        point(b, bb, ch, basis, s + 1, e);
        if (s > 0) point(b, bb, ch, basis, s - 1, prev);
        if (s + 2 <= last) point(b, bb, ch, basis, s + 2, next);
        ms_rgba8 col = ms_rep_rgba(b, atom);
        int rc;
        if (cyl) {
            ms_rep_stretch(s > 0 ? prev : NULL, a, e, s + 2 <= last ? next : NULL, r, s0, s1);
            rc = ms_dl_cylinder(dl, s0, s1, r, col, 0, res);
        } else {
            rc = ms_dl_line(dl, a, e, 2, col, MS_LINE_SOLID);
        }
        if (rc) return -1;
    }
    return 0;
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    ms_rep_backbone bb;
    memset(&bb, 0, sizeof bb);
    if (ms_rep_backbone_build(b->m, &bb, err)) return -1;
    float basis[4][4], r = b->p[0];
    int res = ms_rep_res(b->p[1]), cyl = !(res <= 2 || r < 0.01f), rc = 0;
    if (!cyl) dl->lit = 0;
    ms_rep_spline_basis(basis, 0);
    for (size_t c = 0; c < bb.nchains && rc == 0; c++)
        if (bb.chains[c].n >= 2) rc = chain_tube(b, &bb, &bb.chains[c], basis, r, res, cyl, dl);
    ms_rep_backbone_free(&bb);
    if (rc) ms_error_set(err, "out of memory for display list");
    return rc ? -1 : 0;
}

const ms_rep_method ms_rep_tube = {
    "Tube", 2, {{"bond radius", 0.3f}, {"bond resolution", 12.0f}}, 0, build};
