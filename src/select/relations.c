/* relations.c: selections defined through other atoms: `same K as S` (the values of K found
 * in S, as a set: a table per string, a bitmap or hash set of numbers), `withinbonds n of S`
 * (a breadth-first walk of n bonds) and `sequence "re"` (regular expressions over the
 * one-letter sequence of each backbone-linked protein or nucleic chain). All linear. */
#include "config.h"
#include "select/selint.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* ---------------------------------------------------------------- a set of numbers */

/* Integers in a bitmap over [min, max] when that range is small, else (and for floats)
 * keys in an open-addressing hash set. Floats are keyed at 1e-6, as VMD compares them
 * printed with %f. */
typedef struct numset {
    int bitmap;
    int64_t min;
    uint64_t *bits;
    int64_t *keys;
    uint8_t *used;
    size_t mask;
} numset;

static int64_t num_key(double v, int is_int)
{
    if (is_int) return (int64_t)v;
    if (!(v == v)) return INT64_MIN;                /* all NaNs alike */
    if (fabs(v) < 9e12) return llround(v * 1e6);
    int64_t k;
    memcpy(&k, &v, sizeof k);
    return k;
}

static size_t hash64(int64_t k)
{
    uint64_t h = (uint64_t)k * 0x9E3779B97F4A7C15ull;
    return (size_t)(h ^ (h >> 29));
}

static int numset_has(const numset *s, int64_t k)
{
    if (s->bitmap) {
        if (k < s->min) return 0;
        uint64_t off = (uint64_t)(k - s->min);
        return off / 64 <= s->mask && ((s->bits[off / 64] >> (off & 63)) & 1);
    }
    for (size_t i = hash64(k) & s->mask; s->used[i]; i = (i + 1) & s->mask)
        if (s->keys[i] == k) return 1;
    return 0;
}

static void numset_add(numset *s, int64_t k)
{
    if (s->bitmap) {
        uint64_t off = (uint64_t)(k - s->min);
        s->bits[off / 64] |= 1ull << (off & 63);
        return;
    }
    size_t i = hash64(k) & s->mask;
    while (s->used[i] && s->keys[i] != k) i = (i + 1) & s->mask;
    s->used[i] = 1;
    s->keys[i] = k;
}

/* Build the set of the keys of keys[0..n). */
static int numset_build(numset *s, const int64_t *keys, size_t n, int is_int, size_t natoms)
{
    memset(s, 0, sizeof *s);
    int64_t lo = INT64_MAX, hi = INT64_MIN;
    for (size_t i = 0; i < n; i++) {
        lo = MS_MIN(lo, keys[i]);
        hi = MS_MAX(hi, keys[i]);
    }
    if (n && is_int && (uint64_t)(hi - lo) <= 64 * (uint64_t)natoms + 65536) {
        s->bitmap = 1;
        s->min = lo;
        s->mask = (size_t)((uint64_t)(hi - lo) / 64);
        if (!(s->bits = ms_calloc_array(s->mask + 1, sizeof *s->bits))) return -1;
    } else {
        size_t cap = 16;
        while (cap < 2 * n + 2) cap *= 2;
        s->mask = cap - 1;
        s->keys = ms_alloc_array(cap, sizeof *s->keys);
        s->used = ms_calloc_array(cap, 1);
        if (!s->keys || !s->used) return -1;
    }
    for (size_t i = 0; i < n; i++) numset_add(s, keys[i]);
    return 0;
}

static void numset_free(numset *s)
{
    free(s->bits);
    free(s->keys);
    free(s->used);
}

/* ---------------------------------------------------------------- same K as S */

typedef struct same_job {
    const ms_selkw *kw;
    const uint8_t *has;     /* strings: per class */
    const numset *set;      /* numbers */
} same_job;

static int same_block(const ms_selctx *c, const void *data, size_t begin, size_t len,
                      const uint64_t *mask, uint64_t *out, void *scratch)
{
    const same_job *j = data;
    const uint32_t *cls = NULL;
    double *v = scratch;
    if (j->has) cls = ms_selkw_classes(j->kw, c, begin, len, scratch);
    else ms_selkw_numbers(j->kw, c, begin, len, v);
    int is_int = j->kw->kind == SK_INT;
    for (size_t w = 0; w * 64 < len; w++) {
        uint64_t bits = 0;
        for (uint64_t m = mask[w]; m; m &= m - 1) {
            int b = __builtin_ctzll(m);
            size_t k = w * 64 + (size_t)b;
            int hit = j->has ? j->has[cls[k]] : numset_has(j->set, num_key(v[k], is_int));
            bits |= (uint64_t)hit << b;
        }
        out[w] = bits;
    }
    return 0;
}

static int same_strings(ms_selctx *c, const ms_selkw *k, const ms_bitset *src,
                        const ms_bitset *mask, ms_bitset *out)
{
    uint32_t ncls = ms_selkw_nclasses(k, c->m);
    uint8_t *has = ms_calloc_array(ncls, 1);
    if (!has) goto oom;
    for (size_t w = 0; w < ms_bitset_nwords(src); w++)
        for (uint64_t m = src->words[w]; m; m &= m - 1) {
            uint32_t buf;
            has[*ms_selkw_classes(k, c, w * 64 + (size_t)__builtin_ctzll(m), 1, &buf)] = 1;
        }
    same_job j = {k, has, NULL};
    int rc = ms_sel_for_blocks(c, mask, out, same_block, &j, MS_SEL_BLOCK * sizeof(double));
    free(has);
    return rc;
oom:
    ms_error_set(c->err, "same %s as: out of memory", k->name);
    return -1;
}

static int same_numbers(ms_selctx *c, const ms_selkw *k, const ms_bitset *src,
                        const ms_bitset *mask, ms_bitset *out)
{
    size_t n = ms_bitset_count(src), at = 0;
    int64_t *keys = ms_alloc_array(n, sizeof *keys);
    numset set;
    if (!keys) goto oom;
    for (size_t w = 0; w < ms_bitset_nwords(src); w++)
        for (uint64_t m = src->words[w]; m; m &= m - 1) {
            double v;
            ms_selkw_numbers(k, c, w * 64 + (size_t)__builtin_ctzll(m), 1, &v);
            keys[at++] = num_key(v, k->kind == SK_INT);
        }
    int built = numset_build(&set, keys, n, k->kind == SK_INT, c->n) == 0;
    free(keys);
    if (!built) {
        numset_free(&set);
        goto oom;
    }
    same_job j = {k, NULL, &set};
    int rc = ms_sel_for_blocks(c, mask, out, same_block, &j, MS_SEL_BLOCK * sizeof(double));
    numset_free(&set);
    return rc;
oom:
    ms_error_set(c->err, "same %s as: out of memory", k->name);
    return -1;
}

/* same residue as: residues are runs of consecutive atoms, so whole runs of bits are set
 * without reading every atom. */
static int same_residue(ms_selctx *c, const ms_bitset *src, const ms_bitset *mask,
                        ms_bitset *out)
{
    const ms_molecule *m = c->m;
    uint8_t *mark = ms_calloc_array(m->nresidues, 1);
    if (!mark) {
        ms_error_set(c->err, "same residue as: out of memory");
        return -1;
    }
    memset(out->words, 0, ms_bitset_nwords(out) * sizeof *out->words);
    for (size_t w = 0; w < ms_bitset_nwords(src); w++)
        for (uint64_t bits = src->words[w]; bits; bits &= bits - 1) {
            int32_t r = m->atoms.residue[w * 64 + (size_t)__builtin_ctzll(bits)];
            if (mark[r]) continue;
            mark[r] = 1;
            for (uint32_t i = m->res_start[r]; i < m->res_start[r + 1]; i++) ms_bitset_set(out, i);
        }
    ms_bitset_and(out, mask);
    free(mark);
    return 0;
}

int ms_sel_eval_same(ms_selctx *c, const ms_selkw *k, const ms_bitset *src,
                     const ms_bitset *mask, ms_bitset *out)
{
    if (ms_selkw_prepare(k, c)) return -1;
    if (!strcmp(k->name, "residue") && c->m->res_start && c->m->nresidues)
        return same_residue(c, src, mask, out);
    if (k->kind == SK_STRING) return same_strings(c, k, src, mask, out);
    return same_numbers(c, k, src, mask, out);
}

/* ---------------------------------------------------------------- withinbonds */

int ms_sel_eval_withinbonds(ms_selctx *c, long depth, const ms_bitset *src,
                            const ms_bitset *mask, ms_bitset *out)
{
    const ms_molecule *m = c->m;
    ms_bitset seen;
    uint32_t *cur = ms_alloc_array(c->n, sizeof *cur), *next = ms_alloc_array(c->n, sizeof *next);
    if (!cur || !next || ms_bitset_copy(&seen, src)) {
        free(cur);
        free(next);
        ms_error_set(c->err, "withinbonds: out of memory");
        return -1;
    }
    size_t ncur = ms_bitset_indices(src, cur);
    for (long d = 0; d < depth && ncur && m->has_bonds; d++) {
        size_t nnext = 0;
        for (size_t q = 0; q < ncur; q++)
            for (uint32_t b = m->bonds.start[cur[q]]; b < m->bonds.start[cur[q] + 1]; b++) {
                uint32_t j = m->bonds.to[b];
                if (ms_bitset_get(&seen, j)) continue;
                ms_bitset_set(&seen, j);
                next[nnext++] = j;
            }
        uint32_t *t = cur;
        cur = next;
        next = t;
        ncur = nnext;
    }
    for (size_t w = 0; w < ms_bitset_nwords(out); w++)
        out->words[w] = seen.words[w] & mask->words[w];
    ms_bitset_free(&seen);
    free(cur);
    free(next);
    return 0;
}

/* ---------------------------------------------------------------- sequence */

char ms_sel_one_letter(const char *resname, int nucleic)
{
    static const char *const protein[][2] = {
        {"GLY", "G"}, {"ALA", "A"}, {"VAL", "V"}, {"PHE", "F"}, {"PRO", "P"}, {"MET", "M"},
        {"ILE", "I"}, {"LEU", "L"}, {"ASP", "D"}, {"GLU", "E"}, {"LYS", "K"}, {"ARG", "R"},
        {"SER", "S"}, {"THR", "T"}, {"TYR", "Y"}, {"HIS", "H"}, {"CYS", "C"}, {"ASN", "N"},
        {"GLN", "Q"}, {"TRP", "W"}, {"HSE", "H"}, {"HSD", "H"}, {"HSP", "H"}, {"CYX", "C"}};
    static const char *const nuc[][2] = {
        {"ADE", "A"}, {"A", "A"}, {"THY", "T"}, {"T", "T"}, {"CYT", "C"}, {"C", "C"},
        {"GUA", "G"}, {"G", "G"}, {"URA", "U"}, {"U", "U"}};
    const char *const (*t)[2] = nucleic ? nuc : protein;
    size_t n = nucleic ? MS_COUNTOF(nuc) : MS_COUNTOF(protein);
    for (size_t i = 0; i < n; i++)
        if (!strcasecmp(resname, t[i][0])) return t[i][1][0];
    return 'X';
}

/* Mark the residues r0..r1-1 (one chain) whose letters a pattern matches. */
static void match_chain(const ms_selctx *c, const ms_selnode *nd, size_t r0, size_t r1,
                        int nucleic, char *seq, uint8_t *resmark)
{
    const ms_molecule *m = c->m;
    size_t n = r1 - r0;
    for (size_t i = 0; i < n; i++)
        seq[i] = ms_sel_one_letter(ms_mol_str(m, m->atoms.resname[m->res_start[r0 + i]]), nucleic);
    seq[n] = '\0';
    for (size_t v = 0; v < nd->nvals; v++) {
        size_t start = 0;
        regmatch_t mt;
        while (start <= n &&
               regexec(nd->vals[v].re, seq + start, 1, &mt, start ? REG_NOTBOL : 0) == 0) {
            size_t b = start + (size_t)mt.rm_so, e = start + (size_t)mt.rm_eo;
            memset(resmark + r0 + b, 1, e - b);
            start = e > b ? e : e + 1;
        }
    }
}

/* 0 for protein, 1 for nucleic, -1 for other residues. */
static int residue_kind(const ms_molecule *m, size_t r)
{
    uint16_t f = m->atoms.flags[m->res_start[r]];
    return f & MS_AF_PROTEIN ? 0 : f & MS_AF_NUCLEIC ? 1 : -1;
}

/* Does residue r continue the chain of residue r-1 through the backbone: C bonded to N for
 * proteins, O3' (or O3*) to P for nucleic acids? */
static int chained(const ms_molecule *m, size_t r, int nucleic, const ms_str names[3])
{
    if (!m->has_bonds) return 0;
    for (uint32_t i = m->res_start[r - 1]; i < m->res_start[r]; i++) {
        ms_str nm = m->atoms.name[i];
        if (nucleic ? nm != names[1] && nm != names[2] : nm != names[0]) continue;
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
            uint32_t j = m->bonds.to[k];
            if ((size_t)m->atoms.residue[j] == r && m->atoms.name[j] == names[nucleic ? 4 : 3])
                return 1;
        }
    }
    return 0;
}

/* sequence: the one-letter codes of each chain of protein (or nucleic) residues linked
 * through their backbones, in order, searched with each pattern; matched residues are
 * selected whole. */
int ms_sel_eval_sequence(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                         ms_bitset *out)
{
    ms_molecule *m = c->m;
    uint8_t *resmark = ms_calloc_array(m->nresidues, 1);
    char *seq = ms_alloc_array(m->nresidues + 1, 1);
    if (!resmark || !seq) {
        free(resmark);
        free(seq);
        ms_error_set(c->err, "sequence: out of memory");
        return -1;
    }
    const char *nm[5] = {"C", "O3'", "O3*", "N", "P"};
    ms_str names[5];
    for (int k = 0; k < 5; k++) names[k] = ms_strtab_find(m->strings, nm[k]);
    for (size_t r0 = 0; m->res_start && r0 < m->nresidues;) {
        int kind = residue_kind(m, r0);
        size_t r1 = r0 + 1;
        while (kind >= 0 && r1 < m->nresidues && residue_kind(m, r1) == kind &&
               chained(m, r1, kind, names))
            r1++;
        if (kind >= 0) match_chain(c, nd, r0, r1, kind, seq, resmark);
        r0 = r1;
    }
    for (size_t w = 0; w < ms_bitset_nwords(out); w++) {
        uint64_t bits = 0;
        for (uint64_t mm = mask->words[w]; mm; mm &= mm - 1) {
            int b = __builtin_ctzll(mm);
            bits |= (uint64_t)resmark[m->atoms.residue[w * 64 + (size_t)b]] << b;
        }
        out->words[w] = bits;
    }
    free(resmark);
    free(seq);
    return 0;
}
