/* update.c: bringing a rep up to date: its selection (re-evaluated when the text, the
 * structure or the atom count changed, and with selupdate when the frame did; kept when the
 * result is the same), its colours (recomputed when the colouring, the colour table or the
 * structure changed, and per frame for colupdate and the time-dependent methods), and its
 * display list, rebuilt only when the key of its inputs changed, into the list's own memory,
 * once per frame drawframes names, from the coordinates smoothrep averages. */
#include "config.h"
#include "rep/rep_int.h"
#include "ss/ss.h"

#include <stdlib.h>
#include <string.h>

/* Words of the selection language that read secondary structure. */
static int mentions_ss(const char *text)
{
    static const char *const words[] = {"helix", "sheet", "coil", "structure", "turn",
                                        "bridge", "extended_beta"};
    for (size_t i = 0; i < MS_COUNTOF(words); i++)
        if (strstr(text, words[i])) return 1;
    return 0;
}

static int needs_ss(const ms_rep *r)
{
    return (ms_rep_method_at((size_t)r->style.method)->flags & MS_REP_NEEDS_SS) ||
           r->coloring.method == MS_COL_STRUCTURE || mentions_ss(r->seltext);
}

/* Secondary structure for a molecule whose file had none: DSSP, computed once. It changes
 * only the atoms' ss codes, so the reps that do not read them (a QuickSurf coloured by chain)
 * keep their selection, colours and list. */
static int ensure_ss(ms_molecule *m, ms_replist *l, const ms_rep *r, ms_error *err)
{
    if (m->ss_known || m->nframes == 0 || !needs_ss(r)) return 0;
    if (ms_ss_ensure(m, m->frame, err)) return -1;
    if (m->ss_known) l->ss_gen++;
    return 0;
}

/* The structure's generation as r sees it: both counts only grow, so their sum changes
 * whenever one r depends on does. */
static unsigned long struct_gen_of(const ms_replist *l, const ms_rep *r)
{
    return l->struct_gen + (needs_ss(r) ? l->ss_gen : 0);
}

/* ---------------------------------------------------------------- selection */

static int same_bits(const ms_bitset *a, const ms_bitset *b)
{
    return a->nbits == b->nbits &&
           (a->nbits == 0 || !memcmp(a->words, b->words, ms_bitset_nwords(a) * sizeof *a->words));
}

/* Evaluate r's selection on frame f into bits and an index list. */
static int evaluate(ms_rep *r, ms_molecule *m, long f, ms_bitset *bits, uint32_t **idx,
                    size_t *cap, size_t *n, ms_error *err)
{
    if (ms_sel_eval(r->sel, m, f, bits, err)) return -1;
    *n = ms_bitset_count(bits);
    if (ms_grow((void **)idx, cap, *n + 1, sizeof **idx)) {
        ms_bitset_free(bits);
        ms_error_set(err, "out of memory");
        return -1;
    }
    ms_bitset_indices(bits, *idx);
    return 0;
}

static int update_selection(ms_molecule *m, ms_replist *l, ms_rep *r, ms_error *err)
{
    ms_rep_cache *c = r->cache;
    int stale = !c->sel_valid || c->sel_struct != struct_gen_of(l, r) || c->sel_natoms != m->atoms.n ||
                (r->selupdate && (c->sel_frame != m->frame || c->sel_coord != l->coord_gen));
    if (!stale) return 0;
    ms_bitset bits;
    if (ms_sel_eval(r->sel, m, -1, &bits, err)) return -1;
    if (!c->sel_valid || !same_bits(&bits, &c->on)) {
        size_t n = ms_bitset_count(&bits);
        if (ms_grow((void **)&c->idx, &c->idxcap, n + 1, sizeof *c->idx)) {
            ms_bitset_free(&bits);
            ms_error_set(err, "out of memory");
            return -1;
        }
        ms_bitset_free(&c->on);
        c->on = bits;
        c->nsel = ms_bitset_indices(&c->on, c->idx);
        c->sel_gen++;
    } else {
        ms_bitset_free(&bits);
    }
    c->sel_valid = 1;
    c->sel_struct = struct_gen_of(l, r);
    c->sel_coord = l->coord_gen;
    c->sel_frame = m->frame;
    c->sel_natoms = m->atoms.n;
    return 0;
}

/* ---------------------------------------------------------------- colours */

static int update_colors(ms_rep_state *reps, ms_molecule *m, ms_replist *l, ms_rep *r, ms_error *err)
{
    ms_rep_cache *c = r->cache;
    ms_colmethod meth = r->coloring.method;
    int per_frame = r->colupdate || ms_rep_coloring_timed(meth);
    int stale = !c->col_valid || c->col_colors != reps->colors->version ||
                c->col_struct != struct_gen_of(l, r) || c->colcap < m->atoms.n ||
                (per_frame && c->col_frame != m->frame) ||
                (r->colupdate && c->col_coord != l->coord_gen) || meth == MS_COL_THROB;
    if (!stale) return 0;
    if (c->colcap < m->atoms.n) {
        uint16_t *p = realloc(c->col, (m->atoms.n + 1) * sizeof *p);
        if (!p) {
            ms_error_set(err, "out of memory");
            return -1;
        }
        c->col = p;
        c->colcap = m->atoms.n;
    }
    if (ms_rep_color_ids(reps->colors, m, &r->coloring, m->frame, r->range_auto, &r->cmin, &r->cmax,
                         c->col, err))
        return -1;
    r->range_auto = 0;
    c->col_valid = 1;
    c->col_colors = reps->colors->version;
    c->col_struct = struct_gen_of(l, r);
    c->col_coord = l->coord_gen;
    c->col_frame = m->frame;
    c->col_gen++;
    return 0;
}

int ms_rep_update_data(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err)
{
    ms_replist *l = ms_replist_of(reps, m);
    if (!l) return 0;
    return ensure_ss(m, l, r, err) || update_selection(m, l, r, err) ||
           update_colors(reps, m, l, r, err) ? -1 : 0;
}

/* ---------------------------------------------------------------- display list */

static int draws_now(const ms_rep *r) { return !strcmp(r->frames, "now"); }

static int draws_volume(const ms_rep *r)
{
    return (ms_rep_method_at((size_t)r->style.method)->flags & MS_REP_VOLUME) != 0;
}

static void make_key(ms_rep_state *reps, const ms_molecule *m, const ms_replist *l, const ms_rep *r,
                     ms_rep_key *k)
{
    memset(k, 0, sizeof *k);
    k->style_gen = r->cache->style_gen;
    k->struct_gen = struct_gen_of(l, r);
    k->coord_gen = l->coord_gen;
    k->sel_gen = r->cache->sel_gen;
    k->col_gen = r->cache->col_gen;
    k->colors_version = reps->colors->version;
    k->vol_gen = l->vol_gen;
    if (draws_volume(r)) {   /* the data sets alone: no atoms, no frames */
        k->struct_gen = k->coord_gen = k->sel_gen = 0;
        k->frame = -1;
        return;
    }
    k->frame = draws_now(r) || strstr(r->frames, "now") ? m->frame : -1;
    k->nframes = !draws_now(r) || r->smooth ? m->nframes : 0;
}

/* Scratch buffers are kept for the next build up to this size in all; beyond it (per-atom
 * buffers of a large molecule: 12 bytes an atom for QuickSurf's colours, 7 for a NewCartoon
 * of one protein in 1M atoms) they are freed, so that they do not sit beside the
 * tracer's structures through a render. */
#define SCRATCH_KEEP ((size_t)4 << 20)

static void release_scratch(ms_rep_scratch *s)
{
    size_t bytes = 0;
    for (int k = 0; k < MS_REP_NSCRATCH; k++) bytes += s->cap[k];
    if (bytes > SCRATCH_KEEP) ms_rep_scratch_free(s);
}

int ms_rep_update(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err)
{
    ms_rep_cache *c = r->cache;
    if ((m->nframes == 0 || m->frame < 0) && !draws_volume(r)) {
        /* nothing to draw (VMD needs a frame too, but for volumes) */
        ms_dl_clear(&c->dl);
        c->dl_valid = 0;
        return 0;
    }
    if (ms_rep_update_data(reps, m, r, err)) return -1;
    ms_replist *l = ms_replist_of(reps, m);
    ms_rep_key key;
    make_key(reps, m, l, r, &key);
    if (c->dl_valid && !memcmp(&key, &c->key, sizeof key)) return 0;
    ms_dl_clear(&c->dl);
    c->dl.lit = 1;
    c->dl_valid = 0;
    if (ms_rep_build_frames(reps, m, r, err)) {
        ms_dl_clear(&c->dl);
        return -1;
    }
    c->dl_valid = 1;
    c->key = key;
    c->builds++;
    release_scratch(&c->scratch);
    return 0;
}

/* The selection and colours of frame f when they differ from the current frame's. */
typedef struct frame_data {
    ms_bitset on;
    uint32_t *idx;
    size_t n, cap;
    uint16_t *col;
} frame_data;

static int frame_specific(ms_rep_state *reps, ms_molecule *m, ms_rep *r, long f, frame_data *fd,
                          ms_rep_build *b, ms_error *err)
{
    if (f == m->frame) return 0;
    if (r->selupdate) {
        if (evaluate(r, m, f, &fd->on, &fd->idx, &fd->cap, &fd->n, err)) return -1;
        b->on = &fd->on;
        b->idx = fd->idx;
        b->nsel = fd->n;
    }
    if (ms_rep_coloring_timed(r->coloring.method) || r->colupdate) {
        float lo = r->cmin, hi = r->cmax;
        if (!fd->col && !(fd->col = ms_alloc_array(m->atoms.n + 1, sizeof *fd->col))) {
            ms_error_set(err, "out of memory");
            return -1;
        }
        if (ms_rep_color_ids(reps->colors, m, &r->coloring, f, 0, &lo, &hi, fd->col, err)) return -1;
        b->color = fd->col;
    }
    return 0;
}

static const float *frame_pos(ms_molecule *m, ms_rep *r, long f, ms_error *err)
{
    if (r->smooth <= 0) {
        const ms_frame *fr = ms_mol_frame(m, (size_t)f, err);   /* streamed: read now */
        return fr ? fr->pos : NULL;
    }
    if (m->stream) {
        ms_error_set(err, "trajectory smoothing needs every frame in memory: molecule %d "
                     "streams %s (load it without -stream)", m->id, m->stream->src.path);
        return NULL;
    }
    ms_rep_cache *c = r->cache;
    if (ms_grow((void **)&c->pos, &c->poscap, 3 * m->atoms.n + 1, sizeof *c->pos)) {
        ms_error_set(err, "out of memory smoothing coordinates");
        return NULL;
    }
    ms_rep_smooth(m, f, r->smooth, c->pos);
    return c->pos;
}

/* The builder's input common to every frame (coordinates and frame data come later). */
static void build_input(ms_molecule *m, ms_rep *r, ms_rep_build *b)
{
    ms_rep_cache *c = r->cache;
    memset(b, 0, sizeof *b);
    b->m = m;
    b->on = &c->on;
    b->idx = c->idx;
    b->nsel = c->nsel;
    b->color = c->col;
    b->palette = c->palette;
    b->p = ms_rep_style_params(&r->style);
    b->scratch = &c->scratch;
    b->coloring = &r->coloring;
    b->cmin = r->cmin;
    b->cmax = r->cmax;
}

/* A volume method: one build from the data sets (and the current frame's coordinates, when
 * there is one). */
static int build_volume(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err)
{
    ms_rep_build b;
    build_input(m, r, &b);
    ms_rep_volume_colors(reps->colors, m, &r->coloring, &b.vc);
    b.pos = m->nframes && m->frame >= 0 ? m->frames[m->frame].pos : NULL;
    return ms_rep_method_at((size_t)r->style.method)->build(&b, &r->cache->dl, err);
}

int ms_rep_build_frames(ms_rep_state *reps, ms_molecule *m, ms_rep *r, ms_error *err)
{
    ms_rep_cache *c = r->cache;
    if (!c->sel_valid || !c->col_valid) return 0;
    for (int id = 0; id < MS_COLOR_MAX; id++)
        c->palette[id] = ms_rgba8_from_float(ms_color_rgb(reps->colors, id), 1.0f);
    if (draws_volume(r)) return build_volume(reps, m, r, err);
    if (m->nframes == 0 || m->frame < 0) return 0;
    const ms_rep_method *meth = ms_rep_method_at((size_t)r->style.method);
    long *frames = NULL, now = m->frame;
    size_t nf = 1;
    if (!draws_now(r) && ms_rep_frames_list(r->frames, (long)m->nframes, m->frame, &frames, &nf, err))
        return -1;
    int rc = 0;
    for (size_t k = 0; k < nf && rc == 0; k++) {
        long f = frames ? frames[k] : now;
        frame_data fd;
        memset(&fd, 0, sizeof fd);
        ms_rep_build b;
        build_input(m, r, &b);
        rc = !(b.pos = frame_pos(m, r, f, err)) || frame_specific(reps, m, r, f, &fd, &b, err) ||
             meth->build(&b, &c->dl, err) ? -1 : 0;
        ms_bitset_free(&fd.on);
        free(fd.idx);
        free(fd.col);
    }
    free(frames);
    return rc;
}

const ms_displaylist *ms_rep_list(const ms_rep *r) { return &r->cache->dl; }

size_t ms_rep_cache_bytes(const ms_rep *r)
{
    const ms_rep_cache *c = r->cache;
    size_t bytes = (c->on.nbits + 63) / 64 * sizeof(uint64_t) + c->idxcap * sizeof(uint32_t) +
                   c->colcap * sizeof(uint16_t) + c->poscap * sizeof(float);
    for (int k = 0; k < MS_REP_NSCRATCH; k++) bytes += c->scratch.cap[k];
    return bytes;
}

const uint32_t *ms_rep_atoms(const ms_rep *r, size_t *n)
{
    *n = r->cache->sel_valid ? r->cache->nsel : 0;
    return r->cache->idx;
}

unsigned long ms_rep_builds(const ms_rep *r) { return r->cache->builds; }
