/* test_scene.c: unit tests of the scene module: display list growth and bounds, normal
 * quantization (OpenGL 1.2.1 table 2.6), VMD's colour scale formula and default colours,
 * materials' shininess scale, matrices, the camera projection, tessellation, the stroke
 * font, user graphics ids (VMD's replace and delete rules), and the level of detail
 * (lod.h: triangle bound, bounding box within a cell, mean colours and normals, no
 * degenerate triangle, the scene's cache). Expected values are worked
 * out by hand from the formulas in doc/vmd-behaviour.md. */
#include "config.h"
#include "ms_test.h"
#include "render/export.h"
#include "scene/color.h"
#include "scene/displaylist.h"
#include "scene/graphics.h"
#include "scene/lod.h"
#include "vecmath/vecf.h"
#include "scene/material.h"
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

static int near(float a, float b, float tol) { return fabsf(a - b) <= tol; }

static void test_displaylist(void)
{
    t_suite = "displaylist";
    ms_displaylist dl;
    ms_dl_init(&dl);
    ms_error err = {{0}};
    ms_rgba8 red = {255, 0, 0, 255};
    int ok = 1;
    for (int i = 0; i < 100000; i++) {
        float c[3] = {(float)i, -(float)i, 0.5f};
        ok &= ms_dl_sphere(&dl, c, 1.0f, red, 12) == 0;
    }
    t_ok(ok && dl.spheres.n == 100000 && dl.spheres.xyz[3 * 99999] == 99999.0f,
         "100000 spheres appended past the first capacity");
    long first = ms_dl_extend(&dl, MS_DL_SPHERES, 1000, &err);
    t_ok(first == 100000 && dl.spheres.n == 101000, "extend claims a block at the end (%ld)", first);
    for (int i = 0; i < 1000; i++) {
        float *p = dl.spheres.xyz + 3 * (first + i);
        p[0] = p[1] = p[2] = 0;
        dl.spheres.radius[first + i] = 2;
        dl.spheres.color[first + i] = red;
        dl.spheres.res[first + i] = 6;
    }
    float lo[3], hi[3];
    t_ok(ms_dl_bounds(&dl, lo, hi) && lo[0] == 0 && hi[0] == 99999 && lo[1] == -99999 && hi[2] == 0.5f,
         "bounds span the spheres' centres");
    float a[3] = {0, 0, 0}, b[3] = {0, 0, 5};
    ms_dl_cylinder(&dl, a, b, 0.5f, red, MS_CAP_BASE, 12);
    ms_dl_text(&dl, a, "hello", 1, 1, red);
    ms_dl_text(&dl, b, "world", 1, 1, red);
    t_ok(!strcmp(dl.texts.chars + dl.texts.start[1], "world"), "texts keep their strings");
    float p[9] = {0, 0, 0, 1, 0, 0, 0, 1, 0}, n[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    ms_rgba8 cols[3] = {red, red, red};
    ms_dl_triangle(&dl, p, n, cols);
    t_ok(dl.mesh.nverts == 3 && dl.mesh.ntris == 1 && dl.mesh.tri[2] == 2 && dl.mesh.normal[2] == 127,
         "a triangle is three vertices and one face with quantized normals");
    t_ok(ms_dl_count(&dl) == 101000 + 1 + 2 + 1, "count of every primitive");
    ms_dl_clear(&dl);
    t_ok(ms_dl_count(&dl) == 0 && dl.spheres.cap >= 101000, "clear keeps the memory");
    ms_dl_free(&dl);
    t_ok(dl.spheres.cap == 0 && dl.lit == 1, "free releases it");
    t_ok(ms_dl_extend(&dl, MS_DL_SPHERES, (size_t)-1 / 2, &err) < 0 && strstr(err.msg, "memory"),
         "an impossible block is refused with an error");
    ms_dl_free(&dl);
}

/* A bond is one cylinder; its pieces are VMD's two halves, in the list's order or the one
 * set, and a plain cylinder is one piece. */
static void test_bond_pieces(void)
{
    t_suite = "bond pieces";
    ms_displaylist dl;
    ms_dl_init(&dl);
    ms_error err = {{0}};
    ms_rgba8 red = {255, 0, 0, 255}, blue = {0, 0, 255, 255};
    float a[3] = {0, 0, 0}, j[3] = {1, 0, 0}, b[3] = {2, 0, 0}, c[3] = {0, 3, 0};
    ms_dl_bond(&dl, a, j, b, 0.2f, red, blue, MS_CAP_APEX, 12);
    ms_dl_cylinder(&dl, a, c, 0.1f, red, 0, 12);
    ms_dl_bond(&dl, c, j, b, 0.2f, blue, red, MS_CYL_INWARD, 12);
    t_ok(dl.cylinders.n == 3 && ms_dl_piece_count(&dl.cylinders) == 5, "3 cylinders, 5 pieces (%zu)",
         ms_dl_piece_count(&dl.cylinders));
    ms_dl_pieces it = ms_dl_pieces_of(&dl.cylinders);
    ms_dl_piece p[6];
    int n = 0;
    while (n < 6 && ms_dl_pieces_next(&it, &p[n])) n++;
    t_ok(n == 5, "the walk gives every piece (%d)", n);
    t_ok(p[0].a[0] == 0 && p[0].b[0] == 1 && p[0].color.r == 255 && p[0].caps == 0 &&
         p[1].a[0] == 1 && p[1].b[0] == 2 && p[1].color.b == 255 && p[1].caps == MS_CAP_APEX,
         "a bond: base to joint in colour 1, joint to apex in colour 2, its apex cap on the second");
    t_ok(p[2].cylinder == 1 && p[2].b[1] == 3, "a plain cylinder is one piece");
    t_ok(p[3].a[1] == 3 && p[3].b[0] == 1 && p[4].a[0] == 2 && p[4].b[0] == 1 && p[4].color.r == 255,
         "inward halves: each from its end to the joint");
    uint32_t *o = ms_dl_cylinder_order(&dl, 5, &err);
    uint32_t want[5] = {2 * 2 + 1, 2 * 0, 2 * 1, 2 * 2, 2 * 0 + 1};
    memcpy(o, want, sizeof want);
    it = ms_dl_pieces_of(&dl.cylinders);
    n = 0;
    while (n < 6 && ms_dl_pieces_next(&it, &p[n])) n++;
    t_ok(n == 5 && p[0].cylinder == 2 && p[0].a[0] == 2 && p[1].cylinder == 0 && p[4].b[0] == 2,
         "a set order is followed");
    ms_dl_cylinder(&dl, a, c, 0.1f, red, 0, 12);
    t_ok(dl.cylinders.norder == 0 && ms_dl_piece_count(&dl.cylinders) == 6,
         "appending a cylinder drops the order");
    ms_dl_free(&dl);
    t_ok(dl.cylinders.order == NULL && dl.cylinders.n == 0, "free releases the order");
}

static void test_normals(void)
{
    t_suite = "normals";
    /* table 2.6: f = (2c + 1) / 255 */
    t_ok(ms_normal_dequantize(127) == 1.0f && ms_normal_dequantize(-128) == -1.0f,
         "127 and -128 are +1 and -1");
    t_ok(near(ms_normal_dequantize(0), 1.0f / 255.0f, 1e-7f), "0 is 1/255");
    t_ok(ms_normal_quantize(1.0f) == 127 && ms_normal_quantize(-1.0f) == -128 &&
         ms_normal_quantize(2.0f) == 127, "the ends quantize to 127 and -128 (clamped)");
    float worst = 0;
    for (int i = -1000; i <= 1000; i++) {
        float f = i / 1000.0f;
        worst = fmaxf(worst, fabsf(ms_normal_dequantize(ms_normal_quantize(f)) - f));
    }
    t_ok(worst <= 1.0f / 255.0f + 1e-6f, "round trip within one step (%g)", worst);
}

static void test_colors(void)
{
    t_suite = "color";
    ms_error err = {{0}};
    ms_colors *c = ms_colors_new(&err);
    t_ok(c != NULL, "created");
    if (!c) return;
    const float *cyan = ms_color_rgb(c, ms_color_index(c, "cyan"));
    t_ok(ms_color_index(c, "cyan") == 10 && cyan[0] == .25f && cyan[1] == .75f, "cyan is 10");
    t_ok(ms_color_index(c, "Orange3") == 32 && ms_color_index(c, "1056") == 1056 &&
         ms_color_index(c, "1057") == -1 && ms_color_index(c, "nope") == -1, "names and ids");
    /* RWB with midpoint 0.5 and offset 0.1 (hand-computed) */
    const float *s0 = ms_color_rgb(c, 33), *s256 = ms_color_rgb(c, 33 + 256), *s1023 = ms_color_rgb(c, 1056);
    t_ok(s0[0] == 1 && near(s0[1], 0.1f, 1e-6f) && near(s0[2], 0.1f, 1e-6f), "scale start: red + 0.1");
    t_ok(s256[0] == 1 && near(s256[1], 0.600489f, 1e-5f) && near(s256[2], 0.600489f, 1e-5f),
         "scale 256: (1, 0.600489, 0.600489)");
    t_ok(near(s1023[0], 0.1f, 1e-6f) && s1023[2] == 1, "scale end: blue + 0.1");
    t_ok(ms_color_scale_index(0.5f, 0, 1) == 544 && ms_color_scale_index(1, 0, 1) == 1056 &&
         ms_color_scale_index(-3, 0, 1) == 33 && ms_color_scale_index(2, 2, 2) == 545,
         "value to scale index, clamped, min == max gives the middle");
    int name = ms_color_category_index(c, "Name"), res = ms_color_category_index(c, "Resname");
    t_ok(ms_color_for_value(c, name, "1HB") == 8 && ms_color_for_value(c, name, "CA") == 10,
         "Name keyed by the first non-digit letter (1HB white, CA cyan)");
    size_t n0 = c->cats[res].n;
    int first = ms_color_for_value(c, res, "XYZ"), second = ms_color_for_value(c, res, "XYY");
    t_ok(first == (int)(n0 % 32) && second == (int)((n0 + 1) % 32),
         "new residue names take the item count mod 32 (%d, %d)", first, second);
    unsigned long v = c->version;
    t_ok(ms_color_item_set(c, res, "XYZ", 1) == 0 && c->version > v && ms_color_item_get(c, res, "XYZ") == 1,
         "setting an item bumps the version");
    t_ok(ms_color_set_restype(c, "XYZ", "Acidic") == 0 && !strcmp(ms_color_restype(c, "XYZ"), "Acidic") &&
         ms_color_set_restype(c, "XYZ", "Sour") < 0 && !strcmp(ms_color_restype(c, "ALA"), "Nonpolar"),
         "residue types");
    ms_colors_free(c);
}

static void test_materials(void)
{
    t_suite = "material";
    ms_error err = {{0}};
    ms_materials *m = ms_materials_new(&err);
    t_ok(m && m->n == 23, "23 default materials");
    if (!m) return;
    t_ok(near(ms_material_shininess_from_ui(0.534f), 40.0f, 0.05f) &&
         near(ms_material_shininess_to_ui(40.0f), 0.534020f, 1e-5f), "1000^0.534 is 40");
    int g = ms_material_index(m, "glossy");
    t_ok(g == 8 && m->list[g].specular == 1.0f && near(ms_material_get(&m->list[g], MS_MAT_SHININESS), 0.88f, 1e-5f),
         "Glossy: specular 1, shininess 0.88");
    int i = ms_material_add(m, NULL, g, &err);
    t_ok(i == 23 && !strcmp(m->list[i].name, "Material23") && m->list[i].specular == 1.0f,
         "an unnamed copy is Material23");
    int id = m->list[i].id;
    t_ok(ms_material_delete(m, 0, &err) < 0 && ms_material_delete(m, i, &err) == 0 &&
         ms_material_by_id(m, id) == &m->list[0], "Opaque stays; a deleted id falls back to Opaque");
    ms_material_set(m, g, MS_MAT_SPECULAR, 0.25f);
    t_ok(ms_material_restore_default(m, g, &err) == 0 && m->list[g].specular == 1.0f, "default restores");
    ms_materials_free(m);
}

static void test_matrices_and_camera(void)
{
    t_suite = "camera";
    float r[16], p[3], x[3] = {1, 0, 0};
    ms_mat4_axis_rotation(r, 'z', ms_deg_rad(90));
    ms_mat4_point(r, x, p);
    t_ok(near(p[0], 0, 1e-6f) && near(p[1], 1, 1e-6f), "z 90 turns x into y");
    ms_mat4_scaling(r, 0.25f);
    t_ok(near(ms_mat4_scale_factor(r), 0.25f, 1e-6f), "scale factor");
    ms_scene s;
    ms_scene_init(&s);
    s.width = 400;
    s.height = 200;
    s.settings.cam.projection = MS_PROJ_PERSPECTIVE;
    s.settings.cam.eye[2] = 2;
    s.settings.cam.dir[2] = -1;
    s.settings.cam.up[1] = 1;
    s.settings.cam.height = 6;
    s.settings.cam.distance = -2;
    float px, py, d, o[3] = {0, 0, 0}, top[3] = {0, 1.5f, 0}, side[3] = {1.5f, 0, -2};
    ms_scene_project(&s, o, &px, &py, &d);
    t_ok(px == 200 && py == 100 && d == 2, "the origin is the image centre, 2 from the eye");
    ms_scene_project(&s, top, &px, &py, &d);
    t_ok(near(py, 0, 1e-4f), "y 1.5 at z 0 is the top edge (half-height 0.75 per unit depth)");
    ms_scene_project(&s, side, &px, &py, &d);
    t_ok(near(px, 200 + 200 * (1.5f * 4 / 4) / (3 * 2), 1e-3f), "x at depth 4 (%g)", px);
    s.settings.cam.projection = MS_PROJ_ORTHOGRAPHIC;
    ms_scene_project(&s, top, &px, &py, &d);
    t_ok(near(py, 0, 1e-4f) && near(ms_scene_pixel_size(&s, 5), 3.0f / 200, 1e-6f),
         "orthographic: half-height 1.5 at every depth");
}

static void count_tri(void *ud, const float p[9], const float n[9])
{
    int *k = ud;
    float c[3] = {1, 2, 3};
    for (int v = 0; v < 3; v++) {
        float d = sqrtf(powf(p[3 * v] - c[0], 2) + powf(p[3 * v + 1] - c[1], 2) + powf(p[3 * v + 2] - c[2], 2));
        if (fabsf(d - 2.0f) > 1e-4f) k[1]++;
    }
    k[0]++;
}

static void count_seg(void *ud, const float a[3], const float b[3])
{
    ++*(int *)ud;
}

static void test_tessellation(void)
{
    t_suite = "tessellation";
    int k[2] = {0, 0};
    float c[3] = {1, 2, 3};
    ms_tess_sphere(c, 2.0f, 6, count_tri, k);
    t_ok(k[0] == 2 * 12 * 5 && k[1] == 0, "sphere res 6: 120 triangles, every vertex on the sphere");
    k[0] = 0;
    float a[3] = {0, 0, 0}, b[3] = {0, 0, 1};
    ms_tess_cone(a, b, 1, 1, 8, MS_CAP_BASE | MS_CAP_APEX, count_tri, k);
    t_ok(k[0] == 8 * 4, "closed cylinder of 8 sides: 16 side and 16 cap triangles");
    int segs = 0;
    ms_export_text("I", a, 1, count_seg, &segs);
    t_ok(segs == 3, "'I' is three strokes");
    segs = 0;
    float e[3] = {0.1f, 0, 0};
    ms_export_dashes(a, e, count_seg, &segs);
    t_ok(segs == 3, "a 0.1 dashed line is 3 dashes of 0.02");
}

/* The fast number text must read back as printf's does. */
static void test_numfmt(void)
{
    t_suite = "numfmt";
    char a[32], b[32];
    int same = 0, close = 0, n = 0;
    unsigned x = 12345;
    for (int i = 0; i < 200000; i++) {
        x = x * 1103515245u + 12345u;
        float v = ((float)(x >> 8) / (float)(1u << 24) - 0.5f) * powf(10.0f, (float)(i % 14) - 6.0f);
        ms_fmt_g(a, v);
        snprintf(b, sizeof b, "%g", v);
        n++;
        same += !strcmp(a, b);
        double da = strtod(a, NULL), db = strtod(b, NULL);
        close += fabs(da - db) <= 1.0000001e-6 * fabs(db) * 10;   /* one unit in the 6th digit */
    }
    t_ok(close == n, "every value reads back within one unit of the 6th digit (%d of %d)", close, n);
    t_ok(same >= n - n / 10000, "the text is printf's %%g, ties to even included (%d of %d)", same, n);
    ms_fmt_g(a, 0.25098f);
    ms_fmt_g(b, -1234.5678f);
    t_ok(!strcmp(a, "0.25098") && !strcmp(b, "-1234.57"), "examples: %s %s", a, b);
    ms_fmt_f3(a, -0.25f);
    ms_fmt_f3(b, 1.0f);
    t_ok(!strcmp(a, "-0.250") && !strcmp(b, "1.000"), "%%.3f examples: %s %s", a, b);
}

static void test_ugraphics(void)
{
    t_suite = "graphics";
    ms_ugraphics *g = ms_ugraphics_new();
    ms_ug_item it;
    memset(&it, 0, sizeof it);
    it.kind = MS_UG_SPHERE;
    it.radius = 1;
    int a = ms_ugraphics_add(g, &it), b = ms_ugraphics_add(g, &it), c = ms_ugraphics_add(g, &it);
    t_ok(a == 0 && b == 1 && c == 2, "ids count from 0");
    ms_ugraphics_delete(g, 1);
    t_ok(ms_ugraphics_find(g, 1) < 0 && ms_ugraphics_add(g, &it) == 3, "a deleted id is not reused");
    t_ok(ms_ugraphics_replace(g, 0) == 0 && ms_ugraphics_add(g, &it) == 0 &&
         ms_ugraphics_find(g, 0) == 0 && ms_ugraphics_add(g, &it) == 4,
         "replace: the next item takes the id and its place; then ids go on");
    t_ok(ms_ugraphics_replace(g, 42) < 0, "replace of a missing id fails");
    it.kind = MS_UG_POINT;
    it.data[0] = 10;
    ms_ugraphics_add(g, &it);
    float ctr[3], scale;
    t_ok(ms_ugraphics_cov(g, ctr, &scale) && ctr[0] == 5 && scale == 2.0f / 10, "centre and scale of the graphics");

    /* display lists: built once, rebuilt when the items or the colours change */
    ms_error err = {{0}};
    ms_colors *colors = ms_colors_new(&err);
    ms_ugraphics_delete_all(g);
    memset(&it, 0, sizeof it);
    it.kind = MS_UG_COLOR;
    it.iv[0] = 1;                                   /* red */
    ms_ugraphics_add(g, &it);
    it.kind = MS_UG_SPHERE;
    it.radius = 2;
    ms_ugraphics_add(g, &it);
    it.kind = MS_UG_MATERIAL;
    it.iv[0] = 7;
    ms_ugraphics_add(g, &it);
    it.kind = MS_UG_POINT;
    ms_ugraphics_add(g, &it);
    t_ok(ms_ugraphics_update(g, colors, &err) == 0 && g->nlists == 2 && g->lists[0].spheres.n == 1 &&
         g->lists[0].spheres.color[0].r == 255 && g->lists[0].spheres.color[0].g == 0 &&
         g->lists[1].material == 7 && g->lists[1].points.n == 1,
         "a new list where the material changes; colours resolved at build");
    g->lists[0].spheres.radius[0] = -1;             /* marks the built list */
    ms_ugraphics_update(g, colors, &err);
    t_ok(g->lists[0].spheres.radius[0] == -1, "no change, no rebuild");
    float green[3] = {0, 1, 0};
    ms_color_set_rgb(colors, 1, green);
    ms_ugraphics_update(g, colors, &err);
    t_ok(g->lists[0].spheres.radius[0] == 2 && g->lists[0].spheres.color[0].g == 255,
         "a colour change rebuilds with the new RGB");
    ms_colors_free(colors);
    ms_ugraphics_free(g);
}

/* ---------------------------------------------------------------- level of detail */

/* A UV sphere of radius r at c: nu x nv quads, red above z = c[2], blue below. */
static void lod_sphere(ms_displaylist *dl, const float c[3], float r, int nu, int nv)
{
    for (int j = 0; j <= nv; j++)
        for (int i = 0; i <= nu; i++) {
            float th = (float)M_PI * (float)j / (float)nv, ph = 2.0f * (float)M_PI * (float)i / (float)nu;
            float n[3] = {sinf(th) * cosf(ph), sinf(th) * sinf(ph), cosf(th)};
            float p[3] = {c[0] + r * n[0], c[1] + r * n[1], c[2] + r * n[2]};
            ms_rgba8 col = n[2] >= 0 ? (ms_rgba8){255, 0, 0, 255} : (ms_rgba8){0, 0, 255, 255};
            ms_dl_vertex(dl, p, n, col);
        }
    for (int j = 0; j < nv; j++)
        for (int i = 0; i < nu; i++) {
            uint32_t a = (uint32_t)(j * (nu + 1) + i), b = a + 1, d = a + (uint32_t)nu + 1;
            ms_dl_tri(dl, a, b, d + 1);
            ms_dl_tri(dl, a, d + 1, d);
        }
}

static void mesh_bounds(const ms_dl_mesh *m, float lo[3], float hi[3])
{
    for (int k = 0; k < 3; k++) {
        lo[k] = INFINITY;
        hi[k] = -INFINITY;
    }
    for (size_t v = 0; v < m->nverts; v++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], m->xyz[3 * v + k]);
            hi[k] = fmaxf(hi[k], m->xyz[3 * v + k]);
        }
}

/* Every triangle has three different vertices at three different places. */
static int no_degenerate(const ms_dl_mesh *m)
{
    for (size_t t = 0; t < m->ntris; t++) {
        const uint32_t *v = m->tri + 3 * t;
        if (v[0] >= m->nverts || v[1] >= m->nverts || v[2] >= m->nverts) return 0;
        for (int e = 0; e < 3; e++) {
            const float *p = m->xyz + 3 * v[e], *q = m->xyz + 3 * v[(e + 1) % 3];
            if (v[e] == v[(e + 1) % 3] || (p[0] == q[0] && p[1] == q[1] && p[2] == q[2])) return 0;
        }
    }
    return 1;
}

static void test_lod_decimate(void)
{
    t_suite = "lod";
    ms_error err = {{0}};
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {1, 2, 3};
    lod_sphere(&dl, c, 10.0f, 200, 100);
    ms_dl_mesh out;
    float cell = 0;
    int rc = ms_mesh_decimate(&dl.mesh, 2000, &out, &cell, &err);
    t_ok(rc == 0 && out.ntris <= 2000 && out.ntris >= 500, "40000 triangles to at most 2000: %zu "
         "(cell %g)", out.ntris, cell);
    t_ok(no_degenerate(&out), "no degenerate triangle");
    float lo[3], hi[3], olo[3], ohi[3];
    mesh_bounds(&dl.mesh, lo, hi);
    mesh_bounds(&out, olo, ohi);
    int box = 1;
    for (int k = 0; k < 3; k++)
        box &= olo[k] >= lo[k] - 1e-4f && olo[k] <= lo[k] + cell && ohi[k] <= hi[k] + 1e-4f &&
               ohi[k] >= hi[k] - cell;
    t_ok(box, "bounding box kept within a cell: x %g..%g of %g..%g", olo[0], ohi[0], lo[0], hi[0]);
    int normals = 1, colours = 1;
    for (size_t v = 0; v < out.nverts; v++) {
        float d[3], n[3];
        for (int k = 0; k < 3; k++) {
            d[k] = out.xyz[3 * v + k] - c[k];
            n[k] = ms_normal_dequantize(out.normal[3 * v + k]);
        }
        normals &= ms_v3f_dot(d, n) > 0.9f * sqrtf(ms_v3f_dot(d, d));
        ms_rgba8 col = out.color[v];
        if (d[2] > cell) colours &= col.r == 255 && col.b == 0;
        if (d[2] < -cell) colours &= col.r == 0 && col.b == 255;
        colours &= col.r + col.b >= 254 && col.r + col.b <= 256 && col.a == 255;
    }
    t_ok(normals, "mean normals point out of the sphere");
    t_ok(colours, "colours are means: red above, blue below, mixed only at the equator");
    ms_mesh_free(&out);
    t_ok(ms_mesh_decimate(&dl.mesh, 0, &out, NULL, &err) == 0 && out.ntris == 0,
         "a budget of 0 triangles leaves none");
    ms_mesh_free(&out);
    t_ok(ms_mesh_cluster(&dl.mesh, 0.0f, &out, &err) == -1 && strstr(err.msg, "cell size"),
         "a cell of 0 is refused: %s", err.msg);
    ms_dl_free(&dl);
}

static void test_lod_cluster(void)
{
    ms_error err = {{0}};
    ms_displaylist dl;
    ms_dl_init(&dl);
    /* two vertices in the cube [0,1)^3, one in each of two others: one triangle of 2 kept */
    float p[4][3] = {{0.1f, 0.1f, 0.1f}, {0.5f, 0.3f, 0.1f}, {1.5f, 0.2f, 0.2f}, {0.2f, 1.5f, 0.2f}};
    float n[3] = {0, 0, 1};
    ms_rgba8 col[4] = {{0, 0, 0, 255}, {200, 100, 51, 255}, {9, 9, 9, 255}, {7, 7, 7, 255}};
    for (int i = 0; i < 4; i++) ms_dl_vertex(&dl, p[i], n, col[i]);
    ms_dl_tri(&dl, 0, 1, 2);       /* two corners in one cube: dropped */
    ms_dl_tri(&dl, 1, 2, 3);
    ms_dl_mesh out;
    int rc = ms_mesh_cluster(&dl.mesh, 1.0f, &out, &err);
    t_ok(rc == 0 && out.nverts == 3 && out.ntris == 1, "3 cubes, 1 triangle kept (%zu, %zu)",
         out.nverts, out.ntris);
    if (rc == 0 && out.nverts == 3) {
        uint32_t a = out.tri[0];
        t_ok(near(out.xyz[3 * a], 0.3f, 1e-6f) && near(out.xyz[3 * a + 1], 0.2f, 1e-6f) &&
             out.color[a].r == 100 && out.color[a].g == 50 && out.color[a].b == 26,
             "the shared cube's vertex is the mean of its two (colour %d %d %d)",
             out.color[a].r, out.color[a].g, out.color[a].b);
    }
    ms_mesh_free(&out);
    ms_dl_free(&dl);
}

static void test_lod_scene(void)
{
    ms_error err = {{0}};
    ms_materials *mats = ms_materials_new(&err);
    ms_displaylist a, b;
    ms_dl_init(&a);
    ms_dl_init(&b);
    float c1[3] = {0, 0, 0}, c2[3] = {30, 0, 0}, id[16];
    lod_sphere(&a, c1, 10.0f, 100, 50);               /* 10000 triangles */
    lod_sphere(&b, c2, 5.0f, 50, 50);                 /* 5000 */
    ms_dl_sphere(&a, c1, 1.0f, (ms_rgba8){1, 2, 3, 255}, 12);
    ms_mat4_identity(id);
    ms_scene s;
    ms_scene_init(&s);
    ms_scene_add(&s, &a, id, mats, &err);
    ms_scene_add(&s, &b, id, mats, &err);
    ms_scene_lod lod;
    ms_scene_lod_init(&lod);
    size_t tris = 0;
    t_ok(ms_scene_lod_apply(&lod, &s, 20000, &tris, &err) == 0 && tris == 15000 &&
         s.items[0].dl == &a, "under the budget the scene is left as it is");
    int rc = ms_scene_lod_apply(&lod, &s, 3000, &tris, &err);
    const ms_displaylist *la = s.items[0].dl, *lb = s.items[1].dl;
    t_ok(rc == 0 && tris <= 3000 && tris >= 1000 && la != &a && lb != &b &&
         la->mesh.ntris <= 2000 && lb->mesh.ntris <= 1000,
         "15000 triangles to %zu (%zu + %zu), shared in proportion", tris, la->mesh.ntris,
         lb->mesh.ntris);
    t_ok(la->spheres.n == 1 && la->spheres.xyz == a.spheres.xyz && la->material == a.material,
         "the other primitives are the list's own");
    const ms_dl_mesh *kept = &la->mesh;
    float *xyz = kept->xyz;
    s.items[0].dl = &a;
    s.items[1].dl = &b;
    ms_scene_lod_apply(&lod, &s, 3000, &tris, &err);
    t_ok(s.items[0].dl->mesh.xyz == xyz, "the next frame takes the cached mesh");
    /* b rebuilt with as many triangles (so a's share of the budget is unchanged) but a
     * larger radius: its decimated copy must be made again from the new mesh */
    ms_dl_clear(&b);
    lod_sphere(&b, c2, 6.0f, 50, 50);
    s.items[0].dl = &a;
    s.items[1].dl = &b;
    ms_scene_lod_apply(&lod, &s, 3000, &tris, &err);
    const ms_dl_mesh *nb = &s.items[1].dl->mesh;
    float far = 0;
    for (size_t v = 0; v < nb->nverts; v++) {
        float dx = nb->xyz[3 * v] - c2[0], dy = nb->xyz[3 * v + 1] - c2[1],
              dz = nb->xyz[3 * v + 2] - c2[2];
        far = fmaxf(far, sqrtf(dx * dx + dy * dy + dz * dz));
    }
    t_ok(s.items[0].dl->mesh.xyz == xyz && nb->ntris > 0 && far > 5.3f && tris <= 3000 &&
         lod.n == 2, "a rebuilt list is decimated again, the other kept (%zu, radius %.2f)",
         tris, far);
    ms_displaylist small;
    ms_dl_init(&small);
    lod_sphere(&small, c2, 1.0f, 20, 20);              /* 800 triangles: kept whole */
    ms_scene_add(&s, &small, id, mats, &err);
    s.items[0].dl = &a;
    s.items[1].dl = &b;
    ms_scene_lod_apply(&lod, &s, 3000, &tris, &err);
    t_ok(s.items[2].dl == &small && tris <= 3000 && s.items[0].dl->mesh.ntris < a.mesh.ntris,
         "a small mesh is kept whole, the large ones share the rest (%zu)", tris);
    ms_scene_lod_free(&lod);
    ms_scene_free(&s);
    ms_dl_free(&small);
    ms_dl_free(&a);
    ms_dl_free(&b);
    ms_materials_free(mats);
}

int main(void)
{
    test_displaylist();
    test_bond_pieces();
    test_normals();
    test_colors();
    test_materials();
    test_matrices_and_camera();
    test_tessellation();
    test_numfmt();
    test_ugraphics();
    test_lod_decimate();
    test_lod_cluster();
    test_lod_scene();
    return t_done();
}
