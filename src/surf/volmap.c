/* volmap.c: `volmap density` on the QuickSurf engine: each atom a normalised Gaussian of
 * width sigma = radscale * radius, weighted, summed on QuickSurf's grid. The weights travel
 * through the engine's colour channel (T = sum g_i c_i / iso with iso = 1 and c_i = (w_i
 * norm_i, 0, 0)), so the density loops, cell grid and threading are the engine's own. */
#include "config.h"
#include "surf/qsurf.h"

#include <stdlib.h>
#include <string.h>

#define VOLMAP_PI 3.14159265358979323846

void ms_volmap_params_default(ms_volmap_params *p)
{
    memset(p, 0, sizeof *p);
    p->res = 1.0f;
    p->radscale = 1.0f;
    p->quality = 3;
}

/* Atom k of the input: its index in the arrays. */
static size_t src_index(const ms_volmap_in *in, size_t k)
{
    return in->index ? in->index[k] : k;
}

int ms_volmap_density(const ms_volmap_in *in, const ms_volmap_params *p, ms_qsurf_volume *out,
                      ms_error *err)
{
    memset(out, 0, sizeof *out);
    if (!(p->res > 0) || !(p->radscale > 0)) {
        ms_error_set(err, "resolution and radius scale must be positive");
        return -1;
    }
    size_t n = in->n + (p->use_box ? 2 : 0);
    float *pos = ms_alloc_array(3 * (n ? n : 1), sizeof *pos);
    float *rad = ms_alloc_array(n ? n : 1, sizeof *rad);
    float *rgb = ms_calloc_array(3 * (n ? n : 1), sizeof *rgb);
    int rc = -1;
    if (!pos || !rad || !rgb) {
        ms_error_set(err, "out of memory for %zu atoms", n);
        goto done;
    }
    for (size_t k = 0; k < in->n; k++) {
        size_t i = src_index(in, k);
        memcpy(pos + 3 * k, in->pos + 3 * i, 3 * sizeof *pos);
        rad[k] = in->radius[i];
        double s = (double)p->radscale * rad[k], w = in->weight ? in->weight[i] : 1.0;
        rgb[3 * k] = s > 0 ? (float)(w / (s * s * s * 15.749609945722419)) : 0.0f;
    }
    ms_qsurf_atoms a;
    memset(&a, 0, sizeof a);
    ms_qsurf_radius_range(rad, in->n, NULL, 0, &a.minrad, &a.maxrad);
    if (p->use_box) {
        /* Two weightless atoms at the corners pin the grid (every frame alike). */
        for (int c = 0; c < 2; c++) {
            memcpy(pos + 3 * (in->n + (size_t)c), c ? p->box_hi : p->box_lo, 3 * sizeof *pos);
            rad[in->n + (size_t)c] = a.minrad > 0 ? a.minrad : 1.0f;
        }
    }
    a.n = n;
    a.pos = pos;
    a.radius = rad;
    a.rgb = rgb;
    ms_qsurf_params qp;
    ms_qsurf_params_default(&qp);
    qp.radscale = p->radscale;
    qp.isovalue = 1.0f;
    qp.gridspacing = p->res;
    qp.quality = p->quality;
    qp.backend = MS_QSURF_CPU;
    if (ms_qsurf_density(&a, &qp, out, err) < 0) goto done;
    /* The weighted density is the first colour channel. */
    free(out->data);
    free(out->rgb[1]);
    free(out->rgb[2]);
    out->data = out->rgb[0];
    out->rgb[0] = out->rgb[1] = out->rgb[2] = NULL;
    rc = 0;
done:
    free(pos);
    free(rad);
    free(rgb);
    return rc;
}
