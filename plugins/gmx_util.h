/* gmx_util.h: what the GROMACS trajectory plugins (xtc.c, trr.c) share: XDR numbers (32-bit
 * big-endian integers and IEEE floats) and the conversion between GROMACS' box (three box
 * vectors in nm, one per row) and a unit cell a b c (Angstrom) alpha beta gamma (degrees).
 * Header-only (static inline), so each plugin stays one module with no extra link. */
#ifndef MS_GMX_UTIL_H
#define MS_GMX_UTIL_H

#include <math.h>
#include <stdint.h>
#include <string.h>

#define MS_GMX_PI 3.14159265358979323846

static inline uint32_t ms_be32(const unsigned char *p)
{
    return (uint32_t)p[0] << 24 | (uint32_t)p[1] << 16 | (uint32_t)p[2] << 8 | p[3];
}

static inline float ms_be_float(const unsigned char *p)
{
    uint32_t v = ms_be32(p);
    float f;
    memcpy(&f, &v, 4);
    return f;
}

static inline void ms_put_be32(unsigned char *p, uint32_t v)
{
    p[0] = (unsigned char)(v >> 24), p[1] = (unsigned char)(v >> 16);
    p[2] = (unsigned char)(v >> 8), p[3] = (unsigned char)v;
}

static inline void ms_put_be_float(unsigned char *p, float f)
{
    uint32_t v;
    memcpy(&v, &f, 4);
    ms_put_be32(p, v);
}

/* Box vectors (nm, row k is vector k) -> a b c (Angstrom) alpha beta gamma (degrees); a
 * zero vector gives 90 degree angles. */
static inline void ms_gmx_box_to_cell(const double v[9], float cell[6])
{
    double len[3];
    for (int k = 0; k < 3; k++)
        len[k] = sqrt(v[3 * k] * v[3 * k] + v[3 * k + 1] * v[3 * k + 1] + v[3 * k + 2] * v[3 * k + 2]);
    static const int pair[3][2] = {{1, 2}, {0, 2}, {0, 1}};
    for (int k = 0; k < 3; k++) {
        const double *a = v + 3 * pair[k][0], *b = v + 3 * pair[k][1];
        double la = len[pair[k][0]], lb = len[pair[k][1]], ang = 90.0;
        if (la > 0 && lb > 0) {
            double c = (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]) / (la * lb);
            ang = c == 0 ? 90.0 : acos(c > 1 ? 1 : c < -1 ? -1 : c) * 180.0 / MS_GMX_PI;
        }
        cell[k] = (float)(10.0 * len[k]);
        cell[3 + k] = (float)ang;
    }
}

/* The box (nm, lower triangular: a along x, b in the xy plane) of a cell a b c (Angstrom)
 * alpha beta gamma (degrees); right angles are exact. */
static inline void ms_gmx_cell_to_box(const float c[6], float box[9])
{
    double al = c[3] * MS_GMX_PI / 180, be = c[4] * MS_GMX_PI / 180, ga = c[5] * MS_GMX_PI / 180;
    double ca = c[3] == 90 ? 0 : cos(al), cb = c[4] == 90 ? 0 : cos(be);
    double cg = c[5] == 90 ? 0 : cos(ga), sg = c[5] == 90 ? 1 : sin(ga);
    double a = c[0] / 10.0, b = c[1] / 10.0, cc = c[2] / 10.0;
    double z2 = 1 - cb * cb - ((ca - cb * cg) / sg) * ((ca - cb * cg) / sg);
    memset(box, 0, 9 * sizeof *box);
    box[0] = (float)a;
    box[3] = (float)(b * cg);
    box[4] = (float)(b * sg);
    box[6] = (float)(cc * cb);
    box[7] = (float)(cc * (ca - cb * cg) / sg);
    box[8] = (float)(cc * sqrt(z2 > 0 ? z2 : 0));
}

#endif
