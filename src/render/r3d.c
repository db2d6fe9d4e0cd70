/* r3d.c: the `Raster3D` device: the scene as input for Raster3D's `render` (.r3d): the header
 * records (tiles making the display's size, no anti-aliasing, the background, shadows as the
 * display has them, the first light as the shadowing source, VMD's camera as an identity view
 * matrix whose scale makes the image's narrow side as many world units as VMD's view shows
 * at z = 0, and the eye distance for perspective, 0 for orthographic), free-format input,
 * then one object per primitive in world coordinates: spheres (type 2), cylinders with flat
 * ends (5), triangles (1) with their vertex normals (7) and, when they differ, vertex colours
 * (17), lines and text strokes as thin round-ended cylinders (3), points as small spheres.
 * Cones are tessellated. Each display list's material (Phong power, specular, clarity from its
 * opacity) is a material block (8 ... 9). Measured against Debian's raster3d: a point (x, y,
 * z) lands at VMD's pixel. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <string.h>

static void rgb(FILE *f, ms_rgba8 c)
{
    float v[3];
    ms_rgba8_to_float(c, v);
    fprintf(f, " %.3f %.3f %.3f\n", v[0], v[1], v[2]);
}

static void item_begin(void *ud, const ms_scene_item *it)
{
    const ms_material *m = &it->mat;
    fprintf(ud, "8\n%g %g 1 1 1 %g 0 0 0 0\n", MS_MIN(200.0f, m->shininess), m->specular,
            1.0f - m->opacity);
}

static void item_end(void *ud, const ms_scene_item *it)
{
    (void)it;
    fputs("9\n", ud);
}

static void sphere(void *ud, const float c[3], float r, ms_rgba8 col, int res)
{
    (void)res;
    fprintf(ud, "2\n%g %g %g %g", c[0], c[1], c[2], r);
    rgb(ud, col);
}

static void cylinder(void *ud, const float a[3], const float b[3], float r, ms_rgba8 col,
                     int caps, int res)
{
    (void)caps, (void)res;
    fprintf(ud, "5\n%g %g %g %g %g %g %g %g", a[0], a[1], a[2], r, b[0], b[1], b[2], r);
    rgb(ud, col);
}

static void triangle(void *ud, const float p[9], const float n[9], const ms_rgba8 c[3])
{
    FILE *f = ud;
    fprintf(f, "1\n%g %g %g %g %g %g %g %g %g", p[0], p[1], p[2], p[3], p[4], p[5], p[6], p[7],
            p[8]);
    rgb(f, c[0]);
    fprintf(f, "7\n%.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f %.4f\n", n[0], n[1], n[2], n[3],
            n[4], n[5], n[6], n[7], n[8]);
    if (!memcmp(&c[0], &c[1], sizeof *c) && !memcmp(&c[0], &c[2], sizeof *c)) return;
    float v[9];
    for (int k = 0; k < 3; k++) ms_rgba8_to_float(c[k], v + 3 * k);
    fprintf(f, "17\n%.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f %.3f\n", v[0], v[1], v[2], v[3],
            v[4], v[5], v[6], v[7], v[8]);
}

static void line(void *ud, const float a[3], const float b[3], ms_rgba8 col)
{
    float r = MS_EXPORT_LINE_RADIUS;
    fprintf(ud, "3\n%g %g %g %g %g %g %g %g", a[0], a[1], a[2], r, b[0], b[1], b[2], r);
    rgb(ud, col);
}

static void point(void *ud, const float c[3], ms_rgba8 col)
{
    sphere(ud, c, MS_EXPORT_LINE_RADIUS, col, 0);
}

/* The largest tile side up to 32 that divides n. */
static int tile(int n)
{
    for (int t = 32; t > 1; t--)
        if (n % t == 0) return t;
    return 1;
}

static void header(FILE *f, const ms_scene *s)
{
    const ms_camera *cam = &s->settings.cam;
    int nx = tile(s->width), ny = tile(s->height);
    /* the world units the narrow side spans at z = 0, and the eye's distance in those */
    float d = cam->eye[2] - cam->distance, h = cam->height;
    int ortho = cam->projection == MS_PROJ_ORTHOGRAPHIC;
    float span = ortho || d <= 0 ? 0.5f * h : h * cam->eye[2] / d;
    if (s->width < s->height) span *= (float)s->width / (float)s->height;
    float eyepos = ortho ? 0.0f : cam->eye[2] / span;
    const float *src = s->settings.lights[0].pos;
    for (int i = 0; i < MS_SCENE_LIGHTS; i++)
        if (s->settings.lights[i].on) {
            src = s->settings.lights[i].pos;
            break;
        }
    fprintf(f, "molscope %s scene\n%d %d\n%d %d\n1\n%g %g %g\n%s\n25\n0.15\n0.05\n0.25\n%g\n",
            PACKAGE_VERSION, s->width / nx, s->height / ny, nx, ny, s->background[0],
            s->background[1], s->background[2], s->settings.shadows ? "T" : "F", eyepos);
    fprintf(f, "%g %g %g\n", src[0], src[1], src[2]);
    fprintf(f, "1 0 0 0\n0 1 0 0\n0 0 1 0\n%g %g %g %g\n3\n*\n*\n*\n", 0.0f - cam->eye[0],
            0.0f - cam->eye[1], 0.0f, span);
}

static int r3d_body(const ms_scene *s, FILE *f, void *user, ms_error *err)
{
    (void)user, (void)err;
    static const ms_export_visitor v = {
        .item = item_begin, .item_end = item_end, .sphere = sphere, .cylinder = cylinder,
        .triangle = triangle, .line = line, .point = point};
    header(f, s);
    ms_export_walk(s, &v, f);
    return 0;
}

static int write_r3d(const ms_scene *s, const char *path, ms_error *err)
{
    return ms_export_file(s, path, r3d_body, NULL, err);
}

const ms_render_device ms_render_raster3d = {
    .name = "Raster3D",
    .description = "Raster3D scene file (.r3d), for Raster3D's render",
    .default_cmd = "render < %s -sgi %s.rgb; display %s.rgb",
    .write = write_r3d};
