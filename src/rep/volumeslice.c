/* volumeslice.c: VMD's VolumeSlice method (slice 0-1, volid, axis 0/1/2, quality): the
 * plane through volume `volid` at fraction `slice` of its extent along grid axis x, y or z,
 * drawn as a lit triangle mesh whose vertices carry the colour scale's colour of the
 * volume's value there (VMD draws the plane with a 3-D texture; per-vertex colours do the
 * same at the grid's resolution). Quality sets the vertices per grid spacing: 2^(quality -
 * 2), so 2 (the default) puts one vertex on every grid point of the plane, 3 one more
 * between each two, 1 and 0 half and a quarter as many, spread evenly over the plane (values
 * between grid points interpolated); at least two vertices per side. The plane between two grid planes takes values interpolated
 * between them. The colour range is the rep's when it colours by a scale method with a
 * range other than 0 0 (`Volume n` colouring: volume n's min and max, or `mol
 * scaleminmax`), else the volume's own min and max. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <math.h>

typedef struct slice_job {
    const ms_rep_build *b;
    const ms_volume *v;
    ms_displaylist *dl;
    size_t v0;
    int a, u, w, nu, nw;
    double ga;
    float lo, hi;
    int8_t normal[3];
} slice_job;

/* The vertices of rows j in [begin, end) along w. */
static void slice_rows(void *ctx, size_t begin, size_t end, int thread)
{
    slice_job *j = ctx;
    (void)thread;
    const ms_volume *v = j->v;
    ms_dl_mesh *mesh = &j->dl->mesh;
    for (size_t r = begin; r < end; r++)
        for (int i = 0; i < j->nu; i++) {
            double g[3];
            g[j->a] = j->ga;
            g[j->u] = (double)i * (v->n[j->u] - 1) / (j->nu - 1);
            g[j->w] = (double)r * (v->n[j->w] - 1) / (j->nw - 1);
            size_t k = j->v0 + r * (size_t)j->nu + (size_t)i;
            ms_volume_point(v, g, mesh->xyz + 3 * k);
            for (int c = 0; c < 3; c++) mesh->normal[3 * k + c] = j->normal[c];
            float val = ms_volume_value_at(v, g);
            mesh->color[k] = j->b->palette[ms_color_scale_index(val, j->lo, j->hi)];
        }
}

/* The unit normal of the plane spanned by the u and w steps, on the side +a points to. */
static void plane_normal(const ms_volume *v, int a, int u, int w, int8_t out[3])
{
    const float *du = v->delta[u], *dw = v->delta[w], *da = v->delta[a];
    float n[3] = {du[1] * dw[2] - du[2] * dw[1], du[2] * dw[0] - du[0] * dw[2],
                  du[0] * dw[1] - du[1] * dw[0]};
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    if (!(len > 0.0f)) {
        n[0] = n[1] = 0.0f, n[2] = len = 1.0f;
    } else if (n[0] * da[0] + n[1] * da[1] + n[2] * da[2] < 0.0f) {
        len = -len;
    }
    for (int k = 0; k < 3; k++) out[k] = ms_normal_quantize(n[k] / len);
}

/* Vertices along an axis of n grid points at 2^(quality - 2) per spacing. */
static int vertices_along(int n, int quality)
{
    double c = ldexp((double)(n - 1), quality - 2);
    return c < 1.0 ? 2 : (int)MS_MIN(c + 0.5, 1 << 20) + 1;
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    const ms_volume *v = ms_rep_volume(b, b->p[1]);
    if (!v) return 0;
    slice_job j = {.b = b, .v = v, .dl = dl};
    float loc = b->p[0] > 0.0f ? (b->p[0] < 1.0f ? b->p[0] : 1.0f) : 0.0f;
    int axis = (int)b->p[2], quality = (int)b->p[3];
    j.a = axis >= 0 && axis <= 2 ? axis : 0;   /* VMD: any other number is x */
    j.u = (j.a + 1) % 3, j.w = (j.a + 2) % 3;
    if (v->n[j.u] < 2 || v->n[j.w] < 2) return 0;
    quality = quality < 0 ? 0 : quality > 3 ? 3 : quality;
    j.nu = vertices_along(v->n[j.u], quality);
    j.nw = vertices_along(v->n[j.w], quality);
    j.ga = (double)loc * (v->n[j.a] - 1);
    ms_rep_volume_range(b, v, &j.lo, &j.hi);
    plane_normal(v, j.a, j.u, j.w, j.normal);
    size_t nverts = (size_t)j.nu * (size_t)j.nw, ntris = 2 * (size_t)(j.nu - 1) * (size_t)(j.nw - 1);
    size_t t0;
    if (nverts > UINT32_MAX || ms_dl_mesh_extend(dl, nverts, ntris, &j.v0, &t0, err)) {
        if (nverts > UINT32_MAX) ms_error_set(err, "VolumeSlice: %zu vertices is too many", nverts);
        return -1;
    }
    ms_parallel_for((size_t)j.nw, 16, slice_rows, &j);
    uint32_t *t = dl->mesh.tri + 3 * t0;
    for (int r = 0; r + 1 < j.nw; r++)
        for (int i = 0; i + 1 < j.nu; i++) {
            uint32_t p00 = (uint32_t)(j.v0 + (size_t)r * j.nu + i), p10 = p00 + 1;
            uint32_t p01 = p00 + (uint32_t)j.nu, p11 = p01 + 1;
            *t++ = p00, *t++ = p10, *t++ = p11;
            *t++ = p00, *t++ = p11, *t++ = p01;
        }
    return 0;
}

const ms_rep_method ms_rep_volumeslice = {
    "VolumeSlice", 4,
    {{"slice", 0.5f}, {"volid", 0.0f}, {"axis", 0.0f}, {"quality", 2.0f}},
    MS_REP_VOLUME, build};
