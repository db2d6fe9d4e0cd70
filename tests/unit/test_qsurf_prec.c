/* test_qsurf_prec.c: the mesh storage types are compile-time switches. This program builds
 * the QuickSurf sources with double positions, float normals and 16-bit colours (see
 * tests/module.mk) and checks one atom's surface in that precision: the analytic radius,
 * unit normals, the colour at 16 bits, the bytes per vertex. */
#include "config.h"
#include "ms_test.h"
#include "surf/qsurf.h"

#include <math.h>
#include <string.h>

int main(void)
{
    t_suite = "qsurf-precision";
    float pos[3] = {0.5f, 0.25f, -1.0f}, radius = 1.5f, rgb[3] = {0.2f, 0.4f, 0.6f};
    ms_qsurf_atoms a = {.n = 1, .pos = pos, .radius = &radius, .rgb = rgb};
    ms_qsurf_params p;
    ms_qsurf_mesh m = {0};
    ms_error err = {{0}};
    ms_qsurf_params_default(&p);
    p.gridspacing = 0.25f, p.quality = 3, p.backend = MS_QSURF_CPU;
    t_ok(sizeof(ms_qsurf_pos_t) == 8 && sizeof(ms_qsurf_normal_t) == 4 &&
             sizeof(ms_qsurf_color_t) == 2 && MS_QSURF_VERTEX_BYTES == 44,
         "double positions, float normals, 16-bit colours: 44 bytes per vertex (%zu)",
         (size_t)MS_QSURF_VERTEX_BYTES);
    if (!t_ok(ms_qsurf_surface(&a, &p, &m, NULL, &err) == 0 && m.nv > 0, "surface (%s)", err.msg))
        return t_done();
    double want = 1.5 * sqrt(2.0 * log(2.0)), worst = 0.0, unit = 0.0;
    int colors = 1;
    for (size_t v = 0; v < m.nv; v++) {
        double d2 = 0.0, n2 = 0.0;
        for (int k = 0; k < 3; k++) {
            d2 += (m.pos[3 * v + k] - pos[k]) * (m.pos[3 * v + k] - pos[k]);
            n2 += (double)m.normal[3 * v + k] * m.normal[3 * v + k];
            if (abs((int)m.color[4 * v + k] - (int)lrint(rgb[k] * 65535.0)) > 2) colors = 0;
        }
        worst = fmax(worst, fabs(sqrt(d2) - want));
        unit = fmax(unit, fabs(sqrt(n2) - 1.0));
    }
    t_ok(worst < 0.01, "vertices at the analytic radius %.4f (worst %.4f)", want, worst);
    t_ok(unit < 1e-5, "float normals are unit vectors (worst %.1e)", unit);
    t_ok(colors && m.color[3] == 65535, "16-bit colours hold the atom's colour");
    ms_qsurf_mesh_free(&m);
    return t_done();
}
