/* load.h: reading files into molecules through plugins, the way `mol new` and `mol addfile`
 * do: transactional (a failed load leaves nothing behind), frame ranges (first, last, step),
 * and VMD's `waitfor`: the frames beyond it are read later, a batch at a time, by
 * ms_loader_pump (molscope calls it when Tcl is idle, and to the end on `update`, `vwait`
 * and `display update`). */
#ifndef MS_LOAD_H
#define MS_LOAD_H

#include "fileio/registry.h"
#include "molecule/molecule.h"

typedef struct ms_load_opts {
    const char *type;   /* plugin name; NULL = guess from the extension (pdb if unknown) */
    long first, last;   /* file frame range, inclusive; last < 0 = to the end */
    long step;          /* >= 1 */
    long waitfor;       /* frames to read now; < 0 = all */
    int filebonds;      /* use bonds the file lists */
    int autobonds;      /* add bonds by distance unless the file lists every bond */
    int bcast;          /* `bcast on`: load once and broadcast to every MPI rank; the
                         * commands route such loads to ms_par_load_* (parallel.h) */
    const char *assembly; /* build this biological assembly (mmCIF pdbx_struct_assembly id,
                           * PDB REMARK 350 biomolecule number) instead of the asymmetric
                           * unit; NULL = the file's atoms as they are */
    const char *options;  /* reader options for the plugin (ms_struct_sink.options) */
    int stream;           /* frames: 1 read on demand through a window (molscope's -stream),
                           * 0 kept in memory unless they would not fit (then streamed, with
                           * the reason in m->stream->why), -1 always kept */
    long window;          /* frames a stream keeps (0: MS_STREAM_WINDOW) */
} ms_load_opts;

void ms_load_opts_default(ms_load_opts *o);

/* Which plugin reads `path` given opts->type; error names the type and the known ones. */
const ms_plugin *ms_load_pick_plugin(const ms_registry *r, const char *path, const char *type,
                                     ms_error *err);

/* Read a new molecule from a file: its structure, then frames, then the volumetric data
 * sets the file holds. A file of volumes only (a .dx map) makes a molecule with no atoms
 * holding them. With opts->assembly the atoms are the assembly's copies: each generator's
 * atoms under each of its operators, in order, every frame transformed alike; each copy's
 * segname is its 1-based number in the assembly; file bonds are copied with their atoms.
 * The molecule is complete and analysed (bonds, residues, classification) but not yet
 * added to any molecule set. */
ms_molecule *ms_load_new(const ms_registry *r, const char *path, const ms_load_opts *o,
                         ms_error *err);

/* Add a file to an existing molecule: a structure file when the molecule has no atoms,
 * frames otherwise (the atom count must match); a volume file's data sets are appended to
 * the molecule's volumes whatever it holds (of a file of atoms and volumes, a cube, only
 * the volumes when the molecule already has atoms). On error the molecule is as before. */
int ms_load_add(const ms_registry *r, ms_molecule *m, const char *path, const ms_load_opts *o,
                ms_error *err);

/* Move a freshly loaded molecule src into an existing empty molecule dst, keeping dst's
 * identity (id, flags, view, attachments); src is freed. */
void ms_load_adopt(ms_molecule *dst, ms_molecule *src);

/* Read up to max_frames pending frames (all when max_frames < 0). Returns 1 when frames are
 * still pending, 0 when the file is done, -1 on a read error: the frames read before the
 * damage are kept, the rest of the file is not read, and err names the frame, the problem
 * and how many frames of the file are kept. *path_done is set to the file's path when it
 * finished, also after an error (owned by the caller: free it). */
int ms_loader_pump(ms_molecule *m, long max_frames, char **path_done, ms_error *err);
/* Stop reading pending frames and close the file. */
void ms_loader_cancel(ms_molecule *m);

/* Run the distance bond search now if a structure was loaded without coordinates and has
 * received its first frame since. */
int ms_load_finish_bonds(ms_molecule *m, ms_error *err);

#endif
