/* select.h: VMD's atom selection language. A selection text is compiled once into a tree
 * and evaluated per molecule and frame into a bit set of atoms. Distance terms (within,
 * exwithin, pbwithin) and `same ... as` go through a uniform cell grid, so evaluation is
 * linear in the number of atoms. Macros (VMD's defaults plus `atomselect macro`) are global,
 * as in VMD.
 *
 * This is the interface the reps, measure and atomselect (commands/atomsel.h) use. */
#ifndef MS_SELECT_H
#define MS_SELECT_H

#include "base/base.h"
#include "base/bitset.h"
#include "molecule/molecule.h"

typedef struct ms_selexpr ms_selexpr;

/* Compile a selection. On a syntax error, err names the position and the token
 * ("syntax error near 'of' at position 12"); unknown keywords and macros are named. */
ms_selexpr *ms_sel_compile(const char *text, ms_error *err);
/* The one-letter code of a residue name (protein, or nucleic), 'X' when it has none. */
char ms_sel_one_letter(const char *resname, int nucleic);
void ms_sel_free(ms_selexpr *e);
/* The text it was compiled from. */
const char *ms_sel_text(const ms_selexpr *e);
/* Does the result depend on coordinates (x, within, ...), so it must be re-evaluated when
 * the frame changes? */
int ms_sel_uses_coords(const ms_selexpr *e);

/* Evaluate on frame `frame` of m (coordinate terms need a frame; -1 = current, -2 = last,
 * a number past the end = last, as VMD does). out is initialised here (m->atoms.n bits);
 * the caller frees it (on failure it is left empty). */
int ms_sel_eval(const ms_selexpr *e, ms_molecule *m, long frame, ms_bitset *out,
                ms_error *err);

/* Compile and evaluate in one call. */
int ms_sel_select(ms_molecule *m, long frame, const char *text, ms_bitset *out, ms_error *err);

/* ---------------------------------------------------------------- keywords
 * The names the language knows, for `atomselect keywords`, `$sel get/set` and commands that
 * take a keyword (measure ... weight mass). Macros are not keywords: see below. */
typedef struct ms_selkw ms_selkw;

typedef enum {
    MS_SELKW_INT, MS_SELKW_FLOAT, MS_SELKW_STRING, /* a value per atom */
    MS_SELKW_BOOL,                                 /* a singleword: 0 or 1 per atom */
    MS_SELKW_FUNCTION,                             /* sqr, sqrt, abs, ... */
    MS_SELKW_STRFUNCTION                           /* sequence, rasmol */
} ms_selkw_type;

/* A built-in keyword, singleword or function by name (case-sensitive, as VMD); NULL when
 * there is none. */
const ms_selkw *ms_sel_keyword(const char *name);
const char *ms_sel_keyword_name(const ms_selkw *k);
ms_selkw_type ms_sel_keyword_type(const ms_selkw *k);
/* Can `$sel set` write it? */
int ms_sel_keyword_settable(const ms_selkw *k);
/* Every built-in name in VMD's order (keywords, singlewords and functions interleaved as
 * VMD registers them): i from 0 to ms_sel_keyword_count()-1. */
size_t ms_sel_keyword_count(void);
const ms_selkw *ms_sel_keyword_at(size_t i);

/* Values of an int or float keyword, or 0/1 of a singleword, for the atoms idx[0..n) on
 * frame `frame` (-1 = current). */
int ms_sel_get_numbers(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, double *out, ms_error *err);
/* Values of a string keyword; the strings stay valid until the molecule changes. */
int ms_sel_get_strings(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, const char **out, ms_error *err);
/* Write a settable keyword for the atoms idx[0..n): one value each (vals[i] for idx[i]).
 * Numbers for int and float keywords (ints are truncated), strings for string keywords
 * (new names are interned). Coordinates and velocities go to frame `frame`. */
int ms_sel_set_numbers(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, const double *vals, ms_error *err);
int ms_sel_set_strings(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, const char *const *vals, ms_error *err);

/* The frame a selection on m reads for `frame` (-1 = current, -2 = last, beyond the end =
 * last, as VMD does); -1 when m has no frames. */
long ms_sel_resolve_frame(const ms_molecule *m, long frame);

/* ---------------------------------------------------------------- macros
 * Global, as VMD's: the defaults of atomselmacros.dat are defined at start. A macro is a
 * singleword standing for its text; it is expanded when a selection is compiled. */

/* Define or replace a macro. Fails when name is a built-in keyword or a reserved word, is not
 * a plain word, or when text does not compile or refers to the macro itself. */
int ms_sel_macro_define(const char *name, const char *text, ms_error *err);
/* Remove a macro; -1 when there is none by that name. */
int ms_sel_macro_delete(const char *name, ms_error *err);
/* The macro names in definition order: fn(ud, name, text) for each. */
void ms_sel_macro_foreach(void (*fn)(void *ud, const char *name, const char *text), void *ud);
/* Does a macro of this name exist? Its text is copied into buf (NULL for none) when it fits;
 * returns the text length, or -1 when there is no such macro. */
long ms_sel_macro_get(const char *name, char *buf, size_t bufsize);

#endif
