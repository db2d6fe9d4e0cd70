/* cell.c: unit cells as lattice vectors and back, and the check every pbc call makes
 * before it changes a coordinate (the frames exist and have cells). */
#include "config.h"
#include "pbc/pbc.h"

#include <math.h>
#include <string.h>

int ms_pbc_cell_make(const float cell[6], ms_pbc_cell *c)
{
    if (!ms_cell_vectors(cell, c->v)) return 0;
    const double (*v)[3] = c->v;
    /* v is lower triangular: A = (ax 0 0), B = (bx by 0), C = (cx cy cz) */
    double ax = v[0][0], bx = v[1][0], by = v[1][1], cx = v[2][0], cy = v[2][1], cz = v[2][2];
    double inv[3][3] = {{1 / ax, 0, 0},
                        {-bx / (ax * by), 1 / by, 0},
                        {(bx * cy - by * cx) / (ax * by * cz), -cy / (by * cz), 1 / cz}};
    memcpy(c->inv, inv, sizeof inv);
    return 1;
}

static double vlen(const double a[3]) { return sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); }

static double angle_deg(const double a[3], const double b[3])
{
    double d = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (vlen(a) * vlen(b));
    if (d > 1) d = 1;
    if (d < -1) d = -1;
    return acos(d) * 180 / M_PI;
}

int ms_pbc_cell_params(const double v[3][3], float cell[6])
{
    double a = vlen(v[0]), b = vlen(v[1]), c = vlen(v[2]);
    if (!(a > 0 && b > 0 && c > 0) || !isfinite(a + b + c)) return 0;
    float out[6] = {(float)a, (float)b, (float)c, (float)angle_deg(v[1], v[2]),
                    (float)angle_deg(v[0], v[2]), (float)angle_deg(v[0], v[1])};
    memcpy(cell, out, sizeof out);
    return 1;
}

int ms_pbc_check_frames(const ms_molecule *m, size_t first, size_t last, ms_error *err)
{
    if (m->nframes == 0) {
        ms_error_set(err, "molecule %d has no frames", m->id);
        return -1;
    }
    if (first > last || last >= m->nframes) {
        ms_error_set(err, "frames %zu to %zu are not in molecule %d (frames 0 to %zu)", first,
                     last, m->id, m->nframes - 1);
        return -1;
    }
    for (size_t f = first; f <= last; f++) {
        ms_pbc_cell c;
        if (!ms_pbc_cell_make(m->frames[f].cell, &c)) {
            const float *p = m->frames[f].cell;
            ms_error_set(err, "frame %zu of molecule %d has no usable unit cell (%g %g %g %g "
                         "%g %g): set one with pbc set", f, m->id, p[0], p[1], p[2], p[3],
                         p[4], p[5]);
            return -1;
        }
    }
    return 0;
}
