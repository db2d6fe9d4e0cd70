/* color.h: VMD's colour table and colour categories. 33 named colours (ids 0..32) and the
 * 1024-entry colour scale (ids 33..1056, rebuilt from the active scale method); categories
 * of named items (Display Background, Axes X, Name C, Resname ALA, ...) each assigned a
 * colour id, with VMD's defaults; the residue-type table behind the Restype category.
 *
 * Representation builders resolve colours through this: category + item -> colour id ->
 * RGB. Every change bumps `version`, so a cached display list knows it must be rebuilt. */
#ifndef MS_COLOR_H
#define MS_COLOR_H

#include <stddef.h>

#include "base/base.h"
#include "molecule/molecule.h"

#define MS_COLOR_NUM 33                  /* named colours */
#define MS_COLOR_SCALE_BEGIN 33
#define MS_COLOR_SCALE_SIZE 1024
#define MS_COLOR_MAX (MS_COLOR_NUM + MS_COLOR_SCALE_SIZE)   /* 1057 */
#define MS_COLOR_AUTO_CYCLE 32           /* new items get (item count mod 32) */
#define MS_COLOR_SCALE_METHODS 18   /* 12 of three colours, 6 perceptual maps */

typedef struct ms_color_item {
    char *name;
    int color;
} ms_color_item;

typedef struct ms_color_category {
    char *name;
    ms_color_item *items;
    size_t n, cap;
} ms_color_category;

typedef struct ms_color_scale_method {
    char name[8];
    float rgb[3][3];                     /* low, middle, high */
    const float (*map)[3];               /* a perceptual map's 256 entries (colormaps.h), or
                                          * NULL: blended from the three colours */
} ms_color_scale_method;

typedef struct ms_restype {
    char *resname, *type;
} ms_restype;

typedef struct ms_colors {
    float rgb[MS_COLOR_MAX][3];
    ms_color_category *cats;
    size_t ncats, capcats;
    ms_color_scale_method methods[MS_COLOR_SCALE_METHODS];
    int method;                          /* active scale method, 0 = RWB */
    float scale_mid, scale_min, scale_max;   /* 0.5, 0.1 (the offset), 1.0 */
    ms_restype *restypes;
    size_t nrestypes, caprestypes;
    unsigned long version;
} ms_colors;

/* VMD's defaults: colours, scale, categories and items (colordefs), residue types. */
ms_colors *ms_colors_new(ms_error *err);
void ms_colors_free(ms_colors *c);

/* --- colours */
/* The name of colour id 0..32 ("blue" ... "orange3"), NULL otherwise. */
const char *ms_color_name(int id);
/* A colour named (case-insensitively) or numbered 0..1056; -1 when neither. */
int ms_color_index(const ms_colors *c, const char *s);
static inline const float *ms_color_rgb(const ms_colors *c, int id)
{
    return c->rgb[id < 0 ? 0 : id >= MS_COLOR_MAX ? MS_COLOR_MAX - 1 : id];
}
/* The default RGB of colour id (0..1056, the scale entries as the default scale makes them). */
int ms_color_default_rgb(int id, float rgb[3]);
/* Change the RGB of a colour (0..32 named, 33..1056 a colour-scale entry until the scale is
 * next rebuilt); values are clamped to [0, 1]. */
int ms_color_set_rgb(ms_colors *c, int id, const float rgb[3]);

/* --- the colour scale */
int ms_color_scale_method_index(const ms_colors *c, const char *name);
void ms_color_scale_set_method(ms_colors *c, int method);
void ms_color_scale_set_values(ms_colors *c, float mid, float min, float max);
void ms_color_scale_set_colors(ms_colors *c, int method, const float rgb[3][3]);
/* The RGB VMD's formula gives for position x in [0, 1] with the given method colours,
 * midpoint and offset (doc/vmd-behaviour.md section 4). */
void ms_color_scale_eval(const float rgb[3][3], float mid, float offset, float x, float out[3]);
/* Colour id of a value on the scale: 33 + int((v - min) * 1023 / (max - min)), clamped;
 * 33 + 512 when min == max. */
int ms_color_scale_index(float v, float min, float max);

/* --- categories and items */
int ms_color_category_index(const ms_colors *c, const char *name);
/* Add a category (or return the existing one); -1 when memory runs out. */
int ms_color_category_add(ms_colors *c, const char *name);
/* Item lookup: the item's index in the category, or -1. */
int ms_color_item_index(const ms_colors *c, int cat, const char *item);
/* The colour of an item, or -1 when the category has no such item. */
int ms_color_item_get(const ms_colors *c, int cat, const char *item);
/* Set an existing item's colour (0..1056). Returns 0, -1 when the item does not exist. */
int ms_color_item_set(ms_colors *c, int cat, const char *item, int color);
/* Add an item with a colour, or keep the existing one; returns the item's colour, -1 when
 * memory runs out. color < 0 picks VMD's default for new names: item count mod 32. */
int ms_color_item_add(ms_colors *c, int cat, const char *item, int color);

/* The colour of an atom property value in a molecule category, as VMD keys it: Name and
 * Type by the first non-digit character upper-cased, Conformation "" as "all", the others
 * by the full string. Unknown values are added with VMD's default. -1 only when memory runs
 * out. */
int ms_color_for_value(ms_colors *c, int cat, const char *value);
/* Add the items a molecule brings (names, types, elements, residue names, chains, segment
 * names, conformations, its id in Molecule), as VMD does when a structure loads. */
int ms_colors_add_molecule(ms_colors *c, const ms_molecule *m, ms_error *err);

/* --- residue types (Restype category) */
const char *ms_color_restype(const ms_colors *c, const char *resname);
/* Assign a residue type; type must be a Restype item. Returns 0 or -1. */
int ms_color_set_restype(ms_colors *c, const char *resname, const char *type);

#endif
