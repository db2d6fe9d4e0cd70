/* molset.h: the set of loaded molecules: ids, the top molecule, and events other modules
 * (the Tcl trace variables, the colour categories, reps) listen to, in the order they started
 * listening. */
#ifndef MS_MOLSET_H
#define MS_MOLSET_H

#include "molecule/molecule.h"

typedef enum ms_mol_event {
    MS_EV_MOL_NEW,        /* a molecule was added (VMD: vmd_initialize_structure = 1) */
    MS_EV_MOL_DELETE,     /* about to be deleted (vmd_initialize_structure = 0) */
    MS_EV_FRAME,          /* its current frame changed (vmd_frame) */
    MS_EV_FRAMES_ADDED,   /* frames were appended or deleted (vmd_timestep) */
    MS_EV_TRAJ_DONE,      /* a file finished loading (vmd_trajectory_read); arg: path */
    MS_EV_STRUCTURE,      /* atoms' attributes or bonds changed */
    MS_EV_VOLUMES,        /* volumetric data sets were added or deleted */
    MS_EV_STRUCTURE_LOADED,   /* a file gave the molecule its first atoms (VMD then gives it
                               * its default rep; the view is reset after this event) */
    MS_EV_VOLUMES_LOADED  /* a file gave a molecule without atoms its first volumetric data
                           * (VMD then draws it with an Isosurface rep) */
} ms_mol_event;

typedef void (*ms_mol_listener)(void *ud, ms_mol_event ev, ms_molecule *m, const char *arg);
/* A per-molecule attachment owned by another module, freed with the molecule. */
typedef void (*ms_ext_free_fn)(void *ext);

#define MS_MAX_LISTENERS 8
#define MS_MAX_EXT 8

typedef struct ms_molset {
    ms_molecule **mols;     /* in creation order */
    size_t n, cap;
    int next_id;
    int top;                /* id, -1 when none */
    struct {
        ms_mol_listener fn;
        void *ud;
    } listeners[MS_MAX_LISTENERS];
    int nlisteners;
    ms_ext_free_fn ext_free[MS_MAX_EXT];
    int next_ext;           /* next free attachment slot */
} ms_molset;

void ms_molset_init(ms_molset *s);
void ms_molset_free(ms_molset *s);

/* Add a finished molecule: it gets the next id and becomes top. */
int ms_molset_add(ms_molset *s, ms_molecule *m, ms_error *err);
/* Delete a molecule (listeners hear MS_EV_MOL_DELETE first). */
void ms_molset_delete(ms_molset *s, int id);
ms_molecule *ms_molset_get(const ms_molset *s, int id);
ms_molecule *ms_molset_top(const ms_molset *s);
/* Position (0-based, creation order) of a molecule id, or -1. */
int ms_molset_index_of(const ms_molset *s, int id);

/* Set the current frame (clamped to the frames that exist) and tell listeners. A streamed
 * frame is read first: ms_molset_goto returns -1 with err when it cannot be (nothing
 * changes); ms_molset_set_frame then keeps the frame it had. */
int ms_molset_goto(ms_molset *s, ms_molecule *m, long frame, ms_error *err);
void ms_molset_set_frame(ms_molset *s, ms_molecule *m, long frame);
/* Tell every listener of an event of m, in order; when one deletes m (a Tcl trace callback
 * can), the rest are not told. */
void ms_molset_emit(ms_molset *s, ms_mol_event ev, ms_molecule *m, const char *arg);
int ms_molset_listen(ms_molset *s, ms_mol_listener fn, void *ud);
/* Reserve a per-molecule attachment slot (ms_molecule.ext[slot]); -1 when none is left. */
int ms_molset_register_ext(ms_molset *s, ms_ext_free_fn free_fn);

#endif
