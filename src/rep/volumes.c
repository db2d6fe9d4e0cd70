/* volumes.c: what the volume methods (Isosurface, VolumeSlice) share: the data set a rep
 * names, the colours VMD draws volumes with (one solid colour from ColorID or Molecule,
 * else Display Foreground; the box's axis colours), the colour range of volume values, and
 * points coloured by a volume's values through the colour scale. */
#include "config.h"
#include "rep/rep_int.h"
#include "base/threads.h"

#include <stdio.h>

static int item(ms_colors *c, const char *cat, const char *name)
{
    int col = ms_color_item_get(c, ms_color_category_index(c, cat), name);
    return col < 0 ? 0 : col;
}

void ms_rep_volume_colors(ms_colors *colors, ms_molecule *m, const ms_rep_coloring *c,
                          ms_rep_volcolors *out)
{
    static const char *const axis[3] = {"X", "Y", "Z"};
    out->box = item(colors, "Display", "Foreground");
    for (int k = 0; k < 3; k++) out->axis[k] = item(colors, "Axes", axis[k]);
    out->solid = out->box;
    if (c->method == MS_COL_COLORID) {
        out->solid = c->index;
    } else if (c->method == MS_COL_MOLECULE) {
        char id[32];
        snprintf(id, sizeof id, "%d", m->id);
        int col = ms_color_item_add(colors, ms_color_category_index(colors, "Molecule"), id, -1);
        out->solid = col < 0 ? out->box : col;
    }
}

const ms_volume *ms_rep_volume(const ms_rep_build *b, float k)
{
    if (!(k >= 0.0f) || k >= (float)b->m->nvolumes) return NULL;
    const ms_volume *v = &b->m->volumes[(size_t)k];
    return v->data && ms_volume_size(v) ? v : NULL;
}

void ms_rep_volume_range(const ms_rep_build *b, const ms_volume *v, float *lo, float *hi)
{
    int scaled = ms_rep_coloring_scaled(b->coloring->method);
    *lo = scaled ? b->cmin : 0.0f;
    *hi = scaled ? b->cmax : 0.0f;
    if (*lo == 0.0f && *hi == 0.0f) {
        *lo = v->min;
        *hi = v->max;
    }
}

typedef struct scale_job {
    ms_volume_sampler s;
    const float *xyz;
    ms_rgba8 *out;
    const ms_rgba8 *palette;
    float lo, hi;
} scale_job;

static void scale_range(void *ctx, size_t begin, size_t end, int thread)
{
    scale_job *j = ctx;
    (void)thread;
    for (size_t i = begin; i < end; i++) {
        float v = ms_volume_sample(&j->s, j->xyz + 3 * i);
        j->out[i] = j->palette[ms_color_scale_index(v, j->lo, j->hi)];
    }
}

void ms_rep_color_by_volume(const ms_rep_build *b, const ms_volume *v, float lo, float hi,
                            const float *xyz, size_t n, ms_rgba8 *out)
{
    scale_job j = {.xyz = xyz, .out = out, .palette = b->palette, .lo = lo, .hi = hi};
    ms_volume_sampler_init(&j.s, v);
    ms_parallel_for(n, 4096, scale_range, &j);
}
