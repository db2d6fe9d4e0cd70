/* rep.h: representations, VMD's "reps". A rep draws the atoms its selection picks in one of
 * VMD's drawing methods (Lines, VDW, Licorice, NewCartoon ...), coloured by one of VMD's
 * colouring methods (Name, Element, Structure, Beta ...), with a material, for the frames
 * `drawframes` names, optionally smoothed over a window of frames. Each molecule keeps an
 * ordered list of reps (repid = position, name rep<k> stable); the `mol` subcommands of
 * commands/cmd_rep.c edit them with VMD's rules, and the reps give the scene their display
 * lists.
 *
 * A rep caches its display list and rebuilds it only when an input changed: the frame or
 * the coordinates drawn, the structure, the selection's result, the style's parameters, the
 * colour data or the colour table (material changes need no rebuild). Rebuilds reuse the
 * list's memory.
 *
 * Drawing methods live one per file (lines.c, vdw.c, newcartoon.c ...), each a table entry
 * {name, parameters with VMD's defaults, build function} listed in methods.c: adding a
 * method (QuickSurf, Isosurface) is one file and one line there. */
#ifndef MS_REP_H
#define MS_REP_H

#include <stdint.h>

#include "base/bitset.h"
#include "molecule/molset.h"
#include "scene/color.h"
#include "scene/displaylist.h"
#include "scene/material.h"
#include "scene/scene.h"
#include "select/select.h"

/* The module's state: the current and default settings new reps take, and every molecule's
 * reps (ms_rep_state_new below). */
typedef struct ms_rep_state ms_rep_state;

#define MS_REP_MAXPARAMS 10
#define MS_REP_MAXMETHODS 32
#define MS_REP_TEXTMAX 512      /* style and colouring strings, as VMD limits them */

/* ---------------------------------------------------------------- drawing methods */

typedef struct ms_rep_build ms_rep_build;   /* what a builder is given: rep_method.h */

typedef struct ms_rep_param {
    const char *name;
    float def;                  /* VMD's default */
} ms_rep_param;

enum {
    MS_REP_NEEDS_SS = 1u << 0,  /* draws secondary structure (computed when the file had none) */
    /* draws the molecule's volumetric data (Isosurface, VolumeSlice): built once, with or
     * without atoms and frames, whatever drawframes says; a parameter named "volid" picks
     * the data set */
    MS_REP_VOLUME = 1u << 1
};

typedef struct ms_rep_method {
    const char *name;           /* VMD's spelling: "NewCartoon" */
    int nparams;
    ms_rep_param param[MS_REP_MAXPARAMS];
    unsigned flags;
    /* Append the rep's primitives for one frame to dl (which may hold other frames' already).
     * Returns 0, or -1 with err set (out of memory). */
    int (*build)(const ms_rep_build *b, ms_displaylist *dl, ms_error *err);
} ms_rep_method;

size_t ms_rep_method_count(void);
const ms_rep_method *ms_rep_method_at(size_t i);
/* Index of a method named case-insensitively over 15 characters, or -1. */
int ms_rep_method_find(const char *name);

/* ---------------------------------------------------------------- style (VMD's AtomRep)
 * The method and, for every method, the parameters this style last used with it: a style
 * string "Licorice 0.2" changes only the parameters it gives, "-" keeps one. */
typedef struct ms_rep_style {
    int method;
    float param[MS_REP_MAXMETHODS][MS_REP_MAXPARAMS];
    char text[MS_REP_TEXTMAX];  /* VMD's: every parameter written out, "VDW 1.000000 12.000000" */
} ms_rep_style;

/* Lines, every method at its defaults. */
void ms_rep_style_init(ms_rep_style *s);
/* Parse a style string into s; on an error (unknown method, too many or bad numbers, too
 * long) s is unchanged and err names the problem. An empty string changes nothing. */
int ms_rep_style_parse(ms_rep_style *s, const char *text, ms_error *err);
static inline const float *ms_rep_style_params(const ms_rep_style *s)
{
    return s->param[s->method];
}

/* ---------------------------------------------------------------- colouring (AtomColor) */
typedef enum ms_colmethod {
    MS_COL_NAME, MS_COL_TYPE, MS_COL_ELEMENT, MS_COL_RESNAME, MS_COL_RESTYPE, MS_COL_RESID,
    MS_COL_CHAIN, MS_COL_SEGNAME, MS_COL_CONFORMATION, MS_COL_MOLECULE, MS_COL_STRUCTURE,
    MS_COL_COLORID, MS_COL_BETA, MS_COL_OCCUPANCY, MS_COL_MASS, MS_COL_CHARGE, MS_COL_POS,
    MS_COL_POSX, MS_COL_POSY, MS_COL_POSZ, MS_COL_USER, MS_COL_USER2, MS_COL_USER3,
    MS_COL_USER4, MS_COL_FRAGMENT, MS_COL_INDEX, MS_COL_BACKBONE, MS_COL_THROB,
    MS_COL_PHYSICALTIME, MS_COL_TIMESTEP, MS_COL_VELOCITY, MS_COL_VOLUME, MS_COL_NMETHODS
} ms_colmethod;

typedef struct ms_rep_coloring {
    ms_colmethod method;
    int index;                  /* ColorID's colour (clamped to 0..32), Volume's data set */
    char text[MS_REP_TEXTMAX];
} ms_rep_coloring;

const char *ms_rep_colmethod_name(ms_colmethod m);
void ms_rep_coloring_init(ms_rep_coloring *c);      /* Name */
/* Parse "Name", "ColorID 3", "Beta" ... (and VMD's "default" = Name) into c; on an error c
 * is unchanged. */
int ms_rep_coloring_parse(ms_rep_coloring *c, const char *text, ms_error *err);
/* Does the method map data onto the colour scale (so it has a min/max range)? */
int ms_rep_coloring_scaled(ms_colmethod m);
/* Do its colours change with the frame without colupdate (User, Timestep ...), as VMD's? */
int ms_rep_coloring_timed(ms_colmethod m);

/* The colour id (0..1056) of every atom of m for frame `frame` (-1: none), VMD's rules.
 * Scale methods: the data's min and max over all atoms go to *min and *max when
 * recompute_range, else *min and *max are used as given. Category items a molecule lacks
 * are added. */
int ms_rep_color_ids(ms_colors *colors, ms_molecule *m, const ms_rep_coloring *c, long frame,
                     int recompute_range, float *min, float *max, uint16_t *out,
                     ms_error *err);

/* ---------------------------------------------------------------- drawframes, smoothing */

/* Check a drawframes spec: "now", or whitespace-separated items N, a:b, a:step:b (empty b:
 * the last frame) and comma lists N,M,... Returns 0 or -1 with err naming the bad item. */
int ms_rep_frames_check(const char *spec, ms_error *err);
/* The frames a spec draws, in order, those outside 0..nframes-1 left out ("now": current).
 * *out is malloc'd (NULL when there are none). */
int ms_rep_frames_list(const char *spec, long nframes, long current, long **out, size_t *n,
                       ms_error *err);
/* Coordinates of frame f averaged over frames f-half .. f+half (clamped to the existing
 * frames); periodic jumps undone against frame f for orthogonal cells, as VMD does. out
 * holds 3 natoms floats. */
void ms_rep_smooth(const ms_molecule *m, long f, int half, float *out);

/* ---------------------------------------------------------------- reps */

typedef struct ms_rep_cache ms_rep_cache;   /* rep_int.h */

typedef struct ms_rep {
    char name[32];              /* rep<k>: k counts the molecule's reps ever made */
    ms_rep_style style;
    ms_rep_coloring coloring;
    char *seltext;
    ms_selexpr *sel;
    int material;               /* material id (scene/material.h) */
    char *frames;               /* drawframes spec, "now" by default */
    int smooth;                 /* smoothrep: half window, 0 = off */
    int shown, selupdate, colupdate;
    float cmin, cmax;           /* colour scale range */
    int range_auto;             /* take the range from the data when colours are next made */
    int pbc;                    /* periodic images drawn: MS_PBC_* bits, 0 = none */
    int npbc;                   /* images in each direction drawn (numperiodic), 1.. */
    ms_clip clip[MS_SCENE_CLIPS];  /* VMD's clip planes, in the molecule's coordinates */
    ms_rep_cache *cache;
} ms_rep;

/* The settings new reps take: VMD's "current" style, colouring, selection and material. */
typedef struct ms_rep_settings {
    ms_rep_style style;
    ms_rep_coloring coloring;
    char *selection;
    int material;
} ms_rep_settings;

typedef enum ms_rep_what { MS_REP_STYLE, MS_REP_COLOR, MS_REP_SELECTION, MS_REP_MATERIAL } ms_rep_what;

/* Create the module's state (current settings at VMD's defaults Lines, Name, all, Opaque),
 * drawing with colors and materials. It attaches every molecule's reps to the molecules of
 * mols and listens to their events: a structure a file loads gets VMD's default rep
 * (MS_EV_STRUCTURE_LOADED: the current settings are reset to the defaults first), a molecule
 * of volumetric data alone an Isosurface rep (MS_EV_VOLUMES_LOADED). NULL with err set when
 * memory runs out. Free it after the molecules. */
ms_rep_state *ms_rep_state_new(ms_molset *mols, ms_colors *colors, ms_materials *materials,
                               ms_error *err);
void ms_rep_state_free(ms_rep_state *reps);

const ms_rep_settings *ms_rep_current(const ms_rep_state *reps);
/* Change one current setting from its text (style string, colouring, selection, material
 * name or number). Nothing changes on an error. */
int ms_rep_set_current(ms_rep_state *reps, ms_rep_what what, const char *text, ms_error *err);
/* `mol default`: the text a new structure resets the current setting to. */
const char *ms_rep_get_default(const ms_rep_state *reps, ms_rep_what what);
int ms_rep_set_default(ms_rep_state *reps, ms_rep_what what, const char *text, ms_error *err);
/* Reset the current settings to the defaults (VMD does it when a structure loads). */
int ms_rep_reset_current(ms_rep_state *reps, ms_error *err);
/* The text of a setting of a rep, or of the current settings when r is NULL (material: its
 * name). */
const char *ms_rep_text(const ms_rep_state *reps, const ms_rep *r, ms_rep_what what);

size_t ms_rep_count(const ms_rep_state *reps, const ms_molecule *m);
/* Rep i of m, or NULL. */
ms_rep *ms_rep_get(const ms_rep_state *reps, const ms_molecule *m, long i);
/* The repid of the rep named `name`, or -1. */
long ms_rep_find(const ms_rep_state *reps, const ms_molecule *m, const char *name);
/* Append a rep made from the current settings; NULL with err set on failure (also when
 * they name a volume m does not hold). */
ms_rep *ms_rep_add(ms_rep_state *reps, ms_molecule *m, ms_error *err);
void ms_rep_delete(ms_rep_state *reps, ms_molecule *m, size_t i);
/* modstyle / modcolor / modselect / modmaterial of rep r of m: nothing changes on an error
 * (a style or colouring naming a volume m does not hold is one). */
int ms_rep_modify(ms_rep_state *reps, const ms_molecule *m, ms_rep *r, ms_rep_what what,
                  const char *text, ms_error *err);
/* modrep: every current setting at once (all or nothing). */
int ms_rep_apply_current(ms_rep_state *reps, const ms_molecule *m, ms_rep *r, ms_error *err);
/* Does m hold the volumes a style's volid and a `Volume n` colouring name? 0, or -1 with err
 * saying "molecule M has no volume N (it has K)". */
int ms_rep_check_volumes(const ms_molecule *m, const ms_rep_style *s, const ms_rep_coloring *c,
                         ms_error *err);
int ms_rep_set_frames(ms_rep *r, const char *spec, ms_error *err);
/* smoothrep: average over frame - n .. frame + n (0: off). */
void ms_rep_set_smooth(ms_rep *r, int n);
/* scaleminmax min max (fixed until `auto`); auto: from the data at the next colouring. */
void ms_rep_set_range(ms_rep *r, float min, float max);
void ms_rep_auto_range(ms_rep *r);

/* Bring the rep's selection, colours and display list up to date (rebuilding only what an
 * input change requires). Returns 0 or -1 with err set. */
int ms_rep_update(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err);
/* Only the selection and colours (for resetview, scaleminmax and counts). */
int ms_rep_update_data(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err);
const ms_displaylist *ms_rep_list(const ms_rep *r);
/* Bytes a rep keeps besides its display list: the selection, colour ids, smoothed
 * coordinates and builders' scratch buffers. */
size_t ms_rep_cache_bytes(const ms_rep *r);
/* Place the shown reps of m in s, each brought up to date first and placed once per periodic
 * image, model being the molecule's model-to-world transform. 0, or -1 with err naming the
 * rep. */
int ms_rep_to_scene(ms_rep_state *reps, ms_molecule *m, ms_scene *s, const float model[16],
                    ms_error *err);
/* The atoms of m's shown reps, for VMD's resetview: 1 with *shown set to them (the caller
 * frees it with ms_bitset_free), or 0 when no shown rep selects an atom (or memory runs
 * out). */
int ms_rep_shown_atoms(ms_rep_state *reps, ms_molecule *m, ms_bitset *shown);
/* Atoms selected when last evaluated, ascending. */
const uint32_t *ms_rep_atoms(const ms_rep *r, size_t *n);
/* How many times the display list was built (for tests of the cache). */
unsigned long ms_rep_builds(const ms_rep *r);

/* ---------------------------------------------------------------- periodic images
 * VMD's showperiodic: besides (or, with MS_PBC_NOSELF, instead of) the primary image, a rep
 * draws copies translated by i A + j B + k C, A B C the current frame's cell vectors
 * (vecmath.h), for every i in -n..n along a direction drawn both ways, 0..n along +x only,
 * -n..0 along -x only, 0 along x when neither (and so for y and z), n = numperiodic. The
 * copies are the same display list placed again with another transform. Flag n alone draws
 * nothing (as VMD). A frame without a cell (or a degenerate one) draws only the primary
 * image, whatever the flags. */
enum {
    MS_PBC_X = 1, MS_PBC_Y = 2, MS_PBC_Z = 4,            /* flags x y z */
    MS_PBC_OPX = 8, MS_PBC_OPY = 16, MS_PBC_OPZ = 32,    /* flags X Y Z */
    MS_PBC_NOSELF = 64                                   /* flag n */
};
#define MS_REP_MAXPERIODIC 10

/* Set the images from VMD's flag string (characters of "xyzXYZn", any order, "" = none);
 * another character is an error naming it, and nothing changes. */
int ms_rep_set_periodic(ms_rep *r, const char *flags, ms_error *err);
/* The flag string, in VMD's order x y z X Y Z n (out holds at least 8 bytes). */
void ms_rep_periodic_text(const ms_rep *r, char *out);
/* numperiodic: 1..MS_REP_MAXPERIODIC, else an error and nothing changes. */
int ms_rep_set_numperiodic(ms_rep *r, long n, ms_error *err);
/* The translations (molecule coordinates, 3 floats each) of the images r draws for a
 * frame's cell, primary image included when drawn, into *out (malloc'd, NULL when none);
 * -1 with err set when memory runs out. */
int ms_rep_periodic_images(const ms_rep *r, const float cell[6], float **out, size_t *n,
                           ms_error *err);

#endif
