/* rep.c: rep objects and the lists of them molecules carry; VMD's "current" settings new reps
 * take and the defaults a new structure resets them to; the edits the `mol` subcommands make
 * (all or nothing); VMD's periodic images; the molecule events that give loaded molecules
 * their default rep and invalidate caches; the shown reps' display lists placed in a scene
 * (once per periodic image); resetview's atoms (the displayed reps'); the module's state. */
#include "config.h"
#include "rep/rep_int.h"
#include "vecmath/vecf.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const default_text[4] = {"Lines", "Name", "all", "Opaque"};

static ms_replist *list_get(const ms_rep_state *reps, ms_molecule *m, int create)
{
    const ms_rep_state *st = reps;
    if (!st || st->slot < 0) return NULL;
    if (!m->ext[st->slot] && create) {
        ms_replist *l = calloc(1, sizeof *l);
        if (l) l->last_frame = m->frame;
        m->ext[st->slot] = l;
    }
    return m->ext[st->slot];
}

ms_replist *ms_replist_of(const ms_rep_state *reps, const ms_molecule *m)
{
    return list_get(reps, (ms_molecule *)m, 0);
}

/* ---------------------------------------------------------------- rep objects */

ms_rep_cache *ms_rep_cache_new(void)
{
    ms_rep_cache *c = calloc(1, sizeof *c);
    if (c) ms_dl_init(&c->dl);
    return c;
}

void ms_rep_cache_free(ms_rep_cache *c)
{
    if (!c) return;
    ms_bitset_free(&c->on);
    free(c->idx);
    free(c->col);
    free(c->pos);
    ms_dl_free(&c->dl);
    ms_rep_scratch_free(&c->scratch);
    free(c);
}

void ms_rep_free(ms_rep *r)
{
    if (!r) return;
    free(r->seltext);
    ms_sel_free(r->sel);
    free(r->frames);
    ms_rep_cache_free(r->cache);
    free(r);
}

static void free_list(void *p)
{
    ms_replist *l = p;
    for (size_t i = 0; i < l->n; i++) ms_rep_free(l->reps[i]);
    free(l->reps);
    free(l);
}

size_t ms_rep_count(const ms_rep_state *reps, const ms_molecule *m)
{
    ms_replist *l = ms_replist_of(reps, m);
    return l ? l->n : 0;
}

ms_rep *ms_rep_get(const ms_rep_state *reps, const ms_molecule *m, long i)
{
    ms_replist *l = ms_replist_of(reps, m);
    return l && i >= 0 && (size_t)i < l->n ? l->reps[i] : NULL;
}

long ms_rep_find(const ms_rep_state *reps, const ms_molecule *m, const char *name)
{
    ms_replist *l = ms_replist_of(reps, m);
    for (size_t i = 0; l && i < l->n; i++)
        if (!strcmp(l->reps[i]->name, name)) return (long)i;
    return -1;
}

/* The volid a style names (its method's parameter "volid") into *k; 0 when it has none. */
static int style_volid(const ms_rep_style *s, float *k)
{
    const ms_rep_method *meth = ms_rep_method_at((size_t)s->method);
    for (int i = 0; meth && i < meth->nparams; i++)
        if (!strcmp(meth->param[i].name, "volid")) {
            *k = s->param[s->method][i];
            return 1;
        }
    return 0;
}

static int no_volume(const ms_molecule *m, float k, ms_error *err)
{
    if (k >= 0.0f && k < (float)m->nvolumes) return 0;
    ms_error_set(err, "molecule %d has no volume %g (it has %zu)", m->id, (double)k, m->nvolumes);
    return -1;
}

int ms_rep_check_volumes(const ms_molecule *m, const ms_rep_style *s, const ms_rep_coloring *c,
                         ms_error *err)
{
    float k;
    if (s && style_volid(s, &k) && no_volume(m, k, err)) return -1;
    if (c && c->method == MS_COL_VOLUME && no_volume(m, (float)c->index, err)) return -1;
    return 0;
}

ms_rep *ms_rep_add(ms_rep_state *reps, ms_molecule *m, ms_error *err)
{
    const ms_rep_settings *cur = ms_rep_current(reps);
    if (ms_rep_check_volumes(m, &cur->style, &cur->coloring, err)) return NULL;
    ms_replist *l = list_get(reps, m, 1);
    ms_rep *r = calloc(1, sizeof *r);
    if (!l || !r || !(r->cache = ms_rep_cache_new()) || !(r->seltext = ms_strdup(cur->selection)) ||
        !(r->frames = ms_strdup("now")) || ms_grow((void **)&l->reps, &l->cap, l->n + 1, sizeof *l->reps)) {
        ms_rep_free(r);
        ms_error_set(err, "out of memory");
        return NULL;
    }
    if (!(r->sel = ms_sel_compile(cur->selection, err))) {
        ms_rep_free(r);
        return NULL;
    }
    snprintf(r->name, sizeof r->name, "rep%u", l->next_name++);
    r->style = cur->style;
    r->coloring = cur->coloring;
    r->material = cur->material;
    r->shown = 1;
    r->range_auto = 1;
    r->npbc = 1;
    for (int k = 0; k < MS_SCENE_CLIPS; k++)   /* VMD's: off, at the origin, facing +z, grey */
        r->clip[k] = (ms_clip){{0, 0, 0}, {0, 0, 1}, {0.5f, 0.5f, 0.5f}, MS_CLIP_OFF};
    l->reps[l->n++] = r;
    return r;
}

void ms_rep_delete(ms_rep_state *reps, ms_molecule *m, size_t i)
{
    ms_replist *l = list_get(reps, m, 0);
    if (!l || i >= l->n) return;
    ms_rep_free(l->reps[i]);
    memmove(l->reps + i, l->reps + i + 1, (l->n - i - 1) * sizeof *l->reps);
    l->n--;
}

/* ---------------------------------------------------------------- edits */

static int material_id(const ms_rep_state *reps, const char *name, ms_error *err)
{
    int k = ms_material_index(reps->materials, name);
    if (k < 0) {
        ms_error_set(err, "unknown material '%s'", name);
        return -1;
    }
    return reps->materials->list[k].id;
}

static int replace_selection(char **text, ms_selexpr **expr, const char *src, ms_error *err)
{
    ms_selexpr *e = NULL;
    if (expr && !(e = ms_sel_compile(src, err))) return -1;
    char *t = ms_strdup(src);
    if (!t) {
        ms_sel_free(e);
        ms_error_set(err, "out of memory");
        return -1;
    }
    free(*text);
    *text = t;
    if (expr) {
        ms_sel_free(*expr);
        *expr = e;
    }
    return 0;
}

int ms_rep_modify(ms_rep_state *reps, const ms_molecule *m, ms_rep *r, ms_rep_what what,
                  const char *text, ms_error *err)
{
    ms_rep_cache *c = r->cache;
    if (what == MS_REP_STYLE) {
        ms_rep_style s = r->style;
        if (ms_rep_style_parse(&s, text, err) || ms_rep_check_volumes(m, &s, NULL, err)) return -1;
        r->style = s;
        c->style_gen++;
    } else if (what == MS_REP_COLOR) {
        ms_rep_coloring k = r->coloring;
        if (ms_rep_coloring_parse(&k, text, err) || ms_rep_check_volumes(m, NULL, &k, err))
            return -1;
        r->coloring = k;
        r->range_auto = 1;   /* VMD retakes the range whenever a colouring is applied */
        c->col_valid = 0;
    } else if (what == MS_REP_SELECTION) {
        if (replace_selection(&r->seltext, &r->sel, text, err)) return -1;
        c->sel_valid = 0;
    } else {
        int id = material_id(reps, text, err);
        if (id < 0) return -1;
        r->material = id;
    }
    return 0;
}

int ms_rep_apply_current(ms_rep_state *reps, const ms_molecule *m, ms_rep *r, ms_error *err)
{
    const ms_rep_settings *cur = ms_rep_current(reps);
    ms_rep_style s = r->style;
    ms_rep_coloring k = r->coloring;
    ms_selexpr *e = ms_sel_compile(cur->selection, err);
    char *t = e ? ms_strdup(cur->selection) : NULL;
    s.method = cur->style.method;   /* the current method with all its values, as VMD */
    memcpy(s.param[s.method], cur->style.param[s.method], sizeof s.param[s.method]);
    memcpy(s.text, cur->style.text, sizeof s.text);
    if (!e || !t || ms_rep_coloring_parse(&k, cur->coloring.text, err) ||
        ms_rep_check_volumes(m, &s, &k, err)) {
        if (e && !t) ms_error_set(err, "out of memory");
        ms_sel_free(e);
        free(t);
        return -1;
    }
    r->style = s;
    r->coloring = k;
    r->range_auto = 1;
    ms_sel_free(r->sel);
    free(r->seltext);
    r->sel = e;
    r->seltext = t;
    r->material = cur->material;
    r->cache->style_gen++;
    r->cache->col_valid = r->cache->sel_valid = 0;
    return 0;
}

int ms_rep_set_frames(ms_rep *r, const char *spec, ms_error *err)
{
    while (*spec == ' ' || *spec == '\t' || *spec == '\n') spec++;
    if (ms_rep_frames_check(spec, err) || replace_selection(&r->frames, NULL, spec, err)) return -1;
    r->cache->style_gen++;
    return 0;
}

void ms_rep_set_smooth(ms_rep *r, int n)
{
    r->smooth = n < 0 ? 0 : n;
    r->cache->style_gen++;
}

void ms_rep_set_range(ms_rep *r, float min, float max)
{
    r->cmin = min;
    r->cmax = max;
    r->range_auto = 0;
    r->cache->col_valid = 0;
}

void ms_rep_auto_range(ms_rep *r)
{
    r->range_auto = 1;
    r->cache->col_valid = 0;
}

/* ---------------------------------------------------------------- periodic images */

static const char pbc_chars[] = "xyzXYZn";   /* bit k of MS_PBC_* is character k */

int ms_rep_set_periodic(ms_rep *r, const char *flags, ms_error *err)
{
    int pbc = 0;
    for (const char *p = flags; *p; p++) {
        const char *k = strchr(pbc_chars, *p);
        if (!k) {
            ms_error_set(err, "bad periodic flag '%c' in '%s': expected characters of x y z "
                              "X Y Z n", *p, flags);
            return -1;
        }
        pbc |= 1 << (k - pbc_chars);
    }
    r->pbc = pbc;
    return 0;
}

void ms_rep_periodic_text(const ms_rep *r, char *out)
{
    for (int k = 0; pbc_chars[k]; k++)
        if (r->pbc & (1 << k)) *out++ = pbc_chars[k];
    *out = '\0';
}

int ms_rep_set_numperiodic(ms_rep *r, long n, ms_error *err)
{
    if (n < 1 || n > MS_REP_MAXPERIODIC) {
        ms_error_set(err, "number of periodic images must be 1 to %d, got %ld",
                     MS_REP_MAXPERIODIC, n);
        return -1;
    }
    r->npbc = (int)n;
    return 0;
}

int ms_rep_periodic_images(const ms_rep *r, const float cell[6], float **out, size_t *n,
                           ms_error *err)
{
    double v[3][3];
    int lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
    int periodic = r->pbc && cell && ms_cell_vectors(cell, v);
    if (!periodic) memset(v, 0, sizeof v);   /* no cell: the primary image alone */
    for (int k = 0; k < 3 && periodic; k++) {
        if (r->pbc & (MS_PBC_X << k)) hi[k] = r->npbc;
        if (r->pbc & (MS_PBC_OPX << k)) lo[k] = -r->npbc;
    }
    int noself = periodic && (r->pbc & MS_PBC_NOSELF);   /* "n" alone: nothing, as VMD */
    size_t count = (size_t)(hi[0] - lo[0] + 1) * (size_t)(hi[1] - lo[1] + 1) *
                   (size_t)(hi[2] - lo[2] + 1) - (size_t)noself;
    *out = count ? malloc(3 * count * sizeof **out) : NULL;
    *n = 0;
    if (count && !*out) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    for (int i = lo[0]; i <= hi[0]; i++)
        for (int j = lo[1]; j <= hi[1]; j++)
            for (int k = lo[2]; k <= hi[2]; k++) {
                if (noself && !i && !j && !k) continue;
                float *t = *out + 3 * (*n)++;
                for (int c = 0; c < 3; c++)
                    t[c] = (float)(i * v[0][c] + j * v[1][c] + k * v[2][c]);
            }
    return 0;
}

/* ---------------------------------------------------------------- current settings */

const ms_rep_settings *ms_rep_current(const ms_rep_state *reps)
{
    return &reps->current;
}

int ms_rep_set_current(ms_rep_state *reps, ms_rep_what what, const char *text, ms_error *err)
{
    ms_rep_settings *cur = &reps->current;
    if (what == MS_REP_STYLE) {
        ms_rep_style s = cur->style;
        if (ms_rep_style_parse(&s, text, err)) return -1;
        cur->style = s;
    } else if (what == MS_REP_COLOR) {
        ms_rep_coloring k = cur->coloring;
        if (ms_rep_coloring_parse(&k, text, err)) return -1;
        cur->coloring = k;
    } else if (what == MS_REP_SELECTION) {
        ms_selexpr *e = ms_sel_compile(text, err);
        if (!e) return -1;
        ms_sel_free(e);
        return replace_selection(&cur->selection, NULL, text, err);
    } else {
        int id = material_id(reps, text, err);
        if (id < 0) return -1;
        cur->material = id;
    }
    return 0;
}

const char *ms_rep_get_default(const ms_rep_state *reps, ms_rep_what what)
{
    return reps->defaults[what];
}

int ms_rep_set_default(ms_rep_state *reps, ms_rep_what what, const char *text, ms_error *err)
{
    ms_rep_style s;
    ms_rep_coloring k;
    ms_selexpr *e;
    ms_rep_style_init(&s);
    ms_rep_coloring_init(&k);
    if (what == MS_REP_STYLE && ms_rep_style_parse(&s, text, err)) return -1;
    if (what == MS_REP_COLOR && ms_rep_coloring_parse(&k, text, err)) return -1;
    if (what == MS_REP_MATERIAL && material_id(reps, text, err) < 0) return -1;
    if (what == MS_REP_SELECTION) {
        if (!(e = ms_sel_compile(text, err))) return -1;
        ms_sel_free(e);
    }
    return replace_selection(&reps->defaults[what], NULL, text, err);
}

int ms_rep_reset_current(ms_rep_state *reps, ms_error *err)
{
    ms_rep_state *st = reps;
    for (int w = MS_REP_STYLE; w <= MS_REP_MATERIAL; w++)
        if (ms_rep_set_current(reps, (ms_rep_what)w, st->defaults[w], err)) {
            /* a default that no longer parses (a deleted material or macro): VMD's own */
            if (ms_rep_set_current(reps, (ms_rep_what)w, default_text[w], err)) return -1;
        }
    return 0;
}

const char *ms_rep_text(const ms_rep_state *reps, const ms_rep *r, ms_rep_what what)
{
    const ms_rep_settings *cur = ms_rep_current(reps);
    switch (what) {
    case MS_REP_STYLE: return r ? r->style.text : cur->style.text;
    case MS_REP_COLOR: return r ? r->coloring.text : cur->coloring.text;
    case MS_REP_SELECTION: return r ? r->seltext : cur->selection;
    default: return ms_material_by_id(reps->materials, r ? r->material : cur->material)->name;
    }
}

/* ---------------------------------------------------------------- events, scene, view */

/* A structure's first atoms: VMD resets the current settings to the defaults and adds a rep. */
static void new_structure(ms_rep_state *reps, ms_molecule *m)
{
    ms_error err = {{0}};
    if (ms_rep_reset_current(reps, &err) || !ms_rep_add(reps, m, &err))
        fprintf(stderr, "molscope: molecule %d: no default rep: %s\n", m->id, err.msg);
}

/* A molecule of volumetric data alone: VMD resets the current settings and draws the data
 * with an Isosurface rep, here at the method's default parameters (whatever the current
 * style last used with Isosurface, which might name a volume this molecule lacks). */
static void new_volumes(ms_rep_state *reps, ms_molecule *m)
{
    ms_error err = {{0}};
    if (ms_rep_count(reps, m) > 0) return;
    const ms_rep_method *iso = ms_rep_method_at((size_t)ms_rep_method_find("Isosurface"));
    char text[256];
    int len = snprintf(text, sizeof text, "%s", iso->name);
    for (int i = 0; i < iso->nparams && len < (int)sizeof text; i++)
        len += snprintf(text + len, sizeof text - (size_t)len, " %g", (double)iso->param[i].def);
    if (ms_rep_reset_current(reps, &err) || ms_rep_set_current(reps, MS_REP_STYLE, text, &err) ||
        ms_rep_set_current(reps, MS_REP_STYLE, iso->name, &err) || !ms_rep_add(reps, m, &err))
        fprintf(stderr, "molscope: molecule %d: no default rep: %s\n", m->id, err.msg);
}

/* Loads give default reps; structure edits invalidate selections and colours; a coordinate
 * edit arrives as a frame event that leaves the frame number as it was. */
static void on_event(void *ud, ms_mol_event ev, ms_molecule *m, const char *arg)
{
    if (ev == MS_EV_STRUCTURE_LOADED) new_structure(ud, m);
    if (ev == MS_EV_VOLUMES_LOADED) new_volumes(ud, m);
    ms_replist *l = list_get(ud, m, 0);
    if (!l) return;
    if (ev == MS_EV_STRUCTURE) l->struct_gen++;
    else if (ev == MS_EV_FRAMES_ADDED) l->coord_gen++;
    else if (ev == MS_EV_VOLUMES) l->vol_gen++;
    else if (ev == MS_EV_FRAME) {
        if (m->frame == l->last_frame) l->coord_gen++;
        l->last_frame = m->frame;
    }
}

/* The rep's list placed once per periodic image: model * translation * the list's model. */
static int place_images(ms_rep_state *reps, const ms_molecule *m, const ms_rep *r, ms_scene *s,
                        const float model[16], ms_error *err)
{
    const ms_displaylist *dl = &r->cache->dl;
    const float *cell = m->frame >= 0 && (size_t)m->frame < m->nframes ? m->frames[m->frame].cell
                                                                        : NULL;
    float *t, shift[16], a[16], xform[16];
    size_t n;
    if (ms_rep_periodic_images(r, cell, &t, &n, err)) return -1;
    int rc = 0;
    for (size_t i = 0; i < n && !rc; i++) {
        ms_mat4_translation(shift, t[3 * i], t[3 * i + 1], t[3 * i + 2]);
        ms_mat4_mul(model, shift, a);
        ms_mat4_mul(a, dl->model, xform);
        rc = ms_scene_add(s, dl, xform, reps->materials, err);
        if (!rc) ms_scene_clip_last(s, r->clip, MS_SCENE_CLIPS, model);
    }
    free(t);
    return rc;
}

int ms_rep_to_scene(ms_rep_state *reps, ms_molecule *m, ms_scene *s, const float model[16],
                    ms_error *err)
{
    ms_replist *l = list_get(reps, m, 0);
    for (size_t i = 0; l && i < l->n; i++) {
        ms_rep *r = l->reps[i];
        if (!r->shown) continue;
        if (ms_rep_update(reps, m, r, err)) {
            ms_error_prefix(err, "molecule %d rep %zu", m->id, i);
            return -1;
        }
        ms_displaylist *dl = &r->cache->dl;
        dl->material = r->material;
        if (ms_dl_count(dl) == 0) continue;
        if (place_images(reps, m, r, s, model, err)) return -1;
    }
    return 0;
}

/* VMD's resetview: the atoms of the molecule's shown reps, when there are any. */
int ms_rep_shown_atoms(ms_rep_state *reps, ms_molecule *m, ms_bitset *shown)
{
    ms_replist *l = list_get(reps, m, 0);
    const float *pos = ms_mol_pos(m);
    if (!l || !pos || m->atoms.n == 0) return 0;
    if (ms_bitset_init(shown, m->atoms.n)) return 0;
    ms_error err = {{0}};
    for (size_t i = 0; i < l->n; i++)
        if (l->reps[i]->shown && ms_rep_update_data(reps, m, l->reps[i], &err) == 0 &&
            l->reps[i]->cache->on.nbits == m->atoms.n)
            ms_bitset_or(shown, &l->reps[i]->cache->on);
    size_t nw = ms_bitset_nwords(shown);
    for (size_t w = 0; w < nw; w++)
        if (shown->words[w]) return 1;
    ms_bitset_free(shown);
    return 0;
}

/* ---------------------------------------------------------------- the state */

void ms_rep_state_free(ms_rep_state *reps)
{
    if (!reps) return;
    free(reps->current.selection);
    for (int w = 0; w < 4; w++) free(reps->defaults[w]);
    free(reps);
}

ms_rep_state *ms_rep_state_new(ms_molset *mols, ms_colors *colors, ms_materials *materials,
                               ms_error *err)
{
    ms_rep_state *st = calloc(1, sizeof *st);
    if (!st) {
        ms_error_set(err, "out of memory");
        return NULL;
    }
    st->mols = mols;
    st->colors = colors;
    st->materials = materials;
    ms_rep_style_init(&st->current.style);
    ms_rep_coloring_init(&st->current.coloring);
    int ok = (st->current.selection = ms_strdup("all")) != NULL;
    for (int w = 0; w < 4; w++) ok &= (st->defaults[w] = ms_strdup(default_text[w])) != NULL;
    st->current.material = materials->list[0].id;
    st->slot = ms_molset_register_ext(mols, free_list);
    if (!ok || st->slot < 0 || ms_molset_listen(mols, on_event, st)) {
        ms_error_set(err, "%s", ok ? "too many molecule attachments or listeners" : "out of memory");
        ms_rep_state_free(st);
        return NULL;
    }
    return st;
}
