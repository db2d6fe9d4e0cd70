/* pbc.h: periodic boundary conditions over the frames of a molecule, the numbers behind
 * VMD's pbctools (`pbc wrap`, `pbc unwrap`, `pbc join`): cells as lattice vectors,
 * compounds (residues, segments, chains, fragments, bonded groups), wrapping atoms or whole
 * compounds into a parallelepiped cell or the rectangular brick, unwrapping jumps between
 * frames, and making split compounds whole. Triclinic cells everywhere. The per-frame loops
 * run on all cores; nothing here knows about Tcl.
 *
 * A frame range [first, last] is checked whole before any coordinate changes: a frame
 * without a usable cell fails the call and leaves every frame as it was. */
#ifndef MS_PBC_H
#define MS_PBC_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"
#include "molecule/molecule.h"

/* A cell: lattice vectors A, B, C as rows of v (VMD's convention: A along x, B in the xy
 * plane), and the inverse matrix, so fractional coordinates are s = p inv. */
typedef struct ms_pbc_cell {
    double v[3][3], inv[3][3];
} ms_pbc_cell;

/* From a b c alpha beta gamma (degrees); 0 when the cell is unknown or degenerate. */
int ms_pbc_cell_make(const float cell[6], ms_pbc_cell *c);
/* a b c alpha beta gamma of three lattice vectors (rows of v); 0 when one is zero. */
int ms_pbc_cell_params(const double v[3][3], float cell[6]);

/* ---- compounds */

typedef enum ms_pbc_compound {
    MS_PBC_RESIDUE, MS_PBC_SEGMENT, MS_PBC_CHAIN, MS_PBC_FRAGMENT, MS_PBC_CONNECTED
} ms_pbc_compound;

/* Atoms grouped into compounds: the atoms of compound k are atoms[start[k] .. start[k+1]),
 * each ascending. CONNECTED groups atoms bonded to each other within the given atoms. */
typedef struct ms_pbc_groups {
    size_t n;              /* compounds */
    uint32_t *start;       /* n + 1 */
    uint32_t *atoms;       /* the atoms, compound by compound */
} ms_pbc_groups;

/* Group the (ascending) atoms by kind; each atom alone when kind < 0. */
int ms_pbc_groups_make(const ms_molecule *m, int kind, const uint32_t *atoms, size_t n,
                       ms_pbc_groups *g, ms_error *err);
void ms_pbc_groups_free(ms_pbc_groups *g);

/* ---- wrap */

typedef enum ms_pbc_center {
    MS_PBC_CENTER_UNITCELL, MS_PBC_CENTER_ORIGIN, MS_PBC_CENTER_COM, MS_PBC_CENTER_BB
} ms_pbc_center;

typedef struct ms_pbc_wrap_opts {
    const ms_pbc_groups *groups;    /* what moves together: each group by its mean position */
    ms_pbc_center center;
    const uint32_t *centersel;      /* atoms of -centersel (COM and BB), ascending */
    size_t ncentersel;
    double shiftcenter[3];          /* added to the centre, in Angstrom */
    double shiftcenterrel[3];       /* added to the centre, in cell vectors */
    int orthorhombic;               /* into the brick Ax By Cz, not the parallelepiped */
} ms_pbc_wrap_opts;

/* The centre of the wrapping cell in frame f (the cell is frame f's). */
int ms_pbc_center_of(const ms_molecule *m, size_t f, const ms_pbc_cell *c,
                     const ms_pbc_wrap_opts *o, double center[3], ms_error *err);
/* Wrap frames first..last: each group is moved by a lattice vector so that its mean
 * position lies in the cell centred on the centre. */
int ms_pbc_wrap(ms_molecule *m, size_t first, size_t last, const ms_pbc_wrap_opts *o,
                ms_error *err);

/* ---- unwrap and join */

/* Frames first+1..last: each atom moved by the lattice vector that brings it nearest to its
 * (already unwrapped) position in the frame before, so no atom jumps across the cell. */
int ms_pbc_unwrap(ms_molecule *m, size_t first, size_t last, const uint32_t *atoms, size_t n,
                  ms_error *err);

/* Join each group of frames first..last: every atom moved to the image nearest its
 * reference: the group's reference atom (the first atom of the group that is in ref, or
 * the group's first atom when ref is NULL or holds none), or with bondlist the bonded
 * neighbour through which it was reached from the reference atom (so compounds longer than
 * half the cell come out whole). ref: a molecule-sized bit array as bytes (NULL: none). */
int ms_pbc_join(ms_molecule *m, size_t first, size_t last, const ms_pbc_groups *g,
                const uint8_t *ref, int bondlist, ms_error *err);

/* Check that frames first..last exist and have cells (what the calls above check first). */
int ms_pbc_check_frames(const ms_molecule *m, size_t first, size_t last, ms_error *err);

#endif
