/* select.h: VMD's atom selection language. A selection text is compiled once into a tree
 * and evaluated per molecule and frame into a bit set of atoms. Distance terms (within,
 * exwithin, pbwithin) and `same ... as` go through a uniform cell grid, so evaluation is
 * linear in the number of atoms. Macros (VMD's defaults plus `atomselect macro`) are global,
 * as in VMD.
 *
 * This is the interface the representation, measure and atomselect modules use. */
#ifndef MS_SELECT_H
#define MS_SELECT_H

#include "base/base.h"
#include "base/bitset.h"
#include "molecule/molecule.h"

typedef struct ms_selexpr ms_selexpr;

/* Compile a selection. On a syntax error, err names the position and the token
 * ("syntax error near 'of' at position 12"); unknown keywords and macros are named. */
ms_selexpr *ms_sel_compile(const char *text, ms_error *err);
void ms_sel_free(ms_selexpr *e);
/* The text it was compiled from. */
const char *ms_sel_text(const ms_selexpr *e);
/* Does the result depend on coordinates (x, within, ...), so it must be re-evaluated when
 * the frame changes? */
int ms_sel_uses_coords(const ms_selexpr *e);

/* Evaluate on frame `frame` of m (coordinate terms need a frame; -1 = current). out is
 * initialised here (m->atoms.n bits); the caller frees it. */
int ms_sel_eval(const ms_selexpr *e, ms_molecule *m, long frame, ms_bitset *out,
                ms_error *err);

/* Compile and evaluate in one call. */
int ms_sel_select(ms_molecule *m, long frame, const char *text, ms_bitset *out, ms_error *err);

#endif
