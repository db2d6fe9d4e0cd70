/* lammps_util.h: what the LAMMPS plugins (lammpsdata.c, lammpstrj.c) share: LAMMPS' box
 * (lo/hi bounds along x, y, z and the tilt factors xy xz yz) and its conversion to and from a
 * unit cell a b c (Angstrom) alpha beta gamma (degrees), the mapping of fractional and
 * image-shifted coordinates into space, and the `key=value` options a caller passes.
 * Header-only (static inline), so each plugin stays one module with no extra link. */
#ifndef MS_LAMMPS_UTIL_H
#define MS_LAMMPS_UTIL_H

#include <math.h>
#include <stdio.h>
#include <string.h>

#define MS_LMP_PI 3.14159265358979323846

/* A LAMMPS box: the parallelepiped with origin lo and edge vectors A = (lx, 0, 0),
 * B = (xy, ly, 0), C = (xz, yz, lz), where l = hi - lo. */
typedef struct ms_lmp_box {
    double lo[3], hi[3];
    double xy, xz, yz;
    int triclinic;     /* the file gave tilt factors */
} ms_lmp_box;

/* a b c alpha beta gamma of a box; 0 when an edge is not positive (cell left zero). */
static inline int ms_lmp_box_to_cell(const ms_lmp_box *b, float cell[6])
{
    double lx = b->hi[0] - b->lo[0], ly = b->hi[1] - b->lo[1], lz = b->hi[2] - b->lo[2];
    memset(cell, 0, 6 * sizeof *cell);
    if (!(lx > 0 && ly > 0 && lz > 0)) return 0;
    double A = lx, B = sqrt(ly * ly + b->xy * b->xy),
           C = sqrt(lz * lz + b->xz * b->xz + b->yz * b->yz);
    double ca = (b->xy * b->xz + ly * b->yz) / (B * C), cb = b->xz / C, cg = b->xy / B;
    double deg = 180.0 / MS_LMP_PI;
    cell[0] = (float)A, cell[1] = (float)B, cell[2] = (float)C;
    cell[3] = (float)(acos(ca) * deg), cell[4] = (float)(acos(cb) * deg);
    cell[5] = (float)(acos(cg) * deg);
    return 1;
}

/* The box of a cell (lo at origin); 0 when the cell is unknown or degenerate. */
static inline int ms_lmp_cell_to_box(const float cell[6], const double origin[3], ms_lmp_box *b)
{
    double a = cell[0], bb = cell[1], c = cell[2], rad = MS_LMP_PI / 180.0;
    memset(b, 0, sizeof *b);
    if (!(a > 0 && bb > 0 && c > 0)) return 0;
    double ca = cos(cell[3] * rad), cb = cos(cell[4] * rad), cg = cos(cell[5] * rad);
    double lx = a, xy = bb * cg, xz = c * cb;
    double ly2 = bb * bb - xy * xy;
    if (!(ly2 > 0)) return 0;
    double ly = sqrt(ly2), yz = (bb * c * ca - xy * xz) / ly;
    double lz2 = c * c - xz * xz - yz * yz;
    if (!(lz2 > 0)) return 0;
    double l[3] = {lx, ly, sqrt(lz2)};
    for (int d = 0; d < 3; d++) b->lo[d] = origin[d], b->hi[d] = origin[d] + l[d];
    b->xy = fabs(xy) < 1e-9 * a ? 0 : xy;
    b->xz = fabs(xz) < 1e-9 * a ? 0 : xz;
    b->yz = fabs(yz) < 1e-9 * a ? 0 : yz;
    b->triclinic = b->xy != 0 || b->xz != 0 || b->yz != 0;
    return 1;
}

/* A dump's BOX BOUNDS of a triclinic box give the bounding box of the tilted cell: the
 * box's own lo/hi along x and y are those minus the tilts' extremes. */
static inline void ms_lmp_box_from_bounds(ms_lmp_box *b)
{
    double xs[4] = {0, b->xy, b->xz, b->xy + b->xz}, xmin = 0, xmax = 0;
    for (int k = 1; k < 4; k++) {
        if (xs[k] < xmin) xmin = xs[k];
        if (xs[k] > xmax) xmax = xs[k];
    }
    b->lo[0] -= xmin, b->hi[0] -= xmax;
    b->lo[1] -= b->yz < 0 ? b->yz : 0, b->hi[1] -= b->yz > 0 ? b->yz : 0;
}

/* The inverse of ms_lmp_box_from_bounds, for writers. */
static inline void ms_lmp_bounds_of_box(const ms_lmp_box *b, double lo[3], double hi[3])
{
    double xs[4] = {0, b->xy, b->xz, b->xy + b->xz}, xmin = 0, xmax = 0;
    for (int k = 1; k < 4; k++) {
        if (xs[k] < xmin) xmin = xs[k];
        if (xs[k] > xmax) xmax = xs[k];
    }
    memcpy(lo, b->lo, sizeof b->lo);
    memcpy(hi, b->hi, sizeof b->hi);
    lo[0] += xmin, hi[0] += xmax;
    lo[1] += b->yz < 0 ? b->yz : 0, hi[1] += b->yz > 0 ? b->yz : 0;
}

/* Position of fractional coordinates s (with lo added when add_lo) plus image shifts n:
 * r = [lo] + (s0 + n0) A + (s1 + n1) B + (s2 + n2) C. Cartesian input is shifted only:
 * pass s = 0 and add the result to it. */
static inline void ms_lmp_to_space(const ms_lmp_box *b, const double s[3], int add_lo,
                                   double r[3])
{
    double lx = b->hi[0] - b->lo[0], ly = b->hi[1] - b->lo[1], lz = b->hi[2] - b->lo[2];
    r[0] = s[0] * lx + s[1] * b->xy + s[2] * b->xz;
    r[1] = s[1] * ly + s[2] * b->yz;
    r[2] = s[2] * lz;
    if (add_lo)
        for (int d = 0; d < 3; d++) r[d] += b->lo[d];
}

/* The box a writer gives a frame: its cell placed around the centre of the atoms' bounding
 * box (returns 1), else that bounding box (a flat dimension widened to 1 A; returns 0). */
static inline int ms_lmp_frame_box(size_t natoms, const float *pos, const float cell[6],
                                    ms_lmp_box *b)
{
    double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    for (size_t i = 0; i < natoms; i++)
        for (int d = 0; d < 3; d++) {
            double x = pos[3 * i + d];
            if (i == 0 || x < lo[d]) lo[d] = x;
            if (i == 0 || x > hi[d]) hi[d] = x;
        }
    double c[3], zero[3] = {0, 0, 0}, half[3], one[3] = {0.5, 0.5, 0.5};
    for (int d = 0; d < 3; d++) c[d] = 0.5 * (lo[d] + hi[d]);
    if (ms_lmp_cell_to_box(cell, zero, b)) {
        ms_lmp_to_space(b, one, 0, half);
        for (int d = 0; d < 3; d++) {
            double l = b->hi[d] - b->lo[d];
            b->lo[d] = c[d] - half[d];
            b->hi[d] = b->lo[d] + l;
        }
        return 1;
    }
    memset(b, 0, sizeof *b);
    for (int d = 0; d < 3; d++) {
        double pad = hi[d] - lo[d] < 1e-3 ? 0.5 : 0.0;
        b->lo[d] = lo[d] - pad, b->hi[d] = hi[d] + pad;
    }
    return 0;
}

/* The value of `key` in an options string ("atom_style=full other=x"), copied into out;
 * 0 when the key is absent. */
static inline int ms_lmp_option(const char *options, const char *key, char *out, size_t n)
{
    size_t kl = strlen(key);
    for (const char *p = options; p && *p;) {
        p += strspn(p, " \t");
        size_t wl = strcspn(p, " \t");
        if (wl > kl && !strncmp(p, key, kl) && p[kl] == '=') {
            snprintf(out, n, "%.*s", (int)(wl - kl - 1), p + kl + 1);
            return 1;
        }
        p += wl;
    }
    return 0;
}

#endif
