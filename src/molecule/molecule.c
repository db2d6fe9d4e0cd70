/* molecule.c: creating, growing and freeing molecules; frames and their cell vectors; the bond
 * table setter. */
#include "config.h"
#include "molecule/molecule.h"
#include "molecule/analysis.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Every per-atom array of ms_atoms, with its element size, so growth and release are one
 * loop instead of fifteen copies. */
#define ATOM_FIELD(f) {offsetof(ms_atoms, f), sizeof(*((ms_atoms *)0)->f)}
static const struct {
    size_t offset, elsize;
} atom_fields[] = {
    ATOM_FIELD(name),      ATOM_FIELD(type),      ATOM_FIELD(resname),
    ATOM_FIELD(segname),   ATOM_FIELD(chain),     ATOM_FIELD(resid),
    ATOM_FIELD(insertion), ATOM_FIELD(altloc),    ATOM_FIELD(atomicnumber),
    ATOM_FIELD(beta),      ATOM_FIELD(occupancy), ATOM_FIELD(charge),
    ATOM_FIELD(mass),      ATOM_FIELD(radius),    ATOM_FIELD(flags),
    ATOM_FIELD(ss),        ATOM_FIELD(residue),   ATOM_FIELD(fragment),
};

static void **atom_field(ms_atoms *a, size_t k)
{
    return (void **)((char *)a + atom_fields[k].offset);
}

size_t ms_atoms_field_count(void) { return MS_COUNTOF(atom_fields); }

void **ms_atoms_field(ms_atoms *a, size_t k, size_t *elsize)
{
    *elsize = atom_fields[k].elsize;
    return atom_field(a, k);
}

static const float identity4[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};

ms_molecule *ms_mol_new(ms_error *err)
{
    ms_molecule *m = calloc(1, sizeof *m);
    if (!m || !(m->strings = ms_strtab_new())) {
        free(m);
        ms_error_set(err, "out of memory creating a molecule");
        return NULL;
    }
    m->frame = -1;
    m->active = m->displayed = 1;
    m->scale = 1.0f;
    memcpy(m->rotate, identity4, sizeof identity4);
    return m;
}

static void free_bonds(ms_bonds *b)
{
    free(b->start);
    free(b->to);
    free(b->order);
    free(b->type);
    memset(b, 0, sizeof *b);
}

void ms_mol_free(ms_molecule *m)
{
    if (!m) return;
    ms_mol_free_contents(m);
    free(m);
}

/* A frame's arrays, unless a keeper (keep_pos) takes its coordinates. */
static void free_frame(ms_molecule *m, ms_frame *f)
{
    if (!(m->keep_pos && f->pos && m->keep_pos(m->keep_pos_ud, f->pos))) free(f->pos);
    free(f->vel);
    f->pos = f->vel = NULL;
}

void ms_mol_free_contents(ms_molecule *m)
{
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++) free(*atom_field(&m->atoms, k));
    free_bonds(&m->bonds);
    for (int k = 0; k < MS_TERM_KINDS; k++) ms_terms_clear(&m->terms[k]);
    for (size_t f = 0; f < m->nframes; f++) free_frame(m, &m->frames[f]);
    free(m->frames);
    if (m->stream) {
        if (m->stream->src.free) m->stream->src.free(m->stream->src.ud);
        free(m->stream->src.path);
        free(m->stream);
    }
    for (size_t i = 0; i < m->nfiles; i++) {
        free(m->files[i].path);
        free(m->files[i].type);
    }
    free(m->files);
    ms_mol_free_volumes(m);
    for (int i = 0; i < 4; i++) free(m->user[i]);
    free(m->pfrag);
    free(m->nfrag);
    free(m->res_start);
    free(m->remarks);
    free(m->name);
    ms_strtab_free(m->strings);
    memset(m, 0, sizeof *m);
}

/* Bytes of one atom in every per-atom array. */
static size_t atom_bytes(void)
{
    size_t b = 0;
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++) b += atom_fields[k].elsize;
    return b;
}

/* Room for n atoms in every per-atom array; prefault: commit the new pages now (a reader
 * said how many atoms come), else they come as the atoms do (growth by half). A count is a
 * file's hint, not its atoms: pages are committed only when they take at most half the
 * memory available, so a header claiming more atoms than the file holds costs nothing. */
static int reserve_atoms(ms_molecule *m, size_t n, int prefault, ms_error *err)
{
    if (n <= m->atoms.cap) return 0;
    size_t more;
    if (prefault && (ms_mul_size(n - m->atoms.n, atom_bytes(), &more) || more > ms_mem_available() / 2))
        prefault = 0;
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++) {
        size_t bytes, elsize = atom_fields[k].elsize;
        void **p = atom_field(&m->atoms, k);
        void *q;
        if (ms_mul_size(n, elsize, &bytes) || !(q = realloc(*p, bytes))) {
            ms_error_set(err, "out of memory for %zu atoms", n);
            return -1;
        }
        *p = q;
        if (prefault)
            ms_prefault((char *)q + m->atoms.n * elsize, (n - m->atoms.n) * elsize);
    }
    m->atoms.cap = n;
    return 0;
}

int ms_mol_reserve_atoms(ms_molecule *m, size_t n, ms_error *err)
{
    return reserve_atoms(m, n, 1, err);
}

/* Zero element i of an array of elements of `size` bytes: plain stores for the usual sizes
 * (a memset call per field and atom costs a load of millions of atoms a fifth of its time). */
static void zero_element(void *base, size_t i, size_t size)
{
    char *p = (char *)base + i * size;
    static const uint64_t zero = 0;
    switch (size) {
    case 1: *p = 0; break;
    case 2: memcpy(p, &zero, 2); break;
    case 4: memcpy(p, &zero, 4); break;
    case 8: memcpy(p, &zero, 8); break;
    default: memset(p, 0, size);
    }
}

long ms_mol_add_blank_atom(ms_molecule *m, ms_error *err)
{
    ms_atoms *a = &m->atoms;
    if (a->n == a->cap) {
        size_t ncap = a->cap ? a->cap + a->cap / 2 : 1024;
        if (reserve_atoms(m, ncap, 0, err)) return -1;
    }
    size_t i = a->n++;
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++)
        zero_element(*atom_field(a, k), i, atom_fields[k].elsize);
    a->ss[i] = MS_SS_COIL_CODE;
    return (long)i;
}

long ms_mol_add_blank_atoms(ms_molecule *m, size_t n, ms_error *err)
{
    return ms_mol_add_atoms_given(m, n, NULL, 0, err);
}

/* Whether the array at `field` (an ms_atoms member's address) is one of given[0 .. ngiven). */
static int field_given(void *field, void *const *given, size_t ngiven)
{
    for (size_t g = 0; g < ngiven; g++)
        if (given[g] == field) return 1;
    return 0;
}

long ms_mol_add_atoms_given(ms_molecule *m, size_t n, void *const *given, size_t ngiven,
                            ms_error *err)
{
    ms_atoms *a = &m->atoms;
    if (n > a->cap - a->n) {
        size_t want = a->n + n, grown = a->cap + a->cap / 2;
        if (want < a->n || reserve_atoms(m, want > grown ? want : grown, 0, err)) {
            if (want < a->n) ms_error_set(err, "out of memory for %zu more atoms", n);
            return -1;
        }
    }
    size_t first = a->n;
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++)
        if (!field_given(atom_field(a, k), given, ngiven))
            memset((char *)*atom_field(a, k) + first * atom_fields[k].elsize, 0,
                   n * atom_fields[k].elsize);
    if (!field_given(&a->ss, given, ngiven))
        memset(a->ss + first, MS_SS_COIL_CODE, n);
    a->n += n;
    return (long)first;
}

void ms_mol_shrink(ms_molecule *m)
{
    ms_atoms *a = &m->atoms;
    if (a->n == a->cap || a->n == 0) return;
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++) {
        void **p = atom_field(a, k);
        void *q = realloc(*p, a->n * atom_fields[k].elsize);
        if (q) *p = q;
    }
    a->cap = a->n;
}

ms_frame *ms_mol_add_frame(ms_molecule *m, int with_vel, ms_error *err)
{
    if (ms_grow((void **)&m->frames, &m->frames_cap, m->nframes + 1, sizeof *m->frames)) {
        ms_error_set(err, "out of memory for frame %zu", m->nframes);
        return NULL;
    }
    ms_frame *f = &m->frames[m->nframes];
    memset(f, 0, sizeof *f);
    f->spos = -1;
    f->pos = ms_alloc_array(m->atoms.n * 3, sizeof(float));
    f->vel = with_vel ? ms_alloc_array(m->atoms.n * 3, sizeof(float)) : NULL;
    if (!f->pos || (with_vel && !f->vel)) {
        free(f->pos);
        free(f->vel);
        ms_error_set(err, "out of memory for frame %zu of %zu atoms", m->nframes, m->atoms.n);
        return NULL;
    }
    ms_prefault(f->pos, m->atoms.n * 3 * sizeof(float));  /* a reader fills it whole */
    ms_prefault(f->vel, with_vel ? m->atoms.n * 3 * sizeof(float) : 0);
    m->nframes++;
    return f;
}

void ms_mol_truncate_frames(ms_molecule *m, size_t first)
{
    while (m->nframes > first) {
        free_frame(m, &m->frames[--m->nframes]);
    }
    if (m->frame >= (int)m->nframes) m->frame = (int)m->nframes - 1;
}

void ms_mol_delete_frames(ms_molecule *m, size_t first, size_t last, size_t step)
{
    if (step == 0) step = 1;
    if (last >= m->nframes) last = m->nframes - 1;
    size_t w = 0;
    for (size_t r = 0; r < m->nframes; r++) {
        int drop = r >= first && r <= last && (r - first) % step == 0;
        if (drop) {
            free_frame(m, &m->frames[r]);
        } else {
            m->frames[w++] = m->frames[r];
        }
    }
    m->nframes = w;
    if (m->frame >= (int)w) m->frame = (int)w - 1;
    if (m->frame < 0 && w > 0) m->frame = 0;
}

const float *ms_mol_pos(const ms_molecule *m)
{
    if (m->frame < 0 || (size_t)m->frame >= m->nframes) return NULL;
    return m->frames[m->frame].pos;
}

/* ---------------------------------------------------------------- streamed frames */

size_t ms_mol_resident_frames(const ms_molecule *m)
{
    size_t n = 0;
    for (size_t f = 0; f < m->nframes; f++) n += m->frames[f].pos != NULL;
    return n;
}

/* The least recently used frame of the window that may leave it (not the current one), or
 * -1; *n counts the window's frames. */
static long window_victim(const ms_molecule *m, size_t *n)
{
    long victim = -1;
    *n = 0;
    for (size_t f = 0; f < m->nframes; f++) {
        const ms_frame *fr = &m->frames[f];
        if (!fr->pos || fr->spos < 0) continue;
        (*n)++;
        if ((long)f != m->frame && (victim < 0 || fr->used < m->frames[victim].used))
            victim = (long)f;
    }
    return victim;
}

/* Arrays for a frame about to be read: a leaving frame's when the window is full (one
 * buffer goes round), new ones otherwise. */
static int window_take(ms_molecule *m, ms_frame *to, ms_error *err)
{
    size_t n;
    long v = window_victim(m, &n);
    if (v >= 0 && n >= m->stream->window) {
        ms_frame *old = &m->frames[v];
        if (!(m->keep_pos && m->keep_pos(m->keep_pos_ud, old->pos))) {
            to->pos = old->pos;
            to->vel = old->vel;
            old->pos = old->vel = NULL;
            return 0;
        }
        old->pos = NULL;
        free(old->vel);
        old->vel = NULL;
    }
    to->pos = ms_alloc_array(m->atoms.n * 3, sizeof(float));
    to->vel = m->stream->with_vel ? ms_alloc_array(m->atoms.n * 3, sizeof(float)) : NULL;
    if (!to->pos || (m->stream->with_vel && !to->vel)) {
        free_frame(m, to);
        ms_error_set(err, "out of memory for a frame of %zu atoms", m->atoms.n);
        return -1;
    }
    return 0;
}

ms_frame *ms_mol_frame(ms_molecule *m, size_t f, ms_error *err)
{
    ms_frame *fr = &m->frames[f];
    if (m->stream) fr->used = ++m->stream->clock;
    if (fr->pos) return fr;
    if (!m->stream || fr->spos < 0) {
        ms_error_set(err, "molecule %d: frame %zu has no coordinates", m->id, f);
        return NULL;
    }
    if (window_take(m, fr, err)) return NULL;
    const ms_frame_source *s = &m->stream->src;
    if (s->read(s->ud, fr->spos, fr->pos, fr->vel, err)) {
        free_frame(m, fr);
        ms_error_prefix(err, "%s: frame %zu", s->path, f);
        return NULL;
    }
    return fr;
}

ms_frame *ms_mol_frame_pin(ms_molecule *m, size_t f, ms_error *err)
{
    ms_frame *fr = ms_mol_frame(m, f, err);
    if (fr) fr->spos = -1;
    return fr;
}

const float *ms_mol_frame_pos(const ms_molecule *m, size_t f, ms_error *err)
{
    const ms_frame *fr = ms_mol_frame((ms_molecule *)m, f, err);
    return fr ? fr->pos : NULL;
}

int ms_mol_pin_frames(ms_molecule *m, size_t first, size_t last, ms_error *err)
{
    if (!m->stream) return 0;
    for (size_t f = first; f <= last; f++)
        if (!ms_mol_frame_pin(m, f, err)) return -1;
    return 0;
}

int ms_mol_goto(ms_molecule *m, size_t f, ms_error *err)
{
    if (!ms_mol_frame(m, f, err)) return -1;
    m->frame = (int)f;
    return 0;
}

int ms_mol_stream_start(ms_molecule *m, const ms_frame_source *src, size_t window,
                        int with_vel, ms_error *err)
{
    if (m->stream) {
        ms_error_set(err, "molecule %d already streams %s: one streamed file a molecule",
                     m->id, m->stream->src.path);
        return -1;
    }
    ms_stream *s = calloc(1, sizeof *s);
    if (!s) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    s->src = *src;
    s->window = window < 2 ? 2 : window;
    s->with_vel = with_vel;
    m->stream = s;
    return 0;
}

ms_frame *ms_mol_add_streamed_frame(ms_molecule *m, long long spos, ms_error *err)
{
    if (ms_grow((void **)&m->frames, &m->frames_cap, m->nframes + 1, sizeof *m->frames)) {
        ms_error_set(err, "out of memory for frame %zu", m->nframes);
        return NULL;
    }
    ms_frame *f = &m->frames[m->nframes++];
    memset(f, 0, sizeof *f);
    f->spos = spos;
    return f;
}

int ms_cell_vectors(const float cell[6], double v[3][3])
{
    double a = cell[0], b = cell[1], c = cell[2];
    double al = cell[3] * M_PI / 180, be = cell[4] * M_PI / 180, ga = cell[5] * M_PI / 180;
    if (!(a > 0 && b > 0 && c > 0) || !(sin(ga) != 0)) return 0;
    double cx = c * cos(be), cy = c * (cos(al) - cos(be) * cos(ga)) / sin(ga);
    double cz2 = c * c - cx * cx - cy * cy;
    if (!(cz2 > 0) || !isfinite(a) || !isfinite(b) || !isfinite(cz2)) return 0;
    double vv[3][3] = {{a, 0, 0}, {b * cos(ga), b * sin(ga), 0}, {cx, cy, sqrt(cz2)}};
    memcpy(v, vv, sizeof vv);
    return 1;
}

int ms_mol_set_bonds(ms_molecule *m, size_t npairs, const uint32_t *pairs, const float *order,
                     ms_error *err)
{
    if (ms_bonds_build(m, pairs, npairs, order, err)) return -1;
    return ms_analysis_classify(m, err);
}

int ms_terms_add(ms_molecule *m, int kind, const uint32_t *atoms, ms_str type, ms_error *err)
{
    ms_terms *t = &m->terms[kind];
    size_t w = ms_term_width(kind);
    for (size_t k = 0; k < w; k++)
        if (atoms[k] >= m->atoms.n) {
            ms_error_set(err, "a term names atom %lu, but there are %zu atoms",
                         (unsigned long)atoms[k], m->atoms.n);
            return -1;
        }
    if (t->n == t->cap) { /* atoms and types grow together, so their capacities agree */
        size_t cap = t->cap ? 2 * t->cap : 64;
        uint32_t *at = realloc(t->atoms, cap * w * sizeof *at);
        if (!at) goto oom;
        t->atoms = at;
        if (t->type) {
            ms_str *ty = realloc(t->type, cap * sizeof *ty);
            if (!ty) goto oom;
            t->type = ty;
        }
        t->cap = cap;
    }
    ms_str blank = MS_STR_NONE;
    if ((type != MS_STR_NONE || t->type) &&
        (blank = ms_strtab_intern_cstr(m->strings, "")) == MS_STR_NONE)
        goto oom;
    if (type != MS_STR_NONE && !t->type) {
        if (!(t->type = ms_alloc_array(t->cap, sizeof *t->type))) goto oom;
        for (size_t k = 0; k < t->n; k++) t->type[k] = blank;
    }
    if (t->type) t->type[t->n] = type != MS_STR_NONE ? type : blank;
    memcpy(t->atoms + w * t->n, atoms, w * sizeof *atoms);
    t->n++;
    return 0;
oom:
    ms_error_set(err, "out of memory for %zu terms", t->n + 1);
    return -1;
}

void ms_terms_clear(ms_terms *t)
{
    free(t->atoms);
    free(t->type);
    memset(t, 0, sizeof *t);
}

static size_t bond_bytes(const ms_molecule *m)
{
    if (!m->has_bonds) return 0;
    size_t nb = m->bonds.start[m->atoms.n];
    return (m->atoms.n + 1) * sizeof(uint32_t) + nb * sizeof(uint32_t) +
           (m->bonds.order ? nb * sizeof(float) : 0) + (m->bonds.type ? nb * sizeof(ms_str) : 0);
}

static size_t topology_bytes(const ms_molecule *m)
{
    size_t bytes = (m->nresidues + 1) * sizeof(uint32_t);
    for (int k = 0; k < MS_TERM_KINDS; k++) {
        const ms_terms *t = &m->terms[k];
        bytes += t->cap * ms_term_width(k) * sizeof(uint32_t);
        if (t->type) bytes += t->cap * sizeof(ms_str);
    }
    if (m->pfrag) bytes += m->atoms.n * sizeof(int32_t);
    if (m->nfrag) bytes += m->atoms.n * sizeof(int32_t);
    return bytes;
}

void ms_mol_memory_of(const ms_molecule *m, ms_mol_memory *out)
{
    memset(out, 0, sizeof *out);
    for (size_t k = 0; k < MS_COUNTOF(atom_fields); k++) out->atoms += atom_fields[k].elsize;
    out->atoms *= m->atoms.cap;
    out->strings = ms_strtab_bytes(m->strings);
    out->bonds = bond_bytes(m);
    out->topology = topology_bytes(m);
    for (size_t f = 0; f < m->nframes; f++)
        if (m->frames[f].pos)
            out->frames += 3 * m->atoms.n * sizeof(float) * (m->frames[f].vel ? 2 : 1);
    for (int k = 0; k < 4; k++)
        if (m->user[k]) out->other += m->atoms.cap * sizeof(float);
    for (size_t v = 0; v < m->nvolumes; v++)
        out->other += ms_volume_size(&m->volumes[v]) * sizeof(float);
}

size_t ms_mol_structure_bytes(const ms_molecule *m)
{
    ms_mol_memory mm;
    ms_mol_memory_of(m, &mm);
    return mm.atoms + mm.strings + mm.bonds + mm.topology;
}

int ms_mol_add_file(ms_molecule *m, const char *path, const char *type, ms_error *err)
{
    ms_molfile *f = realloc(m->files, (m->nfiles + 1) * sizeof *f);
    if (!f) goto oom;
    m->files = f;
    f[m->nfiles] = (ms_molfile){.path = ms_strdup(path), .type = ms_strdup(type), .first = 0,
                                .last = -1, .step = 1, .filebonds = 1, .autobonds = 1};
    if (!f[m->nfiles].path || !f[m->nfiles].type) {
        free(f[m->nfiles].path);
        free(f[m->nfiles].type);
        goto oom;
    }
    m->nfiles++;
    return 0;
oom:
    ms_error_set(err, "out of memory");
    return -1;
}
