/* combine.h: new molecules made of the atoms of others (topotools' mergemols,
 * selections2mol and replicatemol), and term-list edits that topotools needs: keeping only
 * some terms of a kind. Everything an atom carries comes along: its attributes, the bonds
 * (orders and types) and terms (types) among the atoms taken, frames and the cell. */
#ifndef MS_COMBINE_H
#define MS_COMBINE_H

#include "molecule/molecule.h"

/* Atoms of one molecule to copy: indices ascending (NULL: all), and the frame to take
 * (-1: the molecule's current frame). */
typedef struct ms_mol_part {
    const ms_molecule *m;
    const uint32_t *atoms;
    size_t natoms;
    long frame;
} ms_mol_part;

/* A molecule of the parts' atoms, in order, copied ncopies times (copy c moved by
 * shift[c], NULL: no shift). With all_frames and parts whose molecules have the same number
 * of frames, every frame is copied; otherwise the one frame of each part. The cell is the
 * first part's (the caller scales it for replicas). Bonds, residues, fragments and
 * classification are rebuilt. NULL with err set. */
ms_molecule *ms_mol_combine(const ms_mol_part *parts, size_t nparts, size_t ncopies,
                            const float (*shift)[3], int all_frames, ms_error *err);

/* Keep the terms of a kind whose keep[k] is non-zero, in order. */
void ms_terms_keep(ms_terms *t, int kind, const uint8_t *keep);

#endif
