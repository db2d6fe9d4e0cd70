/* newribbons.c: VMD's NewRibbons method (thickness, resolution, width, spline): a ribbon
 * along each chain of half width max(width, 1) * thickness / 3 and half height thickness / 3
 * (VMD's scaling), flat in the peptide planes. */
#include "config.h"
#include "rep/rep_int.h"

#include <string.h>

static void fill(const ms_rep_build *b, const ms_rep_backbone *bb, float *cp, float *perp,
                 float *w, float *h)
{
    float thick = b->p[0] / 3.0f, width = (b->p[2] < 1 ? 1 : b->p[2]) * thick;
    for (size_t r = 0; r < bb->n; r++) {
        memcpy(cp + 3 * r, ms_rep_xyz(b, bb->atom[r]), 3 * sizeof(float));
        w[r] = width;
        h[r] = thick;
    }
    for (size_t c = 0; c < bb->nchains; c++)
        ms_rep_chain_perps(b, bb, &bb->chains[c], perp + 3 * bb->chains[c].first);
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    return ms_rep_ribbon_method(b, fill, dl, err);
}

const ms_rep_method ms_rep_newribbons = {
    "NewRibbons", 4,
    {{"thickness", 0.3f}, {"resolution", 12.0f}, {"width", 3.0f}, {"spline", 0.0f}}, 0, build};
