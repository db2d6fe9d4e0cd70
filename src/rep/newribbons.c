/* newribbons.c: VMD's NewRibbons method (thickness, resolution, width, spline): a ribbon
 * along each chain of half width max(width, 1) * thickness / 3 and half height thickness / 3
 * (VMD's scaling), flat in the peptide planes. */
#include "config.h"
#include "rep/rep_int.h"

#include <string.h>

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    ms_rep_backbone bb;
    memset(&bb, 0, sizeof bb);
    if (ms_rep_backbone_build(b->m, &bb, err)) return -1;
    int rc = -1;
    float *geo = ms_rep_scratch_get(b->scratch, MS_SCR_PATH, (bb.n + 1) * 8 * sizeof(float), err);
    if (!geo) goto done;
    float *cp = geo, *perp = geo + 3 * bb.n, *w = geo + 6 * bb.n, *h = geo + 7 * bb.n;
    float thick = b->p[0] / 3.0f, width = (b->p[2] < 1 ? 1 : b->p[2]) * thick;
    for (size_t r = 0; r < bb.n; r++) {
        memcpy(cp + 3 * r, ms_rep_xyz(b, bb.atom[r]), 3 * sizeof(float));
        w[r] = width;
        h[r] = thick;
    }
    for (size_t c = 0; c < bb.nchains; c++)
        ms_rep_chain_perps(b, &bb, &bb.chains[c], perp + 3 * bb.chains[c].first);
    ms_rep_ribbon rib = {&bb, cp, perp, w, h, b->p[3] != 0, ms_rep_res(b->p[1]),
                         ms_rep_ribbon_divs(b->p[1])};
    rc = ms_rep_ribbon_build(b, &rib, dl, err);
done:
    ms_rep_backbone_free(&bb);
    return rc;
}

const ms_rep_method ms_rep_newribbons = {
    "NewRibbons", 4,
    {{"thickness", 0.3f}, {"resolution", 12.0f}, {"width", 3.0f}, {"spline", 0.0f}}, 0, build};
