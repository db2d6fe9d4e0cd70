/* material.h: VMD's material list: Opaque and Transparent plus the materials of VMD's
 * materials.dat, each with ambient, specular, diffuse, shininess (the Phong exponent, shown
 * to users on VMD's 0..1 scale: exponent = 1000^x), mirror, opacity, outline, outline width
 * and transparency mode. Display lists name a material by its id, which never changes while
 * the material exists (names can be renamed; list positions shift on delete). */
#ifndef MS_MATERIAL_H
#define MS_MATERIAL_H

#include <stddef.h>

#include "base/base.h"

typedef enum ms_mat_prop {
    MS_MAT_AMBIENT, MS_MAT_SPECULAR, MS_MAT_DIFFUSE, MS_MAT_SHININESS, MS_MAT_MIRROR,
    MS_MAT_OPACITY, MS_MAT_OUTLINE, MS_MAT_OUTLINEWIDTH, MS_MAT_TRANSMODE, MS_MAT_NPROPS
} ms_mat_prop;

typedef struct ms_material {
    char *name;
    int id;              /* stable identity (what display lists store) */
    float ambient, specular, diffuse;
    float shininess;     /* Phong exponent, 1..1000 */
    float mirror, opacity, outline, outlinewidth, transmode;
} ms_material;

typedef struct ms_materials {
    ms_material *list;   /* in VMD's order; 0 = Opaque, 1 = Transparent */
    size_t n, cap;
    int next_id;
    unsigned long version;
} ms_materials;

ms_materials *ms_materials_new(ms_error *err);
void ms_materials_free(ms_materials *m);

/* Position in the list of a material named (case-insensitively) or numbered; -1 if none. */
int ms_material_index(const ms_materials *m, const char *name_or_index);
/* The material with a given id, or Opaque when that material was deleted. */
const ms_material *ms_material_by_id(const ms_materials *m, int id);

/* material add [name] [copy from]: NULL name gives "Material<N>"; returns the new index or
 * -1 (name taken, source missing, out of memory) with err set. */
int ms_material_add(ms_materials *m, const char *name, int copy_from, ms_error *err);
int ms_material_rename(ms_materials *m, int index, const char *name, ms_error *err);
/* Opaque and Transparent cannot be deleted. */
int ms_material_delete(ms_materials *m, int index, ms_error *err);
/* Restore a built-in material's values; -1 for a material the user added. */
int ms_material_restore_default(ms_materials *m, int index, ms_error *err);

/* Properties as users see them (shininess on the 0..1 scale). */
const char *ms_material_prop_name(ms_mat_prop p);
int ms_material_prop_from_name(const char *name);   /* -1 when unknown */
float ms_material_get(const ms_material *mat, ms_mat_prop p);
void ms_material_set(ms_materials *m, int index, ms_mat_prop p, float value);

/* VMD's shininess scale: exponent = 1000^x, and back. */
float ms_material_shininess_from_ui(float x);
float ms_material_shininess_to_ui(float exponent);

#endif
