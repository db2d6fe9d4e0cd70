/* licorice.c: VMD's Licorice method (bond radius, sphere resolution, bond resolution, bond
 * cutoff): spheres of the bond radius at the atoms and two half cylinders per bond, each in
 * its atom's colour; a radius of 0 draws Lines instead. */
#include "config.h"
#include "rep/rep_int.h"

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    float brad = b->p[0];
    int bres = ms_rep_res(b->p[2]);
    ms_rep_bondlist bl;
    if (ms_rep_bonds_get(b, b->p[3], &bl, err)) return -1;
    if (brad == 0.0f) return ms_rep_bond_lines(b, &bl, 1.0f, dl, err);
    if (ms_rep_atom_spheres(b, 0.0f, brad, ms_rep_res(b->p[1]), dl, err)) return -1;
    if (bres <= 2 || brad < 0.01f) return 0;
    return ms_rep_bond_cylinders(b, &bl, brad, bres, dl, err);
}

const ms_rep_method ms_rep_licorice = {
    "Licorice", 4,
    {{"bond radius", 0.3f}, {"sphere resolution", 12.0f}, {"bond resolution", 12.0f},
     {"bond cutoff", 0.0f}},
    0, build};
