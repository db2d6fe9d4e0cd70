/* strokes.c: lines, points and text for the ray tracer, drawn as the Tachyon exporter draws
 * them: a line is a thin open cylinder (radius 0.002 per unit of VMD's width; dashed lines in
 * VMD's dashes), a point a small sphere, text the strokes of molscope's font as cylinders
 * with spheres at their joints, all in world space (text faces the screen). */
#include "config.h"
#include "rt/rt_common.h"
#include "render/export.h"
#include "vecmath/vecf.h"

#include <string.h>

typedef struct strokes {
    ms_displaylist *dl;
    ms_rgba8 col;
    float radius, last[3];
    int have_last, oom;
} strokes;

static void stroke(void *ud, const float a[3], const float b[3])
{
    strokes *s = ud;
    if (!s->have_last || memcmp(s->last, a, sizeof s->last))
        s->oom |= ms_dl_sphere(s->dl, a, s->radius, s->col, 12);
    s->oom |= ms_dl_cylinder(s->dl, a, b, s->radius, s->col, 0, 12);
    s->oom |= ms_dl_sphere(s->dl, b, s->radius, s->col, 12);
    memcpy(s->last, b, sizeof s->last);
    s->have_last = 1;
}

static void dash(void *ud, const float a[3], const float b[3])
{
    strokes *s = ud;
    s->oom |= ms_dl_cylinder(s->dl, a, b, s->radius, s->col, 0, 12);
}

/* Lines, points and text of a placed list as world-space cylinders and spheres (sizes in
 * world units, as the exporter writes them). */
int rt_strokes(const ms_scene_item *it, ms_displaylist *out)
{
    const ms_displaylist *dl = it->dl;
    strokes s = {out, {0, 0, 0, 0}, 0, {0, 0, 0}, 0, 0};
    for (size_t i = 0; i < dl->lines.n; i++) {
        float a[3], b[3];
        ms_mat4_point(it->xform, dl->lines.a + 3 * i, a);
        ms_mat4_point(it->xform, dl->lines.b + 3 * i, b);
        s.radius = dl->lines.width[i] * MS_EXPORT_LINE_RADIUS;
        s.col = dl->lines.color[i];
        if (dl->lines.style[i] == MS_LINE_DASHED) ms_export_dashes(a, b, dash, &s);
        else s.oom |= ms_dl_cylinder(out, a, b, s.radius, s.col, 0, 12);
    }
    for (size_t i = 0; i < dl->points.n; i++) {
        float c[3];
        ms_mat4_point(it->xform, dl->points.xyz + 3 * i, c);
        s.oom |= ms_dl_sphere(out, c, dl->points.size[i] * MS_EXPORT_LINE_RADIUS, dl->points.color[i], 12);
    }
    for (size_t i = 0; i < dl->texts.n; i++) {
        float c[3];
        ms_mat4_point(it->xform, dl->texts.xyz + 3 * i, c);
        s.radius = dl->texts.thickness[i] * MS_EXPORT_LINE_RADIUS;
        s.col = dl->texts.color[i];
        s.have_last = 0;
        ms_export_text(dl->texts.chars + dl->texts.start[i], c, dl->texts.size[i], stroke, &s);
    }
    return s.oom ? -1 : 0;
}
