/* volume.h: volumetric data sets attached to a molecule (density maps, potentials): a
 * regular grid of float values with its origin, axes and summary statistics. A molecule
 * keeps a list of them (ms_molecule.volumes), freed with it. The grid layout is that of
 * QuickSurf's ms_qsurf_volume (surf/qsurf.h): the same origin, step vectors, counts and x-
 * fastest data, so an Isosurface or VolumeSlice rep fills an ms_qsurf_volume from these
 * fields and hands the data to the marching cubes without copying it. */
#ifndef MS_VOLUME_H
#define MS_VOLUME_H

#include <stddef.h>

#include "base/base.h"

typedef struct ms_volume {
    char *name;
    float origin[3];       /* position of point (0, 0, 0), Angstrom */
    float delta[3][3];     /* step vector between neighbouring points along x, y, z */
    int n[3];              /* points along each axis */
    float *data;           /* n[0] n[1] n[2] values, x fastest */
    float min, max, mean, sigma;   /* over all points (sigma: population RMS deviation) */
} ms_volume;

struct ms_molecule;

/* Points in a volume (n[0] n[1] n[2]). */
size_t ms_volume_size(const ms_volume *v);
/* Recompute min, max, mean and sigma (in parallel over the data). */
void ms_volume_stats(ms_volume *v);
/* Free what a volume owns (not the struct). */
void ms_volume_clear(ms_volume *v);

/* The value at a point in space by trilinear interpolation; `outside` beyond the grid. For
 * an orthogonal or skewed grid alike (the position is solved in the grid's own axes). */
float ms_volume_value(const ms_volume *v, const float p[3], float outside);
/* The grid coordinates (i, j, k as reals) of a point in space. Returns -1 when the axes are
 * degenerate. */
int ms_volume_grid_coords(const ms_volume *v, const float p[3], double g[3]);
/* The value at grid coordinates g (reals) by trilinear interpolation, each clamped to
 * 0 .. n - 1 first. */
float ms_volume_value_at(const ms_volume *v, const double g[3]);
/* The point in space of grid coordinates g: origin + g[0] delta[0] + g[1] delta[1] + ... */
void ms_volume_point(const ms_volume *v, const double g[3], float p[3]);
/* The bounding box of the grid's eight corners. */
void ms_volume_bounds(const ms_volume *v, float lo[3], float hi[3]);

/* Many lookups in one volume: the inverse of its axes is computed once. */
typedef struct ms_volume_sampler {
    const ms_volume *v;
    double inv[3][3];      /* grid coordinates = inv (p - origin) */
    int ok;                /* 0 when the volume is empty or its axes are degenerate */
} ms_volume_sampler;

void ms_volume_sampler_init(ms_volume_sampler *s, const ms_volume *v);
/* The value at p as a 3-D texture with clamped edges gives it: interpolated at the point of
 * the grid nearest p in grid coordinates (each clamped to 0 .. n - 1); 0 when !s->ok. */
float ms_volume_sample(const ms_volume_sampler *s, const float p[3]);

/* Append a volume to a molecule, taking over what v owns (v is zeroed). Statistics are
 * computed. Returns its index, or -1 (out of memory; v is then freed). */
long ms_mol_add_volume(struct ms_molecule *m, ms_volume *v, ms_error *err);
/* Delete volume k (later ones move down by one). Returns -1 when there is no volume k. */
int ms_mol_delete_volume(struct ms_molecule *m, size_t k);
/* Free every volume of a molecule. */
void ms_mol_free_volumes(struct ms_molecule *m);

#endif
