/* tess.c: tessellating spheres, cylinders and cones into triangles for file formats that
 * have no such primitives (and for Tachyon's cones). */
#include "config.h"
#include "render/export.h"
#include "vecmath/vecf.h"

#include <math.h>

/* Emit a triangle from three points and three normals. */
static void tri(ms_tri_cb cb, void *ud, const float *a, const float *b, const float *c,
                const float *na, const float *nb, const float *nc)
{
    float p[9], n[9];
    for (int k = 0; k < 3; k++) {
        p[k] = a[k]; p[3 + k] = b[k]; p[6 + k] = c[k];
        n[k] = na[k]; n[3 + k] = nb[k]; n[6 + k] = nc[k];
    }
    cb(ud, p, n);
}

static void sphere_point(const float c[3], float r, int i, int j, int stacks, int slices,
                         float p[3], float n[3])
{
    double th = M_PI * i / stacks, ph = 2.0 * M_PI * j / slices;
    n[0] = (float)(sin(th) * cos(ph));
    n[1] = (float)cos(th);
    n[2] = (float)(sin(th) * sin(ph));
    for (int k = 0; k < 3; k++) p[k] = c[k] + r * n[k];
}

void ms_tess_sphere(const float c[3], float r, int res, ms_tri_cb cb, void *ud)
{
    int stacks = res < 2 ? 2 : res > 512 ? 512 : res, slices = 2 * stacks;
    for (int i = 0; i < stacks; i++)
        for (int j = 0; j < slices; j++) {
            float p[4][3], n[4][3];
            sphere_point(c, r, i, j, stacks, slices, p[0], n[0]);
            sphere_point(c, r, i + 1, j, stacks, slices, p[1], n[1]);
            sphere_point(c, r, i + 1, j + 1, stacks, slices, p[2], n[2]);
            sphere_point(c, r, i, j + 1, stacks, slices, p[3], n[3]);
            if (i > 0) tri(cb, ud, p[0], p[3], p[2], n[0], n[3], n[2]);
            if (i < stacks - 1) tri(cb, ud, p[0], p[2], p[1], n[0], n[2], n[1]);
        }
}

/* Two unit vectors perpendicular to the axis and each other. */
static void frame(const float axis[3], float u[3], float v[3])
{
    float t[3] = {1, 0, 0};
    if (fabsf(axis[0]) > 0.9f) {
        t[0] = 0;
        t[1] = 1;
    }
    ms_v3f_cross(axis, t, u);
    ms_v3f_normalize(u);
    ms_v3f_cross(axis, u, v);
}

void ms_tess_cone(const float base[3], const float apex[3], float rb, float ra, int res,
                  int caps, ms_tri_cb cb, void *ud)
{
    int n = res < 3 ? 3 : res > 1024 ? 1024 : res;
    float ax[3] = {apex[0] - base[0], apex[1] - base[1], apex[2] - base[2]};
    float len = sqrtf(ax[0] * ax[0] + ax[1] * ax[1] + ax[2] * ax[2]);
    if (len <= 0) return;
    float u[3], v[3], dir[3] = {ax[0] / len, ax[1] / len, ax[2] / len};
    frame(dir, u, v);
    float slope = (rb - ra) / len;      /* the side normal tilts towards the apex */
    float back[3] = {-dir[0], -dir[1], -dir[2]};
    for (int i = 0; i < n; i++) {
        float pb[2][3], pa[2][3], nn[2][3];
        for (int s = 0; s < 2; s++) {
            double ang = 2.0 * M_PI * (i + s) / n;
            float cs = (float)cos(ang), sn = (float)sin(ang);
            for (int k = 0; k < 3; k++) {
                float radial = cs * u[k] + sn * v[k];
                pb[s][k] = base[k] + rb * radial;
                pa[s][k] = apex[k] + ra * radial;
                nn[s][k] = radial + slope * dir[k];
            }
            ms_v3f_normalize(nn[s]);
        }
        tri(cb, ud, pb[0], pb[1], pa[1], nn[0], nn[1], nn[1]);
        if (ra > 0) tri(cb, ud, pb[0], pa[1], pa[0], nn[0], nn[1], nn[0]);
        if ((caps & MS_CAP_BASE) && rb > 0) tri(cb, ud, base, pb[1], pb[0], back, back, back);
        if ((caps & MS_CAP_APEX) && ra > 0) tri(cb, ud, apex, pa[0], pa[1], dir, dir, dir);
    }
}
