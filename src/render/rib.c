/* rib.c: the `RenderMan` device: the scene as a RenderMan Interface Bytestream (.rib) for
 * prman, Aqsis, Pixie or 3Delight: VMD's camera (perspective with VMD's field of view, or
 * orthographic with VMD's half-height window), its lights as distant lights plus an ambient
 * one, the background as the imager's colour, and the world in world coordinates (the right-
 * handed scene is carried into RenderMan's left-handed camera by a mirror in z, so the image
 * is not mirrored). Spheres are Sphere quadrics, cylinders Cylinder quadrics with Disk caps,
 * cones Hyperboloids (truncated or pointed), triangles Polygons with normals and vertex
 * colours, lines and text linear Curves, points Points; each list is one attribute block
 * with its material (plastic, or constant when unlit) and opacity. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <math.h>
#include <string.h>

typedef struct rib {
    FILE *f;
    const ms_scene_item *it;
    ms_rgba8 last;
    int has_last;
} rib;

static void color(rib *r, ms_rgba8 c)
{
    if (r->has_last && !memcmp(&c, &r->last, sizeof c)) return;
    float f[3];
    ms_rgba8_to_float(c, f);
    fprintf(r->f, "Color [%.3f %.3f %.3f]\n", f[0], f[1], f[2]);
    r->last = c;
    r->has_last = 1;
}

static void item_begin(void *ud, const ms_scene_item *it)
{
    rib *r = ud;
    const ms_material *m = &it->mat;
    r->it = it;
    r->has_last = 0;
    fprintf(r->f, "AttributeBegin\nOpacity [%g %g %g]\n", m->opacity, m->opacity, m->opacity);
    if (it->dl->lit)
        fprintf(r->f, "Surface \"plastic\" \"Ka\" [%g] \"Kd\" [%g] \"Ks\" [%g] \"roughness\" [%g]\n",
                m->ambient, m->diffuse, m->specular, 1.0f / MS_MAX(1.0f, m->shininess));
    else
        fputs("Surface \"constant\"\n", r->f);
}

static void item_end(void *ud, const ms_scene_item *it)
{
    (void)it;
    fputs("AttributeEnd\n", ((rib *)ud)->f);
}

static void sphere(void *ud, const float c[3], float rad, ms_rgba8 col, int res)
{
    (void)res;
    rib *r = ud;
    color(r, col);
    fprintf(r->f, "TransformBegin\nTranslate %g %g %g\nSphere %g %g %g 360\nTransformEnd\n",
            c[0], c[1], c[2], rad, -rad, rad);
}

/* Open a transform that puts +z along a->b with its origin at a; the length is returned. */
static float along(rib *r, const float a[3], const float b[3])
{
    float d[3] = {b[0] - a[0], b[1] - a[1], b[2] - a[2]};
    float len = sqrtf(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    fprintf(r->f, "TransformBegin\nTranslate %g %g %g\n", a[0], a[1], a[2]);
    if (len > 0) {
        float ax = -d[1], ay = d[0], s = sqrtf(ax * ax + ay * ay);
        float angle = atan2f(s, d[2]) * (float)(180.0 / M_PI);
        if (s > 1e-6f * len) fprintf(r->f, "Rotate %g %g %g 0\n", angle, ax / s, ay / s);
        else if (d[2] < 0) fputs("Rotate 180 1 0 0\n", r->f);
    }
    return len;
}

static void cylinder(void *ud, const float a[3], const float b[3], float rad, ms_rgba8 col,
                     int caps, int res)
{
    (void)res;
    rib *r = ud;
    color(r, col);
    float len = along(r, a, b);
    fprintf(r->f, "Cylinder %g 0 %g 360\n", rad, len);
    if (caps & MS_CAP_BASE) fprintf(r->f, "Disk 0 %g 360\n", rad);
    if (caps & MS_CAP_APEX) fprintf(r->f, "Disk %g %g 360\n", len, rad);
    fputs("TransformEnd\n", r->f);
}

static void cone(void *ud, const float base[3], const float apex[3], float rb, float ra,
                 ms_rgba8 col, int res)
{
    (void)res;
    rib *r = ud;
    color(r, col);
    float len = along(r, base, apex);
    fprintf(r->f, "Hyperboloid [%g 0 0] [%g 0 %g] 360\nDisk 0 %g 360\nTransformEnd\n", rb, ra,
            len, rb);
}

static void triple(FILE *f, const char *name, const float *v, int n)
{
    fprintf(f, " \"%s\" [", name);
    for (int i = 0; i < 3 * n; i++) fprintf(f, "%s%g", i ? " " : "", v[i]);
    fputc(']', f);
}

static void colors(FILE *f, const ms_rgba8 *c, int n)
{
    float v[9];
    for (int k = 0; k < n; k++) ms_rgba8_to_float(c[k], v + 3 * k);
    triple(f, "Cs", v, n);
}

static void triangle(void *ud, const float p[9], const float n[9], const ms_rgba8 c[3])
{
    rib *r = ud;
    fputs("Polygon", r->f);
    triple(r->f, "P", p, 3);
    triple(r->f, "N", n, 3);
    colors(r->f, c, 3);
    fputc('\n', r->f);
}

static void line(void *ud, const float a[3], const float b[3], ms_rgba8 col)
{
    rib *r = ud;
    float p[6] = {a[0], a[1], a[2], b[0], b[1], b[2]};
    ms_rgba8 c[2] = {col, col};
    fputs("Curves \"linear\" [2] \"nonperiodic\"", r->f);
    triple(r->f, "P", p, 2);
    colors(r->f, c, 2);
    fprintf(r->f, " \"constantwidth\" [%g]\n", 2 * MS_EXPORT_LINE_RADIUS);
}

static void point(void *ud, const float c[3], ms_rgba8 col)
{
    rib *r = ud;
    fputs("Points", r->f);
    triple(r->f, "P", c, 1);
    colors(r->f, &col, 1);
    fprintf(r->f, " \"constantwidth\" [%g]\n", 2 * MS_EXPORT_LINE_RADIUS);
}

/* ---------------------------------------------------------------- the frame */

static void camera(FILE *f, const ms_scene *s, const char *path)
{
    const ms_camera *cam = &s->settings.cam;
    float aspect = (float)s->width / (float)s->height;
    fprintf(f, "##RenderMan RIB\nversion 3.03\n# written by molscope %s\n", PACKAGE_VERSION);
    fprintf(f, "Display \"%s.tif\" \"file\" \"rgb\"\n", path);
    fprintf(f, "Format %d %d 1\nFrameAspectRatio %g\n", s->width, s->height, aspect);
    float half = 0.5f * cam->height, d = cam->eye[2] - cam->distance;
    if (cam->projection == MS_PROJ_ORTHOGRAPHIC) {
        half *= 0.5f;
        fprintf(f, "Projection \"orthographic\"\nScreenWindow %g %g %g %g\n", -half * aspect,
                half * aspect, -half, half);
    } else {
        /* RenderMan's field of view is the angle of the smaller side */
        if (aspect < 1) half *= aspect;
        fprintf(f, "Projection \"perspective\" \"fov\" [%g]\n",
                2.0 * atan(half / (d > 0 ? d : 1.0f)) * 180.0 / M_PI);
    }
    fprintf(f, "Imager \"background\" \"color background\" [%g %g %g]\n", s->background[0],
            s->background[1], s->background[2]);
    fprintf(f, "Scale 1 1 -1\nTranslate %g %g %g\n", 0.0f - cam->eye[0], 0.0f - cam->eye[1],
            0.0f - cam->eye[2]);
}

static void lights(FILE *f, const ms_scene *s)
{
    fputs("LightSource \"ambientlight\" 0 \"intensity\" [1]\n", f);
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        const ms_light *l = &s->settings.lights[i];
        if (!l->on) continue;
        fprintf(f, "LightSource \"distantlight\" %d \"from\" [%g %g %g] \"to\" [0 0 0] "
                   "\"intensity\" [1] \"lightcolor\" [%g %g %g]\n",
                i + 1, l->pos[0], l->pos[1], l->pos[2], l->color[0], l->color[1], l->color[2]);
    }
}

static int rib_body(const ms_scene *s, FILE *f, void *path, ms_error *err)
{
    (void)err;
    static const ms_export_visitor v = {
        .item = item_begin, .item_end = item_end, .sphere = sphere, .cylinder = cylinder,
        .cone = cone, .triangle = triangle, .line = line, .point = point};
    rib r = {.f = f};
    camera(f, s, path);
    fputs("WorldBegin\n", f);
    lights(f, s);
    ms_export_walk(s, &v, &r);
    fputs("WorldEnd\n", f);
    return 0;
}

static int write_rib(const ms_scene *s, const char *path, ms_error *err)
{
    return ms_export_file(s, path, rib_body, (void *)path, err);
}

const ms_render_device ms_render_renderman = {
    .name = "RenderMan",
    .description = "RenderMan RIB scene file (prman, Aqsis, Pixie, 3Delight)",
    .default_cmd = "prman %s",
    .write = write_rib};
