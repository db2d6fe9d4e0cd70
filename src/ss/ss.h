/* ss.h: secondary structure computed from the backbone, as Kabsch & Sander's DSSP defines it
 * (Biopolymers 22, 2577, 1983), for molecules whose file gave none (no HELIX/SHEET records)
 * or on request (`mol ssrecalc`). The codes are those of VMD's `structure` keyword
 * (MS_SS_CODES): H alpha helix, G 3-10 helix, I pi helix, E strand in a ladder, B isolated
 * bridge, T hydrogen-bonded turn, C everything else (DSSP's bends and loops, non-protein).
 *
 * As in VMD, structure is computed on demand and does not follow the frames: it is computed
 * once, from the frame current at the time, and again only when asked (ms_ss_compute,
 * `mol ssrecalc`). Selections of structure words and representations that draw structure
 * call ms_ss_ensure before they read atoms.ss. */
#ifndef MS_SS_H
#define MS_SS_H

#include "base/base.h"
#include "molecule/molecule.h"

/* Assign atoms.ss of every atom from the backbone of frame `frame` (negative: the current
 * one): protein residues (MS_AF_PROTEIN) with atoms N, CA, C and O (OT1 or OC1 for a
 * missing O; the first alternate location) get DSSP's assignment, all other atoms coil;
 * sets m->ss_known. Returns 0, or -1 with err set when the molecule has no such frame or
 * memory runs out (atoms.ss is then unchanged). Linear in the number of atoms: hydrogen
 * bonds are searched through a cell grid on the CA atoms, in parallel. */
int ms_ss_compute(ms_molecule *m, long frame, ms_error *err);

/* Make sure m has secondary structure before atoms.ss is read: compute it (frame negative:
 * the current one) unless it is already known (from the file's records, an earlier
 * computation, or set by `$sel set structure`). A molecule without coordinates yet is left
 * coil and not marked known, so that it is computed once a frame arrives. It changes the
 * molecule without telling listeners (callers are about to read the structure
 * themselves); call it from the thread that owns the molecule, before any parallel loop
 * reads atoms.ss. Returns 0 or -1 with err set. */
int ms_ss_ensure(ms_molecule *m, long frame, ms_error *err);

/* Per-residue assignment for a list of backbones, the core of ms_ss_compute and what the
 * unit tests exercise directly: residue k has N, CA, C, O at bb[12k .. 12k+12) (x y z
 * each, finite); seg[k] names its chain (residues with different seg are never
 * peptide-bonded); proline[k] is nonzero for prolines (no amide hydrogen). Breaks inside a
 * chain are found from the C-N distance (> 2.5 A). out[k] receives a code of MS_SS_CODES. */
int ms_ss_dssp(size_t nres, const float *bb, const uint32_t *seg, const uint8_t *proline,
               char *out, ms_error *err);

#endif
