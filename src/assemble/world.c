/* world.c: making the world at VMD's defaults and freeing it, the user graphics attached to
 * molecules, and keeping the colour categories in step with the molecules. */
#include "config.h"
#include "assemble/world.h"
#include "assemble/devices.h"
#include "assemble/view.h"

#include <stdio.h>
#include <string.h>

ms_ugraphics *ms_world_ugraphics(ms_world *w, ms_molecule *m)
{
    if (w->ugraphics_slot < 0) return NULL;
    if (!m->ext[w->ugraphics_slot]) m->ext[w->ugraphics_slot] = ms_ugraphics_new();
    return m->ext[w->ugraphics_slot];
}

static void free_ugraphics(void *p)
{
    ms_ugraphics_free(p);
}

/* New molecules bring their names, residue names ... into the colour categories. */
static void on_mol_event(void *ud, ms_mol_event ev, ms_molecule *m, const char *arg)
{
    ms_world *w = ud;
    if (ev == MS_EV_MOL_DELETE) ms_labels_forget_molecule(&w->labels, m->id);
    if (ev != MS_EV_MOL_NEW && ev != MS_EV_STRUCTURE) return;
    ms_error err = {{0}};
    if (ms_colors_add_molecule(w->colors, m, &err))
        fprintf(stderr, "molscope: molecule %d: %s\n", m->id, err.msg);
}

int ms_world_init(ms_world *w, ms_molset *mols, ms_error *err)
{
    memset(w, 0, sizeof *w);
    w->mols = mols;
    w->width = w->height = 512;
    w->ugraphics_slot = -1;
    ms_labels_init(&w->labels);
    if (!(w->colors = ms_colors_new(err)) || !(w->materials = ms_materials_new(err)))
        goto fail;
    w->view = ms_view_new();
    w->renderers = ms_renderers_new();
    if (!w->view || !w->renderers) {
        ms_error_set(err, "out of memory");
        goto fail;
    }
    if ((w->ugraphics_slot = ms_molset_register_ext(mols, free_ugraphics)) < 0 ||
        ms_molset_listen(mols, on_mol_event, w)) {
        ms_error_set(err, "too many molecule attachments or listeners");
        goto fail;
    }
    if (!(w->reps = ms_rep_state_new(mols, w->colors, w->materials, err))) goto fail;
    return 0;
fail:
    ms_world_free(w);
    return -1;
}

void ms_world_free(ms_world *w)
{
    ms_rep_state_free(w->reps);
    ms_labels_free(&w->labels);
    ms_renderers_free(w->renderers);
    ms_view_free(w->view);
    ms_materials_free(w->materials);
    ms_colors_free(w->colors);
    w->reps = NULL;
    w->renderers = NULL;
    w->view = NULL;
    w->materials = NULL;
    w->colors = NULL;
}
