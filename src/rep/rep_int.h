/* rep_int.h: what the files of src/rep share and nothing outside reads: the input a drawing
 * method's builder gets, reusable scratch memory, the helpers several methods use (atom
 * spheres, the bonds drawn, half-bond cylinders and lines, pair search through a cell grid,
 * polymer backbones, splines, the ribbon extrusion), the per-rep cache, the per-molecule rep
 * lists and the module's state. */
#ifndef MS_REP_INT_H
#define MS_REP_INT_H

#include "rep/rep.h"
#include "scene/color.h"

/* A VMD method molscope does not draw yet (its canonical name), or NULL. */
const char *ms_rep_method_unavailable(const char *name);

/* ---------------------------------------------------------------- scratch memory
 * Buffers kept by a rep between builds, so a rebuild allocates nothing new. */
#define MS_REP_NSCRATCH 8
typedef struct ms_rep_scratch {
    void *buf[MS_REP_NSCRATCH];
    size_t cap[MS_REP_NSCRATCH];
} ms_rep_scratch;

/* At least `bytes` bytes in slot (contents not kept); NULL with err set. */
void *ms_rep_scratch_get(ms_rep_scratch *s, int slot, size_t bytes, ms_error *err);
void ms_rep_scratch_free(ms_rep_scratch *s);

/* Slots by user, so that helpers called by one builder never share one. */
enum {
    MS_SCR_COUNTS, MS_SCR_BONDSTART, MS_SCR_BONDTO, MS_SCR_PAIRS, MS_SCR_CHAIN,
    MS_SCR_PATH, MS_SCR_EXTRA, MS_SCR_EXTRA2
};

/* ---------------------------------------------------------------- the builder's input */

/* The colour ids the volume methods draw with (VMD's): `solid`, the colour of ColorID or
 * Molecule colouring and Display Foreground for every other method; the volume box's edges
 * along x, y and z from the origin (Axes X, Y, Z) and its other edges (Display
 * Foreground). */
typedef struct ms_rep_volcolors {
    int solid, axis[3], box;
} ms_rep_volcolors;

struct ms_rep_build {
    ms_molecule *m;
    const float *pos;           /* coordinates drawn (the frame's, or smoothed) */
    const ms_bitset *on;        /* selected atoms */
    const uint32_t *idx;        /* the same, ascending */
    size_t nsel;
    const uint16_t *color;      /* colour id of every atom */
    const ms_rgba8 *palette;    /* RGBA of every colour id */
    const float *p;             /* the method's parameters */
    ms_rep_scratch *scratch;
    const ms_rep_coloring *coloring;
    float cmin, cmax;           /* the rep's colour scale range */
    ms_rep_volcolors vc;
};

static inline ms_rgba8 ms_rep_rgba(const ms_rep_build *b, size_t atom)
{
    return b->palette[b->color[atom]];
}
static inline int ms_rep_on(const ms_rep_build *b, size_t atom)
{
    return ms_bitset_get(b->on, atom);
}
static inline const float *ms_rep_xyz(const ms_rep_build *b, size_t atom)
{
    return b->pos + 3 * atom;
}
/* A tessellation resolution parameter as a device count (VMD truncates to int). */
static inline uint16_t ms_rep_res(float v)
{
    return v < 1 ? 1 : v > 1000 ? 1000 : (uint16_t)v;
}

/* The colour ids volume methods use for a rep of m coloured by c. */
void ms_rep_volume_colors(ms_colors *colors, ms_molecule *m, const ms_rep_coloring *c,
                          ms_rep_volcolors *out);
/* Volume k of the builder's molecule, or NULL (a volid a later voldelete removed). */
const ms_volume *ms_rep_volume(const ms_rep_build *b, float k);
/* The colour range a volume method maps values of volume v with: the rep's when it colours
 * by a scale method, unless that is 0 0 (no range was taken: VMD's rule); else v's own min
 * and max. */
void ms_rep_volume_range(const ms_rep_build *b, const ms_volume *v, float *lo, float *hi);
/* out[i] = the colour scale's colour (lo .. hi) of volume v's value at point i of xyz (at
 * the nearest point of its grid for points outside it), for n points, in parallel. */
void ms_rep_color_by_volume(const ms_rep_build *b, const ms_volume *v, float lo, float hi,
                            const float *xyz, size_t n, ms_rgba8 *out);

/* Exclusive prefix sum of v[0..n) in place; returns the total. */
size_t ms_rep_scan(size_t *v, size_t n);

/* ---------------------------------------------------------------- atoms and bonds */

/* A sphere per selected atom, radius = radius * radscale + fixrad (VMD: none at all when
 * radscale + fixrad <= 0). */
int ms_rep_atom_spheres(const ms_rep_build *b, float radscale, float fixrad, int res,
                        ms_displaylist *dl, ms_error *err);

/* The bonds a bond method draws, CSR over all atoms: the molecule's, or with cutoff > 0
 * every pair of selected atoms at most cutoff apart (never H-H, never across different
 * non-blank altlocs), as VMD's bond cutoff parameter does. */
typedef struct ms_rep_bondlist {
    const uint32_t *start, *to;
} ms_rep_bondlist;
int ms_rep_bonds_get(const ms_rep_build *b, float cutoff, ms_rep_bondlist *out, ms_error *err);
/* May atoms i and j be bonded by distance (VMD's H-H and altloc rules)? */
int ms_rep_may_bond(const ms_molecule *m, uint32_t i, uint32_t j);

/* A cylinder per bond between selected atoms, from the lower atom to the higher, each half
 * in its atom's colour (CPK, Licorice: VMD's two half cylinders, each from its atom to the
 * middle, in VMD's order for the exporters). These must be the list's only cylinders. */
int ms_rep_bond_cylinders(const ms_rep_build *b, const ms_rep_bondlist *bl, float radius, int res,
                          ms_displaylist *dl, ms_error *err);
/* VMD's Lines: a whole line for a bond whose atoms share a colour, two half lines
 * otherwise, a point for a selected atom with no bond drawn; unlit. */
int ms_rep_bond_lines(const ms_rep_build *b, const ms_rep_bondlist *bl, float width,
                      ms_displaylist *dl, ms_error *err);

/* VMD's gap-free joint of a cylinder from start to end with the cylinders from prev and to
 * next (either may be NULL): the ends move out by r tan(angle / 2); s and e get them. */
void ms_rep_stretch(const float *prev, const float *start, const float *end,
                    const float *next, float r, float *s, float *e);

/* Pairs (i < j) of atoms of idx[0..n) at most cutoff apart for which keep(ctx, i, j) is true
 * (keep may be NULL), found through a uniform cell grid in linear time. *pairs holds 2 per
 * pair (scratch slot MS_SCR_PAIRS). */
typedef int (*ms_rep_pair_fn)(const void *ctx, uint32_t i, uint32_t j);
int ms_rep_pairs(const ms_rep_build *b, float cutoff, ms_rep_pair_fn keep, const void *ctx,
                 uint32_t **pairs, size_t *npairs, ms_error *err);

/* ---------------------------------------------------------------- polymers */

/* A run of bonded polymer residues: protein (control atom CA, guide O or OT1) or nucleic
 * (control atom P, else C5' or C5* or the first atom; guides O1P or OP1 and O2P or
 * OP2). */
typedef struct ms_rep_chain {
    size_t first, n;            /* into the backbone arrays */
    int nucleic;
} ms_rep_chain;

typedef struct ms_rep_backbone {
    size_t n, cap;              /* residues in chains */
    uint32_t *atom;             /* control atom of each */
    int32_t *guide, *guide2;    /* guide atoms (-1 when missing) */
    ms_rep_chain *chains;
    size_t nchains, chcap;
} ms_rep_backbone;

/* The chains of m: runs of consecutive protein (nucleic) residues each bonded to the one
 * before; with no protein residue at all, runs of atoms named CA with consecutive resids
 * (VMD's CA-only rule). */
int ms_rep_backbone_build(ms_molecule *m, ms_rep_backbone *bb, ms_error *err);
void ms_rep_backbone_free(ms_rep_backbone *bb);

/* Cubic spline bases: VMD's modified Catmull-Rom (slope 1.25) or the uniform B-spline. */
void ms_rep_spline_basis(float basis[4][4], int bspline);
/* The point at t in [0, 1] of the segment from p1 to p2 (p0, p3 its neighbours). */
void ms_rep_spline_eval(const float basis[4][4], const float *p0, const float *p1,
                        const float *p2, const float *p3, float t, float out[3]);

/* The ribbon extrusion of NewRibbons and NewCartoon: along each chain a spline through the
 * control points, an elliptical cross-section of half width w and half height h (per
 * residue; w < 0 marks a sheet's last residue, drawn as an arrowhead 1.75x as wide that
 * narrows to the next residue's width) oriented by the guide vectors; each selected residue
 * owns the piece between the midpoints to its neighbours, in its CA's colour. */
typedef struct ms_rep_ribbon {
    const ms_rep_backbone *bb;
    const float *cp;            /* control point per backbone residue (3 floats) */
    const float *perp;          /* guide (width) direction per residue (3 floats) */
    const float *w, *h;         /* half width, half height per residue */
    int bspline;
    int panels;                 /* vertices around the cross-section */
    int divs;                   /* sections per residue (even) */
} ms_rep_ribbon;
int ms_rep_ribbon_build(const ms_rep_build *b, const ms_rep_ribbon *r, ms_displaylist *dl,
                        ms_error *err);
/* VMD's ribbon guide vectors from the peptide planes (CA(i)-CA(i-1) and O(i-1)), flipped to
 * stay within 90 degrees of the running average, for the chain's residues; nucleic chains
 * use the phosphate oxygens' bisector. perp gets 3 floats per residue of the chain. */
void ms_rep_chain_perps(const ms_rep_build *b, const ms_rep_backbone *bb,
                        const ms_rep_chain *ch, float *perp);
/* Sections per residue for a VMD resolution: about a third of VMD's res + 2, even, >= 2. */
int ms_rep_ribbon_divs(float res);
/* The build of NewRibbons and NewCartoon (parameters p[1] resolution, p[3] spline): the
 * backbone, scratch for the ribbon's cp, perp (3 floats per residue), w and h (1 float),
 * filled by fill, then ms_rep_ribbon_build into dl. */
typedef void (*ms_rep_ribbon_fill)(const ms_rep_build *b, const ms_rep_backbone *bb,
                                   float *cp, float *perp, float *w, float *h);
int ms_rep_ribbon_method(const ms_rep_build *b, ms_rep_ribbon_fill fill, ms_displaylist *dl,
                         ms_error *err);

/* ---------------------------------------------------------------- per-rep cache */

/* What a display list was built from: equal keys, equal lists. */
typedef struct ms_rep_key {
    unsigned long style_gen, struct_gen, coord_gen, sel_gen, col_gen, colors_version, vol_gen;
    long frame;
    size_t nframes;
} ms_rep_key;

struct ms_rep_cache {
    /* selection: re-evaluated when its text, the structure or the atom count changed, and
     * with selupdate when the frame or coordinates did */
    ms_bitset on;
    uint32_t *idx;
    size_t nsel, idxcap;
    int sel_valid;
    unsigned long sel_struct, sel_coord, sel_gen;
    long sel_frame;
    size_t sel_natoms;
    /* colours, one id per atom */
    uint16_t *col;
    size_t colcap;
    int col_valid;
    unsigned long col_colors, col_struct, col_coord, col_gen;
    long col_frame;
    /* the display list */
    ms_displaylist dl;
    int dl_valid;
    ms_rep_key key;
    unsigned long style_gen, builds;
    float *pos;                 /* smoothed coordinates */
    size_t poscap;
    ms_rep_scratch scratch;
    ms_rgba8 palette[MS_COLOR_MAX];   /* RGBA of every colour id at the last build */
};

/* The reps of one molecule (its attachment) and what its events changed. */
typedef struct ms_replist {
    ms_rep **reps;
    size_t n, cap;
    unsigned next_name;
    unsigned long struct_gen, coord_gen, vol_gen;
    unsigned long ss_gen;       /* secondary structure computed: only reps reading it care */
    long last_frame;
} ms_replist;

/* The module's state (rep.h): what it draws with and the settings new reps take. */
struct ms_rep_state {
    ms_molset *mols;            /* the molecules, their events and attachments */
    ms_colors *colors;
    ms_materials *materials;
    int slot;                   /* molecule attachment slot */
    ms_rep_settings current;
    char *defaults[4];          /* by ms_rep_what */
};

ms_replist *ms_replist_of(const ms_rep_state *reps, const ms_molecule *m);
/* Free a rep and its cache. */
void ms_rep_free(ms_rep *r);
ms_rep_cache *ms_rep_cache_new(void);
void ms_rep_cache_free(ms_rep_cache *c);
/* The method's builder over the frames drawframes names (update.c). */
int ms_rep_build_frames(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err);

#endif
