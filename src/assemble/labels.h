/* labels.h: VMD's labels: atoms named by their text, and bonds, angles and dihedrals between
 * atoms of any molecules, drawn as dashed lines with their value. Each category holds an
 * ordered list (the label's index is its position); a label is shown or hidden, has a text
 * offset and (atoms) a text format with VMD's substitutions. The text size and thickness
 * are shared. Labels follow the molecules: the values are measured at the current frame when
 * drawn, and a label loses its place when one of its molecules is deleted. */
#ifndef MS_LABELS_H
#define MS_LABELS_H

#include <stddef.h>
#include <stdint.h>

#include "molecule/molset.h"
#include "scene/color.h"
#include "scene/material.h"
#include "scene/scene.h"

typedef enum ms_label_cat {
    MS_LABEL_ATOMS, MS_LABEL_BONDS, MS_LABEL_ANGLES, MS_LABEL_DIHEDRALS, MS_LABEL_NCATS
} ms_label_cat;

#define MS_LABEL_FORMAT_MAX 128

typedef struct ms_label {
    int n;                      /* atoms: 1 to 4 by category */
    int mol[4];
    uint32_t atom[4];
    int shown;
    float offset[2];            /* of the text, in screen units (x right, y up) */
    char format[MS_LABEL_FORMAT_MAX];   /* atoms' text; "" for the value of the others */
} ms_label;

typedef struct ms_labels {
    ms_label *v[MS_LABEL_NCATS];
    size_t n[MS_LABEL_NCATS], cap[MS_LABEL_NCATS];
    float size, thickness;      /* VMD's textsize and textthickness, 1 and 1 */
} ms_labels;

/* VMD's category names, and the one a word names (case-insensitively; -1 when none). */
const char *ms_label_cat_name(int cat);
int ms_label_cat_find(const char *word);
/* VMD's default text format of an atom label. */
#define MS_LABEL_ATOM_FORMAT "%R%d:%a"

void ms_labels_init(ms_labels *L);
void ms_labels_free(ms_labels *L);
/* Add a label of cat on the atoms (mol[i], atom[i]), i < cat + 1, checked against mols:
 * its index, the index of the same label when it is there already, or -1 with err set. */
long ms_labels_add(ms_labels *L, const ms_molset *mols, int cat, const int *mol,
                   const uint32_t *atom, ms_error *err);
/* Delete label i of cat (every label of cat when i < 0). */
void ms_labels_delete(ms_labels *L, int cat, long i);
/* Delete the labels that name molecule molid. */
void ms_labels_forget_molecule(ms_labels *L, int molid);

/* The value of a label at frame `frame` of its molecules (-1: each one's current frame):
 * distance, angle or dihedral (degrees); 0 for atoms. -1 when a molecule lacks the frame. */
int ms_label_value(const ms_molset *mols, const ms_label *l, long frame, double *value);
/* The number of frames a label can be measured at (its molecules' fewest). */
long ms_label_frames(const ms_molset *mols, const ms_label *l);
/* The text a label shows: an atom's format with its substitutions (%R resname, %r one-letter
 * resname, %d resid, %a name, %t type, %e element, %q charge, %b beta, %o occupancy,
 * %s segname, %c chain, %i index, %1i index + 1, %% a percent sign), else the value. */
void ms_label_text(const ms_molset *mols, int cat, const ms_label *l, char *buf, size_t size);

/* The shown labels of displayed molecules as a display list of the scene (world coordinates,
 * unlit), with VMD's Labels colours. 0, or -1 with err set. */
int ms_labels_to_scene(const ms_labels *L, const ms_molset *mols, const ms_colors *colors,
                       const ms_materials *mats, ms_scene *s, ms_error *err);

#endif
