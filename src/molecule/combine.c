/* combine.c: molecules made of the atoms of others (combine.h), and term filtering. */
#include "config.h"
#include "molecule/combine.h"
#include "molecule/analysis.h"

#include <stdlib.h>
#include <string.h>

void ms_terms_keep(ms_terms *t, int kind, const uint8_t *keep)
{
    size_t w = ms_term_width(kind), n = 0;
    for (size_t k = 0; k < t->n; k++) {
        if (!keep[k]) continue;
        memmove(t->atoms + w * n, t->atoms + w * k, w * sizeof *t->atoms);
        if (t->type) t->type[n] = t->type[k];
        n++;
    }
    t->n = n;
}

/* Where each atom of a part's molecule goes in the new one (-1: not taken). */
static int32_t *part_map(const ms_mol_part *p, size_t base, ms_error *err)
{
    int32_t *map = malloc((p->m->atoms.n + 1) * sizeof *map);
    if (!map) {
        ms_error_set(err, "out of memory");
        return NULL;
    }
    for (size_t i = 0; i < p->m->atoms.n; i++) map[i] = p->atoms ? -1 : (int32_t)(base + i);
    for (size_t k = 0; p->atoms && k < p->natoms; k++) map[p->atoms[k]] = (int32_t)(base + k);
    return map;
}

static size_t part_count(const ms_mol_part *p) { return p->atoms ? p->natoms : p->m->atoms.n; }
static uint32_t part_atom(const ms_mol_part *p, size_t k) { return p->atoms ? p->atoms[k] : (uint32_t)k; }

/* Re-intern a string of src in dst. */
static ms_str restr(ms_molecule *dst, const ms_molecule *src, ms_str s)
{
    return s == MS_STR_NONE ? s : ms_strtab_intern_cstr(dst->strings, ms_mol_str(src, s));
}

/* Copy the atoms of a part (every per-atom field; strings re-interned). */
static int copy_atoms(ms_molecule *m, const ms_mol_part *p, ms_error *err)
{
    const ms_atoms *s = &p->m->atoms;
    size_t nf = ms_atoms_field_count();
    for (size_t k = 0; k < part_count(p); k++) {
        uint32_t i = part_atom(p, k);
        long j = ms_mol_add_blank_atom(m, err);
        if (j < 0) return -1;
        for (size_t f = 0; f < nf; f++) {
            size_t es;
            void **dst = ms_atoms_field(&m->atoms, f, &es);
            void **src = ms_atoms_field((ms_atoms *)s, f, &es);
            memcpy((char *)*dst + es * (size_t)j, (char *)*src + es * i, es);
        }
        ms_str *strs[5] = {m->atoms.name, m->atoms.type, m->atoms.resname, m->atoms.segname,
                           m->atoms.chain};
        for (int q = 0; q < 5; q++)
            if ((strs[q][j] = restr(m, p->m, strs[q][j])) == MS_STR_NONE) {
                ms_error_set(err, "out of memory");
                return -1;
            }
    }
    return 0;
}

typedef struct bond_acc {
    uint32_t *pairs;
    float *order;
    ms_str *type;
    size_t n, cap, ocap, tcap;
} bond_acc;

/* The bonds of a part's atoms that stay inside it, mapped. */
static int copy_bonds(ms_molecule *m, const ms_mol_part *p, const int32_t *map, bond_acc *b,
                      ms_error *err)
{
    const ms_molecule *s = p->m;
    for (size_t i = 0; s->has_bonds && i < s->atoms.n; i++)
        for (uint32_t k = s->bonds.start[i]; k < s->bonds.start[i + 1]; k++) {
            uint32_t j = s->bonds.to[k];
            if (j <= i || map[i] < 0 || map[j] < 0) continue;
            if (ms_grow((void **)&b->pairs, &b->cap, 2 * (b->n + 1), sizeof *b->pairs) ||
                ms_grow((void **)&b->order, &b->ocap, b->n + 1, sizeof *b->order) ||
                ms_grow((void **)&b->type, &b->tcap, b->n + 1, sizeof *b->type)) {
                ms_error_set(err, "out of memory");
                return -1;
            }
            b->pairs[2 * b->n] = (uint32_t)map[i], b->pairs[2 * b->n + 1] = (uint32_t)map[j];
            b->order[b->n] = s->bonds.order ? s->bonds.order[k] : 1.0f;
            b->type[b->n] = s->bonds.type ? restr(m, s, s->bonds.type[k]) : MS_STR_NONE;
            b->n++;
        }
    return 0;
}

/* The terms whose atoms are all in the part, mapped. */
static int copy_terms(ms_molecule *m, const ms_mol_part *p, const int32_t *map, ms_error *err)
{
    for (int kind = 0; kind < MS_TERM_KINDS; kind++) {
        const ms_terms *t = &p->m->terms[kind];
        size_t w = ms_term_width(kind);
        for (size_t k = 0; k < t->n; k++) {
            uint32_t at[4];
            int in = 1;
            for (size_t q = 0; q < w && in; q++) in = map[t->atoms[w * k + q]] >= 0;
            if (!in) continue;
            for (size_t q = 0; q < w; q++) at[q] = (uint32_t)map[t->atoms[w * k + q]];
            ms_str ty = t->type ? restr(m, p->m, t->type[k]) : MS_STR_NONE;
            if (ms_terms_add(m, kind, at, ty, err)) return -1;
        }
    }
    return 0;
}

static long part_frame(const ms_mol_part *p, size_t f, int all)
{
    if (all) return (long)f;
    long fr = p->frame >= 0 ? p->frame : p->m->frame;
    return fr >= 0 && (size_t)fr < p->m->nframes ? fr : -1;
}

/* Frame fr of a part, in memory (a streamed one read into its window, a cache), or NULL
 * with err. */
static const ms_frame *part_src(const ms_mol_part *part, long fr, ms_error *err)
{
    return ms_mol_frame((ms_molecule *)part->m, (size_t)fr, err);
}

/* Frames: every one (all) or one, the parts' coordinates placed copy after copy. */
static int copy_frames(ms_molecule *m, const ms_mol_part *parts, size_t nparts, size_t ncopies,
                       const float (*shift)[3], int all, ms_error *err)
{
    size_t nfr = all ? parts[0].m->nframes : 1;
    for (size_t f = 0; f < nfr; f++) {
        int any = 0, vel = 1;
        for (size_t p = 0; p < nparts; p++) {
            long fr = part_frame(&parts[p], f, all);
            const ms_frame *src = fr >= 0 ? part_src(&parts[p], fr, err) : NULL;
            if (fr >= 0 && !src) return -1;
            any |= fr >= 0;
            vel &= src && src->vel != NULL;
        }
        if (!any) return 0;
        ms_frame *out = ms_mol_add_frame(m, vel, err);
        if (!out) return -1;
        size_t at = 0;
        memset(out->cell, 0, sizeof out->cell);
        for (size_t c = 0; c < ncopies; c++)
            for (size_t p = 0; p < nparts; p++) {
                long fr = part_frame(&parts[p], f, all);
                const ms_frame *src = fr >= 0 ? part_src(&parts[p], fr, err) : NULL;
                if (fr >= 0 && !src) return -1;
                if (src && c == 0 && p == 0) {
                    memcpy(out->cell, src->cell, sizeof out->cell);
                    out->time = src->time;
                    memcpy(out->energy, src->energy, sizeof out->energy);
                }
                for (size_t k = 0; k < part_count(&parts[p]); k++, at++)
                    for (int d = 0; d < 3; d++) {
                        uint32_t i = part_atom(&parts[p], k);
                        out->pos[3 * at + d] = (src ? src->pos[3 * i + d] : 0.0f) +
                                               (shift ? shift[c][d] : 0.0f);
                        if (vel) out->vel[3 * at + d] = src->vel[3 * i + d];
                    }
            }
    }
    m->frame = m->nframes ? 0 : -1;
    return 0;
}

static int add_parts(ms_molecule *m, const ms_mol_part *parts, size_t nparts, size_t ncopies,
                     bond_acc *b, ms_error *err)
{
    for (size_t c = 0; c < ncopies; c++)
        for (size_t p = 0; p < nparts; p++) {
            int32_t *map = part_map(&parts[p], m->atoms.n, err);
            int rc = !map || copy_atoms(m, &parts[p], err) ||
                     copy_bonds(m, &parts[p], map, b, err) || copy_terms(m, &parts[p], map, err);
            free(map);
            if (rc) return -1;
        }
    return 0;
}

static int any_type(const bond_acc *b)
{
    for (size_t k = 0; k < b->n; k++)
        if (b->type[k] != MS_STR_NONE) return 1;
    return 0;
}

static int all_same_frames(const ms_mol_part *parts, size_t nparts)
{
    for (size_t p = 1; p < nparts; p++)
        if (parts[p].m->nframes != parts[0].m->nframes) return 0;
    return nparts && parts[0].m->nframes > 0;
}

ms_molecule *ms_mol_combine(const ms_mol_part *parts, size_t nparts, size_t ncopies,
                            const float (*shift)[3], int all_frames, ms_error *err)
{
    size_t total = 0;
    for (size_t p = 0; p < nparts; p++) total += part_count(&parts[p]);
    if (total * ncopies > 0x7fffffffu) {
        ms_error_set(err, "%zu atoms are too many", total * ncopies);
        return NULL;
    }
    ms_molecule *m = ms_mol_new(err);
    bond_acc b = {0};
    int all = all_frames && all_same_frames(parts, nparts);
    int rc = !m || !(m->name = ms_strdup("molecule")) ||
             ms_mol_reserve_atoms(m, total * ncopies, err) ||
             add_parts(m, parts, nparts, ncopies, &b, err) ||
             ms_bonds_build(m, b.pairs, b.n, b.order, err) ||
             (any_type(&b) && ms_bonds_set_types(m, b.pairs, b.type, b.n, err)) ||
             copy_frames(m, parts, nparts, ncopies, shift, all, err) ||
             ms_analysis_classify(m, err);
    free(b.pairs), free(b.order), free(b.type);
    if (!rc) { /* the copied secondary structure stands when every source had one */
        m->ss_known = 1;
        for (size_t p = 0; p < nparts; p++) m->ss_known &= parts[p].m->ss_known;
    }
    if (rc) {
        if (m && !err->msg[0]) ms_error_set(err, "out of memory");
        ms_mol_free(m);
        return NULL;
    }
    return m;
}
