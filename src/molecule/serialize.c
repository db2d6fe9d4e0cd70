/* serialize.c: packing a molecule into a header and blocks of its arrays, unpacking them
 * into a new molecule, and checking what was unpacked. */
#include "config.h"
#include "molecule/serialize.h"

#include <stdlib.h>
#include <string.h>

static const char mol_magic[8] = "MSMOL02";
static const char frm_magic[8] = "MSFRM02";
#define ENDIAN_MARK 0x01020304u
#define NO_STRING UINT64_MAX

/* Header flags: which optional parts follow. */
enum {
    HF_BONDS = 1 << 0, HF_ORDER = 1 << 1, HF_BTYPE = 1 << 2, HF_SS_KNOWN = 1 << 3,
    HF_AUTOBONDS = 1 << 4, HF_RES_START = 1 << 5, HF_POLYFRAG = 1 << 6, HF_ACTIVE = 1 << 7,
    HF_DISPLAYED = 1 << 8, HF_FIXED = 1 << 9, HF_USER0 = 1 << 10, /* .. HF_USER0 << 3 */
    HF_TTYPE0 = 1 << 14 /* .. HF_TTYPE0 << 2: terms of kind k have types */
};

void ms_molser_free(ms_molser *s)
{
    free(s->head);
    free(s->block);
    memset(s, 0, sizeof *s);
}

/* ---------------------------------------------------------------- writing a header */

typedef struct wbuf {
    unsigned char *p;
    size_t len, cap;
    int oom;
} wbuf;

static void put(wbuf *w, const void *data, size_t n)
{
    if (w->oom) return;
    if (ms_grow((void **)&w->p, &w->cap, w->len + n, 1)) {
        w->oom = 1;
        return;
    }
    memcpy(w->p + w->len, data, n);
    w->len += n;
}

static void put_u64(wbuf *w, uint64_t v) { put(w, &v, sizeof v); }

static void put_str(wbuf *w, const char *s)
{
    if (!s) {
        put_u64(w, NO_STRING);
        return;
    }
    size_t n = strlen(s);
    put_u64(w, n);
    put(w, s, n);
}

static void put_magic(wbuf *w, const char magic[8])
{
    uint32_t mark = ENDIAN_MARK;
    float one = 1.0f;
    put(w, magic, 8);
    put(w, &mark, sizeof mark);
    put(w, &one, sizeof one);
}

/* ---------------------------------------------------------------- reading one */

typedef struct rbuf {
    const unsigned char *p;
    size_t len, pos;
    int bad;          /* ran past the end, or a value made no sense */
    int oom;
} rbuf;

static void get(rbuf *r, void *out, size_t n)
{
    if (r->bad || n > r->len - r->pos) {
        r->bad = 1;
        if (n <= 64) memset(out, 0, n); /* scalars read as 0; big blocks stay untouched */
        return;
    }
    memcpy(out, r->p + r->pos, n);
    r->pos += n;
}

static uint64_t get_u64(rbuf *r)
{
    uint64_t v;
    get(r, &v, sizeof v);
    return v;
}

/* A malloc'd string, or NULL (absent, or r->bad / r->oom set). */
static char *get_str(rbuf *r)
{
    uint64_t n = get_u64(r);
    if (r->bad || n == NO_STRING) return NULL;
    if (n > r->len - r->pos || memchr(r->p + r->pos, '\0', (size_t)n)) {
        r->bad = 1;
        return NULL;
    }
    char *s = malloc((size_t)n + 1);
    if (!s) {
        r->oom = 1;
        return NULL;
    }
    memcpy(s, r->p + r->pos, (size_t)n);
    s[n] = '\0';
    r->pos += (size_t)n;
    return s;
}

static int check_magic(rbuf *r, const char magic[8], const char *what, ms_error *err)
{
    char m[8];
    uint32_t mark;
    float one;
    get(r, m, sizeof m);
    get(r, &mark, sizeof mark);
    get(r, &one, sizeof one);
    if (r->bad || memcmp(m, magic, sizeof m) != 0) {
        ms_error_set(err, "not a molscope %s header", what);
        return -1;
    }
    if (mark != ENDIAN_MARK || one != 1.0f) {
        ms_error_set(err, "%s written on a machine with another byte order", what);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- block lists */

typedef struct blist {
    ms_molser *s;
    size_t cap;
    int oom;
} blist;

static void add_block(blist *b, const void *data, size_t bytes)
{
    if (b->oom || bytes == 0) return;
    if (ms_grow((void **)&b->s->block, &b->cap, b->s->nblocks + 1, sizeof *b->s->block)) {
        b->oom = 1;
        return;
    }
    b->s->block[b->s->nblocks].data = (void *)data;
    b->s->block[b->s->nblocks].bytes = bytes;
    b->s->nblocks++;
}

/* The arrays of m in their fixed order (the same for packing and unpacking). */
static void structure_blocks(ms_molecule *m, uint64_t flags, uint64_t nb, blist *b)
{
    size_t n = m->atoms.n;
    for (size_t k = 0; k < ms_atoms_field_count(); k++) {
        size_t el;
        void **p = ms_atoms_field(&m->atoms, k, &el);
        add_block(b, *p, n * el);
    }
    if (flags & HF_BONDS) {
        add_block(b, m->bonds.start, (n + 1) * sizeof *m->bonds.start);
        add_block(b, m->bonds.to, nb * sizeof *m->bonds.to);
        if (flags & HF_ORDER) add_block(b, m->bonds.order, nb * sizeof *m->bonds.order);
        if (flags & HF_BTYPE) add_block(b, m->bonds.type, nb * sizeof *m->bonds.type);
    }
    if (flags & HF_RES_START)
        add_block(b, m->res_start, (m->nresidues + 1) * sizeof *m->res_start);
    for (int k = 0; k < 4; k++)
        if (flags & (HF_USER0 << k)) add_block(b, m->user[k], n * sizeof *m->user[k]);
    if (flags & HF_POLYFRAG) {
        add_block(b, m->pfrag, n * sizeof *m->pfrag);
        add_block(b, m->nfrag, n * sizeof *m->nfrag);
    }
    for (int k = 0; k < MS_TERM_KINDS; k++) {
        const ms_terms *t = &m->terms[k];
        if (!t->n) continue;
        add_block(b, t->atoms, t->n * ms_term_width(k) * sizeof *t->atoms);
        if (flags & ((uint64_t)HF_TTYPE0 << k)) add_block(b, t->type, t->n * sizeof *t->type);
    }
}

/* ---------------------------------------------------------------- the structure */

static uint64_t structure_flags(const ms_molecule *m)
{
    uint64_t f = 0;
    if (m->has_bonds) f |= HF_BONDS;
    if (m->has_bonds && m->bonds.order) f |= HF_ORDER;
    if (m->has_bonds && m->bonds.type) f |= HF_BTYPE;
    if (m->ss_known) f |= HF_SS_KNOWN;
    if (m->autobonds_pending) f |= HF_AUTOBONDS;
    if (m->res_start) f |= HF_RES_START;
    if (m->pfrag && m->nfrag) f |= HF_POLYFRAG;
    if (m->active) f |= HF_ACTIVE;
    if (m->displayed) f |= HF_DISPLAYED;
    if (m->fixed) f |= HF_FIXED;
    for (int k = 0; k < 4; k++)
        if (m->user[k]) f |= (uint64_t)HF_USER0 << k;
    for (int k = 0; k < MS_TERM_KINDS; k++)
        if (m->terms[k].n && m->terms[k].type) f |= (uint64_t)HF_TTYPE0 << k;
    return f;
}

static void put_view(wbuf *w, const ms_molecule *m)
{
    put(w, m->center, sizeof m->center);
    put(w, &m->scale, sizeof m->scale);
    put(w, m->rotate, sizeof m->rotate);
    put(w, m->global, sizeof m->global);
}

int ms_molser_pack(const ms_molecule *m, ms_molser *out, ms_error *err)
{
    memset(out, 0, sizeof *out);
    size_t n = m->atoms.n;
    uint64_t flags = structure_flags(m), nb = m->has_bonds ? m->bonds.start[n] : 0;
    wbuf w = {0};
    put_magic(&w, mol_magic);
    put_u64(&w, n);
    put_u64(&w, nb);
    put_u64(&w, m->nresidues);
    put_u64(&w, m->nfragments);
    put_u64(&w, flags);
    for (int k = 0; k < MS_TERM_KINDS; k++) put_u64(&w, m->terms[k].n);
    put_view(&w, m);
    put_str(&w, m->name);
    put_str(&w, m->remarks);
    put_u64(&w, m->nfiles);
    for (size_t i = 0; i < m->nfiles; i++) {
        put_str(&w, m->files[i].path);
        put_str(&w, m->files[i].type);
    }
    uint32_t ns = ms_strtab_count(m->strings);
    put_u64(&w, ns);
    for (uint32_t id = 0; id < ns; id++) put_str(&w, ms_strtab_get(m->strings, id));
    out->head = w.p;
    out->head_len = w.len;
    blist b = {.s = out};
    structure_blocks((ms_molecule *)m, flags, nb, &b);
    if (w.oom || b.oom) {
        ms_molser_free(out);
        ms_error_set(err, "out of memory packing a molecule");
        return -1;
    }
    return 0;
}

/* Names, remarks, files and the string table from the header into m. */
static int unpack_text(rbuf *r, ms_molecule *m, ms_error *err)
{
    m->name = get_str(r);
    m->remarks = get_str(r);
    uint64_t nfiles = get_u64(r);
    if (nfiles > (r->len - r->pos) / 16) r->bad = 1; /* each file takes 16 bytes or more */
    for (uint64_t i = 0; i < nfiles && !r->bad && !r->oom; i++) {
        char *path = get_str(r), *type = get_str(r);
        if (path && type && ms_mol_add_file(m, path, type, err)) r->oom = 1;
        else if (!r->bad && !r->oom && (!path || !type)) r->bad = 1;
        free(path);
        free(type);
    }
    uint64_t ns = get_u64(r);
    if (ns == 0 || ns > (r->len - r->pos) / 8 + 1) r->bad = 1;
    for (uint64_t id = 0; id < ns && !r->bad && !r->oom; id++) {
        char *s = get_str(r);
        if (!s) {
            r->bad |= !r->oom;
            break;
        }
        ms_str got = ms_strtab_intern_cstr(m->strings, s);
        if (got == MS_STR_NONE) r->oom = 1;
        else if (got != id) r->bad = 1; /* a repeated string, or "" not first */
        free(s);
    }
    if (r->oom) ms_error_set(err, "out of memory unpacking a molecule");
    else if (r->bad) ms_error_set(err, "damaged molecule header");
    return r->bad || r->oom ? -1 : 0;
}

/* Allocate every array the header announces. */
static int unpack_alloc(ms_molecule *m, uint64_t n, uint64_t nb, uint64_t flags,
                        const uint64_t *nterms, ms_error *err)
{
    if (n && ms_mol_reserve_atoms(m, (size_t)n, err)) return -1;
    m->atoms.n = (size_t)n;
    int oom = 0;
    if (flags & HF_BONDS) {
        m->has_bonds = 1;
        oom |= !(m->bonds.start = ms_alloc_array((size_t)n + 1, sizeof(uint32_t)));
        oom |= !(m->bonds.to = ms_alloc_array((size_t)nb, sizeof(uint32_t)));
        if (flags & HF_ORDER) oom |= !(m->bonds.order = ms_alloc_array((size_t)nb, sizeof(float)));
        if (flags & HF_BTYPE) oom |= !(m->bonds.type = ms_alloc_array((size_t)nb, sizeof(ms_str)));
    }
    if (flags & HF_RES_START)
        oom |= !(m->res_start = ms_alloc_array(m->nresidues + 1, sizeof(uint32_t)));
    for (int k = 0; k < 4; k++)
        if (flags & ((uint64_t)HF_USER0 << k))
            oom |= !(m->user[k] = ms_alloc_array((size_t)n, sizeof(float)));
    if (flags & HF_POLYFRAG) {
        oom |= !(m->pfrag = ms_alloc_array((size_t)n, sizeof(int32_t)));
        oom |= !(m->nfrag = ms_alloc_array((size_t)n, sizeof(int32_t)));
    }
    for (int k = 0; k < MS_TERM_KINDS; k++) {
        ms_terms *t = &m->terms[k];
        if (!nterms[k]) continue;
        t->n = t->cap = (size_t)nterms[k];
        oom |= !(t->atoms = ms_alloc_array(t->n * ms_term_width(k), sizeof *t->atoms));
        if (flags & ((uint64_t)HF_TTYPE0 << k))
            oom |= !(t->type = ms_alloc_array(t->n, sizeof *t->type));
    }
    if (oom) ms_error_set(err, "out of memory for a molecule of %llu atoms", (unsigned long long)n);
    return oom ? -1 : 0;
}

/* Bytes of the blocks that follow a structure header with these counts. */
static uint64_t structure_bytes(uint64_t n, uint64_t nb, uint64_t nres, uint64_t flags,
                                const uint64_t *nterms)
{
    ms_atoms none = {0};
    uint64_t per_atom = 0, total;
    for (size_t k = 0; k < ms_atoms_field_count(); k++) {
        size_t el;
        ms_atoms_field(&none, k, &el);
        per_atom += el;
    }
    for (int k = 0; k < 4; k++) per_atom += flags & ((uint64_t)HF_USER0 << k) ? 4 : 0;
    per_atom += flags & HF_POLYFRAG ? 8 : 0;
    total = per_atom * n;
    if (flags & HF_BONDS)
        total += 4 * (n + 1) + 4 * nb * (1 + !!(flags & HF_ORDER) + !!(flags & HF_BTYPE));
    if (flags & HF_RES_START) total += 4 * (nres + 1);
    for (int k = 0; k < MS_TERM_KINDS; k++)
        total += nterms[k] * 4 * (ms_term_width(k) + !!(flags & ((uint64_t)HF_TTYPE0 << k)));
    return total;
}

/* ms_molser_unpack, refusing headers whose blocks would take more than limit bytes. */
static ms_molecule *unpack_limited(const void *head, size_t len, uint64_t limit,
                                   ms_molser *out, ms_error *err)
{
    memset(out, 0, sizeof *out);
    rbuf r = {.p = head, .len = len};
    if (check_magic(&r, mol_magic, "molecule", err)) return NULL;
    uint64_t n = get_u64(&r), nb = get_u64(&r), nres = get_u64(&r), nfrag = get_u64(&r);
    uint64_t flags = get_u64(&r), nterms[MS_TERM_KINDS];
    int terms_ok = 1;
    for (int k = 0; k < MS_TERM_KINDS; k++) {
        nterms[k] = get_u64(&r);
        terms_ok &= nterms[k] <= UINT32_MAX;
    }
    if (r.bad || n > 0x7fffffffu || nb > UINT32_MAX || (nb && !(flags & HF_BONDS)) ||
        nres > n || nfrag > n || (nres && !(flags & HF_RES_START)) || !terms_ok ||
        structure_bytes(n, nb, nres, flags, nterms) > limit) {
        ms_error_set(err, "damaged molecule header (counts)");
        return NULL;
    }
    ms_molecule *m = ms_mol_new(err);
    if (!m) return NULL;
    get(&r, m->center, sizeof m->center);
    get(&r, &m->scale, sizeof m->scale);
    get(&r, m->rotate, sizeof m->rotate);
    get(&r, m->global, sizeof m->global);
    m->nresidues = (size_t)nres;
    m->nfragments = (size_t)nfrag;
    m->ss_known = (flags & HF_SS_KNOWN) != 0;
    m->autobonds_pending = (flags & HF_AUTOBONDS) != 0;
    m->active = (flags & HF_ACTIVE) != 0;
    m->displayed = (flags & HF_DISPLAYED) != 0;
    m->fixed = (flags & HF_FIXED) != 0;
    if (unpack_text(&r, m, err) || unpack_alloc(m, n, nb, flags, nterms, err)) goto fail;
    if (r.pos != r.len) {
        ms_error_set(err, "damaged molecule header (%zu bytes too many)", r.len - r.pos);
        goto fail;
    }
    blist b = {.s = out};
    structure_blocks(m, flags, nb, &b);
    if (b.oom) {
        ms_error_set(err, "out of memory");
        goto fail;
    }
    out->nbonds = (size_t)nb;
    return m;
fail:
    ms_molser_free(out);
    ms_mol_free(m);
    return NULL;
}

ms_molecule *ms_molser_unpack(const void *head, size_t len, ms_molser *out, ms_error *err)
{
    return unpack_limited(head, len, UINT64_MAX, out, err);
}

/* ---------------------------------------------------------------- checks */

static int check_atoms(const ms_molecule *m, ms_error *err)
{
    const ms_atoms *a = &m->atoms;
    uint32_t ns = ms_strtab_count(m->strings);
    size_t nfrag = m->nfragments ? m->nfragments : 1;
    for (size_t i = 0; i < a->n; i++) {
        if (a->name[i] >= ns || a->type[i] >= ns || a->resname[i] >= ns ||
            a->segname[i] >= ns || a->chain[i] >= ns) {
            ms_error_set(err, "atom %zu names a string that does not exist", i);
            return -1;
        }
        if (a->atomicnumber[i] > 118 || a->fragment[i] < 0 || (size_t)a->fragment[i] >= nfrag) {
            ms_error_set(err, "atom %zu has a bad element or fragment number", i);
            return -1;
        }
        if (m->pfrag && (m->pfrag[i] < -1 || m->pfrag[i] >= (int32_t)a->n ||
                         m->nfrag[i] < -1 || m->nfrag[i] >= (int32_t)a->n)) {
            ms_error_set(err, "atom %zu has a bad polymer fragment number", i);
            return -1;
        }
    }
    return 0;
}

static int check_residues(const ms_molecule *m, ms_error *err)
{
    if (!m->res_start) return 0;
    const uint32_t *rs = m->res_start;
    size_t nres = m->nresidues, n = m->atoms.n;
    if (rs[0] != 0 || rs[nres] != n) goto bad;
    for (size_t r = 0; r < nres; r++)
        if (rs[r] >= rs[r + 1]) goto bad;
    for (size_t i = 0; i < n; i++) {
        int32_t r = m->atoms.residue[i];
        if (r < 0 || (size_t)r >= nres || i < rs[r] || i >= rs[r + 1]) goto bad;
    }
    return 0;
bad:
    ms_error_set(err, "damaged residue table");
    return -1;
}

static int check_bonds(const ms_molecule *m, size_t nb, ms_error *err)
{
    if (!m->has_bonds) return 0;
    const ms_bonds *b = &m->bonds;
    size_t n = m->atoms.n;
    uint32_t ns = ms_strtab_count(m->strings);
    if (b->start[0] != 0 || b->start[n] != nb) goto bad;
    for (size_t i = 0; i < n; i++)
        if (b->start[i] > b->start[i + 1]) goto bad;
    for (size_t k = 0; k < b->start[n]; k++)
        if (b->to[k] >= n || (b->type && b->type[k] >= ns)) goto bad;
    return 0;
bad:
    ms_error_set(err, "damaged bond table");
    return -1;
}

static int check_terms(const ms_molecule *m, ms_error *err)
{
    uint32_t ns = ms_strtab_count(m->strings);
    for (int k = 0; k < MS_TERM_KINDS; k++) {
        const ms_terms *t = &m->terms[k];
        for (size_t q = 0; q < t->n * ms_term_width(k); q++)
            if (t->atoms[q] >= m->atoms.n) goto bad;
        for (size_t q = 0; t->type && q < t->n; q++)
            if (t->type[q] >= ns) goto bad;
    }
    return 0;
bad:
    ms_error_set(err, "damaged angle, dihedral or improper table");
    return -1;
}

int ms_molser_finish(ms_molecule *m, const ms_molser *s, ms_error *err)
{
    if (check_atoms(m, err) || check_residues(m, err) || check_bonds(m, s->nbonds, err) ||
        check_terms(m, err))
        return -1;
    m->frame = m->nframes ? (int)m->nframes - 1 : -1;
    return 0;
}

/* ---------------------------------------------------------------- frames */

int ms_molser_pack_frames(const ms_molecule *m, size_t first, size_t count, ms_molser *out,
                          ms_error *err)
{
    memset(out, 0, sizeof *out);
    if (first > m->nframes || count > m->nframes - first) {
        ms_error_set(err, "frames %zu..%zu do not exist", first, first + count);
        return -1;
    }
    if (m->stream) {   /* the blocks point at every frame at once */
        ms_error_set(err, "molecule %d streams its frames from %s: they cannot be sent",
                     m->id, m->stream->src.path);
        return -1;
    }
    size_t bytes = m->atoms.n * 3 * sizeof(float);
    wbuf w = {0};
    blist b = {.s = out};
    put_magic(&w, frm_magic);
    put_u64(&w, m->atoms.n);
    put_u64(&w, count);
    for (size_t f = first; f < first + count; f++) {
        const ms_frame *fr = &m->frames[f];
        uint8_t has_vel = fr->vel != NULL;
        put(&w, &has_vel, 1);
        put(&w, fr->cell, sizeof fr->cell);
        put(&w, &fr->time, sizeof fr->time);
        put(&w, fr->energy, sizeof fr->energy);
        add_block(&b, fr->pos, bytes);
        if (fr->vel) add_block(&b, fr->vel, bytes);
    }
    out->head = w.p;
    out->head_len = w.len;
    if (w.oom || b.oom) {
        ms_molser_free(out);
        ms_error_set(err, "out of memory packing frames");
        return -1;
    }
    return 0;
}

int ms_molser_unpack_frames(ms_molecule *m, const void *head, size_t len, ms_molser *out,
                            ms_error *err)
{
    memset(out, 0, sizeof *out);
    rbuf r = {.p = head, .len = len};
    if (check_magic(&r, frm_magic, "frame", err)) return -1;
    uint64_t n = get_u64(&r), count = get_u64(&r);
    const size_t per_frame = 1 + sizeof(float[6]) + sizeof(double) + sizeof(float[MS_EN_KINDS]);
    if (r.bad || n != m->atoms.n || count > (r.len - r.pos) / per_frame ||
        (r.len - r.pos) != count * per_frame) {
        ms_error_set(err, "frame header does not fit the molecule (%llu atoms, it has %zu)",
                     (unsigned long long)n, m->atoms.n);
        return -1;
    }
    size_t before = m->nframes, bytes = m->atoms.n * 3 * sizeof(float);
    blist b = {.s = out};
    for (uint64_t k = 0; k < count; k++) {
        uint8_t has_vel;
        get(&r, &has_vel, 1);
        ms_frame *f = ms_mol_add_frame(m, has_vel != 0, err);
        if (!f) goto fail;
        get(&r, f->cell, sizeof f->cell);
        get(&r, &f->time, sizeof f->time);
        get(&r, f->energy, sizeof f->energy);
        add_block(&b, f->pos, bytes);
        if (f->vel) add_block(&b, f->vel, bytes);
    }
    if (b.oom) {
        ms_error_set(err, "out of memory");
        goto fail;
    }
    if (m->nframes) m->frame = (int)m->nframes - 1;
    return 0;
fail:
    ms_molser_free(out);
    ms_mol_truncate_frames(m, before);
    return -1;
}

/* ---------------------------------------------------------------- one buffer */

/* Append a header (length first) and its blocks. */
static void put_molser(wbuf *w, const ms_molser *s)
{
    put_u64(w, s->head_len);
    put(w, s->head, s->head_len);
    for (size_t k = 0; k < s->nblocks; k++) put(w, s->block[k].data, s->block[k].bytes);
}

int ms_mol_serialize(const ms_molecule *m, void **buf, size_t *len, ms_error *err)
{
    ms_molser st, fr;
    if (ms_molser_pack(m, &st, err)) return -1;
    if (ms_molser_pack_frames(m, 0, m->nframes, &fr, err)) {
        ms_molser_free(&st);
        return -1;
    }
    wbuf w = {0};
    put_molser(&w, &st);
    put_molser(&w, &fr);
    ms_molser_free(&st);
    ms_molser_free(&fr);
    if (w.oom) {
        free(w.p);
        ms_error_set(err, "out of memory serialising a molecule");
        return -1;
    }
    *buf = w.p;
    *len = w.len;
    return 0;
}

/* Read a header's length and return the header; fill the blocks from what follows. */
static const unsigned char *get_head(rbuf *r, size_t *len)
{
    uint64_t n = get_u64(r);
    if (r->bad || n > r->len - r->pos) {
        r->bad = 1;
        return NULL;
    }
    const unsigned char *h = r->p + r->pos;
    r->pos += (size_t)n;
    *len = (size_t)n;
    return h;
}

static void get_blocks(rbuf *r, const ms_molser *s)
{
    for (size_t k = 0; k < s->nblocks; k++) get(r, s->block[k].data, s->block[k].bytes);
}

ms_molecule *ms_mol_deserialize(const void *buf, size_t len, ms_error *err)
{
    rbuf r = {.p = buf, .len = len};
    size_t hlen;
    const unsigned char *h = get_head(&r, &hlen);
    ms_molser s;
    ms_molecule *m = h ? unpack_limited(h, hlen, r.len - r.pos, &s, err) : NULL;
    if (!m) {
        if (!h) ms_error_set(err, "damaged molecule buffer (no header)");
        return NULL;
    }
    get_blocks(&r, &s);
    int rc = r.bad ? 0 : ms_molser_finish(m, &s, err);
    ms_molser_free(&s);
    if (r.bad) goto wrong_length;
    if (rc) goto fail;
    if (!(h = get_head(&r, &hlen))) goto wrong_length;
    if (ms_molser_unpack_frames(m, h, hlen, &s, err)) goto fail;
    get_blocks(&r, &s);
    ms_molser_free(&s);
    if (r.bad || r.pos != r.len) goto wrong_length;
    return m;
wrong_length:
    ms_error_set(err, "damaged molecule buffer (wrong length)");
fail:
    ms_mol_free(m);
    return NULL;
}
