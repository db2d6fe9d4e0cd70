/* relations.c: selections defined through other atoms: `same K as S` (the values of K found
 * in S, as a set: a table per string, a bitmap or hash set of numbers), `withinbonds n of S`
 * (a breadth-first walk of n bonds) and `sequence "re"` (regular expressions over the
 * one-letter sequence of each protein and nucleic fragment). All linear in the atoms. */
#include "config.h"
#include "select/selint.h"
#include "molecule/analysis.h"

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

int ms_sel_eval_same(ms_selctx *c, const ms_selkw *k, const ms_bitset *src,
                     const ms_bitset *mask, ms_bitset *out)
{
    if (ms_selkw_prepare(k, c)) return -1;
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

static char one_letter(const char *resname, int nucleic)
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

/* Mark the residues of one fragment (res[0..n)) whose letters a pattern matches. */
static void match_fragment(const ms_selctx *c, const ms_selnode *nd, const uint32_t *res,
                           size_t n, int nucleic, char *seq, uint8_t *resmark)
{
    const ms_molecule *m = c->m;
    for (size_t i = 0; i < n; i++)
        seq[i] = one_letter(ms_mol_str(m, m->atoms.resname[m->res_start[res[i]]]), nucleic);
    seq[n] = '\0';
    for (size_t v = 0; v < nd->nvals; v++) {
        size_t start = 0;
        regmatch_t mt;
        while (start <= n &&
               regexec(nd->vals[v].re, seq + start, 1, &mt, start ? REG_NOTBOL : 0) == 0) {
            size_t b = start + (size_t)mt.rm_so, e = start + (size_t)mt.rm_eo;
            for (size_t k = b; k < e; k++) resmark[res[k]] = 1;
            start = e > b ? e : e + 1;
        }
    }
}

/* Residues of each fragment in order (frag[] per atom, -1 outside): counting sort. */
static int fragments_residues(const ms_molecule *m, const int32_t *frag, uint32_t **res,
                              size_t **off, size_t *nfrag)
{
    size_t nf = 0;
    for (size_t r = 0; r < m->nresidues; r++)
        nf = MS_MAX(nf, (size_t)(frag[m->res_start[r]] + 1));
    *off = ms_calloc_array(nf + 2, sizeof **off);
    *res = ms_alloc_array(m->nresidues + 1, sizeof **res);
    if (!*off || !*res) return -1;
    for (size_t r = 0; r < m->nresidues; r++)
        if (frag[m->res_start[r]] >= 0) (*off)[frag[m->res_start[r]] + 2]++;
    for (size_t f = 2; f < nf + 2; f++) (*off)[f] += (*off)[f - 1];
    for (size_t r = 0; r < m->nresidues; r++)
        if (frag[m->res_start[r]] >= 0) (*res)[(*off)[frag[m->res_start[r]] + 1]++] = (uint32_t)r;
    *nfrag = nf;
    return 0;
}

int ms_sel_eval_sequence(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                         ms_bitset *out)
{
    ms_molecule *m = c->m;
    if (ms_mol_polymer_fragments(m, c->err)) return -1;
    uint8_t *resmark = ms_calloc_array(m->nresidues, 1);
    char *seq = ms_alloc_array(m->nresidues + 1, 1);
    int rc = resmark && seq ? 0 : -1;
    for (int nucleic = 0; rc == 0 && nucleic < 2 && m->res_start; nucleic++) {
        uint32_t *res = NULL;
        size_t *off = NULL, nf = 0;
        rc = fragments_residues(m, nucleic ? m->nfrag : m->pfrag, &res, &off, &nf);
        for (size_t f = 0; rc == 0 && f < nf; f++)
            match_fragment(c, nd, res + off[f], off[f + 1] - off[f], nucleic, seq, resmark);
        free(res);
        free(off);
    }
    if (rc == 0) {
        for (size_t w = 0; w < ms_bitset_nwords(out); w++) {
            uint64_t bits = 0;
            for (uint64_t mm = mask->words[w]; mm; mm &= mm - 1) {
                int b = __builtin_ctzll(mm);
                bits |= (uint64_t)resmark[m->atoms.residue[w * 64 + (size_t)b]] << b;
            }
            out->words[w] = bits;
        }
    } else {
        ms_error_set(c->err, "sequence: out of memory");
    }
    free(resmark);
    free(seq);
    return rc;
}
