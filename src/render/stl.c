/* stl.c: the `STL` device: the scene as an ASCII stereolithography file, triangles only (as
 * VMD's STL renderer draws): spheres, cylinders and cones tessellated at their resolution,
 * meshes as they are; lines, points and text are left out. Each facet's normal is its
 * face's, pointing the way its vertex normals do. STL has no colours. */
#include "config.h"
#include "render/export.h"
#include "render/render.h"

#include <math.h>

/* The face normal of p, turned to agree with the vertex normals n. */
static void face_normal(const float p[9], const float n[9], float out[3])
{
    float u[3], v[3];
    for (int k = 0; k < 3; k++) {
        u[k] = p[3 + k] - p[k];
        v[k] = p[6 + k] - p[k];
    }
    out[0] = u[1] * v[2] - u[2] * v[1];
    out[1] = u[2] * v[0] - u[0] * v[2];
    out[2] = u[0] * v[1] - u[1] * v[0];
    float len = sqrtf(out[0] * out[0] + out[1] * out[1] + out[2] * out[2]);
    float dot = 0;
    for (int k = 0; k < 3; k++) dot += out[k] * (n[k] + n[3 + k] + n[6 + k]);
    float s = len > 0 ? (dot < 0 ? -1.0f : 1.0f) / len : 0;
    for (int k = 0; k < 3; k++) out[k] *= s;
}

static void facet(void *ud, const float p[9], const float n[9], const ms_rgba8 c[3])
{
    (void)c;
    FILE *f = ud;
    float fn[3];
    face_normal(p, n, fn);
    fprintf(f, " facet normal %g %g %g\n  outer loop\n", fn[0], fn[1], fn[2]);
    for (int k = 0; k < 3; k++)
        fprintf(f, "   vertex %g %g %g\n", p[3 * k], p[3 * k + 1], p[3 * k + 2]);
    fputs("  endloop\n endfacet\n", f);
}

static int stl_body(const ms_scene *s, FILE *f, void *user, ms_error *err)
{
    (void)user, (void)err;
    static const ms_export_visitor v = {.triangle = facet};
    fputs("solid molscope\n", f);
    ms_export_walk(s, &v, f);
    fputs("endsolid molscope\n", f);
    return 0;
}

static int write_stl(const ms_scene *s, const char *path, ms_error *err)
{
    return ms_export_file(s, path, stl_body, NULL, err);
}

const ms_render_device ms_render_stl = {
    .name = "STL",
    .description = "Stereolithography (ASCII STL), triangles only",
    .default_cmd = "true",
    .write = write_stl};
