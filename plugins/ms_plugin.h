/* ms_plugin.h: the file-format plugin interface of molscope.
 *
 * A plugin is a shared object exporting one function, ms_plugin_entry(), that returns a
 * static description of the format: its name, extensions, and the functions that read and
 * write it. A plugin never sees molscope's molecule or Tcl: it pushes what it reads into a
 * sink the host provides, and reads what it writes from a view the host provides. Every
 * function reports failure by returning MS_PLUGIN_ERROR after filling the error buffer with
 * a message naming the line or record ("line 12: bad coordinate field").
 *
 * This header is self-contained (C99, no molscope symbols), so plugins build on their own.
 *
 * ABI history. 1: structures and frames. 2: volumetric data (read_volume_meta,
 * read_volume_data, write_volume and the MS_CAN_*_VOLUME bits, appended to ms_plugin) and
 * biological assemblies (add_assembly, appended to ms_struct_sink). 3: typed bonds, terms and
 * options (appended to the sink and the view). 4 (this header): atoms and bonds in bulk
 * (set_strings, add_atoms, add_bonds, appended to the sink) and seekable frames (tell_frame,
 * seek_frame, appended to ms_plugin) for trajectories read on demand. The host still loads
 * ABI 1 to 3 plugins: it copies their shorter description into a zeroed current one, so the
 * new members read as NULL; it fills every sink member, so a plugin may call any its ABI
 * names. */
#ifndef MS_PLUGIN_H
#define MS_PLUGIN_H

#include <stdarg.h>
#include <stddef.h>
#include <stdint.h>
#include <stdio.h>

#ifdef __cplusplus
extern "C" {
#endif

#define MS_PLUGIN_ABI 4
#define MS_PLUGIN_ABI_MIN 1  /* the oldest ABI the host still loads */

enum { MS_PLUGIN_OK = 0, MS_PLUGIN_EOF = 1, MS_PLUGIN_ERROR = -1 };

/* Error buffer filled by a failing plugin call. */
typedef struct ms_perr {
    char msg[512];
} ms_perr;

static inline int ms_perr_set(ms_perr *e, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
static inline int ms_perr_set(ms_perr *e, const char *fmt, ...)
{
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(e->msg, sizeof e->msg, fmt, ap);
    va_end(ap);
    return MS_PLUGIN_ERROR;
}

/* Which optional fields of ms_atom_in hold data. */
enum {
    MS_HAS_BETA = 1u << 0,
    MS_HAS_OCCUPANCY = 1u << 1,
    MS_HAS_CHARGE = 1u << 2,
    MS_HAS_MASS = 1u << 3,
    MS_HAS_RADIUS = 1u << 4,
    MS_HAS_ATOMICNUMBER = 1u << 5, /* atomicnumber (else element symbol, else guessed) */
    MS_HAS_POS = 1u << 6,          /* x, y, z: this atom's position in the first frame */
    MS_HAS_VEL = 1u << 7           /* vx, vy, vz */
};

/* One atom as a file describes it. Strings may point into the plugin's own buffers: the
 * host copies what it keeps before add_atom returns. NULL strings mean "". */
typedef struct ms_atom_in {
    const char *name, *type, *resname, *segname, *chain, *element;
    int resid;
    char insertion, altloc; /* ' ' or '\0' when blank */
    int hetero;             /* a HETATM record */
    unsigned has;           /* MS_HAS_* bits */
    float beta, occupancy, charge, mass, radius;
    int atomicnumber;
    float x, y, z, vx, vy, vz;
} ms_atom_in;

/* Secondary-structure codes, as VMD's `structure` keyword spells them. */
enum {
    MS_SS_ALPHA = 'H', MS_SS_310 = 'G', MS_SS_PI = 'I', MS_SS_EXTENDED = 'E',
    MS_SS_BRIDGE = 'B', MS_SS_TURN = 'T', MS_SS_COIL = 'C'
};

/* The kinds of term a force field lists besides bonds (ABI 3): an angle names 3 atoms, a
 * dihedral or an improper 4, in the order the file gives them. */
enum { MS_PTERM_ANGLE = 0, MS_PTERM_DIHEDRAL = 1, MS_PTERM_IMPROPER = 2 };

/* ABI 4: atoms in bulk. The string fields of an atom, as set_strings and ms_atom_columns
 * name them. */
enum {
    MS_STRF_NAME, MS_STRF_TYPE, MS_STRF_RESNAME, MS_STRF_SEGNAME, MS_STRF_CHAIN, MS_STRF_STRINGS
};

/* A run of atoms as columns (ABI 4, add_atoms): what n add_atom calls would give, one array
 * per field. A string field is an index per atom into the table set_strings declared for it
 * (NULL: "" for every atom). A NULL number column is a field the file does not have (the
 * host fills its default, as add_atom without the MS_HAS_ bit); an atomic number outside
 * 1..118 is unknown (guessed from the name, as add_atom does). Insertion codes and altlocs
 * are blank, no atom is a HETATM. */
typedef struct ms_atom_columns {
    size_t n;
    const uint32_t *str[MS_STRF_STRINGS];
    const int32_t *resid;
    const float *beta, *occupancy, *charge, *mass, *radius;
    const int32_t *atomicnumber;
    const float *pos;             /* 3n: x y z of the first frame, NULL when none */
} ms_atom_columns;

/* Where a structure reader puts what it reads. Each function returns 0, or -1 when the host
 * ran out of memory (the plugin then returns MS_PLUGIN_ERROR with a message). */
typedef struct ms_struct_sink ms_struct_sink;
struct ms_struct_sink {
    void *host;
    /* A hint: about this many atoms follow (may be wrong either way). */
    int (*reserve)(ms_struct_sink *s, size_t natoms);
    int (*add_atom)(ms_struct_sink *s, const ms_atom_in *a);
    /* A bond between atoms i and j (0-based, in the order added); order 1 if unknown. */
    int (*add_bond)(ms_struct_sink *s, size_t i, size_t j, float order);
    /* The file lists every bond (a PSF): no distance search is needed. */
    void (*bonds_complete)(ms_struct_sink *s);
    /* A secondary-structure range (PDB HELIX/SHEET), inclusive, in one chain. */
    int (*add_ss_range)(ms_struct_sink *s, char code, const char *chain, int resid0,
                        char insertion0, int resid1, char insertion1);
    /* Unit cell of the first frame: a b c (Angstrom) alpha beta gamma (degrees). */
    void (*set_cell)(ms_struct_sink *s, const float cell[6]);
    /* Physical time of the first frame, when the file gives one. */
    void (*set_time)(ms_struct_sink *s, double time);
    /* A line of free text (PDB REMARK, title). */
    int (*add_remark)(ms_struct_sink *s, const char *text);
    /* ABI 2. One generator of biological assembly `id` (mmCIF pdbx_struct_assembly_gen,
     * PDB REMARK 350): copies of the atoms in nranges half-open index ranges [r[0], r[1])
     * (0-based, in the order added), one copy per operator. ops holds nops 3x4 matrices,
     * row-major [R | t], Angstrom, the copies coming in that order. An assembly with
     * several generators is their copies in the order reported. Call it after the atoms. */
    int (*add_assembly)(ms_struct_sink *s, const char *id, size_t nranges,
                        const size_t (*ranges)[2], size_t nops, const double (*ops)[12]);
    /* ABI 3. add_bond with a type name (a force field's bond type; NULL or "" for none). */
    int (*add_typed_bond)(ms_struct_sink *s, size_t i, size_t j, float order, const char *type);
    /* ABI 3. One angle, dihedral or improper (kind MS_PTERM_*): 3 or 4 atoms, 0-based in the
     * order added, with a type name (NULL for none). Call it after the atoms. */
    int (*add_term)(ms_struct_sink *s, int kind, const size_t *atoms, const char *type);
    /* ABI 3. Reader options the caller gave (`key=value` words separated by blanks, such as
     * "atom_style=full"), NULL when none; a reader ignores keys it does not know. */
    const char *options;
    /* ABI 4. The distinct strings (n of them) of string field `field` (MS_STRF_*) that later
     * add_atoms calls index. They stay valid and unchanged until the next set_strings of
     * that field or the end of read_structure; the host interns each once, when an atom
     * first uses it. Returns -1 for a bad field as well. */
    int (*set_strings)(ms_struct_sink *s, int field, size_t n, const char *const *strings);
    /* ABI 4. Append c->n atoms (after those added so far, by either call). Returns -1, with
     * nothing added, when an index is outside its table or the host ran out of memory. */
    int (*add_atoms)(ms_struct_sink *s, const ms_atom_columns *c);
    /* ABI 4. n bonds from[k]-to[k] (0-based), orders (NULL: all 1) as add_bond. */
    int (*add_bonds)(ms_struct_sink *s, size_t n, const uint32_t *from, const uint32_t *to,
                     const float *order);
};

/* One frame to fill. pos (3*natoms floats) is NULL when the host only skips this frame;
 * vel is NULL unless the host wants velocities. */
typedef struct ms_frame_out {
    float *pos, *vel;
    float cell[6];    /* set has_cell when the file gives a cell */
    double time;      /* set has_time when the file gives one */
    int has_cell, has_time, has_vel;
} ms_frame_out;

/* What a writer reads: a read-only view of the atoms (already restricted to a selection),
 * their bonds and the frames to write. */
typedef struct ms_struct_view ms_struct_view;
struct ms_struct_view {
    void *host;
    size_t natoms;
    /* Fill *a for atom i (0-based in the view). Strings stay valid while the view lives. */
    void (*get_atom)(const ms_struct_view *v, size_t i, ms_atom_in *a);
    /* Bonds of atom i: *to points at count view indices (each bond appears for both atoms). */
    size_t (*get_bonds)(const ms_struct_view *v, size_t i, const unsigned **to);
    const char *remarks; /* may be NULL */
    /* ABI 3. Order and type ("" when none) of the k-th bond get_bonds lists for atom i. */
    void (*get_bond_info)(const ms_struct_view *v, size_t i, size_t k, float *order,
                          const char **type);
    /* ABI 3. The terms of a kind (MS_PTERM_*) whose atoms are all in the view, and term k:
     * its atoms as view indices (3 or 4) and its type ("" when none). */
    size_t (*count_terms)(const ms_struct_view *v, int kind);
    void (*get_term)(const ms_struct_view *v, int kind, size_t k, size_t *atoms,
                     const char **type);
    /* ABI 3. Writer options the caller gave, as ms_struct_sink.options; NULL when none. */
    const char *options;
};

typedef struct ms_frame_in {
    const float *pos;   /* 3*natoms */
    const float *vel;   /* NULL when none */
    float cell[6];
    double time;
    int index;          /* 0-based number of this frame among those written */
} ms_frame_in;

enum {
    MS_CAN_READ_STRUCTURE = 1u << 0,
    MS_CAN_READ_FRAMES = 1u << 1,
    MS_CAN_WRITE_STRUCTURE = 1u << 2,
    MS_CAN_WRITE_FRAMES = 1u << 3,
    MS_CAN_READ_VOLUME = 1u << 4,   /* ABI 2 */
    MS_CAN_WRITE_VOLUME = 1u << 5   /* ABI 2 */
};

/* ABI 2: one volumetric data set (a density map, a potential): values on a regular grid.
 * Point (i, j, k) lies at origin + i delta[0] + j delta[1] + k delta[2] (Angstrom; the
 * axes need not be orthogonal); data is n[0] n[1] n[2] floats with i varying fastest. */
typedef struct ms_volume_meta {
    char name[256];
    double origin[3];
    double delta[3][3];   /* step vector between neighbouring points along each axis */
    long n[3];
} ms_volume_meta;

typedef struct ms_plugin {
    int abi;                 /* MS_PLUGIN_ABI */
    const char *name;        /* type name, as in `mol new x type pdb` */
    const char *description;
    const char *extensions;  /* space-separated, without dots: "pdb ent"; a word with a '*'
                              * is a pattern for whole file names ("POSCAR*"), tried when no
                              * plugin has the file's extension */
    unsigned caps;           /* MS_CAN_* bits */

    /* Reading. open_read sets *natoms to the atom count, or -1 when only read_structure
     * can tell (that call then fixes it). read_frame returns MS_PLUGIN_EOF after the last
     * frame; a structure reader that gave positions for the first frame does not return
     * that frame again from read_frame. */
    void *(*open_read)(const char *path, long *natoms, ms_perr *err);
    int (*read_structure)(void *h, ms_struct_sink *sink, ms_perr *err);
    int (*read_frame)(void *h, long natoms, ms_frame_out *frame, ms_perr *err);
    void (*close_read)(void *h);

    /* Writing. write_structure comes first when the format holds a structure; frames
     * follow; close_write flushes and reports any error (a full disk). The host opens the
     * output itself (a temporary file it renames into place, or a device or FIFO written
     * in place) and passes open_write the name "/dev/fd/N" of its descriptor: a plugin may
     * open that name (on Linux it reaches the same file) or, better, duplicate descriptor
     * N, as plugin_util's ms_out_open does. */
    void *(*open_write)(const char *path, long natoms, ms_perr *err);
    int (*write_structure)(void *h, const ms_struct_view *view, ms_perr *err);
    int (*write_frame)(void *h, const ms_struct_view *view, const ms_frame_in *frame,
                       ms_perr *err);
    int (*close_write)(void *h, ms_perr *err);

    /* ABI 2: volumetric data. read_volume_meta describes set k (0-based) of an open file,
     * MS_PLUGIN_EOF when there is no set k; read_volume_data fills data (n[0] n[1] n[2]
     * floats, x fastest) for a set already described. A file may hold a structure and
     * volumes (a Gaussian cube): the host reads the structure first. write_volume writes
     * one set to a file opened with open_write(path, 0, err), before close_write. */
    int (*read_volume_meta)(void *h, int k, ms_volume_meta *meta, ms_perr *err);
    int (*read_volume_data)(void *h, int k, float *data, ms_perr *err);
    int (*write_volume)(void *h, const ms_volume_meta *meta, const float *data, ms_perr *err);

    /* ABI 4: seekable frames, NULL when the format cannot seek. tell_frame gives a token for
     * the frame read_frame returns next (a byte offset, a frame number: only seek_frame
     * reads it); seek_frame makes read_frame return that frame next. A host streaming a
     * trajectory records each frame's token while it reads the file once, then reads any
     * frame again later: seek_frame, read_frame. */
    int (*tell_frame)(void *h, long long *token, ms_perr *err);
    int (*seek_frame)(void *h, long long token, ms_perr *err);
} ms_plugin;

/* The size of an ABI 2 or 3 description: the members before tell_frame. */
#define MS_PLUGIN_ABI3_SIZE offsetof(ms_plugin, tell_frame)

/* The size of an ABI 1 description: the members before read_volume_meta. */
#define MS_PLUGIN_ABI1_SIZE offsetof(ms_plugin, read_volume_meta)

/* The one symbol a plugin exports. */
typedef const ms_plugin *(*ms_plugin_entry_fn)(void);
#define MS_PLUGIN_ENTRY_NAME "ms_plugin_entry"

#ifdef __cplusplus
}
#endif
#endif
