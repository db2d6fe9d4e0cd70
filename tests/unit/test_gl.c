/* test_gl.c: the offscreen OpenGL device, on every back-end that starts (each is skipped
 * when it cannot). Scenes are built directly in C with VMD's camera; every expected value
 * comes from the camera model and the shading formulas worked out here, or from 1tii.pdb:
 * an empty scene is all background; a sphere's colour at the pixel ms_scene_project
 * predicts is the Diffuse material's Lambert term; silhouette areas of a sphere (both
 * projections), a cylinder, a cone and a triangle are within 1% of their analytic areas;
 * depth cueing follows VMD's three formulas; a translucent sphere over an opaque one is
 * their 50/50 blend; the nearest atom of 1tii shows its element colour; occlusion culling
 * changes no pixel; OSMesa and EGL images agree (mean absolute difference under 0.5 of
 * 255); bad sizes are errors. */
#include "config.h"
#include "ms_test.h"
#include "assemble/view.h"
#include "fileio/load.h"
#include "gl/gl.h"
#include "vecmath/vecf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

#include "builtin/builtin.h"

#define W 401
#define H 401
static const ms_rgba8 RED = {255, 0, 0, 255}, BLUE = {0, 0, 255, 255}, WHITE = {255, 255, 255, 255};
/* VMD's Diffuse material: ambient 0, specular 0, diffuse 0.62; for areas the same with
 * ambient 0.3, so that no pixel turned away from the light is as black as the background. */
static const ms_material DIFFUSE = {"Diffuse", 3, 0, 0, 0.62f, 40, 0, 1, 0, 0, 0};
static const ms_material AMBIENT = {"Ambient", 5, 0.3f, 0, 0.62f, 40, 0, 1, 0, 0, 0};

/* VMD's camera and background black; only light 0 on, so a lit value is diffuse * N.L0. */
static void scene_init(ms_scene *s, int ortho)
{
    ms_scene_init(s);
    s->width = W;
    s->height = H;
    ms_camera *c = &s->settings.cam;
    c->projection = ortho ? MS_PROJ_ORTHOGRAPHIC : MS_PROJ_PERSPECTIVE;
    c->eye[2] = 2;
    c->dir[2] = -1;
    c->up[1] = 1;
    c->height = 6;
    c->distance = -2;
    c->near_clip = 0.5f;
    c->far_clip = 10;
    s->settings.lights[0].on = 1;
    memcpy(s->settings.lights[0].pos, ms_view_default_light(0), sizeof s->settings.lights[0].pos);
    s->settings.lights[0].color[0] = s->settings.lights[0].color[1] = s->settings.lights[0].color[2] = 1;
}

static void add(ms_scene *s, ms_displaylist *dl, const ms_material *m)
{
    float id[16];
    ms_error err;
    ms_mat4_identity(id);
    ms_materials mats = {(ms_material *)m, 1, 1, m->id + 1, 0};
    dl->material = m->id;
    ms_scene_add(s, dl, id, &mats, &err);
}

/* The Lambert value light 0 gives a surface of normal n, as a byte. */
static double lambert(double colour, const float n[3])
{
    const float *l = ms_view_default_light(0);
    double len = sqrt(l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    double nl = (n[0] * l[0] + n[1] * l[1] + n[2] * l[2]) / len;
    return 255.0 * colour * 0.62 * (nl > 0 ? nl : 0);
}

/* The normal of an orthographic sphere (projected centre x, y; radius rp pixels) at the
 * centre of pixel (px, py). */
static void normal_at(float x, float y, float rp, int px, int py, float n[3])
{
    n[0] = ((float)px + 0.5f - x) / rp;
    n[1] = -((float)py + 0.5f - y) / rp;
    n[2] = sqrtf(fmaxf(0, 1 - n[0] * n[0] - n[1] * n[1]));
}

static const uint8_t *px(const ms_image *img, int x, int y)
{
    return img->rgb + 3 * ((size_t)y * (size_t)img->width + (size_t)x);
}

static size_t count_not(const ms_image *img, const uint8_t bg[3])
{
    size_t n = 0;
    for (size_t i = 0; i < (size_t)img->width * (size_t)img->height; i++)
        n += memcmp(img->rgb + 3 * i, bg, 3) != 0;
    return n;
}

static int draw(ms_gl *g, const ms_scene *s, ms_image *img)
{
    ms_error err = {{0}};
    if (ms_gl_render(g, s, img, NULL, &err) == 0) return 0;
    t_ok(0, "render: %s", err.msg);
    return -1;
}

/* ---------------------------------------------------------------- background */

static void test_empty(ms_gl *g)
{
    ms_scene s;
    ms_image img;
    scene_init(&s, 0);
    s.background[0] = 0.2f; s.background[1] = 0.4f; s.background[2] = 0.6f;
    if (draw(g, &s, &img)) return;
    const uint8_t bg[3] = {51, 102, 153};
    t_ok(count_not(&img, bg) == 0, "a scene with nothing in it is all background (51 102 153)");
    ms_image_free(&img);
    ms_displaylist dl;
    ms_dl_init(&dl);
    float behind[3] = {0, 0, 5}, far[3] = {0, 0, -20}, off[3] = {30, 0, 0};
    ms_dl_sphere(&dl, behind, 0.5f, RED, 12);    /* behind the eye */
    ms_dl_sphere(&dl, far, 0.5f, RED, 12);       /* beyond the far plane */
    ms_dl_sphere(&dl, off, 0.5f, RED, 12);       /* off the screen */
    add(&s, &dl, &DIFFUSE);
    if (draw(g, &s, &img) == 0) {
        t_ok(count_not(&img, bg) == 0, "spheres behind the eye, past the far plane and off the screen draw nothing");
        ms_image_free(&img);
    }
    s.settings.bg_gradient = 1;
    s.bg_top[0] = 1; s.bg_bottom[2] = 1;
    if (draw(g, &s, &img) == 0) {
        const uint8_t *top = px(&img, 0, 0), *bot = px(&img, W - 1, H - 1);
        t_ok(top[0] >= 254 && top[2] <= 1 && bot[2] >= 254 && bot[0] <= 1,
             "background gradient: top colour at the top, bottom colour at the bottom");
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- spheres */

static double radius_px(const ms_image *img)
{
    const uint8_t bg[3] = {0, 0, 0};
    return sqrt((double)count_not(img, bg) / M_PI);
}

/* One sphere of radius 0.5 at the origin; its silhouette radius is 0.5 * H / 3 pixels
 * (orthographic: the view is 3 units tall) or, under perspective from 2 units away,
 * tan(asin(0.5 / 2)) / 0.75 * H / 2 pixels. */
static void test_sphere_area(ms_gl *g)
{
    double expect[2] = {0.5 / sqrt(4.0 - 0.25) / 0.75 * H / 2.0, 0.5 * H / 3.0}, got[2] = {0, 0};
    for (int ortho = 0; ortho < 2; ortho++) {
        ms_scene s;
        ms_displaylist dl;
        ms_image img;
        scene_init(&s, ortho);
        ms_dl_init(&dl);
        float c[3] = {0, 0, 0};
        ms_dl_sphere(&dl, c, 0.5f, RED, 12);
        add(&s, &dl, &AMBIENT);
        if (draw(g, &s, &img) == 0) {
            got[ortho] = radius_px(&img);
            double a = M_PI * got[ortho] * got[ortho], e = M_PI * expect[ortho] * expect[ortho];
            t_ok(fabs(a - e) < 0.01 * e, "%s sphere: silhouette %.0f pixels, pi r^2 = %.0f",
                 ortho ? "orthographic" : "perspective", a, e);
            const uint8_t *corner = px(&img, 0, 0), *corner2 = px(&img, W - 1, H - 1);
            t_ok(!corner[0] && !corner[1] && !corner[2] && !corner2[0], "corners are background");
            ms_image_free(&img);
        }
        ms_scene_free(&s);
        ms_dl_free(&dl);
    }
    t_ok(fabs(got[0] / got[1] - expect[0] / expect[1]) < 0.01,
         "perspective / orthographic size %.4f, expected %.4f", got[0] / got[1], expect[0] / expect[1]);
}

/* A sphere off the axis: at the pixel ms_scene_project gives for its centre (orthographic:
 * the normal there faces the viewer) the colour is the Lambert term. */
static void test_sphere_colour(ms_gl *g)
{
    ms_scene s;
    ms_displaylist dl;
    ms_image img;
    scene_init(&s, 1);
    ms_dl_init(&dl);
    float c[3] = {0.7f, -0.4f, 0.3f}, n[3], x, y;
    ms_dl_sphere(&dl, c, 0.3f, RED, 12);
    add(&s, &dl, &DIFFUSE);
    ms_scene_project(&s, c, &x, &y, NULL);
    normal_at(x, y, 0.3f * H / 3, (int)x, (int)y, n);
    if (draw(g, &s, &img) == 0) {
        const uint8_t *p = px(&img, (int)x, (int)y);
        double e = lambert(1.0, n);
        t_ok(fabs(p[0] - e) <= 2 && p[1] == 0 && p[2] == 0,
             "sphere colour at its projected pixel (%d %d): %d %d %d, expected %.1f 0 0",
             (int)x, (int)y, p[0], p[1], p[2], e);
        const uint8_t *q = px(&img, (int)(x + 0.3f * H / 3 + 2), (int)y);
        t_ok(!q[0], "just outside its rim is background");
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* Depth cue: two spheres on the axis; at each centre pixel the colour is f * lit (black
 * background), with f VMD's formula at the distance of the surface point. */
static double fog_factor(ms_cuemode m, double d)
{
    double f = m == MS_CUE_LINEAR ? (10.0 - d) / (10.0 - 0.5) : m == MS_CUE_EXP ? exp(-0.32 * d)
                                                                           : exp(-(0.32 * d) * (0.32 * d));
    return f < 0 ? 0 : f > 1 ? 1 : f;
}

static void test_depthcue(ms_gl *g)
{
    static const char *names[3] = {"Linear", "Exp", "Exp2"};
    for (int m = 0; m < 3; m++) {
        ms_scene s;
        ms_displaylist dl;
        ms_image img;
        scene_init(&s, 1);
        s.settings.depthcue = 1;
        s.settings.cuemode = (ms_cuemode)m;
        s.settings.cue_start = 0.5f; s.settings.cue_end = 10; s.settings.cue_density = 0.32f;
        ms_dl_init(&dl);
        float c1[3] = {-0.6f, 0, 1}, c2[3] = {0.6f, 0, -4}, n[3] = {0, 0, 1}, x1, y1, x2, y2;
        ms_dl_sphere(&dl, c1, 0.3f, WHITE, 12);
        ms_dl_sphere(&dl, c2, 0.3f, WHITE, 12);
        add(&s, &dl, &DIFFUSE);
        ms_scene_project(&s, c1, &x1, &y1, NULL);
        ms_scene_project(&s, c2, &x2, &y2, NULL);
        if (draw(g, &s, &img) == 0) {
            int near = px(&img, (int)x1, (int)y1)[1], far = px(&img, (int)x2, (int)y2)[1];
            double e1 = fog_factor(s.settings.cuemode, 2 - 1 - 0.3) * lambert(1, n);
            double e2 = fog_factor(s.settings.cuemode, 2 + 4 - 0.3) * lambert(1, n);
            t_ok(fabs(near - e1) <= 2 && fabs(far - e2) <= 2 && far < near,
                 "depth cue %s: near %d (expected %.1f), far %d (expected %.1f)", names[m], near,
                 e1, far, e2);
            ms_image_free(&img);
        }
        ms_scene_free(&s);
        ms_dl_free(&dl);
    }
}

/* A red sphere of opacity 0.5 in front of an opaque blue one: at the common centre pixel
 * the image is half of each lit colour. */
static void test_translucent(ms_gl *g)
{
    ms_scene s;
    ms_displaylist front, back;
    ms_image img;
    scene_init(&s, 1);
    ms_dl_init(&front);
    ms_dl_init(&back);
    float c1[3] = {0, 0, 1}, c2[3] = {0, 0, 0}, n[3] = {0, 0, 1};
    ms_dl_sphere(&front, c1, 0.25f, RED, 12);
    ms_dl_sphere(&back, c2, 0.5f, BLUE, 12);
    ms_material glass = DIFFUSE;
    glass.id = 1;
    glass.opacity = 0.5f;
    add(&s, &back, &DIFFUSE);
    add(&s, &front, &glass);
    if (draw(g, &s, &img) == 0) {
        const uint8_t *p = px(&img, W / 2, H / 2), *q = px(&img, W / 2 + 50, H / 2);
        double e = 0.5 * lambert(1, n);
        t_ok(fabs(p[0] - e) <= 3 && fabs(p[2] - e) <= 3 && p[1] == 0,
             "translucent red over opaque blue: %d %d %d, expected %.1f 0 %.1f", p[0], p[1], p[2], e, e);
        t_ok(q[0] == 0 && q[2] > 50, "outside the red sphere only blue (%d %d %d)", q[0], q[1], q[2]);
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_free(&front);
    ms_dl_free(&back);
}

/* Outline (VMD's Edgy: outline 0.62, width 0.94): the shade is multiplied by
 * (1 - a) + e a, e = 1 - (1 - (N.V)^2)^((1 - w) 32); 1 where the surface faces the viewer. */
static void test_outline(ms_gl *g)
{
    int vals[2][2];
    float x, y, n[3], c[3] = {0, 0, 0};
    int ix = W / 2 - (int)(0.9f * 0.5f * H / 3);
    for (int k = 0; k < 2; k++) {
        ms_scene s;
        ms_displaylist dl;
        ms_image img;
        ms_material m = DIFFUSE;
        m.outline = k ? 0.62f : 0;
        m.outlinewidth = k ? 0.94f : 0;
        scene_init(&s, 1);
        ms_dl_init(&dl);
        ms_dl_sphere(&dl, c, 0.5f, WHITE, 12);
        add(&s, &dl, &m);
        ms_scene_project(&s, c, &x, &y, NULL);
        vals[k][0] = vals[k][1] = -1;
        if (draw(g, &s, &img) == 0) {
            vals[k][0] = px(&img, (int)x, (int)y)[0];
            vals[k][1] = px(&img, ix, (int)y)[0];
            ms_image_free(&img);
        }
        ms_scene_free(&s);
        ms_dl_free(&dl);
    }
    normal_at(x, y, 0.5f * H / 3, ix, (int)y, n);
    double e = 1 - pow(1 - n[2] * n[2], 0.06 * 32), f = 0.38 + e * 0.62;
    t_ok(vals[1][0] == vals[0][0] && fabs(vals[1][1] - f * vals[0][1]) <= 2,
         "outline: centre unchanged (%d %d), rim %d -> %d (expected %.1f, N.V %.3f)", vals[0][0],
         vals[1][0], vals[0][1], vals[1][1], f * vals[0][1], n[2]);
}

/* A cylinder running from the middle of the view to beyond the far plane is drawn up to
 * the far plane (its far end's ball is clipped, its middle is not), culled or not. */
static void test_far_cylinder(ms_gl *g)
{
    float a[3] = {0.5f, 0, 0}, b[3] = {0.5f, 0, -20}, mid[3] = {0.5f, 0, -3}, x, y;
    for (int cull = 0; cull < 2; cull++) {
        ms_scene s;
        ms_displaylist dl;
        ms_image img;
        scene_init(&s, 0);
        ms_dl_init(&dl);
        ms_dl_cylinder(&dl, a, b, 0.05f, WHITE, 0, 12);
        add(&s, &dl, &AMBIENT);
        ms_scene_project(&s, mid, &x, &y, NULL);
        setenv("MOLSCOPE_GL_CULL", cull ? "1" : "0", 1);
        if (draw(g, &s, &img) == 0) {
            const uint8_t *p = px(&img, (int)x, (int)y);
            t_ok(p[0] > 50, "a cylinder into the far plane is drawn 5 units away (%s): %d",
                 cull ? "culling" : "no culling", p[0]);
            ms_image_free(&img);
        }
        unsetenv("MOLSCOPE_GL_CULL");
        ms_scene_free(&s);
        ms_dl_free(&dl);
    }
}

/* A sphere cut by the near plane shows its inside instead of vanishing. */
static void test_near_clip(ms_gl *g)
{
    ms_scene s;
    ms_displaylist dl;
    ms_image img;
    scene_init(&s, 0);
    ms_dl_init(&dl);
    float c[3] = {0, 0, 1.6f};               /* 0.4 from the eye, radius 0.3: crosses 0.5 */
    ms_dl_sphere(&dl, c, 0.3f, WHITE, 12);
    add(&s, &dl, &DIFFUSE);
    if (draw(g, &s, &img) == 0) {
        const uint8_t *p = px(&img, W / 2, H / 2);
        t_ok(p[0] > 0, "a sphere crossing the near plane is cut open (centre %d)", p[0]);
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- other primitives */

static void area_check(ms_gl *g, ms_displaylist *dl, double expect, const char *what)
{
    ms_scene s;
    ms_image img;
    scene_init(&s, 1);
    add(&s, dl, &AMBIENT);
    if (draw(g, &s, &img) == 0) {
        const uint8_t bg[3] = {0, 0, 0};
        double a = (double)count_not(&img, bg);
        t_ok(fabs(a - expect) < 0.01 * expect, "%s: %.0f pixels, expected %.0f", what, a, expect);
        ms_image_free(&img);
    }
    ms_scene_free(&s);
}

/* Orthographic: H / 3 pixels per unit. */
static void test_shapes(ms_gl *g)
{
    double u = H / 3.0;
    ms_displaylist dl;
    ms_dl_init(&dl);
    float a[3] = {-0.6f, 0, 0}, b[3] = {0.6f, 0, 0};
    ms_dl_cylinder(&dl, a, b, 0.2f, RED, 0, 12);
    area_check(g, &dl, 1.2 * 0.4 * u * u, "open cylinder side on: a 1.2 x 0.4 rectangle");
    ms_dl_clear(&dl);
    ms_dl_cone(&dl, a, b, 0.3f, 0, RED, 12);
    area_check(g, &dl, 0.5 * 1.2 * 0.6 * u * u, "cone side on: a triangle 1.2 long, 0.6 at the base");
    ms_dl_clear(&dl);
    float c0[3] = {0, 0, 0.5f}, c1[3] = {0, 0, -0.5f};
    ms_dl_cylinder(&dl, c0, c1, 0.4f, RED, MS_CAP_BASE, 12);
    area_check(g, &dl, M_PI * 0.16 * u * u, "capped cylinder end on: a disc of radius 0.4");
    ms_dl_clear(&dl);
    float p[9] = {-0.5f, -0.5f, 0, 0.7f, -0.5f, 0, -0.5f, 0.6f, 0}, n[9] = {0, 0, 1, 0, 0, 1, 0, 0, 1};
    ms_rgba8 cols[3] = {RED, RED, RED};
    ms_dl_triangle(&dl, p, n, cols);
    area_check(g, &dl, 0.5 * 1.2 * 1.1 * u * u, "triangle: 1.2 x 1.1 / 2");
    ms_dl_free(&dl);
}

/* A bond as two half cylinders coloured by their atoms: drawn merged when they are list
 * neighbours, as two cylinders when they are not; both images are the same but for pixels
 * on the seam. */
static void test_half_bonds(ms_gl *g)
{
    ms_image img[2];
    int ok = 1;
    float a[3] = {-0.6f, 0, 0}, b[3] = {0.6f, 0, 0}, m[3] = {0, 0, 0}, away[3] = {0, 0, 5};
    for (int split = 0; split < 2; split++) {
        ms_displaylist dl;
        ms_scene s;
        ms_dl_init(&dl);
        ms_dl_cylinder(&dl, a, m, 0.2f, RED, 0, 12);
        if (split) ms_dl_cylinder(&dl, away, away, 0.2f, RED, 0, 12);   /* behind the eye */
        ms_dl_cylinder(&dl, b, m, 0.2f, BLUE, 0, 12);
        scene_init(&s, 1);
        add(&s, &dl, &AMBIENT);
        ok &= draw(g, &s, &img[split]) == 0;
        ms_scene_free(&s);
        ms_dl_free(&dl);
    }
    if (!ok) return;
    const uint8_t bg[3] = {0, 0, 0};
    size_t lit = count_not(&img[0], bg), diff = 0;
    for (size_t i = 0; i < (size_t)W * H; i++) diff += memcmp(img[0].rgb + 3 * i, img[1].rgb + 3 * i, 3) != 0;
    double e = 1.2 * 0.4 * (H / 3.0) * (H / 3.0);
    const uint8_t *l = px(&img[0], W / 2 - 40, H / 2), *r = px(&img[0], W / 2 + 40, H / 2);
    t_ok(fabs((double)lit - e) < 0.01 * e && l[0] > 100 && !l[2] && r[2] > 100 && !r[0],
         "a bond of two half cylinders: %zu pixels (expected %.0f), red half then blue half", lit, e);
    t_ok(diff <= (size_t)H, "merged and separate halves differ only along the seam (%zu pixels)", diff);
    ms_image_free(&img[0]);
    ms_image_free(&img[1]);
}

/* Lines are their width in pixels; points squares of their size; text strokes. */
static void test_lines(ms_gl *g)
{
    ms_displaylist dl;
    ms_dl_init(&dl);
    float a[3] = {-1, 0.013f, 0}, b[3] = {1, 0.013f, 0}, c[3] = {0.5f, 0.8f, 0};
    ms_dl_line(&dl, a, b, 3, WHITE, MS_LINE_SOLID);
    ms_scene s;
    ms_image img;
    scene_init(&s, 1);
    add(&s, &dl, &DIFFUSE);
    if (draw(g, &s, &img) == 0) {
        int n = 0;
        for (int y = 0; y < H; y++) n += px(&img, W / 2, y)[0] == 255;
        t_ok(n == 3, "a line of width 3 is 3 pixels thick (%d), unlit white", n);
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_clear(&dl);
    ms_dl_point(&dl, c, 5, WHITE);
    area_check(g, &dl, 25, "a point of size 5 is 5 x 5 pixels");
    ms_dl_clear(&dl);
    ms_dl_text(&dl, c, "MOLSCOPE", 1, 1, WHITE);
    scene_init(&s, 1);
    add(&s, &dl, &DIFFUSE);
    if (draw(g, &s, &img) == 0) {
        const uint8_t bg[3] = {0, 0, 0};
        size_t lit = count_not(&img, bg);
        t_ok(lit > 40 && lit < 8 * 0.1 * H / 3 * 0.1 * H / 3, "text draws its strokes (%zu pixels)", lit);
        ms_image_free(&img);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

/* ---------------------------------------------------------------- 1tii */

static ms_molecule *load_1tii(void)
{
    ms_registry reg;
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    char path[1024];
    snprintf(path, sizeof path, "%s/1tii.pdb", t_data());
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    ms_error err = {{0}};
    ms_molecule *m = ms_load_new(&reg, path, &o, &err);
    ms_registry_free(&reg);
    if (!m) t_ok(0, "load 1tii.pdb: %s", err.msg);
    return m;
}

static ms_rgba8 element_colour(int z)
{
    return z == 6 ? (ms_rgba8){64, 191, 191, 255} : z == 8 ? RED : z == 7 ? BLUE : (ms_rgba8){255, 255, 0, 255};
}

/* VDW spheres of every atom and Licorice's bonds (half cylinders coloured by atom), placed
 * as resetview places them. */
static void molecule_list(const ms_molecule *m, ms_displaylist *dl, float xform[16])
{
    const float *p = ms_mol_pos(m);
    float lo[3], hi[3], ext = 0, t[16], sc[16];
    for (size_t i = 0; i < m->atoms.n; i++)
        ms_dl_sphere(dl, p + 3 * i, m->atoms.radius[i], element_colour(m->atoms.atomicnumber[i]), 12);
    for (size_t i = 0; i < m->atoms.n; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            size_t j = m->bonds.to[k];
            float mid[3];
            if (j < i) continue;
            for (int d = 0; d < 3; d++) mid[d] = 0.5f * (p[3 * i + d] + p[3 * j + d]);
            ms_dl_cylinder(dl, p + 3 * i, mid, 0.3f, element_colour(m->atoms.atomicnumber[i]), 0, 12);
            ms_dl_cylinder(dl, p + 3 * j, mid, 0.3f, element_colour(m->atoms.atomicnumber[j]), 0, 12);
        }
    ms_dl_bounds(dl, lo, hi);
    for (int k = 0; k < 3; k++) ext = fmaxf(ext, hi[k] - lo[k]);
    ms_mat4_translation(t, -0.5f * (lo[0] + hi[0]), -0.5f * (lo[1] + hi[1]), -0.5f * (lo[2] + hi[2]));
    ms_mat4_scaling(sc, 1.5f / ext);
    ms_mat4_mul(sc, t, xform);
}

static void add_xform(ms_scene *s, ms_displaylist *dl, const float xform[16])
{
    ms_materials mats = {(ms_material *)&DIFFUSE, 1, 1, 4, 0};
    ms_error err;
    dl->material = DIFFUSE.id;
    ms_scene_add(s, dl, xform, &mats, &err);
}

/* The atom whose sphere reaches nearest the viewer is seen at its projected centre, with
 * its element's colour (orthographic: the normal there faces the viewer). */
static void test_nearest_atom(ms_gl *g, const ms_displaylist *dl, const float xform[16])
{
    ms_scene s;
    ms_image img;
    scene_init(&s, 1);
    add_xform(&s, (ms_displaylist *)dl, xform);
    size_t best = 0;
    float bestz = -1e30f, c[3], x, y;
    for (size_t i = 0; i < dl->spheres.n; i++) {
        ms_mat4_point(xform, dl->spheres.xyz + 3 * i, c);
        float z = c[2] + dl->spheres.radius[i] * ms_mat4_scale_factor(xform);
        if (z > bestz) { bestz = z; best = i; }
    }
    ms_mat4_point(xform, dl->spheres.xyz + 3 * best, c);
    ms_scene_project(&s, c, &x, &y, NULL);
    float n[3], rp = dl->spheres.radius[best] * ms_mat4_scale_factor(xform) * H / 3;
    normal_at(x, y, rp, (int)x, (int)y, n);
    if (draw(g, &s, &img) == 0) {
        const uint8_t *p = px(&img, (int)x, (int)y);
        ms_rgba8 col = dl->spheres.color[best];
        double e[3] = {lambert(col.r / 255.0, n), lambert(col.g / 255.0, n), lambert(col.b / 255.0, n)};
        t_ok(fabs(p[0] - e[0]) <= 3 && fabs(p[1] - e[1]) <= 3 && fabs(p[2] - e[2]) <= 3,
             "1tii: nearest atom %zu at (%d %d) shows %d %d %d, expected %.0f %.0f %.0f", best,
             (int)x, (int)y, p[0], p[1], p[2], e[0], e[1], e[2]);
        ms_image_free(&img);
    }
    ms_scene_free(&s);
}

/* Occlusion culling (forced on and off) leaves every pixel as it is: both projections, the
 * whole molecule at 401 and at 61 pixels (atoms smaller than a pixel) and a close-up whose
 * atoms cross the near plane. */
static void test_cull_invariance(ms_gl *g, const ms_displaylist *dl, const float xform[16])
{
    static const char *views[3] = {"401 px", "61 px", "close-up"};
    for (int v = 0; v < 6; v++) {
        int ortho = v & 1, view = v / 2;
        ms_scene s;
        ms_image img[2];
        int ok = 1;
        float zoom[16], t[16], x[16];
        ms_mat4_translation(t, 0.1f, 0, 1.2f);
        ms_mat4_scaling(zoom, 4);
        ms_mat4_mul(zoom, xform, x);
        ms_mat4_mul(t, x, x);
        scene_init(&s, ortho);
        if (view == 1) s.width = s.height = 61;
        add_xform(&s, (ms_displaylist *)dl, view == 2 ? x : xform);
        for (int c = 0; c < 2; c++) {
            setenv("MOLSCOPE_GL_CULL", c ? "1" : "0", 1);
            ok &= draw(g, &s, &img[c]) == 0;
        }
        unsetenv("MOLSCOPE_GL_CULL");
        if (ok) {
            size_t diff = 0;
            for (size_t i = 0; i < 3 * (size_t)s.width * s.height; i++)
                diff += img[0].rgb[i] != img[1].rgb[i];
            const uint8_t bg[3] = {0, 0, 0};
            size_t lit = count_not(&img[0], bg);
            t_ok(diff == 0 && lit > (size_t)s.width * s.height / 10,
                 "%s 1tii VDW + Licorice, %s (%zu pixels drawn): culling changes %zu values",
                 ortho ? "orthographic" : "perspective", views[view], lit, diff);
            ms_image_free(&img[0]);
            ms_image_free(&img[1]);
        }
        ms_scene_free(&s);
    }
}

/* ---------------------------------------------------------------- errors */

static void test_bad_sizes(ms_gl *g)
{
    ms_scene s;
    ms_image img;
    ms_error err = {{0}};
    scene_init(&s, 0);
    s.width = 0;
    t_ok(ms_gl_render(g, &s, &img, NULL, &err) == -1 && strstr(err.msg, "0x401") && !img.rgb,
         "a zero width is an error: %s", err.msg);
    s.width = ms_gl_max_side(g) + 1;
    t_ok(ms_gl_render(g, &s, &img, NULL, &err) == -1 && strstr(err.msg, "outside"),
         "a width past the device's limit is an error: %s", err.msg);
    s.width = 16;
    s.height = 16;
    t_ok(ms_gl_render(g, &s, &img, NULL, &err) == 0 && img.width == 16, "and the device still draws afterwards");
    ms_image_free(&img);
    ms_scene_free(&s);
}

/* ---------------------------------------------------------------- both back-ends */

static void run_backend(ms_gl *g, const ms_displaylist *mol, const float xform[16])
{
    test_empty(g);
    test_sphere_area(g);
    test_sphere_colour(g);
    test_depthcue(g);
    test_translucent(g);
    test_outline(g);
    test_near_clip(g);
    test_far_cylinder(g);
    test_shapes(g);
    test_half_bonds(g);
    test_lines(g);
    if (mol) {
        test_nearest_atom(g, mol, xform);
        test_cull_invariance(g, mol, xform);
    }
    test_bad_sizes(g);
}

/* A scene of every kind, drawn by both back-ends. */
static void test_agreement(ms_gl *g[2], const ms_displaylist *mol, const float xform[16])
{
    ms_scene s;
    ms_image img[2];
    ms_displaylist dl;
    ms_dl_init(&dl);
    float a[3] = {-1, -1, 0}, b[3] = {1, -1, 0.5f}, c[3] = {-1, 1, 0};
    ms_dl_line(&dl, a, b, 2, WHITE, MS_LINE_DASHED);
    ms_dl_cone(&dl, a, c, 0.2f, 0, RED, 12);
    ms_dl_text(&dl, c, "agree", 1, 1, WHITE);
    scene_init(&s, 0);
    s.settings.depthcue = 1;
    s.settings.cue_density = 0.32f;
    s.settings.cuemode = MS_CUE_EXP2;
    add_xform(&s, (ms_displaylist *)mol, xform);
    add(&s, &dl, &DIFFUSE);
    if (draw(g[0], &s, &img[0]) == 0 && draw(g[1], &s, &img[1]) == 0) {
        double sum = 0;
        for (size_t i = 0; i < 3 * (size_t)W * H; i++) sum += abs(img[0].rgb[i] - img[1].rgb[i]);
        sum /= 3.0 * W * H;
        t_ok(sum < 0.5, "OSMesa and EGL agree: mean absolute difference %.4f (bound 0.5)", sum);
        ms_image_free(&img[0]);
        ms_image_free(&img[1]);
    }
    ms_scene_free(&s);
    ms_dl_free(&dl);
}

int main(void)
{
    ms_gl *g[MS_GL_NKINDS] = {NULL, NULL};
    ms_molecule *m = load_1tii();
    ms_displaylist mol;
    float xform[16];
    ms_dl_init(&mol);
    if (m) molecule_list(m, &mol, xform);
    for (int k = 0; k < MS_GL_NKINDS; k++) {
        ms_error err = {{0}};
        t_suite = ms_gl_kind_name((ms_gl_kind)k);
        g[k] = ms_gl_open((ms_gl_kind)k, &err);
        if (!g[k]) {
            t_skip("all", err.msg);
            continue;
        }
        printf("# %s\n", ms_gl_info(g[k]));
        run_backend(g[k], m ? &mol : NULL, xform);
    }
    t_suite = "osmesa-egl";
    if (g[0] && g[1] && m) test_agreement(g, &mol, xform);
    else t_skip("agreement", "needs both back-ends");
    for (int k = 0; k < MS_GL_NKINDS; k++) ms_gl_close(g[k]);
    ms_dl_free(&mol);
    ms_mol_free(m);
    return t_done();
}
