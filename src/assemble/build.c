/* build.c: assembling the scene from the world (world.h): the settings, the display lists of
 * every displayed molecule from the sources below, the axes and the stage. */
#include "config.h"
#include "assemble/view.h"
#include "assemble/world.h"

#include <string.h>

/* ---------------------------------------------------------------- sources
 * A source appends molecule m's display lists to s, with model as its model-to-world
 * transform. Adding a kind of per-molecule graphics is a function and a line in the table. */
typedef int (*source_fn)(ms_world *w, ms_molecule *m, ms_scene *s, const float model[16],
                         ms_error *err);

/* The molecule's user graphics (graphics / draw). */
static int ugraphics_source(ms_world *w, ms_molecule *m, ms_scene *s, const float model[16],
                            ms_error *err)
{
    if (w->ugraphics_slot < 0 || !m->ext[w->ugraphics_slot]) return 0;
    ms_ugraphics *g = m->ext[w->ugraphics_slot];
    if (ms_ugraphics_update(g, w->colors, err)) return -1;
    for (size_t i = 0; i < g->nlists; i++) {
        if (ms_dl_count(&g->lists[i]) == 0) continue;
        if (ms_scene_add(s, &g->lists[i], model, w->materials, err)) return -1;
    }
    return 0;
}

/* The molecule's shown reps. */
static int reps_source(ms_world *w, ms_molecule *m, ms_scene *s, const float model[16],
                       ms_error *err)
{
    return ms_rep_to_scene(w->reps, m, s, model, err);
}

static const source_fn sources[] = {
    ugraphics_source,
    reps_source,
};

/* ---------------------------------------------------------------- assembling */

static void display_color(const ms_colors *c, const char *item, float rgb[3])
{
    int id = ms_color_item_get(c, ms_color_category_index(c, "Display"), item);
    memcpy(rgb, ms_color_rgb(c, id < 0 ? 16 : id), 3 * sizeof(float));
}

static void copy_settings(ms_world *w, ms_scene *s)
{
    const ms_view *v = w->view;
    s->width = w->width;
    s->height = w->height;
    s->settings = v->settings;
    display_color(w->colors, "Background", s->background);
    display_color(w->colors, "BackgroundTop", s->bg_top);
    display_color(w->colors, "BackgroundBot", s->bg_bottom);
}

static int add_decorations(ms_world *w, ms_scene *s, ms_error *err)
{
    const ms_view *v = w->view;
    float xform[16];
    if (v->axes != MS_AXES_OFF) {
        ms_displaylist *dl = ms_scene_new_list(s, err);
        if (!dl || ms_view_axes_list(v, w->colors, (float)s->width / (float)s->height, dl,
                                     xform, err) ||
            ms_scene_add(s, dl, xform, w->materials, err))
            return -1;
    }
    if (v->stage != MS_STAGE_OFF) {
        ms_displaylist *dl = ms_scene_new_list(s, err);
        if (!dl || ms_view_stage_list(v, w->colors, dl, xform, err) ||
            ms_scene_add(s, dl, xform, w->materials, err))
            return -1;
    }
    return 0;
}

int ms_world_build_scene(ms_world *w, ms_scene *s, ms_error *err)
{
    w->scene_builds++;
    ms_scene_init(s);
    copy_settings(w, s);
    for (size_t i = 0; i < w->mols->n; i++) {
        ms_molecule *m = w->mols->mols[i];
        if (!m->displayed) continue;
        float model[16];
        ms_view_mol_model(m, model);
        for (size_t k = 0; k < MS_COUNTOF(sources); k++)
            if (sources[k](w, m, s, model, err)) goto fail;
    }
    if (ms_labels_to_scene(&w->labels, w->mols, w->colors, w->materials, s, err) == 0 &&
        add_decorations(w, s, err) == 0)
        return 0;
fail:
    ms_scene_free(s);
    return -1;
}
