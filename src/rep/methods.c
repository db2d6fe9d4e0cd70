/* methods.c: the table of drawing methods, in VMD's order. Each method is one file holding
 * its table entry (name, parameters and defaults, builder); adding one is that file and a
 * line below. */
#include "config.h"
#include "rep/rep_int.h"

#include <stddef.h>

extern const ms_rep_method ms_rep_lines, ms_rep_bonds, ms_rep_dynamicbonds, ms_rep_hbonds,
    ms_rep_points, ms_rep_vdw, ms_rep_cpk, ms_rep_licorice, ms_rep_trace, ms_rep_tube,
    ms_rep_newribbons, ms_rep_newcartoon, ms_rep_quicksurf, ms_rep_volumeslice,
    ms_rep_isosurface, ms_rep_beads, ms_rep_dotted, ms_rep_polyhedra;

static const ms_rep_method *const methods[] = {
    &ms_rep_lines,
    &ms_rep_bonds,
    &ms_rep_dynamicbonds,
    &ms_rep_hbonds,
    &ms_rep_points,
    &ms_rep_vdw,
    &ms_rep_cpk,
    &ms_rep_licorice,
    &ms_rep_trace,
    &ms_rep_tube,
    &ms_rep_newribbons,
    &ms_rep_newcartoon,
    &ms_rep_quicksurf,
    &ms_rep_volumeslice,
    &ms_rep_isosurface,
    &ms_rep_beads,
    &ms_rep_dotted,
    &ms_rep_polyhedra,
};

_Static_assert(MS_COUNTOF(methods) <= MS_REP_MAXMETHODS, "raise MS_REP_MAXMETHODS");

/* VMD's other methods: recognised so that a script using one is told it is missing. */
static const char *const unavailable[] = {
    "Ribbons", "Cartoon", "PaperChain", "Twister", "MSMS",
    "NanoShaper", "Surf", "FieldLines", "Orbital", "Solvent",
    "LatticeCubes"};

size_t ms_rep_method_count(void)
{
    return MS_COUNTOF(methods);
}

const ms_rep_method *ms_rep_method_at(size_t i)
{
    return i < MS_COUNTOF(methods) ? methods[i] : NULL;
}

int ms_rep_method_find(const char *name)
{
    for (size_t i = 0; i < MS_COUNTOF(methods); i++)
        if (ms_word_eq(name, methods[i]->name)) return (int)i;
    return -1;
}

const char *ms_rep_method_unavailable(const char *name)
{
    for (size_t i = 0; i < MS_COUNTOF(unavailable); i++)
        if (ms_word_eq(name, unavailable[i])) return unavailable[i];
    return NULL;
}
