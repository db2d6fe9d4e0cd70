/* cpk.c: VMD's CPK method (sphere scale, bond radius, sphere resolution, bond resolution,
 * bond cutoff): spheres of 0.25 * scale * radius and half-bond cylinders of 0.25 * bond
 * radius in the colour of their atom (none when the resolution is 2 or less or the radius
 * under 0.01, as VMD). */
#include "config.h"
#include "rep/rep_int.h"

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    float brad = 0.25f * b->p[1];
    int bres = ms_rep_res(b->p[3]);
    if (ms_rep_atom_spheres(b, 0.25f * b->p[0], 0.0f, ms_rep_res(b->p[2]), dl, err)) return -1;
    if (bres <= 2 || brad < 0.01f) return 0;
    ms_rep_bondlist bl;
    return ms_rep_bonds_get(b, b->p[4], &bl, err) ||
           ms_rep_bond_cylinders(b, &bl, brad, bres, dl, err) ? -1 : 0;
}

const ms_rep_method ms_rep_cpk = {
    "CPK", 5,
    {{"sphere scale", 1.0f}, {"bond radius", 0.3f}, {"sphere resolution", 12.0f},
     {"bond resolution", 12.0f}, {"bond cutoff", 0.0f}},
    0, build};
