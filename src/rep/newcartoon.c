/* newcartoon.c: VMD's NewCartoon method (thickness, resolution, aspect ratio, spline): the
 * ribbon extrusion with VMD's cross-sections by secondary structure: helices (H, G, I) flat
 * ribbons aspect * thickness wide, sheets (E) as wide through control points smoothed over
 * their neighbours and ending in an arrowhead 1.75x wider, coil, turns and bridges as round
 * tubes of the thickness; nucleic backbones as tubes through P. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <string.h>

static int is_helix(char s) { return s == 'H' || s == 'G' || s == 'I'; }

/* Control point, half width and half height of residue q of a chain. */
static void residue(const ms_rep_build *b, const ms_rep_backbone *bb, const ms_rep_chain *ch,
                    size_t q, float thick, float aspect, float *cp, float *w, float *h)
{
    const char *ss = b->m->atoms.ss;
    size_t r = ch->first + q;
    const float *ca = ms_rep_xyz(b, bb->atom[r]);
    char s = ch->nucleic ? 'C' : ss[bb->atom[r]];
    memcpy(cp, ca, 3 * sizeof(float));
    *w = *h = thick;
    if (is_helix(s)) {
        *w = aspect * thick;
    } else if (s == 'E') {
        size_t next = q + 1 < ch->n ? r + 1 : r, prev = q > 0 ? r - 1 : r;
        const float *cn = ms_rep_xyz(b, bb->atom[next]), *cv = ms_rep_xyz(b, bb->atom[prev]);
        for (int k = 0; k < 3; k++) cp[k] = 0.25f * (2 * ca[k] + cn[k] + cv[k]);
        int arrow = q + 1 == ch->n || ss[bb->atom[r + 1]] != 'E';
        *w = arrow ? -1.75f * aspect * thick : aspect * thick;
    }
}

typedef struct chain_job {
    const ms_rep_build *b;
    const ms_rep_backbone *bb;
    float *cp, *perp, *w, *h;
} chain_job;

static void chains(void *ctxp, size_t begin, size_t end, int thread)
{
    const chain_job *j = ctxp;
    for (size_t c = begin; c < end; c++) {
        const ms_rep_chain *ch = &j->bb->chains[c];
        for (size_t q = 0; q < ch->n; q++) {
            size_t r = ch->first + q;
            residue(j->b, j->bb, ch, q, j->b->p[0], j->b->p[2], j->cp + 3 * r, j->w + r, j->h + r);
        }
        ms_rep_chain_perps(j->b, j->bb, ch, j->perp + 3 * ch->first);
    }
}

static void fill(const ms_rep_build *b, const ms_rep_backbone *bb, float *cp, float *perp,
                 float *w, float *h)
{
    chain_job j = {b, bb, cp, perp, w, h};
    ms_parallel_for(bb->nchains, 16, chains, &j);
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    return ms_rep_ribbon_method(b, fill, dl, err);
}

const ms_rep_method ms_rep_newcartoon = {
    "NewCartoon", 4,
    {{"thickness", 0.3f}, {"resolution", 12.0f}, {"aspect ratio", 4.5f}, {"spline", 0.0f}},
    MS_REP_NEEDS_SS, build};
