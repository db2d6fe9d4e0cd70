/* vdw.c: VMD's VDW method (radius scale, sphere resolution): a sphere of radius
 * scale * radius at every selected atom. */
#include "config.h"
#include "rep/rep_int.h"

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    return ms_rep_atom_spheres(b, b->p[0], 0.0f, ms_rep_res(b->p[1]), dl, err);
}

const ms_rep_method ms_rep_vdw = {
    "VDW", 2, {{"sphere scale", 1.0f}, {"sphere resolution", 12.0f}}, 0, build};
