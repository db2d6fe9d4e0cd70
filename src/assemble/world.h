/* world.h: what the pictures are made of, and assembling it into the Scene a device draws.
 *
 * The world is the molecules (the application's molecule set) placed by their transforms,
 * each with its reps (rep/rep.h) and its user graphics (scene/graphics.h), the colour table,
 * the materials, the view (view.h: camera, lights, cueing, axes, stage), every render device's
 * settings (devices.h) and the display size. It holds no Tcl: the application (app/app.h)
 * owns one and the Tcl commands change it.
 *
 * ms_world_build_scene: the view's settings taken whole, the background colours from the
 * colour table, then every displayed molecule's display lists from the sources in build.c's
 * table (its user graphics, then its shown reps), placed with the molecule's model-to-world
 * transform global * rotate * scale * center (ms_view_mol_model), then the axes and the
 * stage. */
#ifndef MS_WORLD_H
#define MS_WORLD_H

#include "assemble/labels.h"
#include "molecule/molset.h"
#include "rep/rep.h"
#include "scene/color.h"
#include "scene/graphics.h"
#include "scene/material.h"
#include "scene/scene.h"

typedef struct ms_world {
    ms_molset *mols;               /* the molecules (not owned) */
    ms_colors *colors;             /* colour table and categories */
    ms_materials *materials;
    struct ms_view *view;          /* view.h */
    struct ms_renderers *renderers;    /* devices.h: every device's settings */
    ms_rep_state *reps;            /* the reps of every molecule, current settings */
    int ugraphics_slot;            /* molecule attachment of user graphics */
    ms_labels labels;              /* VMD's labels (labels.h) */
    int width, height;             /* display size in pixels (VMD's text mode: 512 x 512) */
    unsigned long scene_version;   /* bumped by whatever may change the picture: molecule
                                    * events, view changes, scene-changing commands (the
                                    * live view re-renders when it moves) */
    unsigned long scene_builds;    /* scenes built so far: building may rebuild stale display
                                    * lists, so a holder of an older scene (the live view's
                                    * ray tracer) knows its lists may have changed */
} ms_world;

/* Make the world of the molecules mols at VMD's defaults: colours, materials, the view,
 * device settings, reps, the user-graphics attachment; the colour categories follow the
 * molecules' names (a listener of mols). 0, or -1 with err set and nothing left allocated.
 * Free it after the molecules. */
int ms_world_init(ms_world *w, ms_molset *mols, ms_error *err);
void ms_world_free(ms_world *w);

/* The user graphics of a molecule, created on first use; NULL when memory runs out. */
ms_ugraphics *ms_world_ugraphics(ms_world *w, ms_molecule *m);

/* Assemble the scene (see above) at the display size. On failure the scene is freed and err
 * says why. */
int ms_world_build_scene(ms_world *w, ms_scene *s, ms_error *err);

#endif
