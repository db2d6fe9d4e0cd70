/* graphics.h: user graphics, VMD's `graphics <molid> ...` items: points, lines, cylinders,
 * cones, spheres, triangles (plain, with normals, with per-vertex colours), text, and the
 * state items color, material and materials. Each item has an integer id; `replace` makes the
 * next item take an existing id and place. The items of a molecule become display lists
 * (a new list wherever the material or the lighting changes), rebuilt only when the items or
 * the colour table change. */
#ifndef MS_GRAPHICS_H
#define MS_GRAPHICS_H

#include <stddef.h>

#include "base/base.h"
#include "scene/color.h"
#include "scene/displaylist.h"
#include "scene/material.h"

typedef enum ms_ug_kind {
    MS_UG_NONE,          /* a place kept for `replace` */
    MS_UG_POINT, MS_UG_LINE, MS_UG_CYLINDER, MS_UG_CONE, MS_UG_SPHERE, MS_UG_TRIANGLE,
    MS_UG_TRINORM, MS_UG_TRICOLOR, MS_UG_TEXT, MS_UG_COLOR, MS_UG_MATERIAL, MS_UG_MATERIALS
} ms_ug_kind;

/* One item. data holds points and normals in order (a, b, c, na, nb, nc) followed by the
 * kind's numbers; iv holds integers (see graphics.c for each kind's layout). */
typedef struct ms_ug_item {
    int id;
    ms_ug_kind kind;
    float data[18];
    float radius, radius2, size, thickness;
    int iv[3];
    char *text;
} ms_ug_item;

typedef struct ms_ugraphics {
    ms_ug_item *items;
    size_t n, cap;
    int next_id, max_id;
    size_t next_index;           /* where the next item goes (a replaced place, or n) */
    ms_displaylist *lists;       /* built from the items */
    size_t nlists, caplists;
    int dirty;
    unsigned long built_colors;  /* colour table version the lists were built with */
} ms_ugraphics;

ms_ugraphics *ms_ugraphics_new(void);
void ms_ugraphics_free(ms_ugraphics *g);

/* Add an item (its id is ignored and assigned); text is copied. Returns the new id, or -1
 * when memory runs out. */
int ms_ugraphics_add(ms_ugraphics *g, const ms_ug_item *item);
/* Position of an id in the item list, or -1 when it does not exist. */
long ms_ugraphics_find(const ms_ugraphics *g, int id);
void ms_ugraphics_delete(ms_ugraphics *g, int id);
void ms_ugraphics_delete_all(ms_ugraphics *g);
/* The next added item takes this id's place. Returns 0, or -1 when the id does not exist. */
int ms_ugraphics_replace(ms_ugraphics *g, int id);
/* VMD's description of an item ("sphere {0.000000 ...} radius 1.000000 resolution 6");
 * material items name the material's current list position. buf gets at most size bytes. */
void ms_ugraphics_info(const ms_ugraphics *g, long index, const ms_materials *mats, char *buf,
                       size_t size);

/* Rebuild the display lists if the items or the colours changed (lists start with colour 0,
 * blue, and material 0, Opaque, as VMD's do). Returns 0 or -1 (out of memory). */
int ms_ugraphics_update(ms_ugraphics *g, const ms_colors *colors, ms_error *err);

/* VMD's centre and scale for a molecule that has only graphics: the middle of the bounding
 * box of the items' points, and 2 / (largest extent) (extent 10 for a single point).
 * Returns 0 when there are no items with points. */
int ms_ugraphics_cov(const ms_ugraphics *g, float center[3], float *scale);

#endif
