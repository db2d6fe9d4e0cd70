/* serialize.h: a molecule as bytes, to send it to other processes (MPI ranks) or keep it.
 *
 * A molecule travels as a small header (every count, the interned strings, names, files,
 * view) followed by blocks: the big arrays themselves. The sender's blocks point straight
 * into the molecule; the receiver builds an empty molecule of the right size from the
 * header and its blocks point straight into the new arrays, so a large molecule is never
 * copied a second time. Frames travel the same way, any number at a time, appended to a
 * molecule that already has its structure. The layout is the machine's own (byte order
 * and float format are checked, not converted). ms_mol_serialize / ms_mol_deserialize
 * join everything into one buffer.
 *
 * Unpacking checks everything that could make later code read out of bounds (counts,
 * string ids, residue and fragment numbers, the bond table), so a damaged buffer gives an
 * error, not a crash. */
#ifndef MS_SERIALIZE_H
#define MS_SERIALIZE_H

#include "molecule/molecule.h"

typedef struct ms_molser_block {
    void *data;
    size_t bytes;
} ms_molser_block;

/* A header and the blocks that follow it, in order. */
typedef struct ms_molser {
    unsigned char *head;
    size_t head_len;
    ms_molser_block *block;
    size_t nblocks;
    size_t nbonds;     /* unpacking: bond table entries the header announced */
} ms_molser;

/* Free the header and the block list (not the data the blocks point to). */
void ms_molser_free(ms_molser *s);

/* The structure of m (atoms, strings, bonds, residues, fragments, files, view; not the
 * frames). The blocks point into m: keep m unchanged until they are sent. */
int ms_molser_pack(const ms_molecule *m, ms_molser *out, ms_error *err);
/* A new molecule sized from a structure header, with out's blocks pointing into its
 * arrays; fill every block in order, then call ms_molser_finish. */
ms_molecule *ms_molser_unpack(const void *head, size_t len, ms_molser *out, ms_error *err);
/* Check a molecule whose blocks (s, from ms_molser_unpack) were filled. Returns 0, or -1
 * (free the molecule). */
int ms_molser_finish(ms_molecule *m, const ms_molser *s, ms_error *err);

/* Frames [first, first + count) of m. */
int ms_molser_pack_frames(const ms_molecule *m, size_t first, size_t count, ms_molser *out,
                          ms_error *err);
/* Append the frames a frame header describes to m; out's blocks point into them (fill them
 * all). On error m is unchanged. The current frame becomes the last one. */
int ms_molser_unpack_frames(ms_molecule *m, const void *head, size_t len, ms_molser *out,
                            ms_error *err);

/* The whole molecule, frames included, in one malloc'd buffer. */
int ms_mol_serialize(const ms_molecule *m, void **buf, size_t *len, ms_error *err);
ms_molecule *ms_mol_deserialize(const void *buf, size_t len, ms_error *err);

#endif
