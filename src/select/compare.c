/* compare.c: comparisons of expressions (`x > 5`, `sqr(x) + sqr(y) < 100`, `name eq CA`,
 * `resname =~ "^A"`). Expressions are evaluated a block of atoms at a time into numbers or
 * strings, converted as VMD converts them (strings to numbers by atof, integers to strings
 * by %d and floats by %f). A string keyword compared with a constant is decided once per
 * distinct string. */
#include "config.h"
#include "select/selint.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The value of an expression over a block: numbers or strings, one per atom or one for all
 * (konst). */
typedef struct xval {
    int str, is_int, konst;
    double *num;
    const char **s;
    char *buf;               /* storage for numbers converted to strings */
} xval;

static void xval_free(xval *v)
{
    free(v->num);
    free(v->s);
    free(v->buf);
    memset(v, 0, sizeof *v);
}

static size_t count(const xval *v, size_t len) { return v->konst ? 1 : len; }

static int to_num(xval *v, size_t len)
{
    if (!v->str) return 0;
    size_t n = count(v, len);
    if (!(v->num = ms_alloc_array(n, sizeof *v->num))) return -1;
    for (size_t j = 0; j < n; j++) v->num[j] = strtod(v->s[j], NULL);
    free(v->s);     /* each value has one form at a time */
    free(v->buf);
    v->s = NULL;
    v->buf = NULL;
    v->str = 0;
    return 0;
}

static int to_str(xval *v, size_t len)
{
    if (v->str) return 0;
    size_t n = count(v, len);
    const size_t w = 48;
    v->s = ms_alloc_array(n, sizeof *v->s);
    v->buf = ms_alloc_array(n, w);
    if (!v->s || !v->buf) return -1;
    for (size_t j = 0; j < n; j++) {
        char *b = v->buf + j * w;
        if (v->is_int && fabs(v->num[j]) < 9.2e18) snprintf(b, w, "%lld", (long long)v->num[j]);
        else snprintf(b, w, "%f", v->num[j]);
        v->s[j] = b;
    }
    free(v->num);
    v->num = NULL;
    v->str = 1;
    return 0;
}

static int eval_x(const ms_selctx *c, const ms_selnode *nd, size_t begin, size_t len, xval *v);

static int eval_key(const ms_selctx *c, const ms_selkw *k, size_t begin, size_t len, xval *v)
{
    if (k->kind == SK_STRING) {
        uint32_t *buf = ms_alloc_array(len, sizeof *buf);
        v->s = ms_alloc_array(len, sizeof *v->s);
        if (!buf || !v->s) {
            free(buf);
            return -1;
        }
        const uint32_t *cls = ms_selkw_classes(k, c, begin, len, buf);
        for (size_t j = 0; j < len; j++) v->s[j] = ms_selkw_class_str(k, c->m, cls[j]);
        free(buf);
        v->str = 1;
        return 0;
    }
    if (!(v->num = ms_alloc_array(len, sizeof *v->num))) return -1;
    ms_selkw_numbers(k, c, begin, len, v->num);
    v->is_int = k->kind == SK_INT;
    return 0;
}

static double arith(ms_node_kind k, double a, double b)
{
    switch (k) {
    case EN_ADD: return a + b;
    case EN_SUB: return a - b;
    case EN_MUL: return a * b;
    case EN_DIV: return a / b;
    case EN_MOD: return fmod(a, b);
    default: return pow(a, b);
    }
}

static int eval_binary(const ms_selctx *c, const ms_selnode *nd, size_t begin, size_t len,
                       xval *v)
{
    xval l = {0}, r = {0};
    int rc = -1;
    if (eval_x(c, nd->a, begin, len, &l) || eval_x(c, nd->b, begin, len, &r) ||
        to_num(&l, len) || to_num(&r, len))
        goto done;
    v->konst = l.konst && r.konst;
    size_t n = count(v, len);
    if (!(v->num = ms_alloc_array(n, sizeof *v->num))) goto done;
    for (size_t j = 0; j < n; j++)
        v->num[j] = arith(nd->kind, l.num[l.konst ? 0 : j], r.num[r.konst ? 0 : j]);
    rc = 0;
done:
    xval_free(&l);
    xval_free(&r);
    return rc;
}

static int eval_x(const ms_selctx *c, const ms_selnode *nd, size_t begin, size_t len, xval *v)
{
    memset(v, 0, sizeof *v);
    switch (nd->kind) {
    case EN_NUM:
        v->konst = 1;
        v->is_int = nd->is_int;
        if (!(v->num = malloc(sizeof *v->num))) return -1;
        v->num[0] = nd->d;
        return 0;
    case EN_STR:
        v->konst = v->str = 1;
        if (!(v->s = malloc(sizeof *v->s))) return -1;
        v->s[0] = nd->s;
        return 0;
    case EN_KEY: return eval_key(c, nd->kw, begin, len, v);
    case EN_FUNC: case EN_NEG:
        if (eval_x(c, nd->a, begin, len, v) || to_num(v, len)) return -1;
        v->is_int = 0;
        if (nd->kind == EN_FUNC) ms_selkw_func(nd->kw, v->num, count(v, len));
        else for (size_t j = 0; j < count(v, len); j++) v->num[j] = -v->num[j];
        return 0;
    default:
        return eval_binary(c, nd, begin, len, v);
    }
}

/* ---------------------------------------------------------------- comparisons */


static int str_cmp(int op, const char *a, const char *b)
{
    int d = strcmp(a, b);
    switch (op) {
    case TK_SLT: return d < 0;
    case TK_SLE: return d <= 0;
    case TK_SEQ: return d == 0;
    case TK_SGE: return d >= 0;
    case TK_SGT: return d > 0;
    default: return d != 0;
    }
}

/* l =~ r: r is a regular expression (unanchored); a pattern that does not compile matches
 * nothing. The compiled constant pattern comes in re. */
static int match_one(const regex_t *re, const char *s, const char *pattern, regex_t *last,
                     char **last_pat, int *last_ok)
{
    if (re) return regexec(re, s, 0, NULL, 0) == 0;
    if (!*last_pat || strcmp(*last_pat, pattern)) {
        if (*last_pat && *last_ok) regfree(last);
        free(*last_pat);
        *last_pat = ms_strdup(pattern);
        ms_error e;
        *last_ok = *last_pat && ms_sel_regcomp(last, pattern, 0, 1, &e) == 0;
    }
    return *last_ok && regexec(last, s, 0, NULL, 0) == 0;
}

/* Numeric comparison of one word of atoms: branch-free, the operator chosen outside. */
#define NUM_LOOP(OP)                                                                       \
    for (size_t k = 0; k < n; k++) bits |= (uint64_t)(l[lk * k] OP r[rk * k]) << k;     \
    break

static uint64_t num_word(int op, const double *l, size_t lk, const double *r, size_t rk,
                         size_t n)
{
    uint64_t bits = 0;
    switch (op) {
    case TK_NLT: NUM_LOOP(<);
    case TK_NLE: NUM_LOOP(<=);
    case TK_NEQ: NUM_LOOP(==);
    case TK_NGE: NUM_LOOP(>=);
    case TK_NGT: NUM_LOOP(>);
    default: NUM_LOOP(!=);
    }
    return bits;
}

static int compare_block(const ms_selctx *c, const void *data, size_t begin, size_t len,
                         const uint64_t *mask, uint64_t *out, void *scratch)
{
    const ms_selnode *nd = data;
    int op = nd->op, strop = op >= TK_SLT;
    xval l = {0}, r = {0};
    regex_t last;
    char *last_pat = NULL;
    int last_ok = 0, rc = -1;
    if (eval_x(c, nd->a, begin, len, &l) || eval_x(c, nd->b, begin, len, &r)) goto done;
    if (strop ? to_str(&l, len) || to_str(&r, len) : to_num(&l, len) || to_num(&r, len))
        goto done;
    const regex_t *re = op == TK_MATCH && nd->nvals ? nd->vals[0].re : NULL;
    for (size_t w = 0; w * 64 < len; w++) {
        size_t lj0 = l.konst ? 0 : w * 64, rj0 = r.konst ? 0 : w * 64;
        if (!strop) {
            out[w] = num_word(op, l.num + lj0, !l.konst, r.num + rj0, !r.konst,
                              MS_MIN(64, len - w * 64));
            continue;
        }
        uint64_t bits = 0;
        for (uint64_t m = mask[w]; m; m &= m - 1) {
            int b = __builtin_ctzll(m);
            size_t lj = l.konst ? 0 : w * 64 + (size_t)b, rj = r.konst ? 0 : w * 64 + (size_t)b;
            int hit = op == TK_MATCH ? match_one(re, l.s[lj], r.s[rj], &last, &last_pat, &last_ok)
                                     : str_cmp(op, l.s[lj], r.s[rj]);
            bits |= (uint64_t)hit << b;
        }
        out[w] = bits;
    }
    rc = 0;
done:
    if (last_pat && last_ok) regfree(&last);
    free(last_pat);
    xval_free(&l);
    xval_free(&r);
    return rc;
}

/* ---------------------------------------------------------------- string keyword vs constant */

typedef struct class_cmp {
    const ms_selkw *kw;
    uint8_t *hit;            /* per class */
} class_cmp;

static int class_block(const ms_selctx *c, const void *data, size_t begin, size_t len,
                       const uint64_t *mask, uint64_t *out, void *scratch)
{
    const class_cmp *cc = data;
    const uint32_t *cls = ms_selkw_classes(cc->kw, c, begin, len, scratch);
    for (size_t w = 0; w * 64 < len; w++) {
        uint64_t bits = 0;
        size_t end = MS_MIN(len, w * 64 + 64);
        if (mask[w])
            for (size_t j = w * 64; j < end; j++) bits |= (uint64_t)cc->hit[cls[j]] << (j & 63);
        out[w] = bits;
    }
    return 0;
}

/* The operator with its sides swapped (a < b is b > a). */
static int mirror(int op)
{
    switch (op) {
    case TK_SLT: return TK_SGT;
    case TK_SLE: return TK_SGE;
    case TK_SGE: return TK_SLE;
    case TK_SGT: return TK_SLT;
    default: return op;
    }
}

/* `strkey op "const"` or `"const" op strkey` with a string operator: a table per class.
 * Returns 1 when done, 0 when the comparison has another shape, -1 on error. */
static int try_class_compare(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                             ms_bitset *out)
{
    const ms_selnode *key = nd->a, *konst = nd->b;
    int op = nd->op;
    if (op < TK_SLT) return 0;
    if (key->kind != EN_KEY && op != TK_MATCH) {
        key = nd->b;
        konst = nd->a;
        op = mirror(op);
    }
    if (key->kind != EN_KEY || key->kw->kind != SK_STRING || konst->kind != EN_STR) return 0;
    uint32_t n = ms_selkw_nclasses(key->kw, c->m);
    class_cmp cc = {key->kw, malloc(n ? n : 1)};
    if (!cc.hit) {
        ms_error_set(c->err, "out of memory");
        return -1;
    }
    for (uint32_t k = 0; k < n; k++) {
        const char *s = ms_selkw_class_str(key->kw, c->m, k);
        cc.hit[k] = (uint8_t)(op == TK_MATCH ? regexec(nd->vals[0].re, s, 0, NULL, 0) == 0
                                             : str_cmp(op, s, konst->s));
    }
    int rc = ms_sel_for_blocks(c, mask, out, class_block, &cc, MS_SEL_BLOCK * sizeof(uint32_t));
    free(cc.hit);
    return rc ? -1 : 1;
}

static int prepare_keys(ms_selctx *c, const ms_selnode *nd)
{
    if (!nd) return 0;
    if (nd->kind == EN_KEY && ms_selkw_prepare(nd->kw, c)) return -1;
    return prepare_keys(c, nd->a) || prepare_keys(c, nd->b) ? -1 : 0;
}

int ms_sel_eval_compare(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                        ms_bitset *out)
{
    if (prepare_keys(c, nd->a) || prepare_keys(c, nd->b)) return -1;
    int done = try_class_compare(c, nd, mask, out);
    if (done) return done < 0 ? -1 : 0;
    return ms_sel_for_blocks(c, mask, out, compare_block, nd, 0);
}
