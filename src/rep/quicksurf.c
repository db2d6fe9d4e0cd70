/* quicksurf.c: VMD's QuickSurf method (radius scale, density isovalue, grid spacing,
 * quality 0-3): the Gaussian density surface of the selected atoms from the surface engine
 * (src/surf), coloured through the engine's colour texture from the atoms' colours (one
 * solid colour when every selected atom has the same one, as ColorID and Molecule give).
 * With VMDQUICKSURFBEADS or MOLSCOPE_QUICKSURF_BEADS set, each residue becomes one bead
 * (VMD's bead mode for cellular-scale systems). The engine's mesh is adopted by the display
 * list without a copy. */
#include "config.h"
#include "rep/rep_int.h"
#include "surf/qsurf.h"

#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(ms_qsurf_pos_t) == sizeof(float) &&
                   sizeof(ms_qsurf_normal_t) == sizeof(int8_t) &&
                   sizeof(ms_qsurf_color_t) == sizeof(uint8_t),
               "the display list adopts the surface engine's mesh arrays as they are");

static int uniform_color(const ms_rep_build *b)
{
    for (size_t k = 1; k < b->nsel; k++)
        if (b->color[b->idx[k]] != b->color[b->idx[0]]) return 0;
    return 1;
}

static int beads_requested(void)
{
    return ms_env_flag("VMDQUICKSURFBEADS") || ms_env_flag("MOLSCOPE_QUICKSURF_BEADS");
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    if (b->nsel == 0) return 0;
    const ms_molecule *m = b->m;
    ms_qsurf_atoms a;
    memset(&a, 0, sizeof a);
    a.n = b->nsel;
    a.pos = b->pos;
    a.radius = m->atoms.radius;
    a.index = b->idx;
    ms_rgba8 first = ms_rep_rgba(b, b->idx[0]);
    ms_rgba8_to_float(first, a.solid);
    if (!uniform_color(b)) {
        float *rgb = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA, m->atoms.n * 3 * sizeof(float), err);
        if (!rgb) return -1;
        for (size_t k = 0; k < b->nsel; k++)
            ms_rgba8_to_float(ms_rep_rgba(b, b->idx[k]), rgb + 3 * (size_t)b->idx[k]);
        a.rgb = rgb;
    }
    ms_qsurf_radius_range(m->atoms.radius, m->atoms.n, b->idx, b->nsel, &a.minrad, &a.maxrad);

    ms_qsurf_params p;
    ms_qsurf_params_default(&p);
    p.radscale = b->p[0];
    p.isovalue = b->p[1];
    p.gridspacing = b->p[2];
    p.quality = (int)b->p[3];

    ms_qsurf_beads beads;
    memset(&beads, 0, sizeof beads);
    if (beads_requested()) {
        if (ms_qsurf_beads_build(&a, m->atoms.residue, &beads, err)) return -1;
        ms_qsurf_beads_atoms(&beads, &a);
        a.minrad = a.maxrad = 0.0f; /* the beads' own radius range */
    }
    ms_qsurf_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    int rc = ms_qsurf_surface(&a, &p, &mesh, NULL, err);
    ms_qsurf_beads_free(&beads);
    if (rc) return -1;
    ms_dl_mesh_adopt(dl, (float *)mesh.pos, (int8_t *)mesh.normal, (ms_rgba8 *)mesh.color,
                     mesh.nv, MS_QSURF_MESH_VCAP(&mesh), mesh.index, mesh.nt);
    return 0;
}

const ms_rep_method ms_rep_quicksurf = {
    "QuickSurf", 4,
    {{"radius scale", 1.0f}, {"density isovalue", 0.5f}, {"grid spacing", 1.0f},
     {"quality", 0.0f}},
    0, build};
