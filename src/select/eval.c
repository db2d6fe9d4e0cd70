/* eval.c: evaluating a compiled selection into a bit set. Every node is evaluated under a
 * mask (the atoms still in question): `a and b` evaluates b only on a's atoms, `a or b`
 * only on the atoms a left out, so expensive terms (within, regular expressions) do no
 * work for atoms already decided. Per-atom terms run over blocks of 4096 atoms in
 * parallel; keyword lists on strings are decided once per distinct string. */
#include "config.h"
#include "select/selint.h"
#include "base/threads.h"

#include <math.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <string.h>

/* ---------------------------------------------------------------- bit set helpers */

static size_t nwords(const ms_bitset *b) { return ms_bitset_nwords(b); }

static int is_empty(const ms_bitset *b)
{
    for (size_t i = 0, n = nwords(b); i < n; i++)
        if (b->words[i]) return 0;
    return 1;
}

static void copy_bits(ms_bitset *dst, const ms_bitset *src)
{
    memcpy(dst->words, src->words, nwords(src) * sizeof *src->words);
}

static void clear_bits(ms_bitset *b) { memset(b->words, 0, nwords(b) * sizeof *b->words); }

static int temp_bits(ms_selctx *c, ms_bitset *b)
{
    if (ms_bitset_init(b, c->n) == 0) return 0;
    ms_error_set(c->err, "out of memory evaluating a selection of %zu atoms", c->n);
    return -1;
}

/* ---------------------------------------------------------------- parallel blocks */

typedef struct blocks_job {
    ms_selctx *c;
    const ms_bitset *mask;
    ms_bitset *out;
    ms_block_fn fn;
    const void *data;
    size_t scratch_bytes;
    atomic_int failed;
} blocks_job;

static void blocks_range(void *ctx, size_t b0, size_t b1, int thread)
{
    blocks_job *j = ctx;
    void *scratch = j->scratch_bytes ? malloc(j->scratch_bytes) : NULL;
    if (j->scratch_bytes && !scratch) {
        atomic_store(&j->failed, 1);
        return;
    }
    for (size_t b = b0; b < b1; b++) {
        size_t begin = b * MS_SEL_BLOCK, len = MS_MIN(MS_SEL_BLOCK, j->c->n - begin);
        size_t w0 = begin / 64, nw = (len + 63) / 64;
        const uint64_t *mw = j->mask->words + w0;
        uint64_t *ow = j->out->words + w0, any = 0;
        for (size_t k = 0; k < nw; k++) any |= mw[k];
        if (!any) {
            memset(ow, 0, nw * sizeof *ow);
            continue;
        }
        if (j->fn(j->c, j->data, begin, len, mw, ow, scratch)) atomic_store(&j->failed, 1);
        for (size_t k = 0; k < nw; k++) ow[k] &= mw[k];
    }
    free(scratch);
}

int ms_sel_for_blocks(ms_selctx *c, const ms_bitset *mask, ms_bitset *out, ms_block_fn fn,
                      const void *data, size_t scratch_bytes)
{
    blocks_job j = {c, mask, out, fn, data, scratch_bytes, 0};
    size_t nblocks = (c->n + MS_SEL_BLOCK - 1) / MS_SEL_BLOCK;
    ms_parallel_for(nblocks, 2, blocks_range, &j);
    if (atomic_load(&j.failed)) {
        ms_error_set(c->err, "out of memory evaluating a selection");
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- singlewords */

static int single_block(const ms_selctx *c, const void *data, size_t begin, size_t len,
                        const uint64_t *mask, uint64_t *out, void *scratch)
{
    ms_selkw_single(data, c, begin, len, out);
    return 0;
}

static int eval_single(ms_selctx *c, const ms_selkw *k, const ms_bitset *mask, ms_bitset *out)
{
    if (!strcmp(k->name, "all")) {
        copy_bits(out, mask);
        return 0;
    }
    if (!strcmp(k->name, "none")) {
        clear_bits(out);
        return 0;
    }
    if (ms_selkw_prepare(k, c)) return -1;
    return ms_sel_for_blocks(c, mask, out, single_block, k, 0);
}

/* ---------------------------------------------------------------- keyword lists */

typedef struct numlist {
    const ms_selkw *kw;
    double *lo, *hi;       /* merged intervals, ascending */
    size_t n;
} numlist;

typedef struct strlist {
    const ms_selkw *kw;
    uint8_t *match;        /* per class */
} strlist;

static int cmp_interval(const void *a, const void *b)
{
    const double *x = a, *y = b;
    return x[0] < y[0] ? -1 : x[0] > y[0];
}

/* The values of a numeric keyword list as VMD reads them: an int keyword takes the leading
 * integer of each word (atoi), a float keyword matches within 0.1%; `a to b` is inclusive. */
static void value_interval(const ms_selkw *k, const ms_selval *v, double *iv)
{
    if (k->kind == SK_INT) {
        long lo = strtol(v->lo, NULL, 10), hi = v->hi ? strtol(v->hi, NULL, 10) : lo;
        iv[0] = (double)lo;
        iv[1] = (double)hi;
    } else if (v->hi) {
        iv[0] = strtod(v->lo, NULL);
        iv[1] = strtod(v->hi, NULL);
    } else {
        double d = strtod(v->lo, NULL), delta = fabs(d / 1000);
        iv[0] = d - delta;
        iv[1] = d + delta;
    }
}

static int numlist_build(ms_selctx *c, const ms_selnode *nd, numlist *l)
{
    double *iv = ms_alloc_array(nd->nvals * 2, sizeof *iv);
    l->lo = ms_alloc_array(nd->nvals, sizeof *l->lo);
    l->hi = ms_alloc_array(nd->nvals, sizeof *l->hi);
    if (!iv || !l->lo || !l->hi) {
        free(iv);
        ms_error_set(c->err, "out of memory");
        return -1;
    }
    size_t m = 0;
    for (size_t i = 0; i < nd->nvals; i++) {
        value_interval(nd->kw, &nd->vals[i], &iv[2 * m]);
        if (iv[2 * m] <= iv[2 * m + 1]) m++;     /* drops empty and NaN ranges */
    }
    qsort(iv, m, 2 * sizeof *iv, cmp_interval);
    l->n = 0;
    for (size_t i = 0; i < m; i++) {
        if (l->n && iv[2 * i] <= l->hi[l->n - 1]) {
            l->hi[l->n - 1] = MS_MAX(l->hi[l->n - 1], iv[2 * i + 1]);
        } else {
            l->lo[l->n] = iv[2 * i];
            l->hi[l->n++] = iv[2 * i + 1];
        }
    }
    free(iv);
    return 0;
}

static int in_intervals(const numlist *l, double v)
{
    size_t a = 0, b = l->n;            /* last interval with lo <= v */
    while (a < b) {
        size_t mid = (a + b) / 2;
        if (l->lo[mid] <= v) a = mid + 1;
        else b = mid;
    }
    return a > 0 && v <= l->hi[a - 1];
}

/* One word of atoms against the intervals: branch-free for short lists (`resid 1 to 10`,
 * `index 5 7 9`), a binary search per atom for long ones. */
static uint64_t numlist_word(const numlist *l, const double *v, size_t n, uint64_t m)
{
    uint64_t bits = 0;
    if (l->n <= 4) {
        for (size_t i = 0; i < l->n; i++) {
            double lo = l->lo[i], hi = l->hi[i];
            for (size_t k = 0; k < n; k++) bits |= (uint64_t)((v[k] >= lo) & (v[k] <= hi)) << k;
        }
        return bits;
    }
    for (; m; m &= m - 1) {
        int b = __builtin_ctzll(m);
        if (in_intervals(l, v[b])) bits |= 1ull << b;
    }
    return bits;
}

static int numlist_block(const ms_selctx *c, const void *data, size_t begin, size_t len,
                         const uint64_t *mask, uint64_t *out, void *scratch)
{
    const numlist *l = data;
    double *v = scratch;
    for (size_t w = 0; w * 64 < len; w++) {
        size_t n = MS_MIN(64, len - w * 64);
        out[w] = 0;
        if (!mask[w]) continue;
        ms_selkw_numbers(l->kw, c, begin + w * 64, n, v);
        out[w] = numlist_word(l, v, n, mask[w]);
    }
    return 0;
}

/* Does string s match any value of a string keyword list? */
static int str_matches(const ms_selnode *nd, const char *s)
{
    for (size_t i = 0; i < nd->nvals; i++) {
        const ms_selval *v = &nd->vals[i];
        if (v->kind == SV_EXACT ? !strcmp(v->lo, s)
            : v->kind == SV_REGEX ? regexec(v->re, s, 0, NULL, 0) == 0
            : strcmp(v->lo, s) <= 0 && strcmp(v->hi, s) >= 0)
            return 1;
    }
    return 0;
}

static int strlist_block(const ms_selctx *c, const void *data, size_t begin, size_t len,
                         const uint64_t *mask, uint64_t *out, void *scratch)
{
    const strlist *l = data;
    const uint32_t *cls = ms_selkw_classes(l->kw, c, begin, len, scratch);
    for (size_t w = 0; w * 64 < len; w++) {
        uint64_t bits = 0;
        size_t end = MS_MIN(len, w * 64 + 64);
        if (mask[w])
            for (size_t j = w * 64; j < end; j++) bits |= (uint64_t)l->match[cls[j]] << (j & 63);
        out[w] = bits;
    }
    return 0;
}

/* index and serial lists are ranges of bits: set them directly. */
static void index_ranges(ms_selctx *c, const numlist *l, int serial, const ms_bitset *mask,
                         ms_bitset *out)
{
    clear_bits(out);
    for (size_t i = 0; i < l->n; i++) {
        double lo = MS_MAX(ceil(l->lo[i]) - serial, 0), hi = floor(l->hi[i]) - serial;
        if (!(lo <= hi) || lo >= (double)c->n) continue;
        size_t a = (size_t)lo, b = hi >= (double)c->n - 1 ? c->n - 1 : (size_t)hi;
        for (; a <= b && (a & 63); a++) ms_bitset_set(out, a);
        for (; a + 63 <= b; a += 64) out->words[a / 64] = ~0ull;
        for (; a <= b; a++) ms_bitset_set(out, a);
    }
    ms_bitset_and(out, mask);
}

static int eval_keylist(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                        ms_bitset *out)
{
    if (ms_selkw_prepare(nd->kw, c)) return -1;
    int rc;
    int serial = !strcmp(nd->kw->name, "serial");
    if (serial || !strcmp(nd->kw->name, "index")) {
        numlist l = {nd->kw, NULL, NULL, 0};
        if ((rc = numlist_build(c, nd, &l)) == 0) index_ranges(c, &l, serial, mask, out);
        free(l.lo);
        free(l.hi);
        return rc;
    }
    if (nd->kw->kind == SK_STRING) {
        uint32_t ncls = ms_selkw_nclasses(nd->kw, c->m);
        strlist l = {nd->kw, malloc(ncls ? ncls : 1)};
        if (!l.match) {
            ms_error_set(c->err, "out of memory");
            return -1;
        }
        for (uint32_t k = 0; k < ncls; k++)
            l.match[k] = (uint8_t)str_matches(nd, ms_selkw_class_str(nd->kw, c->m, k));
        rc = ms_sel_for_blocks(c, mask, out, strlist_block, &l, MS_SEL_BLOCK * sizeof(uint32_t));
        free(l.match);
    } else {
        numlist l = {nd->kw, NULL, NULL, 0};
        rc = numlist_build(c, nd, &l);
        if (rc == 0)
            rc = ms_sel_for_blocks(c, mask, out, numlist_block, &l, 64 * sizeof(double));
        free(l.lo);
        free(l.hi);
    }
    return rc;
}

/* ---------------------------------------------------------------- boolean structure */

static int eval_and(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask, ms_bitset *out)
{
    ms_bitset cur, tmp;
    if (temp_bits(c, &cur)) return -1;
    if (temp_bits(c, &tmp)) {
        ms_bitset_free(&cur);
        return -1;
    }
    copy_bits(&cur, mask);
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < nd->nkids && !is_empty(&cur); i++) {
        rc = ms_sel_eval_node(c, nd->kids[i], &cur, &tmp);
        ms_bitset t = cur;
        cur = tmp;
        tmp = t;
    }
    copy_bits(out, &cur);
    ms_bitset_free(&cur);
    ms_bitset_free(&tmp);
    return rc;
}

static int eval_or(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask, ms_bitset *out)
{
    ms_bitset rest, tmp;
    if (temp_bits(c, &rest)) return -1;
    if (temp_bits(c, &tmp)) {
        ms_bitset_free(&rest);
        return -1;
    }
    copy_bits(&rest, mask);
    clear_bits(out);
    int rc = 0;
    for (size_t i = 0; rc == 0 && i < nd->nkids && !is_empty(&rest); i++) {
        rc = ms_sel_eval_node(c, nd->kids[i], &rest, &tmp);
        ms_bitset_or(out, &tmp);
        ms_bitset_andnot(&rest, &tmp);
    }
    ms_bitset_free(&rest);
    ms_bitset_free(&tmp);
    return rc;
}

/* Evaluate child over every atom (the subject of within, same, withinbonds), then call
 * the relation. */
static int eval_relation(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                         ms_bitset *out)
{
    ms_bitset src;
    if (temp_bits(c, &src)) return -1;
    int rc = ms_sel_eval_node(c, nd->a, &c->all, &src);
    if (rc == 0) {
        switch (nd->kind) {
        case SN_WITHIN: case SN_EXWITHIN: case SN_PBWITHIN:
            rc = ms_sel_within(c, mask, &src, nd->d, nd->kind == SN_PBWITHIN, out);
            if (rc == 0 && nd->kind == SN_EXWITHIN) ms_bitset_andnot(out, &src);
            break;
        case SN_WITHINBONDS: rc = ms_sel_eval_withinbonds(c, nd->count, &src, mask, out); break;
        default: rc = ms_sel_eval_same(c, nd->kw, &src, mask, out); break;
        }
    }
    ms_bitset_free(&src);
    return rc;
}

int ms_sel_eval_node(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                     ms_bitset *out)
{
    if (is_empty(mask)) {
        clear_bits(out);
        return 0;
    }
    switch (nd->kind) {
    case SN_AND: return eval_and(c, nd, mask, out);
    case SN_OR: return eval_or(c, nd, mask, out);
    case SN_NOT: {
        if (ms_sel_eval_node(c, nd->a, mask, out)) return -1;
        for (size_t i = 0, n = nwords(out); i < n; i++) out->words[i] = mask->words[i] & ~out->words[i];
        return 0;
    }
    case SN_SINGLE: return eval_single(c, nd->kw, mask, out);
    case SN_KEYLIST: return eval_keylist(c, nd, mask, out);
    case SN_SEQUENCE: return ms_sel_eval_sequence(c, nd, mask, out);
    case SN_COMPARE: return ms_sel_eval_compare(c, nd, mask, out);
    case SN_WITHIN: case SN_EXWITHIN: case SN_PBWITHIN: case SN_WITHINBONDS: case SN_SAME:
        return eval_relation(c, nd, mask, out);
    default:
        ms_error_set(c->err, "internal error: an expression where a selection belongs");
        return -1;
    }
}

/* ---------------------------------------------------------------- entry points */

int ms_sel_eval(const ms_selexpr *e, ms_molecule *m, long frame, ms_bitset *out,
                ms_error *err)
{
    ms_error local = {{0}};
    if (!err) err = &local;
    ms_selctx c;
    out->words = NULL;
    out->nbits = 0;
    if (ms_selctx_init(&c, m, frame, err)) return -1;
    int rc = -1;
    if (ms_bitset_init(out, c.n) == 0) rc = ms_sel_eval_node(&c, e->root, &c.all, out);
    else ms_error_set(err, "out of memory for a selection of %zu atoms", c.n);
    ms_selctx_free(&c);
    if (rc) ms_bitset_free(out);
    return rc;
}

int ms_sel_select(ms_molecule *m, long frame, const char *text, ms_bitset *out, ms_error *err)
{
    ms_selexpr *e = ms_sel_compile(text, err);
    if (!e) {
        out->words = NULL;
        out->nbits = 0;
        return -1;
    }
    int rc = ms_sel_eval(e, m, frame, out, err);
    ms_sel_free(e);
    return rc;
}
