/* lod.h: a lighter level of detail of a Scene for interactive frames (the live view's drag):
 * vertex-clustering decimation of triangle meshes on a uniform grid, and a cache of the
 * decimated meshes of a scene's lists, made once and kept while the lists do not change. */
#ifndef MS_SCENE_LOD_H
#define MS_SCENE_LOD_H

#include "scene/scene.h"

/* Cluster the vertices of a mesh on a grid of cubes of side cell whose corner is the low
 * corner of the mesh's bounding box: one vertex per occupied cube (the mean of its vertices'
 * positions, normals and colours), each triangle mapped to those, and the triangles with two
 * corners in one cube dropped. O(vertices + triangles). out is made (free it with
 * ms_mesh_free). Returns 0, or -1 with err set (out of memory, cell not a positive number). */
int ms_mesh_cluster(const ms_dl_mesh *in, float cell, ms_dl_mesh *out, ms_error *err);

/* ms_mesh_cluster with the smallest cell tried (from the mesh's area, growing) that leaves
 * at most max_tris triangles; *cell_used (may be NULL) receives it. */
int ms_mesh_decimate(const ms_dl_mesh *in, size_t max_tris, ms_dl_mesh *out, float *cell_used,
                     ms_error *err);

void ms_mesh_free(ms_dl_mesh *m);

/* Mesh triangles of every item of a scene. */
size_t ms_scene_triangles(const ms_scene *s);

/* The decimated lists of a scene, kept between frames. */
typedef struct ms_lod_entry ms_lod_entry;
typedef struct ms_scene_lod {
    ms_lod_entry **e;
    size_t n, cap;
} ms_scene_lod;

void ms_scene_lod_init(ms_scene_lod *l);
void ms_scene_lod_free(ms_scene_lod *l);

/* When the scene's meshes hold more than max_tris triangles, point its items at lists whose
 * meshes are decimated (each to its share of max_tris, meshes of 4096 triangles or fewer
 * kept whole when they hold half the budget or less; the other primitives are the
 * original's, shared), made now or taken from l when their list has not changed since
 * (same list, generation and counts). The lists l holds must outlive the scene's use; the
 * entries of lists no longer in the scene are freed. Returns 0 and the triangles the scene
 * holds afterwards in *tris, or -1 with err set (the scene is unchanged). */
int ms_scene_lod_apply(ms_scene_lod *l, ms_scene *s, size_t max_tris, size_t *tris,
                       ms_error *err);

#endif
