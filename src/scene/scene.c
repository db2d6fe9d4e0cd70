/* scene.c: the scene a device draws: placing display lists and VMD's camera projection (the
 * scene is assembled from the molecules in assemble/build.c). */
#include "config.h"
#include "scene/scene.h"
#include "vecmath/vecf.h"

#include "vecmath/vecmath.h"

#include <stdlib.h>
#include <string.h>

void ms_scene_init(ms_scene *s)
{
    memset(s, 0, sizeof *s);
    s->aa_samples = 12;
    s->ao_samples = 12;
}

void ms_scene_free(ms_scene *s)
{
    for (size_t i = 0; i < s->nowned; i++) {
        ms_dl_free(s->owned[i]);
        free(s->owned[i]);
    }
    free(s->owned);
    free(s->items);
    ms_scene_init(s);
}

int ms_scene_add(ms_scene *s, const ms_displaylist *dl, const float xform[16],
                 const ms_materials *mats, ms_error *err)
{
    if (ms_grow((void **)&s->items, &s->capitems, s->nitems + 1, sizeof *s->items)) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    ms_scene_item *it = &s->items[s->nitems++];
    it->dl = dl;
    memcpy(it->xform, xform, sizeof it->xform);
    it->mat = *ms_material_by_id(mats, dl->material);
    it->nclip = 0;
    return 0;
}

int ms_plane_map(const float eq[4], const float m[16], float out[4])
{
    double a[16], inv[16];
    for (int i = 0; i < 16; i++) a[i] = m[i];
    float e[4] = {eq[0], eq[1], eq[2], eq[3]};
    if (ms_mat4d_inverse(a, inv)) {
        memcpy(out, e, sizeof e);
        return -1;
    }
    for (int c = 0; c < 4; c++)
        out[c] = (float)(e[0] * inv[c] + e[1] * inv[4 + c] + e[2] * inv[8 + c] + e[3] * inv[12 + c]);
    return 0;
}

void ms_scene_clip_last(ms_scene *s, const ms_clip *clips, int n, const float model[16])
{
    if (!s->nitems) return;
    ms_scene_item *it = &s->items[s->nitems - 1];
    it->nclip = 0;
    for (int i = 0; i < n && i < MS_SCENE_CLIPS; i++) {
        const ms_clip *c = &clips[i];
        if (c->mode == MS_CLIP_OFF) continue;
        /* kept: (p - center) . normal <= 0 */
        float eq[4] = {-c->normal[0], -c->normal[1], -c->normal[2],
                       c->normal[0] * c->center[0] + c->normal[1] * c->center[1] +
                           c->normal[2] * c->center[2]};
        ms_clip_plane *cp = &it->clip[it->nclip++];
        ms_plane_map(eq, model, cp->eq);
        memcpy(cp->color, c->color, sizeof cp->color);
        cp->solid = c->mode == MS_CLIP_SOLID;
    }
}

ms_displaylist *ms_scene_new_list(ms_scene *s, ms_error *err)
{
    ms_displaylist *dl = malloc(sizeof *dl);
    if (!dl || ms_grow((void **)&s->owned, &s->capowned, s->nowned + 1, sizeof *s->owned)) {
        free(dl);
        ms_error_set(err, "out of memory");
        return NULL;
    }
    ms_dl_init(dl);
    s->owned[s->nowned++] = dl;
    return dl;
}

/* ---------------------------------------------------------------- camera */

/* Distance from the eye to the screen plane, and the visible half-height there. */
static float screen_dist(const ms_camera *c)
{
    return c->eye[2] - c->distance;
}

int ms_scene_project(const ms_scene *s, const float world[3], float *px, float *py, float *depth)
{
    const ms_camera *c = &s->settings.cam;
    float right[3] = {c->dir[1] * c->up[2] - c->dir[2] * c->up[1],
                      c->dir[2] * c->up[0] - c->dir[0] * c->up[2],
                      c->dir[0] * c->up[1] - c->dir[1] * c->up[0]};
    float rel[3] = {world[0] - c->eye[0], world[1] - c->eye[1], world[2] - c->eye[2]};
    float xe = ms_v3f_dot(rel, right), ye = ms_v3f_dot(rel, c->up), d = ms_v3f_dot(rel, c->dir);
    float half_h, xs, ys;
    if (c->projection == MS_PROJ_ORTHOGRAPHIC) {
        half_h = c->height / 4.0f;
        xs = xe;
        ys = ye;
    } else {
        if (d <= 0) return -1;
        half_h = c->height / 2.0f;
        xs = xe * screen_dist(c) / d;
        ys = ye * screen_dist(c) / d;
    }
    float aspect = (float)s->width / (float)s->height;
    *px = 0.5f * (float)s->width * (1.0f + xs / (half_h * aspect));
    *py = 0.5f * (float)s->height * (1.0f - ys / half_h);
    if (depth) *depth = d;
    return 0;
}

float ms_scene_pixel_size(const ms_scene *s, float depth)
{
    const ms_camera *c = &s->settings.cam;
    if (c->projection == MS_PROJ_ORTHOGRAPHIC) return c->height / 2.0f / (float)s->height;
    return c->height * depth / (screen_dist(c) * (float)s->height);
}
