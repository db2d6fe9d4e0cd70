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

/* Append a volume to a molecule, taking over what v owns (v is zeroed). Statistics are
 * computed. Returns its index, or -1 (out of memory; v is then freed). */
long ms_mol_add_volume(struct ms_molecule *m, ms_volume *v, ms_error *err);
/* Delete volume k (later ones move down by one). Returns -1 when there is no volume k. */
int ms_mol_delete_volume(struct ms_molecule *m, size_t k);
/* Free every volume of a molecule. */
void ms_mol_free_volumes(struct ms_molecule *m);

#endif
