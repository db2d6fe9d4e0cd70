/* molecule.h: the Molecule, molscope's central data: atoms as structure-of-arrays with
 * interned strings, residues, fragments, bonds in CSR form, and frames of float32
 * coordinates with their unit cells. About 80 bytes per atom of structure plus 12 bytes per
 * atom per frame. Nothing here knows about Tcl or about drawing. */
#ifndef MS_MOLECULE_H
#define MS_MOLECULE_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"
#include "base/strtab.h"
#include "molecule/volume.h"

/* Per-atom classification flags (ms_atoms.flags). */
enum {
    MS_AF_PROTEIN = 1u << 0,    /* in a protein residue */
    MS_AF_NUCLEIC = 1u << 1,    /* in a nucleic residue */
    MS_AF_PROT_BB = 1u << 2,    /* protein backbone (CA C O N, terminal oxygens) */
    MS_AF_NUC_BB = 1u << 3,     /* nucleic backbone (P O1P ... C5') */
    MS_AF_WATER = 1u << 4,
    MS_AF_HYDROGEN = 1u << 5,   /* by name, as VMD decides */
    MS_AF_HETERO = 1u << 6,     /* read from a HETATM record */
    MS_AF_USER_FLAGS = 8        /* bits 8..15: flag0..flag7 of the selection language */
};

/* Secondary structure codes, as VMD's `structure` keyword spells them. */
#define MS_SS_COIL_CODE 'C'
#define MS_SS_CODES "HGIEBTC"

/* The structure: one array per attribute, natoms long. */
typedef struct ms_atoms {
    size_t n, cap;
    ms_str *name, *type, *resname, *segname, *chain;
    int32_t *resid;
    char *insertion, *altloc;   /* '\0' when blank */
    uint8_t *atomicnumber;      /* 0 = unknown ("X") */
    float *beta, *occupancy, *charge, *mass, *radius;
    uint16_t *flags;            /* MS_AF_* */
    char *ss;                   /* secondary structure code: H G I E B T C */
    int32_t *residue;           /* 0-based unique residue number */
    int32_t *fragment;          /* 0-based connected component */
} ms_atoms;

/* Bonds in compressed-sparse-row form: the partners of atom i are to[start[i] .. start[i+1]),
 * sorted ascending; every bond appears once for each of its atoms. */
typedef struct ms_bonds {
    uint32_t *start;   /* natoms + 1 entries */
    uint32_t *to;
    float *order;      /* parallel to `to`, NULL when every order is 1 */
    ms_str *type;      /* parallel to `to`, NULL when no bond has a type */
} ms_bonds;

/* Angles, dihedrals and impropers as a file lists them (PSF, AMBER prmtop, LAMMPS data) or as
 * topotools makes them: width atom indices a term (3 for an angle, 4 for the others), in
 * the order given, and a type name a term when some term has one. Bonds cannot tell a
 * molecule's angles (VMD keeps them apart too), so nothing derives these from bonds. */
enum { MS_TERM_ANGLE, MS_TERM_DIHEDRAL, MS_TERM_IMPROPER, MS_TERM_KINDS };

typedef struct ms_terms {
    size_t n, cap;
    uint32_t *atoms;   /* width * n atom indices */
    ms_str *type;      /* n types, NULL when no term has a type */
} ms_terms;

/* Atoms a term of this kind names: 3 for an angle, 4 for a dihedral or an improper. */
static inline size_t ms_term_width(int kind) { return kind == MS_TERM_ANGLE ? 3 : 4; }

/* A frame's energies, the terms VMD's timestep keeps (molinfo's keywords bond ... efield, in
 * this order); zeros when unknown: files carry none, a simulation sends them over IMD. */
enum {
    MS_EN_BOND, MS_EN_ANGLE, MS_EN_DIHEDRAL, MS_EN_IMPROPER, MS_EN_VDW, MS_EN_ELEC,
    MS_EN_HBOND, MS_EN_KINETIC, MS_EN_POTENTIAL, MS_EN_TEMPERATURE, MS_EN_TOTAL, MS_EN_EFIELD,
    MS_EN_KINDS
};

/* One frame: coordinates (and velocities when the file had them), cell, time, energies. */
typedef struct ms_frame {
    float *pos;        /* 3 * natoms, x y z interleaved */
    float *vel;        /* NULL when absent */
    float cell[6];     /* a b c alpha beta gamma; zeros when unknown */
    double time;       /* physical time */
    float energy[MS_EN_KINDS];
    long long spos;    /* streamed (ms_stream): the frame's place in its file, the source's
                        * token; -1 for a frame kept in memory (loaded, made or pinned) */
    unsigned long used;/* streamed: when it was last asked for (the window's LRU clock) */
} ms_frame;

/* A streamed molecule's frames (molscope's `mol new ... -stream`): every frame keeps its
 * cell, time and place in the file; only a window of the most recently used ones holds
 * coordinates, read again on demand through the source (fileio sets it). Frames the script
 * changes are pinned: their spos becomes -1 and they stay in memory like VMD's. */
typedef struct ms_frame_source {
    void *ud;
    /* Read the frame at token spos into pos (3 natoms floats) and vel (NULL: not wanted). */
    int (*read)(void *ud, long long spos, float *pos, float *vel, ms_error *err);
    void (*free)(void *ud);
    char *path;           /* the file, for messages */
} ms_frame_source;

typedef struct ms_stream {
    ms_frame_source src;
    size_t window;        /* frames read from the file kept at most (>= 2) */
    unsigned long clock;
    int with_vel;
    char why[256];        /* why it streams, said once by whoever loaded it ("" when asked) */
} ms_stream;

#define MS_STREAM_WINDOW 4

/* A file that contributed to the molecule (for molinfo filename/filetype). */
typedef struct ms_molfile {
    char *path, *type;
    long first, last, step;     /* the load options it was read with (molinfo filespec) */
    int filebonds, autobonds;
} ms_molfile;

struct ms_loader;      /* a reader still delivering frames (fileio/load.h) */

typedef struct ms_molecule {
    int id;
    char *name;
    ms_strtab *strings;
    ms_atoms atoms;
    ms_bonds bonds;
    int has_bonds;            /* bonds.start allocated */
    ms_terms terms[MS_TERM_KINDS]; /* angles, dihedrals, impropers (MS_TERM_*) */
    int ss_known;             /* secondary structure came from the file or was computed */
    size_t nresidues;         /* residue numbers are 0..nresidues-1, contiguous runs */
    uint32_t *res_start;      /* nresidues + 1: first atom of each residue */
    size_t nfragments;

    ms_frame *frames;
    size_t nframes, frames_cap;
    int frame;                /* current frame, -1 when there is none */

    ms_molfile *files;
    size_t nfiles;
    ms_volume *volumes;       /* volumetric data sets (volume.h), in the order added */
    size_t nvolumes;
    char *remarks;

    unsigned active : 1, displayed : 1, fixed : 1;
    unsigned autobonds_pending : 1; /* bonds by distance once the first frame arrives */

    /* View state: model = global * rotate * scale * center (see view/ in later modules). */
    float center[3];          /* the centering translation is -center */
    float scale;
    float rotate[16];         /* row-major 4x4 */
    float global[3];          /* global translation */

    float *user[4];           /* user, user2, user3, user4: allocated on first set */
    int32_t *pfrag, *nfrag;   /* computed on first use (ms_mol_polymer_fragments) */
    struct ms_loader *pending;/* frames still to read in the background */
    ms_stream *stream;        /* NULL unless frames are read on demand (see ms_stream) */
    void *ext[8];             /* per-module attachments (reps, selections...), see molset.h */
    /* Someone else holding a frame's coordinates (Python's numpy views): asked before a
     * frame's pos is freed; when it answers 1 it has taken the array and frees it itself. */
    int (*keep_pos)(void *ud, float *pos);
    void *keep_pos_ud;
} ms_molecule;

/* The per-atom arrays of ms_atoms, for code that treats them all alike (growth,
 * serialisation): how many there are, and array k's address and element size. */
size_t ms_atoms_field_count(void);
void **ms_atoms_field(ms_atoms *a, size_t k, size_t *elsize);

/* Create an empty molecule (no atoms, no frames). */
ms_molecule *ms_mol_new(ms_error *err);
void ms_mol_free(ms_molecule *m);
/* Free everything a molecule owns but not the struct itself (for moving data between). */
void ms_mol_free_contents(ms_molecule *m);

/* Reserve room for n atoms in every per-atom array. */
int ms_mol_reserve_atoms(ms_molecule *m, size_t n, ms_error *err);
/* Append one blank atom (all fields zero / ""), returning its index, or -1. */
long ms_mol_add_blank_atom(ms_molecule *m, ms_error *err);
/* Append n blank atoms at once, returning the first one's index, or -1. */
long ms_mol_add_blank_atoms(ms_molecule *m, size_t n, ms_error *err);
/* The same, except that the arrays named in given[0 .. ngiven) (addresses of ms_atoms
 * members: &m->atoms.name ...) are left as they are, for a caller that writes every one of
 * the n atoms' values in them next (a bulk load: no pass zeroing what is then overwritten). */
long ms_mol_add_atoms_given(ms_molecule *m, size_t n, void *const *given, size_t ngiven,
                            ms_error *err);
/* Release unused capacity of the per-atom arrays after loading. */
void ms_mol_shrink(ms_molecule *m);

/* Append a frame of natoms positions (uninitialised) and return it, or NULL. The current
 * frame is not changed. */
ms_frame *ms_mol_add_frame(ms_molecule *m, int with_vel, ms_error *err);
/* Drop frames [first, nframes). */
void ms_mol_truncate_frames(ms_molecule *m, size_t first);
/* Delete frames first..last step `step` (inclusive), keeping the others in order. */
void ms_mol_delete_frames(ms_molecule *m, size_t first, size_t last, size_t step);
/* Current frame's coordinates, or NULL. The current frame of a streamed molecule is always
 * in memory (ms_mol_goto reads it). */
const float *ms_mol_pos(const ms_molecule *m);

/* Frame f with its coordinates in memory (a streamed frame is read into the window, the
 * least recently used one leaving it; the current frame never leaves), or NULL with err
 * naming the file and frame. The pointers stay valid until window - 1 other frames are
 * read. f must be < nframes. */
ms_frame *ms_mol_frame(ms_molecule *m, size_t f, ms_error *err);
/* Frame f's coordinates, read as ms_mol_frame does, for code given a const molecule (the
 * window is a cache: reading into it does not change the molecule); NULL with err. */
const float *ms_mol_frame_pos(const ms_molecule *m, size_t f, ms_error *err);
/* Read and pin frames first..last (< nframes; a change to all of them: wrap, unwrap,
 * join); -1 with err. */
int ms_mol_pin_frames(ms_molecule *m, size_t first, size_t last, ms_error *err);
/* ms_mol_frame, and the frame is pinned: it stays in memory from now on (for changes). */
ms_frame *ms_mol_frame_pin(ms_molecule *m, size_t f, ms_error *err);
/* Make frame f (< nframes) current, reading it when streamed; on error nothing changes. */
int ms_mol_goto(ms_molecule *m, size_t f, ms_error *err);
/* Start streaming: the molecule owns the source from now (freed with the molecule). */
int ms_mol_stream_start(ms_molecule *m, const ms_frame_source *src, size_t window,
                        int with_vel, ms_error *err);
/* Append a streamed frame (no coordinates in memory) at file token spos. */
ms_frame *ms_mol_add_streamed_frame(ms_molecule *m, long long spos, ms_error *err);
/* Frames holding coordinates now (of a streamed molecule: the window and the pinned). */
size_t ms_mol_resident_frames(const ms_molecule *m);

/* The cell vectors A, B, C (rows of v) of a frame's cell a b c alpha beta gamma (degrees), in
 * VMD's orientation: A along x, B in the xy plane. Returns 1, or 0 (v untouched) when the
 * cell is unknown (zeros) or degenerate (no volume, or not finite). */
int ms_cell_vectors(const float cell[6], double v[3][3]);

/* Replace all bonds with the given undirected pairs (i < j not required; duplicates and
 * self-bonds are dropped). order may be NULL. Recomputes fragments and classification. */
int ms_mol_set_bonds(ms_molecule *m, size_t npairs, const uint32_t *pairs, const float *order,
                     ms_error *err);

/* Append one term of `kind` (ms_term_width(kind) atom indices, each < natoms) with type
 * `type` (MS_STR_NONE: untyped; the first typed term gives the earlier ones type ""). */
int ms_terms_add(ms_molecule *m, int kind, const uint32_t *atoms, ms_str type, ms_error *err);
/* Drop every term of `kind`. */
void ms_terms_clear(ms_terms *t);

/* Per-atom strings. */
static inline const char *ms_mol_str(const ms_molecule *m, ms_str id)
{
    return ms_strtab_get(m->strings, id);
}

/* Bytes a molecule holds, by structure (allocated capacities, not what is in use). */
typedef struct ms_mol_memory {
    size_t atoms;      /* the per-atom arrays of ms_atoms */
    size_t strings;    /* the interned strings */
    size_t bonds;      /* bonds (CSR, orders and types) */
    size_t topology;   /* residues, fragments, angles, dihedrals, impropers */
    size_t frames;     /* coordinates and velocities of every frame */
    size_t other;      /* user fields, volumes' data */
} ms_mol_memory;
void ms_mol_memory_of(const ms_molecule *m, ms_mol_memory *out);

/* Bytes used by the structure (not frames), for memory reports. */
size_t ms_mol_structure_bytes(const ms_molecule *m);

/* Record a file the molecule was read from. */
int ms_mol_add_file(ms_molecule *m, const char *path, const char *type, ms_error *err);

#endif
