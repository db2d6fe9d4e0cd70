/* write.c: the structure view a writer plugin reads (restricted to the selected atoms, with
 * bonds renumbered), frame gathering, and the output: opened by base/safewrite (a file is
 * replaced whole or not at all, a symlink written through, a device or FIFO written in
 * place) and handed to the plugin as /dev/fd/N. */
#include "config.h"
#include "fileio/write.h"
#include "fileio/load.h"
#include "molecule/elements.h"
#include "base/safewrite.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void ms_write_opts_default(ms_write_opts *o)
{
    memset(o, 0, sizeof *o);
    o->last = -1;
    o->step = 1;
}

typedef struct write_view {
    ms_struct_view view;       /* first member */
    const ms_molecule *m;
    const uint32_t *atoms;     /* view index -> molecule index; NULL = identity */
    uint32_t *bond_start, *bond_to;  /* renumbered CSR */
    uint32_t *bond_src;        /* parallel to bond_to: the slot in the molecule's table */
    int32_t *map;              /* molecule index -> view index or -1; NULL = identity */
    uint32_t *terms[MS_TERM_KINDS]; /* the molecule's terms wholly in the view */
    size_t nterms[MS_TERM_KINDS];
    char chain_buf[2], ins_buf[2];
} write_view;

static size_t atom_index(const write_view *w, size_t i)
{
    return w->atoms ? w->atoms[i] : i;
}

static void view_get_atom(const ms_struct_view *v, size_t i, ms_atom_in *out)
{
    const write_view *w = (const write_view *)v;
    const ms_molecule *m = w->m;
    const ms_atoms *a = &m->atoms;
    size_t k = atom_index(w, i);
    memset(out, 0, sizeof *out);
    out->name = ms_mol_str(m, a->name[k]);
    out->type = ms_mol_str(m, a->type[k]);
    out->resname = ms_mol_str(m, a->resname[k]);
    out->segname = ms_mol_str(m, a->segname[k]);
    out->chain = ms_mol_str(m, a->chain[k]);
    out->element = a->atomicnumber[k] ? ms_element_symbol(a->atomicnumber[k]) : "";
    out->resid = a->resid[k];
    out->insertion = a->insertion[k] ? a->insertion[k] : ' ';
    out->altloc = a->altloc[k] ? a->altloc[k] : ' ';
    out->hetero = (a->flags[k] & MS_AF_HETERO) != 0;
    out->beta = a->beta[k];
    out->occupancy = a->occupancy[k];
    out->charge = a->charge[k];
    out->mass = a->mass[k];
    out->radius = a->radius[k];
    out->atomicnumber = a->atomicnumber[k];
    out->has = MS_HAS_BETA | MS_HAS_OCCUPANCY | MS_HAS_CHARGE | MS_HAS_MASS | MS_HAS_RADIUS |
               MS_HAS_ATOMICNUMBER;
}

static size_t view_get_bonds(const ms_struct_view *v, size_t i, const unsigned **to)
{
    const write_view *w = (const write_view *)v;
    if (!w->bond_start) {
        *to = NULL;
        return 0;
    }
    *to = w->bond_to + w->bond_start[i];
    return w->bond_start[i + 1] - w->bond_start[i];
}

static void view_get_bond_info(const ms_struct_view *v, size_t i, size_t k, float *order,
                               const char **type)
{
    const write_view *w = (const write_view *)v;
    const ms_bonds *b = &w->m->bonds;
    uint32_t src = w->bond_src[w->bond_start[i] + k];
    *order = b->order ? b->order[src] : 1.0f;
    *type = b->type ? ms_mol_str(w->m, b->type[src]) : "";
}

static size_t view_count_terms(const ms_struct_view *v, int kind)
{
    const write_view *w = (const write_view *)v;
    return kind >= 0 && kind < MS_TERM_KINDS ? w->nterms[kind] : 0;
}

static void view_get_term(const ms_struct_view *v, int kind, size_t k, size_t *atoms,
                          const char **type)
{
    const write_view *w = (const write_view *)v;
    const ms_terms *t = &w->m->terms[kind];
    size_t src = w->terms[kind] ? w->terms[kind][k] : k, width = ms_term_width(kind);
    for (size_t q = 0; q < width; q++) {
        uint32_t a = t->atoms[width * src + q];
        atoms[q] = w->map ? (size_t)w->map[a] : a;
    }
    *type = t->type ? ms_mol_str(w->m, t->type[src]) : "";
}

/* The selection's map from molecule to view indices, and the terms wholly inside it. */
static int view_build_map(write_view *w, size_t n, ms_error *err)
{
    const ms_molecule *m = w->m;
    for (int kind = 0; kind < MS_TERM_KINDS; kind++) w->nterms[kind] = m->terms[kind].n;
    if (!w->atoms) return 0;
    if (!(w->map = ms_alloc_array(m->atoms.n, sizeof *w->map))) goto oom;
    for (size_t i = 0; i < m->atoms.n; i++) w->map[i] = -1;
    for (size_t i = 0; i < n; i++) w->map[w->atoms[i]] = (int32_t)i;
    for (int kind = 0; kind < MS_TERM_KINDS; kind++) {
        const ms_terms *t = &m->terms[kind];
        size_t width = ms_term_width(kind), kept = 0;
        if (!t->n) continue;
        if (!(w->terms[kind] = ms_alloc_array(t->n, sizeof(uint32_t)))) goto oom;
        for (size_t k = 0; k < t->n; k++) {
            size_t q = 0;
            while (q < width && w->map[t->atoms[width * k + q]] >= 0) q++;
            if (q == width) w->terms[kind][kept++] = (uint32_t)k;
        }
        w->nterms[kind] = kept;
    }
    return 0;
oom:
    ms_error_set(err, "out of memory renumbering atoms");
    return -1;
}

static void view_free(write_view *w)
{
    free(w->bond_start);
    free(w->bond_to);
    free(w->bond_src);
    free(w->map);
    for (int kind = 0; kind < MS_TERM_KINDS; kind++) free(w->terms[kind]);
}

/* Renumber the bonds among the selected atoms. */
static int view_build_bonds(write_view *w, size_t n, ms_error *err)
{
    const ms_molecule *m = w->m;
    if (!m->has_bonds) return 0;
    const int32_t *map = w->map;
    w->bond_start = ms_alloc_array(n + 1, sizeof *w->bond_start);
    size_t total = 0;
    for (size_t i = 0; w->bond_start && i < n; i++) {
        size_t k = atom_index(w, i);
        for (uint32_t b = m->bonds.start[k]; b < m->bonds.start[k + 1]; b++)
            total += !map || map[m->bonds.to[b]] >= 0;
    }
    w->bond_to = ms_alloc_array(total, sizeof *w->bond_to);
    w->bond_src = ms_alloc_array(total, sizeof *w->bond_src);
    if (!w->bond_start || !w->bond_to || !w->bond_src) goto oom;
    size_t pos = 0;
    for (size_t i = 0; i < n; i++) {
        w->bond_start[i] = (uint32_t)pos;
        size_t k = atom_index(w, i);
        for (uint32_t b = m->bonds.start[k]; b < m->bonds.start[k + 1]; b++) {
            uint32_t j = m->bonds.to[b];
            if (map && map[j] < 0) continue;
            w->bond_src[pos] = b;
            w->bond_to[pos++] = map ? (uint32_t)map[j] : j;
        }
    }
    w->bond_start[n] = (uint32_t)pos;
    return 0;
oom:
    ms_error_set(err, "out of memory renumbering bonds");
    return -1;
}

/* Gather the selected atoms' coordinates of one frame. */
static const float *gather(const write_view *w, const float *src, float *buf, size_t n)
{
    if (!w->atoms || !src) return src;
    for (size_t i = 0; i < n; i++) memcpy(buf + 3 * i, src + 3 * (size_t)w->atoms[i], 12);
    return buf;
}

/* Errors of the output name the file; this module's callers name it already. */
static void drop_path(ms_error *err, const char *path)
{
    size_t n = strlen(path);
    if (strncmp(err->msg, path, n) == 0 && strncmp(err->msg + n, ": ", 2) == 0)
        memmove(err->msg, err->msg + n + 2, strlen(err->msg + n + 2) + 1);
}

/* Open the output for a plugin; NULL with err set (without the path). */
static ms_ofile *open_output(const char *path, ms_error *err)
{
    ms_ofile *out = ms_ofile_open(path, err);
    if (!out) drop_path(err, path);
    return out;
}

/* The plugin's run is over (prc and crc what its writing and closing returned): put the
 * output in place, or give it up. 0, or -1 with err set. */
static int finish_output(ms_ofile *out, const char *path, int prc, int crc, const ms_perr *perr,
                         ms_error *err)
{
    if (prc != MS_PLUGIN_OK || crc != MS_PLUGIN_OK) {
        ms_error_set(err, "%s", perr->msg[0] ? perr->msg : "write error");
        ms_ofile_abort(out);
        return -1;
    }
    if (ms_ofile_commit(out, err) == 0) return 0;
    drop_path(err, path);
    return -1;
}

long ms_write_file(const ms_registry *r, ms_molecule *m, const char *path,
                   const ms_write_opts *o, ms_error *err)
{
    const ms_plugin *p = NULL;
    if (o->type && *o->type) p = ms_load_pick_plugin(r, path, o->type, err);
    else if (!(p = ms_registry_for_path(r, path)))
        ms_error_set(err, "cannot tell the file type from the name; give a type");
    if (!p) return -1;
    int can_struct = p->write_structure && (p->caps & MS_CAN_WRITE_STRUCTURE);
    int can_frames = p->write_frame && (p->caps & MS_CAN_WRITE_FRAMES);
    if (!p->open_write || (!can_struct && !can_frames)) {
        ms_error_set(err, "the %s plugin cannot write files", p->name);
        return -1;
    }
    size_t n = o->atoms ? o->natoms : m->atoms.n;
    long first = o->first < 0 ? 0 : o->first, step = o->step < 1 ? 1 : o->step;
    long last = o->last < 0 || o->last >= (long)m->nframes ? (long)m->nframes - 1 : o->last;
    long nwrite = last >= first ? (last - first) / step + 1 : 0;
    if (can_frames && nwrite == 0) {
        ms_error_set(err, "no frames to write (molecule %d has %zu)", m->id, m->nframes);
        return -1;
    }

    write_view w;
    memset(&w, 0, sizeof w);
    w.m = m;
    w.atoms = o->atoms;
    w.view.natoms = n;
    w.view.get_atom = view_get_atom;
    w.view.get_bonds = view_get_bonds;
    w.view.remarks = m->remarks;
    w.view.get_bond_info = view_get_bond_info;
    w.view.count_terms = view_count_terms;
    w.view.get_term = view_get_term;
    w.view.options = o->options;
    float *buf = NULL, *vbuf = NULL;   /* the selected atoms' positions, velocities */
    long written = 0;
    ms_ofile *out = NULL;
    if (view_build_map(&w, n, err) || view_build_bonds(&w, n, err)) goto fail_view;
    if (o->atoms && (!(buf = ms_alloc_array(3 * n, sizeof *buf)) ||
                     !(vbuf = ms_alloc_array(3 * n, sizeof *vbuf)))) {
        ms_error_set(err, "out of memory");
        goto fail_view;
    }
    if (!(out = open_output(path, err))) goto fail_view;
    ms_perr perr = {{0}};
    void *h = p->open_write(ms_ofile_fd_name(out), (long)n, &perr);
    if (!h) {
        ms_error_set(err, "%s", perr.msg[0] ? perr.msg : strerror(errno));
        goto fail_view;
    }
    int rc = can_struct ? p->write_structure(h, &w.view, &perr) : MS_PLUGIN_OK;
    for (long f = first; rc == MS_PLUGIN_OK && can_frames && f <= last; f += step) {
        ms_error ferr = {{0}};
        const ms_frame *fr = ms_mol_frame(m, (size_t)f, &ferr);   /* streamed: read now */
        if (!fr) {
            rc = ms_perr_set(&perr, "%s", ferr.msg);
            break;
        }
        ms_frame_in in;
        memset(&in, 0, sizeof in);
        in.pos = gather(&w, fr->pos, buf, n);
        in.vel = fr->vel ? gather(&w, fr->vel, vbuf, n) : NULL;
        memcpy(in.cell, fr->cell, sizeof in.cell);
        in.time = fr->time;
        in.index = (int)written;
        rc = p->write_frame(h, &w.view, &in, &perr);
        if (rc == MS_PLUGIN_OK) written++;
    }
    int rc_close = p->close_write(h, rc == MS_PLUGIN_OK ? &perr : &(ms_perr){{0}});
    int failed = finish_output(out, path, rc, rc_close, &perr, err);
    out = NULL;
    if (failed) goto fail_view;
    free(buf);
    free(vbuf);
    view_free(&w);
    return written;
fail_view:
    ms_ofile_abort(out);
    free(buf);
    free(vbuf);
    view_free(&w);
    return -1;
}

int ms_write_volume(const ms_registry *r, const ms_volume *v, const char *path,
                    const char *type, ms_error *err)
{
    const ms_plugin *p = NULL;
    if (type && *type) p = ms_load_pick_plugin(r, path, type, err);
    else if (!(p = ms_registry_for_path(r, path)))
        ms_error_set(err, "cannot tell the file type from the name; give a type");
    if (!p) return -1;
    if (!p->open_write || !p->write_volume || !(p->caps & MS_CAN_WRITE_VOLUME)) {
        ms_error_set(err, "the %s plugin cannot write volumetric data", p->name);
        return -1;
    }
    ms_volume_meta meta;
    memset(&meta, 0, sizeof meta);
    snprintf(meta.name, sizeof meta.name, "%s", v->name ? v->name : "");
    for (int d = 0; d < 3; d++) {
        meta.n[d] = v->n[d];
        meta.origin[d] = v->origin[d];
        for (int e = 0; e < 3; e++) meta.delta[d][e] = v->delta[d][e];
    }
    ms_ofile *out = open_output(path, err);
    if (!out) return -1;
    ms_perr perr = {{0}};
    void *h = p->open_write(ms_ofile_fd_name(out), 0, &perr);
    if (!h) {
        ms_error_set(err, "%s", perr.msg[0] ? perr.msg : strerror(errno));
        ms_ofile_abort(out);
        return -1;
    }
    int rc = p->write_volume(h, &meta, v->data, &perr);
    int rc_close = p->close_write(h, rc == MS_PLUGIN_OK ? &perr : &(ms_perr){{0}});
    return finish_output(out, path, rc, rc_close, &perr, err);
}
