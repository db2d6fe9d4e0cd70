/* graphics.c: user graphics items, VMD's id and replace rules, their descriptions, and
 * turning them into display lists.
 *
 * Item layouts (ms_ug_item):
 *   point     data[0..2]
 *   line      data[0..5], iv[0] style (MS_LINE_*), iv[1] width
 *   cylinder  data[0..5], radius, iv[0] resolution, iv[1] filled
 *   cone      data[0..5], radius (base), radius2 (apex), iv[0] resolution
 *   sphere    data[0..2], radius, iv[0] resolution
 *   triangle  data[0..8]
 *   trinorm   data[0..17] (vertices, then unit normals)
 *   tricolor  data[0..17], iv[0..2] colour ids
 *   text      data[0..2], size, thickness, text
 *   color     iv[0] colour id;  material iv[0] material id;  materials iv[0] on/off */
#include "config.h"
#include "scene/graphics.h"

#include <math.h>
#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

ms_ugraphics *ms_ugraphics_new(void)
{
    return calloc(1, sizeof(ms_ugraphics));
}

static void free_lists(ms_ugraphics *g)
{
    for (size_t i = 0; i < g->caplists; i++) ms_dl_free(&g->lists[i]);
    free(g->lists);
    g->lists = NULL;
    g->nlists = g->caplists = 0;
}

void ms_ugraphics_free(ms_ugraphics *g)
{
    if (!g) return;
    for (size_t i = 0; i < g->n; i++) free(g->items[i].text);
    free(g->items);
    free_lists(g);
    free(g);
}

/* ---------------------------------------------------------------- ids */

long ms_ugraphics_find(const ms_ugraphics *g, int id)
{
    /* ids increase along the list (a replaced item keeps its place), so bisect */
    size_t lo = 0, hi = g->n;
    while (lo < hi) {
        size_t mid = (lo + hi) / 2;
        if (g->items[mid].id < id) lo = mid + 1;
        else hi = mid;
    }
    if (lo < g->n && g->items[lo].id == id && g->items[lo].kind != MS_UG_NONE) return (long)lo;
    return -1;
}

int ms_ugraphics_add(ms_ugraphics *g, const ms_ug_item *item)
{
    ms_ug_item it = *item;
    if (item->text && !(it.text = ms_strdup(item->text))) return -1;
    if (g->next_index >= g->n) {
        if (ms_grow((void **)&g->items, &g->cap, g->n + 1, sizeof *g->items)) {
            free(it.text);
            return -1;
        }
        g->next_index = g->n++;
    } else {
        free(g->items[g->next_index].text);
    }
    it.id = g->next_id;
    g->items[g->next_index] = it;
    if (g->next_id == g->max_id) g->max_id++;
    g->next_id = g->max_id;
    g->next_index = g->n;
    g->dirty = 1;
    return it.id;
}

/* Drop the places left empty by replace. */
static void compact(ms_ugraphics *g)
{
    size_t j = 0;
    for (size_t i = 0; i < g->n; i++) {
        if (g->items[i].kind == MS_UG_NONE) {
            free(g->items[i].text);
            continue;
        }
        g->items[j++] = g->items[i];
    }
    g->n = j;
}

void ms_ugraphics_delete(ms_ugraphics *g, int id)
{
    long i = ms_ugraphics_find(g, id);
    if (i < 0) return;
    g->items[i].kind = MS_UG_NONE;
    compact(g);
    /* a delete cancels a pending replace */
    g->next_id = g->max_id;
    g->next_index = g->n;
    g->dirty = 1;
}

void ms_ugraphics_delete_all(ms_ugraphics *g)
{
    for (size_t i = 0; i < g->n; i++) free(g->items[i].text);
    g->n = 0;
    g->next_id = g->max_id = 0;
    g->next_index = 0;
    g->dirty = 1;
}

int ms_ugraphics_replace(ms_ugraphics *g, int id)
{
    long i = ms_ugraphics_find(g, id);
    if (i < 0) return -1;
    if (g->next_index < g->n && g->items[g->next_index].kind == MS_UG_NONE) {
        /* an earlier replace was never used: forget its place */
        int keep = id;
        g->items[g->next_index].kind = MS_UG_NONE;
        compact(g);
        i = ms_ugraphics_find(g, keep);
    }
    free(g->items[i].text);
    g->items[i].text = NULL;
    g->items[i].kind = MS_UG_NONE;
    g->next_id = id;
    g->next_index = (size_t)i;
    g->dirty = 1;
    return 0;
}

/* ---------------------------------------------------------------- info */

static int vec_str(char *buf, size_t size, const float *v)
{
    return snprintf(buf, size, "{%f %f %f}", v[0], v[1], v[2]);
}

/* Append printf output to buf at *pos, never past size. */
static void put(char *buf, size_t size, size_t *pos, const char *fmt, ...)
    __attribute__((format(printf, 4, 5)));
static void put(char *buf, size_t size, size_t *pos, const char *fmt, ...)
{
    if (*pos >= size) return;
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf + *pos, size - *pos, fmt, ap);
    va_end(ap);
    if (n > 0) *pos += (size_t)n;
}

static void put_vecs(char *buf, size_t size, size_t *pos, const float *v, int n)
{
    char t[128];
    for (int i = 0; i < n; i++) {
        vec_str(t, sizeof t, v + 3 * i);
        put(buf, size, pos, " %s", t);
    }
}

void ms_ugraphics_info(const ms_ugraphics *g, long index, const ms_materials *mats, char *buf,
                       size_t size)
{
    const ms_ug_item *it = &g->items[index];
    size_t pos = 0;
    static const char *const names[] = {"", "point", "line", "cylinder", "cone", "sphere",
                                        "triangle", "trinorm", "tricolor", "text", "color",
                                        "material", "materials"};
    if (size) buf[0] = '\0';
    put(buf, size, &pos, "%s", names[it->kind]);
    switch (it->kind) {
    case MS_UG_POINT: case MS_UG_SPHERE: case MS_UG_TEXT: put_vecs(buf, size, &pos, it->data, 1); break;
    case MS_UG_LINE: case MS_UG_CYLINDER: case MS_UG_CONE: put_vecs(buf, size, &pos, it->data, 2); break;
    case MS_UG_TRIANGLE: put_vecs(buf, size, &pos, it->data, 3); break;
    case MS_UG_TRINORM: case MS_UG_TRICOLOR: put_vecs(buf, size, &pos, it->data, 6); break;
    default: break;
    }
    switch (it->kind) {
    case MS_UG_LINE:
        put(buf, size, &pos, " style %s width %d", it->iv[0] ? "dashed" : "solid", it->iv[1]);
        break;
    case MS_UG_CYLINDER:
        put(buf, size, &pos, " radius %f resolution %d filled %d", it->radius, it->iv[0], it->iv[1]);
        break;
    case MS_UG_CONE:
        put(buf, size, &pos, " radius %f radius2 %f resolution %d", it->radius, it->radius2, it->iv[0]);
        break;
    case MS_UG_SPHERE:
        put(buf, size, &pos, " radius %f resolution %d", it->radius, it->iv[0]);
        break;
    case MS_UG_TRICOLOR:
        put(buf, size, &pos, " %d %d %d", it->iv[0], it->iv[1], it->iv[2]);
        break;
    case MS_UG_TEXT:
        put(buf, size, &pos, " {%s} size %f thickness %f", it->text ? it->text : "", it->size,
            it->thickness);
        break;
    case MS_UG_COLOR: case MS_UG_MATERIALS:
        put(buf, size, &pos, " %d", it->iv[0]);
        break;
    case MS_UG_MATERIAL: {
        const ms_material *mat = ms_material_by_id(mats, it->iv[0]);
        put(buf, size, &pos, " %d", (int)(mat - mats->list));
        break;
    }
    default:
        break;
    }
}

/* ---------------------------------------------------------------- display lists */

static ms_displaylist *new_list(ms_ugraphics *g, int material, int lit)
{
    if (g->nlists == g->caplists) {
        size_t old = g->caplists;
        if (ms_grow((void **)&g->lists, &g->caplists, g->nlists + 1, sizeof *g->lists)) return NULL;
        for (size_t i = old; i < g->caplists; i++) ms_dl_init(&g->lists[i]);
    }
    ms_displaylist *dl = &g->lists[g->nlists++];
    ms_dl_clear(dl);
    dl->material = material;
    dl->lit = lit;
    return dl;
}

static void face_normal(const float *p, float n[3])
{
    float u[3], v[3];
    for (int k = 0; k < 3; k++) {
        u[k] = p[3 + k] - p[k];
        v[k] = p[6 + k] - p[k];
    }
    n[0] = u[1] * v[2] - u[2] * v[1];
    n[1] = u[2] * v[0] - u[0] * v[2];
    n[2] = u[0] * v[1] - u[1] * v[0];
    float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] = len > 0 ? n[k] / len : (k == 2);
}

static ms_rgba8 color_of(const ms_colors *c, int id)
{
    return ms_rgba8_from_float(ms_color_rgb(c, id), 1.0f);
}

/* Append one drawing item to dl in colour col; 0 or -1. */
static int draw_item(ms_displaylist *dl, const ms_ug_item *it, const ms_colors *c, ms_rgba8 col)
{
    const float *d = it->data;
    switch (it->kind) {
    case MS_UG_POINT: return ms_dl_point(dl, d, 1.0f, col);
    case MS_UG_LINE: return ms_dl_line(dl, d, d + 3, (float)it->iv[1], col, it->iv[0]);
    case MS_UG_CYLINDER:
        return ms_dl_cylinder(dl, d, d + 3, it->radius, col,
                              it->iv[1] ? MS_CAP_BASE | MS_CAP_APEX : 0, it->iv[0]);
    case MS_UG_CONE: return ms_dl_cone(dl, d, d + 3, it->radius, it->radius2, col, it->iv[0]);
    case MS_UG_SPHERE: return ms_dl_sphere(dl, d, it->radius, col, it->iv[0]);
    case MS_UG_TEXT: return ms_dl_text(dl, d, it->text ? it->text : "", it->size, it->thickness, col);
    case MS_UG_TRIANGLE: {
        float n[9];
        face_normal(d, n);
        memcpy(n + 3, n, 3 * sizeof(float));
        memcpy(n + 6, n, 3 * sizeof(float));
        ms_rgba8 cols[3] = {col, col, col};
        return ms_dl_triangle(dl, d, n, cols);
    }
    case MS_UG_TRINORM: {
        ms_rgba8 cols[3] = {col, col, col};
        return ms_dl_triangle(dl, d, d + 9, cols);
    }
    case MS_UG_TRICOLOR: {
        ms_rgba8 cols[3];
        for (int k = 0; k < 3; k++) cols[k] = color_of(c, it->iv[k]);
        return ms_dl_triangle(dl, d, d + 9, cols);
    }
    default:
        return 0;
    }
}

int ms_ugraphics_update(ms_ugraphics *g, const ms_colors *colors, ms_error *err)
{
    if (!g->dirty && g->built_colors == colors->version && g->nlists) return 0;
    g->nlists = 0;
    int material = 0, lit = 1;
    ms_rgba8 col = color_of(colors, 0);
    ms_displaylist *dl = new_list(g, material, lit);
    for (size_t i = 0; dl && i < g->n; i++) {
        const ms_ug_item *it = &g->items[i];
        if (it->kind == MS_UG_COLOR) {
            col = color_of(colors, it->iv[0]);
        } else if (it->kind == MS_UG_MATERIAL || it->kind == MS_UG_MATERIALS) {
            if (it->kind == MS_UG_MATERIAL) material = it->iv[0];
            else lit = it->iv[0] != 0;
            if (material == dl->material && lit == dl->lit) continue;
            if (ms_dl_count(dl) == 0) {
                dl->material = material;
                dl->lit = lit;
            } else {
                dl = new_list(g, material, lit);
            }
        } else if (draw_item(dl, it, colors, col)) {
            dl = NULL;
        }
    }
    if (!dl) {
        g->nlists = 0;
        ms_error_set(err, "out of memory building user graphics");
        return -1;
    }
    g->dirty = 0;
    g->built_colors = colors->version;
    return 0;
}

/* ---------------------------------------------------------------- centre */

int ms_ugraphics_cov(const ms_ugraphics *g, float center[3], float *scale)
{
    float lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int any = 0;
    for (size_t i = 0; i < g->n; i++) {
        const ms_ug_item *it = &g->items[i];
        int npts = it->kind == MS_UG_POINT || it->kind == MS_UG_SPHERE || it->kind == MS_UG_TEXT ? 1
                   : it->kind == MS_UG_LINE || it->kind == MS_UG_CYLINDER || it->kind == MS_UG_CONE ? 2
                   : it->kind >= MS_UG_TRIANGLE && it->kind <= MS_UG_TRICOLOR ? 3 : 0;
        for (int p = 0; p < npts; p++)
            for (int k = 0; k < 3; k++) {
                float v = it->data[3 * p + k];
                if (!any || v < lo[k]) lo[k] = v;
                if (!any || v > hi[k]) hi[k] = v;
                if (k == 2) any = 1;
            }
    }
    if (!any) return 0;
    float ext = 0;
    for (int k = 0; k < 3; k++) {
        center[k] = (lo[k] + hi[k]) / 2;
        ext = MS_MAX(ext, hi[k] - lo[k]);
    }
    *scale = 2.0f / (ext > 0 ? ext : 10.0f);
    return 1;
}
