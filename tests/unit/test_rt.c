/* test_rt.c: unit tests of TachyonInternal on scenes built in C, against values worked out
 * here from the camera model and Tachyon's shading formulas (doc/vmd-behaviour.md section 8):
 * one sphere under one light (the centre pixel's value, the silhouette's radius), a sphere
 * seen through a 50% transparent one (plain and angle-modulated), ambient occlusion in a 90
 * degree crevice (half the sky) and on an open plane (all of it), a shadow where the light
 * direction puts it and a shadow of glass, fog at the cue distances, mirror reflection, cylinder caps, cone
 * silhouettes, interpolated mesh colours, and the errors (absurd samples and sizes, a scene
 * too large for the memory allowed, an unwritable file). Skipped without Embree.
 *
 * Compiled a second time with MS_TEST_OCLRT as test_oclrt: the same scenes and the same
 * expected values through the OpenCL tracer (oclrt/oclrt.h), with no fallback to
 * TachyonInternal, so that each check is of the OpenCL kernels; skipped without OpenCL. */
#include "config.h"
#include "ms_test.h"
#include "image/image.h"
#include "rt/rt.h"
#include "scene/displaylist.h"
#include "vecmath/vecf.h"
#include "scene/material.h"
#include "scene/scene.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

static ms_materials *mats;

#ifdef MS_TEST_OCLRT
#include <dirent.h>

#include "oclrt/oclrt.h"
#include "oclrt/oclrt_impl.h"
#include "surf/opencl_impl.h"
#define TRACER "TachyonLOpenCLInternal"
static int ocl_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                      ms_error *err)
{
    return ms_oclrt_render(s, o, img, st, NULL, NULL, err) ? -1 : 0;
}
static int ocl_write(const ms_scene *s, const ms_rt_options *o, const char *path, ms_rt_stats *st,
                     ms_error *err)
{
    int fell_back = 0, rc = ms_oclrt_write(s, o, path, st, &fell_back, err);
    return fell_back ? -1 : rc;
}
#define ms_rt_render ocl_render
#define ms_rt_write ocl_write
#else
#define TRACER "TachyonInternal"
#endif

/* VMD's camera, no lights, black background, w x h. */
static void scene_new(ms_scene *s, int w, int h, int ortho)
{
    ms_scene_init(s);
    s->width = w;
    s->height = h;
    ms_camera *c = &s->settings.cam;
    c->projection = ortho ? MS_PROJ_ORTHOGRAPHIC : MS_PROJ_PERSPECTIVE;
    c->eye[2] = 2, c->dir[2] = -1, c->up[1] = 1;
    c->height = 6, c->distance = -2;
    c->near_clip = 0.5f, c->far_clip = 10;
    s->settings.ao_ambient = 0.8f, s->settings.ao_direct = 0.3f;
}

static void light(ms_scene *s, int i, float x, float y, float z)
{
    s->settings.lights[i].on = 1;
    s->settings.lights[i].pos[0] = x, s->settings.lights[i].pos[1] = y, s->settings.lights[i].pos[2] = z;
    s->settings.lights[i].color[0] = s->settings.lights[i].color[1] = s->settings.lights[i].color[2] = 1;
}

/* Place dl (identity transform) with a material of these terms. */
static void place(ms_scene *s, ms_displaylist *dl, float ambient, float diffuse, float specular,
                  float shininess, float opacity)
{
    float id[16];
    ms_mat4_identity(id);
    ms_error err;
    ms_scene_add(s, dl, id, mats, &err);
    ms_material *m = &s->items[s->nitems - 1].mat;
    m->ambient = ambient, m->diffuse = diffuse, m->specular = specular;
    m->shininess = shininess, m->opacity = opacity;
    m->mirror = m->outline = m->outlinewidth = m->transmode = 0;
}

static int render(const ms_scene *s, int aasamples, int aosamples, ms_image *img)
{
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = aasamples;
    o.aosamples = aosamples;
    ms_error err = {{0}};
    int rc = ms_rt_render(s, &o, img, NULL, &err);
    if (rc) printf("# render failed: %s\n", err.msg);
    return rc;
}

static const uint8_t *px(const ms_image *img, int x, int y)
{
    return img->rgb + 3 * ((size_t)y * (size_t)img->width + (size_t)x);
}

/* 8-bit value of a shade in [0, 1] (truncated, as Tachyon writes its images). */
static int v8(float f)
{
    f = f < 0 ? 0 : f > 1 ? 1 : f;
    return (int)(f * 255.0f);
}

static int near8(const uint8_t *p, int r, int g, int b, int tol)
{
    return abs(p[0] - r) <= tol && abs(p[1] - g) <= tol && abs(p[2] - b) <= tol;
}

static float c8(uint8_t v) { return v / 255.0f; }

/* ---------------------------------------------------------------- one sphere, one light */

/* Tachyon's shade of a point with normal n seen along -z (orthographic), one white light
 * along l (unit): col (Kd max(N.L, 0) + Ka) + Ks (N.H / |H|)^p with H = L + V, when lit. */
static void expect_shade(const float n[3], const float l[3], ms_rgba8 col, float ka, float kd,
                         float ks, float p, int out[3])
{
    float ndl = n[0] * l[0] + n[1] * l[1] + n[2] * l[2], h[3] = {l[0], l[1], l[2] + 1};
    float ndh = (n[0] * h[0] + n[1] * h[1] + n[2] * h[2]) / sqrtf(h[0] * h[0] + h[1] * h[1] + h[2] * h[2]);
    float spec = ndl > 0 && ndh > 0 ? ks * powf(ndh, p) : 0, d = ndl > 0 ? kd * ndl : 0;
    out[0] = v8(c8(col.r) * (d + ka) + spec);
    out[1] = v8(c8(col.g) * (d + ka) + spec);
    out[2] = v8(c8(col.b) * (d + ka) + spec);
}

static void test_sphere_shading(void)
{
    t_suite = "sphere under a light";
    ms_scene s;
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {0, 0, 0}, l[3] = {0.57735027f, 0.57735027f, 0.57735027f};
    ms_rgba8 col = {200, 120, 40, 255};
    ms_dl_sphere(&dl, c, 0.5f, col, 12);
    scene_new(&s, 101, 101, 1);
    light(&s, 0, 1, 1, 1);
    place(&s, &dl, 0.1f, 0.65f, 0.5f, 40.0f, 1.0f);
    ms_image img;
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    /* orthographic: 1.5 units from the centre to the edge, 50.5 pixels */
    static const int probe[4][2] = {{50, 50}, {60, 40}, {40, 60}, {50, 35}};
    static const char *const what[4] = {"centre", "towards the light", "away from the light", "above"};
    for (int k = 0; k < 4; k++) {
        float x = ((float)probe[k][0] + 0.5f - 50.5f) / 50.5f * 1.5f;
        float y = (50.5f - (float)probe[k][1] - 0.5f) / 50.5f * 1.5f;
        float n[3] = {x / 0.5f, y / 0.5f, sqrtf(0.25f - x * x - y * y) / 0.5f};
        int e[3];
        expect_shade(n, l, col, 0.1f, 0.65f, 0.5f, 40.0f, e);
        const uint8_t *p = px(&img, probe[k][0], probe[k][1]);
        t_ok(near8(p, e[0], e[1], e[2], 1), "%s: col (Kd N.L + Ka) + Ks (N.H)^p = %d %d %d, got %d %d %d",
             what[k], e[0], e[1], e[2], p[0], p[1], p[2]);
    }
    ms_image_free(&img);
    ms_scene_free(&s);

    /* perspective silhouette: the sphere (radius R at distance D from the eye) spans a screen
     * radius 4 R / sqrt(D^2 - R^2) on the screen 4 away, whose half height (3) is 80 pixels */
    t_suite = "sphere silhouette";
    scene_new(&s, 200, 160, 0);
    light(&s, 0, 0, 0, 1);
    place(&s, &dl, 0.3f, 0.65f, 0.0f, 40.0f, 1.0f);
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    float rpx = 80.0f * (4.0f * 0.5f / sqrtf(4.0f - 0.25f)) / 3.0f;
    int expect = 0, got = 0, gotv = 0;
    for (int i = 0; i < 200; i++) {
        expect += fabsf((float)i + 0.5f - 100.0f) < rpx;
        got += px(&img, i, 80)[0] > 0;
    }
    for (int j = 0; j < 160; j++) gotv += px(&img, 100, j)[0] > 0;
    t_ok(got == expect && gotv == expect, "silhouette %d and %d pixels across and down, expected %d (radius %.2f px)",
         got, gotv, expect, rpx);
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* Outline 1, width 0.9, light along the view: the diffuse term is scaled by
 * e = 1 - (1 - (N.D)^2)^((1 - 0.9) 32); where N.D = -0.5, N.L = 0.5 and e = 1 - 0.75^3.2. */
static void test_outline(void)
{
    t_suite = "outline";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {0, 0, 0};
    ms_dl_sphere(&dl, c, 0.5f, (ms_rgba8){255, 255, 255, 255}, 12);
    ms_scene s;
    ms_image img;
    scene_new(&s, 101, 101, 1);
    light(&s, 0, 0, 0, 1);
    place(&s, &dl, 0, 1, 0, 40, 1);
    s.items[0].mat.outline = 1, s.items[0].mat.outlinewidth = 0.9f;
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    /* the pixel whose centre is nearest x = 0.5 sqrt(0.75) (n_z = 0.5) on the centre row */
    int i = (int)(50.5f + 0.5f * sqrtf(0.75f) / 1.5f * 50.5f);
    float x = ((float)i + 0.5f - 50.5f) / 50.5f * 1.5f, nz = sqrtf(0.25f - x * x) / 0.5f;
    float e = 1 - powf(1 - nz * nz, 0.1f * 32.0f);
    int v = px(&img, i, 50)[0], centre = px(&img, 50, 50)[0];
    t_ok(abs(v - v8(nz * e)) <= 1 && centre == 255, "edge darkened to %d (expected %d), centre %d",
         v, v8(nz * e), centre);
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- transparency */

/* Ambient-only colours: the centre ray meets the front and back of the transparent sphere
 * (both colour A, opacity a) and then the opaque one (B): a A + (1-a)(a A + (1-a) B). */
static void test_transparency(void)
{
    t_suite = "transparency";
    ms_displaylist front, back;
    ms_dl_init(&front);
    ms_dl_init(&back);
    float c1[3] = {0, 0, 1}, c2[3] = {0, 0, -1};
    ms_rgba8 a = {255, 0, 0, 255}, b = {0, 0, 255, 255};
    ms_dl_sphere(&front, c1, 0.3f, a, 12);
    ms_dl_sphere(&back, c2, 0.5f, b, 12);
    for (int r3d = 0; r3d < 2; r3d++) {
        ms_scene s;
        ms_image img;
        scene_new(&s, 21, 21, 1);
        place(&s, &front, 1, 0, 0, 40, 0.5f);
        s.items[0].mat.transmode = (float)r3d;
        place(&s, &back, 1, 0, 0, 40, 1.0f);
        if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
        /* Raster3D: a' = (1 + cos(pi (1 - a) N.D))^2 / 4, face-on N.D = -1: 0.25 */
        float al = r3d ? 0.25f : 0.5f;
        int red = v8(al + (1 - al) * al), blue = v8((1 - al) * (1 - al));
        const uint8_t *p = px(&img, 10, 10);
        t_ok(near8(p, red, 0, blue, 1), "%s: centre %d %d %d, expected %d 0 %d",
             r3d ? "angle-modulated (R3D) opacity 0.5 seen face-on" : "opacity 0.5", p[0], p[1], p[2], red, blue);
        ms_image_free(&img);
        ms_scene_free(&s);
    }
    ms_dl_free(&front);
    ms_dl_free(&back);
}

/* The ray depth: the same spheres as test_transparency (ambient only, opacity 0.5). With one
 * level the transmitted ray sees the (black) background: a A; with two, the back face of the
 * glass and then the background: a A + (1-a) a A; with three, the blue sphere as well. */
static void test_depth(void)
{
    t_suite = "ray depth";
    ms_displaylist front, back;
    ms_dl_init(&front);
    ms_dl_init(&back);
    float c1[3] = {0, 0, 1}, c2[3] = {0, 0, -1};
    ms_dl_sphere(&front, c1, 0.3f, (ms_rgba8){255, 0, 0, 255}, 12);
    ms_dl_sphere(&back, c2, 0.5f, (ms_rgba8){0, 0, 255, 255}, 12);
    ms_scene s;
    scene_new(&s, 21, 21, 1);
    place(&s, &front, 1, 0, 0, 40, 0.5f);
    place(&s, &back, 1, 0, 0, 40, 1.0f);
    static const float red[3] = {0.5f, 0.75f, 0.75f}, blue[3] = {0, 0, 0.25f};
    for (int d = 1; d <= 3; d++) {
        ms_rt_options o;
        ms_rt_options_default(&o);
        o.aasamples = 0;
        o.max_depth = d;
        ms_image img;
        ms_error err = {{0}};
        if (ms_rt_render(&s, &o, &img, NULL, &err)) return t_ok(0, "render: %s", err.msg), (void)0;
        const uint8_t *p = px(&img, 10, 10);
        t_ok(near8(p, v8(red[d - 1]), 0, v8(blue[d - 1]), 1), "depth %d: centre %d %d %d, expected %d 0 %d", d,
             p[0], p[1], p[2], v8(red[d - 1]), v8(blue[d - 1]));
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_free(&front);
    ms_dl_free(&back);
}

/* ---------------------------------------------------------------- ambient occlusion */

static void quad(ms_displaylist *dl, const float p[12], ms_rgba8 c)
{
    float e1[3], e2[3], n[3];
    for (int k = 0; k < 3; k++) e1[k] = p[3 + k] - p[k], e2[k] = p[9 + k] - p[k];
    n[0] = e1[1] * e2[2] - e1[2] * e2[1], n[1] = e1[2] * e2[0] - e1[0] * e2[2], n[2] = e1[0] * e2[1] - e1[1] * e2[0];
    float l = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
    for (int k = 0; k < 3; k++) n[k] /= l;
    long v[4];
    for (int i = 0; i < 4; i++) v[i] = ms_dl_vertex(dl, p + 3 * i, n, c);
    ms_dl_tri(dl, (uint32_t)v[0], (uint32_t)v[1], (uint32_t)v[2]);
    ms_dl_tri(dl, (uint32_t)v[0], (uint32_t)v[2], (uint32_t)v[3]);
}

/* No lights, diffuse 1, grey 0.5, AO ambient 1: pixel = 0.5 A, where A is 1 on an open plane
 * and 1/2 at the bottom of a 90 degree groove (the other face hides half the cosine-weighted
 * sky: its plane holds this face's normal). */
static void test_ao(void)
{
    t_suite = "ambient occlusion";
    ms_displaylist plane, groove;
    ms_dl_init(&plane);
    ms_dl_init(&groove);
    ms_rgba8 grey = {128, 128, 128, 255};
    float L = 50;
    float pl[12] = {-L, -L, 0, L, -L, 0, L, L, 0, -L, L, 0};
    quad(&plane, pl, grey);
    /* faces z = x and z = -x, opening towards the camera, crease along y at x = 0 */
    float f1[12] = {0, -L, 0, 0, L, 0, L, L, L, L, -L, L};
    float f2[12] = {0, L, 0, 0, -L, 0, -L, -L, L, -L, L, L};
    quad(&groove, f1, grey);
    quad(&groove, f2, grey);
    ms_scene s;
    ms_image img;
    float expect = c8(128);
    for (int g = 0; g < 2; g++) {
        scene_new(&s, 41, 41, 1);
        s.settings.ao = 1, s.settings.ao_ambient = 1.0f, s.settings.ao_direct = 1.0f;
        place(&s, g ? &groove : &plane, 0, 1, 0, 40, 1);
        if (render(&s, 15, 64, &img)) return t_ok(0, "render"), (void)0;
        /* the pixel right of the centre column: 0.04 units from the crease */
        float v = c8(px(&img, 21, 20)[0]);
        if (!g)
            t_ok(fabsf(v - expect) < 0.03f * expect, "open plane keeps all its light: %.3f, expected %.3f", v, expect);
        else
            t_ok(fabsf(v - 0.5f * expect) < 0.06f * expect, "90 degree crevice: %.3f, expected half, %.3f", v, 0.5f * expect);
        ms_image_free(&img);
        ms_scene_free(&s);
    }
    ms_dl_free(&plane);
    ms_dl_free(&groove);
}

/* ---------------------------------------------------------------- shadows */

/* A sphere at height h over a plane, light along (1, 0, 1): its shadow centre is at x = -h. */
static void test_shadow(void)
{
    t_suite = "shadows";
    ms_displaylist plane, ball;
    ms_dl_init(&plane);
    ms_dl_init(&ball);
    ms_rgba8 white = {255, 255, 255, 255};
    float L = 5, pl[12] = {-L, -L, 0, L, -L, 0, L, L, 0, -L, L, 0}, c[3] = {0, 0, 0.6f};
    quad(&plane, pl, white);
    ms_dl_sphere(&ball, c, 0.2f, white, 12);
    for (int on = 0; on < 2; on++) {
        ms_scene s;
        ms_image img;
        scene_new(&s, 61, 61, 1);
        s.settings.shadows = on;
        light(&s, 0, 1, 0, 1);
        place(&s, &plane, 0.1f, 0.8f, 0, 40, 1);
        place(&s, &ball, 0.1f, 0.8f, 0, 40, 1);
        if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
        /* ortho: 1.5 units to half the image (30.5 px); x = -0.6 and x = +0.6. The plane's
         * normal is the stored one: (0, 0, 1) quantized to signed bytes and back */
        int xs = (int)(30.5f - 0.6f / 1.5f * 30.5f), xl = (int)(30.5f + 0.6f / 1.5f * 30.5f);
        float n0 = ms_normal_dequantize(ms_normal_quantize(0)), n1 = ms_normal_dequantize(ms_normal_quantize(1));
        float ndl = (n0 + n1) / sqrtf(2.0f) / sqrtf(2 * n0 * n0 + n1 * n1);
        int lit = v8(0.8f * ndl + 0.1f), dark = v8(0.1f);
        const uint8_t *ps = px(&img, xs, 30), *pl2 = px(&img, xl, 30);
        if (on)
            t_ok(ps[0] == dark && pl2[0] == lit, "shadow at x = -h (pixel %d: %d, expected %d); lit at x = +h (%d, expected %d)",
                 xs, ps[0], dark, pl2[0], lit);
        else
            t_ok(ps[0] == lit && pl2[0] == lit, "no shadow without display shadows (%d %d, expected %d)", ps[0], pl2[0], lit);
        ms_image_free(&img);
        ms_scene_free(&s);
    }
    ms_dl_free(&plane);
    ms_dl_free(&ball);
}

/* Light through glass: a sphere of opacity 0.5 at height 0.6 over a plane, light along
 * (1, 0, 1), as in test_shadow. The shadow ray crosses the sphere twice (Tachyon counts both
 * crossings), so its shadow centre at x = -0.6 gets (1 - 0.5)^2 of the light. Alone the
 * sphere is Embree's sphere geometry; beside a cylinder it shares the cylinders' user-geometry
 * tree: both must filter alike. */
static void test_shadow_glass(void)
{
    t_suite = "shadows through glass";
    for (int user = 0; user < 2; user++) {
        ms_displaylist plane, ball;
        ms_dl_init(&plane);
        ms_dl_init(&ball);
        ms_rgba8 white = {255, 255, 255, 255};
        float L = 5, pl[12] = {-L, -L, 0, L, -L, 0, L, L, 0, -L, L, 0}, c[3] = {0, 0, 0.6f};
        quad(&plane, pl, white);
        ms_dl_sphere(&ball, c, 0.2f, white, 12);
        if (user) {
            float a[3] = {4, 4, 0}, b[3] = {4, 4, 0.5f};
            ms_dl_cylinder(&ball, a, b, 0.1f, white, 0, 12);
        }
        ms_scene s;
        ms_image img;
        scene_new(&s, 61, 61, 1);
        s.settings.shadows = 1;
        light(&s, 0, 1, 0, 1);
        place(&s, &plane, 0.1f, 0.8f, 0, 40, 1);
        place(&s, &ball, 0.0f, 0.0f, 0, 40, 0.5f);
        if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
        float n0 = ms_normal_dequantize(ms_normal_quantize(0)), n1 = ms_normal_dequantize(ms_normal_quantize(1));
        float ndl = (n0 + n1) / sqrtf(2.0f) / sqrtf(2 * n0 * n0 + n1 * n1);
        int lit = v8(0.8f * ndl + 0.1f), shade = v8(0.25f * 0.8f * ndl + 0.1f);
        int xs = (int)(30.5f - 0.6f / 1.5f * 30.5f), xl = (int)(30.5f + 0.6f / 1.5f * 30.5f);
        const uint8_t *ps = px(&img, xs, 30), *pl2 = px(&img, xl, 30);
        t_ok(ps[0] == shade && pl2[0] == lit, "%s: its shadow lets 0.25 of the light through (%d, expected %d; lit %d, expected %d)",
             user ? "a sphere in a user-geometry tree" : "Embree's sphere", ps[0], shade, pl2[0], lit);
        ms_image_free(&img);
        ms_scene_free(&s);
        ms_dl_free(&plane);
        ms_dl_free(&ball);
    }
}

/* ---------------------------------------------------------------- fog */

/* White ambient-only squares at depths 1, 2 and 3 from the eye (orthographic), fog to a black
 * background: linear from cue start 1 to end 3 gives 1, 1/2, 0; Exp gives e^(-0.5 depth). */
static void test_fog(void)
{
    t_suite = "fog";
    ms_displaylist dl;
    ms_dl_init(&dl);
    ms_rgba8 white = {255, 255, 255, 255};
    for (int i = 0; i < 3; i++) {
        float x = -1.0f + (float)i, z = 2.0f - (float)(i + 1), w = 0.3f;
        float q[12] = {x - w, -w, z, x + w, -w, z, x + w, w, z, x - w, w, z};
        quad(&dl, q, white);
    }
    static const ms_cuemode modes[] = {MS_CUE_LINEAR, MS_CUE_EXP, MS_CUE_EXP2};
    for (int m = 0; m < 3; m++) {
        ms_scene s;
        ms_image img;
        scene_new(&s, 61, 21, 1);
        s.settings.depthcue = 1, s.settings.cuemode = modes[m];
        s.settings.cue_start = 1, s.settings.cue_end = 3, s.settings.cue_density = 0.5f;
        place(&s, &dl, 1, 0, 0, 40, 1);
        if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
        int ok = 1;
        char got[64] = "", want[64] = "";
        for (int i = 0; i < 3; i++) {
            float d = (float)(i + 1);
            float f = m == 0 ? (3 - d) / 2 : m == 1 ? expf(-0.5f * d) : expf(-0.25f * d * d);
            int x = (int)(30.5f + (-1.0f + (float)i) / 1.5f * 30.5f / (61.0f / 21.0f)), v = px(&img, x, 10)[0];
            ok &= abs(v - v8(f)) <= 1;
            snprintf(got + strlen(got), sizeof got - strlen(got), " %d", v);
            snprintf(want + strlen(want), sizeof want - strlen(want), " %d", v8(f));
        }
        t_ok(ok, "%s fog at depths 1 2 3:%s, expected%s", m == 0 ? "linear" : m == 1 ? "exp" : "exp2", got, want);
        ms_image_free(&img);
        ms_scene_free(&s);
    }
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- other primitives */

/* A plane with mirror 0.5 and no other light reflects half the background back. */
static void test_mirror(void)
{
    t_suite = "mirror";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float pl[12] = {-5, -5, 0, 5, -5, 0, 5, 5, 0, -5, 5, 0};
    quad(&dl, pl, (ms_rgba8){255, 255, 255, 255});
    ms_scene s;
    ms_image img;
    scene_new(&s, 11, 11, 1);
    s.background[2] = 1.0f;
    place(&s, &dl, 0, 0, 0, 40, 1);
    s.items[0].mat.mirror = 0.5f;
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    const uint8_t *p = px(&img, 5, 5);
    t_ok(near8(p, 0, 0, v8(0.5f), 1), "mirror 0.5 shows half the blue background: %d %d %d", p[0], p[1], p[2]);
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* A cylinder from z = -1 to z = 0.5, radius 0.4, seen along its axis in perspective: a ray
 * at screen offset s (of the screen 4 away) is at x = 1.5 s / 4 at the near end and 3 s / 4
 * at the far end. Open: the centre sees through, 0.53 < s < 1.07 sees the inside wall, beyond
 * nothing; capped, the near disc covers s < 1.07. */
static void test_cylinder_caps(void)
{
    t_suite = "cylinders";
    for (int caps = 0; caps < 2; caps++) {
        ms_displaylist dl;
        ms_dl_init(&dl);
        float a[3] = {0, 0, -1}, b[3] = {0, 0, 0.5f};
        ms_dl_cylinder(&dl, a, b, 0.4f, (ms_rgba8){0, 255, 0, 255}, caps ? MS_CAP_BASE | MS_CAP_APEX : 0, 12);
        ms_scene s;
        ms_image img;
        scene_new(&s, 31, 31, 0);
        place(&s, &dl, 1, 0, 0, 40, 1);
        if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
        /* pixel 15 + k: s = k / 15.5 * 3: k = 4 is 0.77, k = 7 is 1.35 */
        const uint8_t *c = px(&img, 15, 15), *e = px(&img, 19, 15), *o = px(&img, 22, 15);
        if (caps)
            t_ok(c[1] == 255 && e[1] == 255 && o[1] == 0, "capped: a disc (centre %d, s 0.77: %d, s 1.35: %d)",
                 c[1], e[1], o[1]);
        else
            t_ok(c[1] == 0 && e[1] == 255 && o[1] == 0, "open: a tube seen into (centre %d, wall %d, outside %d)",
                 c[1], e[1], o[1]);
        ms_image_free(&img);
        ms_scene_free(&s);
        ms_dl_free(&dl);
    }
}

/* Bonds (as Licorice draws them), flat colours, orthographic (11.7 pixels a unit): one
 * cylinder from x = -1 to x = 1, red up to its joint at the origin and blue beyond, and
 * between them a green and a white half cylinder meeting at (0, 0.8) at an angle (plain
 * cylinders). Each half keeps its colour. Wider spheres on the bond's ends (the tracer tests
 * them with the tube) keep theirs, yellow and cyan, as does a magenta sphere on no cylinder
 * at (0, -0.85). */
static void test_half_bonds(void)
{
    t_suite = "bond cylinders";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float o[3] = {0, 0, 0}, l[3] = {-1, 0, 0}, r[3] = {1, 0, 0};
    float k[3] = {0, 0.8f, 0}, kl[3] = {-1, 0.8f, 0}, kr[3] = {1, 1.1f, 0};
    ms_dl_bond(&dl, l, o, r, 0.15f, (ms_rgba8){255, 0, 0, 255}, (ms_rgba8){0, 0, 255, 255},
               MS_CYL_INWARD, 12);
    ms_dl_cylinder(&dl, kl, k, 0.15f, (ms_rgba8){0, 255, 0, 255}, 0, 12);
    ms_dl_cylinder(&dl, kr, k, 0.15f, (ms_rgba8){255, 255, 255, 255}, 0, 12);
    float m[3] = {0, -0.85f, 0};
    ms_dl_sphere(&dl, m, 0.2f, (ms_rgba8){255, 0, 255, 255}, 12);
    ms_dl_sphere(&dl, r, 0.3f, (ms_rgba8){0, 255, 255, 255}, 12);
    ms_dl_sphere(&dl, l, 0.3f, (ms_rgba8){255, 255, 0, 255}, 12);
    ms_scene s;
    ms_image img;
    scene_new(&s, 31, 31, 1);
    place(&s, &dl, 1, 0, 0, 40, 1);
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    int red = 1, blue = 1;
    for (int x = 9; x <= 13; x++) red &= near8(px(&img, x, 15), 255, 0, 0, 0);
    for (int x = 18; x <= 22; x++) blue &= near8(px(&img, x, 15), 0, 0, 255, 0);
    t_ok(red && blue, "one bond: red left of the joint, blue right of it");
    const uint8_t *y = px(&img, 5, 13), *c = px(&img, 26, 13), *mg = px(&img, 15, 25);
    t_ok(near8(y, 255, 255, 0, 0) && near8(c, 0, 255, 255, 0) && near8(mg, 255, 0, 255, 0),
         "spheres: on the ends yellow (%d %d %d) and cyan (%d %d %d), alone magenta (%d %d %d)",
         y[0], y[1], y[2], c[0], c[1], c[2], mg[0], mg[1], mg[2]);
    const uint8_t *g = px(&img, 9, 6), *w = px(&img, 21, 4);
    t_ok(near8(g, 0, 255, 0, 0) && near8(w, 255, 255, 255, 0), "a bent pair: green (%d %d %d), white (%d %d %d)",
         g[0], g[1], g[2], w[0], w[1], w[2]);
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* A cone from base radius 0.6 at x = -1 to a point at x = 1, seen from the side: its height
 * at x is 0.6 (1 - x) / 2. */
static void test_cone(void)
{
    t_suite = "cones";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float a[3] = {-1, 0, 0}, b[3] = {1, 0, 0};
    ms_dl_cone(&dl, a, b, 0.6f, 0.0f, (ms_rgba8){255, 255, 0, 255}, 12);
    ms_scene s;
    ms_image img;
    scene_new(&s, 151, 151, 1);
    place(&s, &dl, 1, 0, 0, 40, 1);
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    int ok = 1;
    for (int k = 0; k < 3; k++) {
        float x = -0.5f + 0.5f * (float)k, half = 0.6f * (1 - x) / 2;
        int col = (int)(75.5f + x / 1.5f * 75.5f), got = 0, expect = 0;
        for (int j = 0; j < 151; j++) {
            float y = (75.5f - ((float)j + 0.5f)) / 75.5f * 1.5f;
            expect += fabsf(y) < half;
            got += px(&img, col, j)[0] > 0;
        }
        ok &= abs(got - expect) <= 1;
    }
    t_ok(ok, "the silhouette narrows linearly to the apex");
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* A triangle with red, green and blue corners: its centroid is their mean. */
static void test_mesh_colors(void)
{
    t_suite = "mesh";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float p[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0}, n[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    ms_rgba8 c[3] = {{255, 0, 0, 255}, {0, 255, 0, 255}, {0, 0, 255, 255}};
    ms_dl_triangle(&dl, p, n, c);
    ms_scene s;
    ms_image img;
    scene_new(&s, 31, 31, 1);
    place(&s, &dl, 1, 0, 0, 40, 1);
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    /* centroid (0, -1/3): pixel row 15.5 + (1/3) / 1.5 * 15.5 */
    const uint8_t *q = px(&img, 15, (int)(15.5f + 1.0f / 3.0f / 1.5f * 15.5f));
    t_ok(near8(q, 85, 85, 85, 6), "centroid colour is the mean of the corners: %d %d %d", q[0], q[1], q[2]);
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- background, depth of field */

/* An empty perspective scene with the gradient on: Tachyon's sky sphere between -m and m with
 * m = min(1, (height / 2) / screen distance) = 0.75; a pixel's value is (d.y + m) / (2 m) of
 * the way from the bottom colour to the top one, d its unit ray direction. */
static void test_gradient(void)
{
    t_suite = "background";
    ms_scene s;
    ms_image img;
    scene_new(&s, 40, 30, 0);
    s.settings.bg_gradient = 1;
    s.bg_top[0] = 1.0f, s.bg_bottom[2] = 1.0f;
    if (render(&s, 0, 0, &img)) return t_ok(0, "render"), (void)0;
    int ok = 1;
    for (int j = 0; j < 30; j += 7) {
        float sy = (1.0f - 2.0f * ((float)j + 0.5f) / 30.0f) * 0.75f, sx = (2.0f * 20.5f / 40.0f - 1.0f) * 0.75f * 40 / 30;
        float dy = sy / sqrtf(1 + sx * sx + sy * sy), v = (dy + 0.75f) / 1.5f;
        const uint8_t *p = px(&img, 20, j);
        ok &= near8(p, v8(v), 0, v8(1 - v), 1);
    }
    t_ok(ok, "the sky sphere gradient from BackgroundBot to BackgroundTop");
    ms_image_free(&img);
    ms_scene_free(&s);
    scene_new(&s, 8, 8, 0);
    s.background[1] = 0.5f;
    if (render(&s, 3, 0, &img)) return t_ok(0, "render"), (void)0;
    t_ok(near8(px(&img, 3, 3), 0, v8(0.5f), 0, 0), "an empty scene is all background");
    ms_image_free(&img);
    ms_scene_free(&s);
}

/* Depth of field focused 2 from the eye (on z = 0), f-number 1: a sphere there keeps a sharp
 * edge, one 3 behind it is blurred over many pixels. */
static void test_dof(void)
{
    t_suite = "depth of field";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float a[3] = {-0.7f, 0, 0}, b[3] = {1.2f, 0, -3};
    ms_dl_sphere(&dl, a, 0.4f, (ms_rgba8){255, 255, 255, 255}, 12);
    ms_dl_sphere(&dl, b, 0.8f, (ms_rgba8){255, 255, 255, 255}, 12);
    ms_scene s;
    ms_image img;
    scene_new(&s, 120, 60, 0);
    s.settings.cam.dof = 1, s.settings.cam.dof_fnumber = 1, s.settings.cam.dof_focaldist = 2;
    place(&s, &dl, 1, 0, 0, 40, 1);
    if (render(&s, 63, 0, &img)) return t_ok(0, "render"), (void)0;
    int soft[2] = {0, 0};
    for (int i = 0; i < 120; i++) {
        int v = px(&img, i, 30)[0];
        if (v > 10 && v < 245) soft[i >= 60]++;
    }
    t_ok(soft[0] <= 4 && soft[1] >= 3 * soft[0] + 6, "in focus: %d soft edge pixels; 3 behind: %d", soft[0], soft[1]);
    ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- progressive passes */

static void test_passes(void)
{
    t_suite = "passes";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {0, 0, 0};
    ms_dl_sphere(&dl, c, 0.5f, (ms_rgba8){255, 255, 255, 255}, 12);
    ms_scene s;
    scene_new(&s, 32, 32, 0);
    light(&s, 0, 0, 0, 1);
    place(&s, &dl, 0.1f, 0.65f, 0.5f, 40, 1);
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = 11;
    o.aosamples = 0;
    ms_rt_stats st;
    ms_image img;
    ms_error err = {{0}};
    int rc = ms_rt_render(&s, &o, &img, &st, &err);
    t_ok(rc == 0 && st.passes == 12 && st.rays[MS_RT_PRIMARY] == 12 * 32 * 32,
         "aasamples 11: 12 passes of one camera ray per pixel (%d passes, %llu rays)", st.passes,
         (unsigned long long)st.rays[MS_RT_PRIMARY]);
    if (!rc) ms_image_free(&img);
    o.max_passes = 3;
    rc = ms_rt_render(&s, &o, &img, &st, &err);
    t_ok(rc == 0 && st.passes == 3, "a pass limit stops early (%d)", st.passes);
    if (!rc) ms_image_free(&img);
    /* progress on stderr (the device asks for it when stderr is a terminal): pass by pass, a
     * line a pass; pixel by pixel (the default), a line a round of tiles, at least 16 rounds
     * and no more than the tiles (here 4), the last at 100%; the OpenCL tracer goes pass by
     * pass whatever the order */
    for (int order = MS_RT_ORDER_PIXELS; order <= MS_RT_ORDER_PASSES; order++) {
#ifdef MS_TEST_OCLRT
        int by_pass = 1;
#else
        int by_pass = order == MS_RT_ORDER_PASSES;
#endif
        char log[512], last[256] = "";
        snprintf(log, sizeof log, "%s/rt_progress.txt", getenv("MS_TEST_OUT") ? getenv("MS_TEST_OUT") : "/tmp");
        fflush(stderr);
        int saved = dup(2);
        FILE *lf = fopen(log, "w");
        int lines = 0, ours = 0;
        if (lf && saved >= 0) {
            dup2(fileno(lf), 2);
            o.progress = 1;
            o.order = order;
            rc = ms_rt_render(&s, &o, &img, &st, &err);
            fflush(stderr);
            dup2(saved, 2);
            o.progress = 0;
            o.order = MS_RT_ORDER_PIXELS;
            if (!rc) ms_image_free(&img);
            fclose(lf);
            lf = fopen(log, "r");
            char line[256];
            const char *want = by_pass ? TRACER ": pass " : TRACER ": ";
            while (lf && fgets(line, sizeof line, lf)) {
                lines++;
                ours += !strncmp(line, want, strlen(want));
                snprintf(last, sizeof last, "%s", line);
            }
            if (lf) fclose(lf);
        }
        if (saved >= 0) close(saved);
        remove(log);
        if (by_pass)
            t_ok(lines == 3 && ours == 3 && !strncmp(last, TRACER ": pass 3/3,", strlen(TRACER ": pass 3/3,")),
                 "progress pass by pass: a line a pass (%d lines for 3 passes; the last: %s)", lines, last);
        else
            t_ok(lines == 4 && ours == 4 && !strncmp(last, TRACER ": 100% of 3 passes,", strlen(TRACER ": 100% of 3 passes,")),
                 "progress pixel by pixel: a line a round of tiles (%d lines for 4 tiles; the last: %s)", lines, last);
    }
    o.max_passes = 0;
    o.aasamples = 60000;
    o.time_budget = 1e-6;
    rc = ms_rt_render(&s, &o, &img, &st, &err);
    t_ok(rc == 0 && st.passes == 1, "a time budget stops after the pass that spends it (%d)", st.passes);
    if (!rc) ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* A session (rt.h): its first pass is the pinhole image whose centre pixel the shading
 * formula gives; after n passes its image is the one ms_rt_render makes with n passes, byte
 * for byte; before any pass there is no image. */
static void test_session(void)
{
    t_suite = "rt session";
    ms_scene s;
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {0, 0, 0}, l[3] = {0.57735027f, 0.57735027f, 0.57735027f}, n[3] = {0, 0, 1};
    ms_rgba8 col = {200, 120, 40, 255};
    ms_dl_sphere(&dl, c, 0.5f, col, 12);
    scene_new(&s, 101, 101, 0);
    light(&s, 0, 1, 1, 1);
    place(&s, &dl, 0.1f, 0.65f, 0.5f, 40.0f, 1.0f);
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = 4;
    ms_error err = {{0}};
    ms_image img, ref;
    ms_rt_session *ss = ms_rt_session_begin(&s, &o, &err);
    if (!t_ok(ss != NULL, "begin (%s)", err.msg)) return;
    t_ok(ms_rt_session_passes(ss) == 0 && ms_rt_session_image(ss, &img, &err) == -1 && !img.rgb,
         "no image before the first pass");
    t_ok(ms_rt_session_pass(ss) == 1 && ms_rt_session_image(ss, &img, &err) == 0, "pass 1");
    int e[3];
    expect_shade(n, l, col, 0.1f, 0.65f, 0.5f, 40.0f, e);
    const uint8_t *p = px(&img, 50, 50);
    t_ok(near8(p, e[0], e[1], e[2], 1), "pass 1: centre pixel %d %d %d, expected %d %d %d",
         p[0], p[1], p[2], e[0], e[1], e[2]);
    ms_image_free(&img);
    for (int k = 2; k <= 5; k++) ms_rt_session_pass(ss);
    int ok = ms_rt_session_passes(ss) == 5 && ms_rt_session_image(ss, &img, &err) == 0 &&
             ms_rt_render(&s, &o, &ref, NULL, &err) == 0;
    t_ok(ok && !memcmp(img.rgb, ref.rgb, 3 * 101 * 101),
         "5 passes: the image ms_rt_render makes with aasamples 4");
    if (ok) {
        ms_image_free(&img);
        ms_image_free(&ref);
    }
    ms_rt_session_end(ss);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- errors */

/* Degenerate primitives are left out, a degenerate camera gives background, and a mesh whose
 * triangle names a missing vertex is an error: nothing crashes or reads out of bounds. */
static void test_degenerate(void)
{
    t_suite = "degenerate input";
    ms_displaylist dl;
    ms_dl_init(&dl);
    ms_rgba8 w = {255, 255, 255, 255};
    float nan3[3] = {NAN, 0, 0}, o[3] = {0, 0, 0}, inf3[3] = {INFINITY, 1, 1}, z[3] = {0, 0, 1};
    ms_dl_sphere(&dl, nan3, 1, w, 12);
    ms_dl_sphere(&dl, o, 0, w, 12);
    ms_dl_sphere(&dl, o, -1, w, 12);
    ms_dl_sphere(&dl, o, NAN, w, 12);
    ms_dl_cylinder(&dl, o, o, 1, w, MS_CAP_BASE | MS_CAP_APEX, 12);
    ms_dl_cylinder(&dl, o, inf3, 1, w, 0, 12);
    ms_dl_cylinder(&dl, o, z, 0, w, MS_CAP_BASE, 12);
    ms_dl_cone(&dl, o, z, 0, 0, w, 12);
    ms_dl_cone(&dl, o, o, 1, 0, w, 12);
    float p[9] = {0, 0, 0, 0, 0, 0, 0, 0, 0}, n[9] = {0};
    ms_rgba8 c[3] = {w, w, w};
    ms_dl_triangle(&dl, p, n, c);
    ms_scene s;
    ms_image img;
    scene_new(&s, 16, 16, 0);
    s.background[0] = 1.0f;
    s.settings.shadows = s.settings.ao = 1;
    light(&s, 0, 0, 0, 1);
    place(&s, &dl, 0.2f, 0.6f, 0.5f, 40, 0.5f);
    int rc = render(&s, 2, 4, &img);
    t_ok(rc == 0 && near8(px(&img, 8, 8), 255, 0, 0, 0), "NaN, zero and infinite sizes are left out: background");
    if (!rc) ms_image_free(&img);
    s.settings.cam.distance = s.settings.cam.eye[2];
    rc = render(&s, 0, 0, &img);
    t_ok(rc == 0, "a camera whose screen is at the eye renders");
    if (!rc) ms_image_free(&img);
    s.settings.cam.distance = -2;
    dl.mesh.tri[2] = 7;
    ms_rt_options opt;
    ms_rt_options_default(&opt);
    ms_error err = {{0}};
    t_ok(ms_rt_render(&s, &opt, &img, NULL, &err) < 0 && strstr(err.msg, "triangle 0"),
         "a triangle naming a missing vertex is an error (%s)", err.msg);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

static void test_errors(void)
{
    t_suite = "errors";
    ms_displaylist dl;
    ms_dl_init(&dl);
    for (int i = 0; i < 20000; i++) {
        float c[3] = {(float)(i % 100), (float)(i / 100), 0};
        ms_dl_sphere(&dl, c, 0.5f, (ms_rgba8){255, 255, 255, 255}, 12);
    }
    ms_scene s;
    scene_new(&s, 64, 64, 0);
    place(&s, &dl, 0.1f, 0.65f, 0.5f, 40, 1);
    ms_rt_options o;
    ms_rt_options_default(&o);
    ms_image img;
    ms_error err = {{0}};
    o.aosamples = 5000;
    t_ok(ms_rt_render(&s, &o, &img, NULL, &err) < 0 && strstr(err.msg, "aosamples 5000"),
         "absurd AO samples refused (%s)", err.msg);
    o.aosamples = 12;
    o.aasamples = -1;
    t_ok(ms_rt_render(&s, &o, &img, NULL, &err) < 0 && strstr(err.msg, "aasamples -1"),
         "negative AA samples refused (%s)", err.msg);
    o.aasamples = 0;
    s.width = 0;
    t_ok(ms_rt_render(&s, &o, &img, NULL, &err) < 0 && strstr(err.msg, "image size"), "size 0 refused (%s)", err.msg);
    s.width = 30000, s.height = 30000;
    o.memory = (size_t)1 << 30;
    t_ok(ms_rt_render(&s, &o, &img, NULL, &err) < 0 && strstr(err.msg, "GB"),
         "an image too large for the memory allowed (%s)", err.msg);
    s.width = s.height = 64;
    o.memory = 300000;        /* the buffers fit, the spheres' tree does not */
    t_ok(ms_rt_render(&s, &o, &img, NULL, &err) < 0 && strstr(err.msg, "too large"),
         "a scene too large for the memory allowed (%s)", err.msg);
    o.memory = 0;
    t_ok(ms_rt_render(&s, &o, &img, NULL, &err) == 0, "the same scene renders with the memory there is");
    ms_image_free(&img);

    const char *bad = "/nonexistent-folder/x.png";
    t_ok(ms_rt_write(&s, &o, bad, NULL, &err) < 0 && strstr(err.msg, "cannot write") && access(bad, F_OK) != 0,
         "an unwritable file: an error, no file (%s)", err.msg);
    char path[512];
    snprintf(path, sizeof path, "%s/rt_unit.frame", getenv("MS_TEST_OUT") ? getenv("MS_TEST_OUT") : "/tmp");
    int ok = ms_rt_write(&s, &o, path, NULL, &err) == 0;
    FILE *f = fopen(path, "rb");
    unsigned char head[18] = {0};
    ok = ok && f && fread(head, 1, 18, f) == 18 && head[2] == 2 && head[12] == 64 && head[16] == 24;
    if (f) fclose(f);
    remove(path);
    t_ok(ok, "a name without a known extension is written as TGA, as VMD does");
    o.aosamples = 5000;
    snprintf(path, sizeof path, "%s/rt_unit_bad.png", getenv("MS_TEST_OUT") ? getenv("MS_TEST_OUT") : "/tmp");
    t_ok(ms_rt_write(&s, &o, path, NULL, &err) < 0 && access(path, F_OK) != 0, "a failed render leaves no file");
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

#ifndef MS_TEST_OCLRT
/* A large mesh's leaves (world.c): compact when asked, or when the fast layout would take more
 * than half the memory allowed or the render's rays are fewer than 3 a triangle; fast
 * otherwise. The layouts give the same picture; the fast one takes more of Embree's memory. */
static size_t leaves_render(const ms_scene *s, int layout, int aasamples, size_t memory,
                            ms_image *img)
{
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = aasamples, o.aosamples = 0, o.leaves = layout, o.memory = memory;
    ms_error err = {{0}};
    if (ms_rt_render(s, &o, img, NULL, &err)) {
        printf("# render failed: %s\n", err.msg);
        return 0;
    }
    ms_rt_memory m;
    ms_rt_last_memory(&m);
    return m.embree;
}

static void test_leaves(void)
{
    t_suite = "leaves";
    enum { N = 730 };              /* (N - 1)^2 quads: 1,062,882 triangles, past 2^20 */
    ms_displaylist dl;
    ms_dl_init(&dl);
    float nrm[3] = {0, 0, 1};
    for (int j = 0; j < N; j++)
        for (int i = 0; i < N; i++) {
            float p[3] = {-2.5f + 5.0f * i / (N - 1), -2.5f + 5.0f * j / (N - 1),
                          0.2f * sinf(0.05f * (float)(i + 2 * j))};
            ms_dl_vertex(&dl, p, nrm, (ms_rgba8){200, 120, 60, 255});
        }
    for (uint32_t j = 0; j + 1 < N; j++)
        for (uint32_t i = 0; i + 1 < N; i++) {
            uint32_t a = j * N + i;
            ms_dl_tri(&dl, a, a + 1, a + N + 1);
            ms_dl_tri(&dl, a, a + N + 1, a + N);
        }
    ms_scene s;
    scene_new(&s, 128, 128, 0);   /* no shadows, no AO: a ray a camera sample */
    light(&s, 0, 0.3f, 0.4f, 1);
    place(&s, &dl, 0.2f, 0.8f, 0, 40, 1);
    ms_image ic, ifast, img;
    size_t compact = leaves_render(&s, MS_RT_LEAVES_COMPACT, 0, 0, &ic);
    size_t fast = leaves_render(&s, MS_RT_LEAVES_FAST, 0, 0, &ifast);
    t_ok(compact && fast > compact * 3 / 2, "the fast leaves take more memory (%zu against %zu bytes)",
         fast, compact);
    t_ok(compact && fast && !memcmp(ic.rgb, ifast.rgb, 3 * 128 * 128), "the two layouts give the same picture");
    size_t one = leaves_render(&s, MS_RT_LEAVES_AUTO, 0, 0, &img);
    t_ok(one && one < (compact + fast) / 2, "16,384 rays for 1M triangles: compact (%zu bytes)", one);
    if (one) ms_image_free(&img);
    /* 194 passes: 3,178,496 rays, just short of 3 a triangle */
    one = leaves_render(&s, MS_RT_LEAVES_AUTO, 193, 0, &img);
    t_ok(one && one < (compact + fast) / 2, "3,178,496 rays: compact (%zu bytes)", one);
    if (one) ms_image_free(&img);
    /* 195 passes of 16,384 pixels: 3,194,880 rays, 3 a triangle */
    size_t many = leaves_render(&s, MS_RT_LEAVES_AUTO, 194, 0, &img);
    t_ok(many > (compact + fast) / 2, "3,194,880 rays: fast (%zu bytes)", many);
    if (many) ms_image_free(&img);
    size_t tight = leaves_render(&s, MS_RT_LEAVES_AUTO, 194, (size_t)200 << 20, &img);
    t_ok(tight && tight < (compact + fast) / 2, "the same rays in 200 MB: compact (%zu bytes)", tight);
    if (tight) ms_image_free(&img);
    if (compact) ms_image_free(&ic);
    if (fast) ms_image_free(&ifast);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}
#endif

#ifdef MS_TEST_OCLRT
/* ---------------------------------------------------------------- OpenCL only */

typedef struct seen {
    int calls, last;
    int centre[64];
} seen;

static int on_pass(void *user, int passes, const ms_image *img)
{
    seen *s = user;
    if (s->calls < 64) s->centre[s->calls] = img->rgb[3 * (16 * 32 + 16)];
    s->calls++;
    s->last = passes;
    return passes >= 5;
}

/* The tracer and QuickSurf use the one device, context and queue of cl/cl.h. */
static void test_shared_engine(void)
{
    t_suite = "OpenCL engine";
    ms_error err = {{0}};
    orc_engine *e = orc_engine_acquire(&err);
    t_ok(e != NULL, "the tracer's engine starts (%s)", err.msg);
    if (!e) return;
    cl_context ctx = e->ctx;
    cl_command_queue queue = e->queue;
    orc_engine_release(e);
    int absent = 0;
    ms_qsurf_cl *cl = ms_qsurf_cl_acquire(1, &absent, &err);
    t_ok(cl && cl->ctx == ctx && cl->queue == queue && !strcmp(cl->dev.name, ms_oclrt_device_name()),
         "QuickSurf's OpenCL engine has the tracer's device, context and queue (%s)",
         cl ? cl->dev.name : err.msg);
    if (cl) ms_qsurf_cl_release(cl);
}

/* The pass callback sees each pass's average; a nonzero return stops the render. */
static void test_callback(void)
{
    t_suite = "pass callback";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {0, 0, 0};
    ms_dl_sphere(&dl, c, 0.5f, (ms_rgba8){255, 255, 255, 255}, 12);
    ms_scene s;
    scene_new(&s, 32, 32, 0);
    light(&s, 0, 0, 0, 1);
    place(&s, &dl, 0.1f, 0.65f, 0.5f, 40, 1);
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = 20;
    ms_image img;
    ms_rt_stats st;
    ms_error err = {{0}};
    seen sn = {0, 0, {0}};
    int rc = ms_oclrt_render(&s, &o, &img, &st, on_pass, &sn, &err);
    /* the sphere's centre faces the light: 0.1 + 0.65 + 0.5 saturates at every pass */
    t_ok(rc == 0 && sn.calls == 5 && sn.last == 5 && st.passes == 5 && sn.centre[0] == 255 && sn.centre[4] == 255,
         "called after passes 1 to 5, stopped by its return (%d calls, %d passes, centre %d)", sn.calls, st.passes,
         sn.centre[0]);
    if (!rc) ms_image_free(&img);
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* An injected allocation failure or build failure: ms_oclrt_render reports a device problem,
 * ms_oclrt_write falls back to TachyonInternal and still writes the image. */
static void test_fallback(void)
{
    t_suite = "fallback";
    ms_displaylist dl;
    ms_dl_init(&dl);
    float c[3] = {0, 0, 0};
    ms_dl_sphere(&dl, c, 0.5f, (ms_rgba8){255, 255, 255, 255}, 12);
    ms_scene s;
    scene_new(&s, 16, 16, 0);
    place(&s, &dl, 1, 0, 0, 40, 1);
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = 0;
    static const int modes[2] = {MS_OCLRT_FAIL_ALLOC, MS_OCLRT_FAIL_BUILD};
    static const char *const want[2] = {"CL_MEM_OBJECT_ALLOCATION_FAILURE", "do not build"};
    for (int k = 0; k < 2; k++) {
        ms_image img;
        ms_error err = {{0}};
        char path[512];
        snprintf(path, sizeof path, "%s/oclrt_fallback.ppm", getenv("MS_TEST_OUT") ? getenv("MS_TEST_OUT") : "/tmp");
        ms_oclrt_fail = modes[k];
        int rc = ms_oclrt_render(&s, &o, &img, NULL, NULL, NULL, &err);
        t_ok(rc == MS_OCLRT_EDEVICE && strstr(err.msg, want[k]), "%s: a device failure (%s)",
             k ? "injected build failure" : "injected allocation failure", err.msg);
        int fell_back = 0;
        remove(path);
        rc = ms_oclrt_write(&s, &o, path, NULL, &fell_back, &err);
        ms_oclrt_fail = MS_OCLRT_FAIL_NONE;
        FILE *f = fopen(path, "rb");
        unsigned char pix[3] = {0, 0, 0};
        int ok = f && fseek(f, -(long)(3 * (8 * 16 + 8)), SEEK_END) == 0 && fread(pix, 1, 3, f) == 3;
        if (f) fclose(f);
        remove(path);
        t_ok(rc == 0 && fell_back && ok && pix[0] == 255, "%s: TachyonInternal wrote the image (centre %d)",
             k ? "injected build failure" : "injected allocation failure", pix[0]);
    }
    ms_image img;
    ms_error err = {{0}};
    int rc = ms_oclrt_render(&s, &o, &img, NULL, NULL, NULL, &err);
    t_ok(rc == 0, "the next render runs on OpenCL again (%s)", rc ? err.msg : "ok");
    if (!rc) ms_image_free(&img);
    /* the built program was cached where MOLSCOPE_OPENCL_CACHE says (run-tests sets it) */
    const char *cache = getenv("MOLSCOPE_OPENCL_CACHE");
    if (cache && *cache) {
        DIR *d = opendir(cache);
        int bins = 0;
        for (struct dirent *e; d && (e = readdir(d));)
            bins += !strncmp(e->d_name, "oclrt-", 6) && strstr(e->d_name, ".bin") && !strstr(e->d_name, ".tmp");
        if (d) closedir(d);
        t_ok(bins >= 1, "the program binary is cached in MOLSCOPE_OPENCL_CACHE (%d files)", bins);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* Our SAH builder against Embree's rtcBuildBVH: a lattice of 8000 spheres over a quad, with
 * cylinders, shadows and AO; the closest hits do not depend on the tree, so the images agree
 * but for hits tied in distance. */
static void test_own_bvh(void)
{
    t_suite = "own BVH builder";
    ms_displaylist dl, plane;
    ms_dl_init(&dl);
    ms_dl_init(&plane);
    for (int i = 0; i < 8000; i++) {
        float c[3] = {-1.5f + 0.15f * (float)(i % 20), -1.5f + 0.15f * (float)(i / 20 % 20), -0.15f * (float)(i / 400)};
        ms_dl_sphere(&dl, c, 0.06f, (ms_rgba8){(uint8_t)(i * 7), 200, (uint8_t)(i * 13), 255}, 12);
        float d[3] = {c[0] + 0.1f, c[1], c[2]};
        if (i % 3 == 0) ms_dl_cylinder(&dl, c, d, 0.02f, (ms_rgba8){255, 255, 255, 255}, MS_CAP_BASE, 12);
    }
    float pl[12] = {-3, -3, -3.2f, 3, -3, -3.2f, 3, 3, -3.2f, -3, 3, -3.2f};
    quad(&plane, pl, (ms_rgba8){128, 128, 128, 255});
    ms_scene s;
    scene_new(&s, 96, 96, 0);
    s.settings.shadows = s.settings.ao = 1;
    light(&s, 0, 1, 1, 1);
    place(&s, &dl, 0.2f, 0.6f, 0.4f, 30, 1);
    place(&s, &plane, 0.2f, 0.6f, 0, 30, 1);
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = 1;
    o.aosamples = 4;
    ms_image img[2];
    ms_error err = {{0}};
    int rc = 0;
    for (int k = 0; k < 2; k++) {
        ms_oclrt_own_bvh = k;
        rc |= ms_oclrt_render(&s, &o, &img[k], NULL, NULL, NULL, &err);
    }
    ms_oclrt_own_bvh = 0;
    if (rc) {
        t_ok(0, "render: %s", err.msg);
    } else {
        size_t n = 3 * 96 * 96, big = 0, lit = 0;
        for (size_t i = 0; i < n; i++) {
            big += abs(img[0].rgb[i] - img[1].rgb[i]) > 1;
            lit += img[0].rgb[i] > 0;
        }
        t_ok(big <= n / 1000 && lit > n / 2, "the same image as with rtcBuildBVH (%zu of %zu values differ by more than 1)",
             big, n);
        ms_image_free(&img[0]);
        ms_image_free(&img[1]);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
    ms_dl_free(&plane);
}
#endif

int main(void)
{
#ifndef MS_TEST_OCLRT
    if (!ms_rt_available()) {
        t_skip(TRACER, "molscope was built without Embree");
        return 0;
    }
#else
    if (!ms_oclrt_available()) {
        t_skip(TRACER, "molscope was built without OpenCL");
        return 0;
    }
    {
        ms_scene s;
        ms_image img;
        ms_rt_options o;
        ms_error err = {{0}};
        scene_new(&s, 4, 4, 0);
        ms_rt_options_default(&o);
        int rc = ms_oclrt_render(&s, &o, &img, NULL, NULL, NULL, &err);
        ms_scene_free(&s);
        if (rc == MS_OCLRT_EDEVICE) {
            t_skip(TRACER, err.msg);
            return 0;
        }
        if (!rc) ms_image_free(&img);
        printf("# OpenCL device: %s\n", ms_oclrt_device_name());
    }
#endif
    ms_error err;
    mats = ms_materials_new(&err);
    test_sphere_shading();
    test_outline();
    test_transparency();
    test_depth();
    test_ao();
    test_shadow();
    test_shadow_glass();
    test_fog();
    test_mirror();
    test_cylinder_caps();
    test_half_bonds();
#ifndef MS_TEST_OCLRT
    test_leaves();
#endif
    test_cone();
    test_mesh_colors();
    test_gradient();
    test_dof();
    test_passes();
    test_session();
    test_degenerate();
#ifdef MS_TEST_OCLRT
    test_shared_engine();
    test_callback();
    /* the memory plan, the fallback and rtcBuildBVH are Embree's */
    if (!ms_rt_available()) {
        t_skip("memory limits, fallback, rtcBuildBVH", "molscope was built without Embree");
        ms_materials_free(mats);
        return t_done();
    }
    test_errors();
    test_fallback();
    test_own_bvh();
    /* the analytic scenes again, on the tree of our own builder */
    printf("# with molscope's own BVH builder\n");
    ms_oclrt_own_bvh = 1;
    test_sphere_shading();
    test_transparency();
    test_shadow_glass();
    test_cylinder_caps();
    test_cone();
    test_mesh_colors();
    test_degenerate();
    ms_oclrt_own_bvh = 0;
#else
    test_errors();
#endif
    ms_materials_free(mats);
    return t_done();
}
