/* parser.c: a recursive-descent parser for VMD's selection grammar, building the tree the
 * evaluator walks. Precedence follows VMD's: or < and < not; `within d of`, `same K as` and
 * a singleword followed by a selection (implicit and) take everything to their right;
 * arithmetic is + - < * / % < ^ (left-associative) < unary minus. A parenthesis may open a
 * selection or an arithmetic expression: the parser tries the selection first and falls
 * back. Macros and rasmol primitives are expanded here into subtrees. Errors name the token
 * and its position. */
#include "config.h"
#include "select/selint.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

#define MAX_DEPTH 1000       /* nesting of parentheses, expressions and macros */

/* What one compilation spends on macros, shared by the nested parses of macro texts. A
 * macro's first use costs nothing (its text bounds what it builds); every later use parses
 * its text again, and the nodes and keyword values those repeated uses build count against
 * MS_SEL_MACRO_NODES. So macros that use the one below twice, level after level, cannot
 * grow a tree (and the time to build it) exponentially. */
struct ms_selbudget {
    char **seen;             /* the macros used so far */
    size_t nseen, cap;
    size_t units;            /* nodes and values built by repeated uses */
    int repeated;            /* > 0 while inside a repeated use */
    int exceeded;            /* the limit was passed: the error is set */
};

typedef struct parser {
    const char *text;
    ms_tok *t;
    size_t ntok, i;
    int depth;
    const char **macros;     /* names being expanded (recursion check) */
    int nmacros;
    ms_selbudget *budget;
    ms_error *err;
    size_t errpos;           /* position of the error in err */
    int uses_coords;
} parser;

static ms_selnode *parse_or(parser *p);
static ms_selnode *parse_compare(parser *p);
static ms_selnode *parse_expr(parser *p);

/* ---------------------------------------------------------------- helpers */

static const ms_tok *tok(const parser *p) { return &p->t[p->i]; }
static ms_tok_kind kind(const parser *p) { return p->t[p->i].kind; }
static ms_tok_kind peek(const parser *p, size_t ahead)
{
    size_t k = p->i + ahead;
    return k < p->ntok ? p->t[k].kind : TK_END;
}

/* Record an error at a position; an error further into the text wins over an earlier one
 * (the parser backtracks, and the furthest failure is the informative one). */
static void *fail_at(parser *p, size_t pos, const char *fmt, ...)
    __attribute__((format(printf, 3, 4)));
static void *fail_at(parser *p, size_t pos, const char *fmt, ...)
{
    if (p->err->msg[0] && pos < p->errpos) return NULL;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(p->err->msg, sizeof p->err->msg, fmt, ap);
    va_end(ap);
    p->errpos = pos;
    return NULL;
}

static void *syntax_error(parser *p)
{
    const ms_tok *t = tok(p);
    if (t->kind == TK_END)
        return fail_at(p, t->pos, "syntax error: unexpected end of selection at position %zu",
                       t->pos);
    return fail_at(p, t->pos, "syntax error near '%.*s' at position %zu", (int)MS_MIN(t->len, 64),
                   p->text + t->pos, t->pos);
}

static void *oom(parser *p)
{
    if (!p->budget->exceeded) ms_error_set(p->err, "out of memory compiling the selection");
    p->errpos = (size_t)-1;
    return NULL;
}

/* The macro limit was passed: like running out of memory, this ends the compilation (no
 * retry of another reading) and the message is passed up unchanged. */
static void *too_large(parser *p)
{
    p->budget->exceeded = 1;
    ms_error_set(p->err, "selection too large after macro expansion (more than %d nodes)",
                 MS_SEL_MACRO_NODES);
    p->errpos = (size_t)-1;
    return NULL;
}

/* Count n more nodes or values; -1 (error set) when a repeated macro use passes the limit. */
static int spend(parser *p, size_t n)
{
    ms_selbudget *b = p->budget;
    if (b->exceeded) return -1;
    if (!b->repeated) return 0;
    b->units += n;
    if (b->units <= MS_SEL_MACRO_NODES) return 0;
    too_large(p);
    return -1;
}

static ms_selnode *node_new(parser *p, ms_node_kind k)
{
    if (spend(p, 1)) return NULL;
    ms_selnode *n = calloc(1, sizeof *n);
    if (!n) return oom(p);
    n->kind = k;
    return n;
}

static ms_selnode *node2(parser *p, ms_node_kind k, ms_selnode *a, ms_selnode *b)
{
    ms_selnode *n = node_new(p, k);
    if (!n) {
        ms_selnode_free(a);
        ms_selnode_free(b);
        return NULL;
    }
    n->a = a;
    n->b = b;
    return n;
}

static ms_selnode *join_fail(parser *p, ms_selnode *a, ms_selnode *b)
{
    ms_selnode_free(a);
    ms_selnode_free(b);
    return oom(p);
}

/* In an or-chain, `name CA or name CB` means `name CA CB`: append b's values to a keyword
 * list of the same keyword already in chain n (one pass over the atoms instead of two).
 * Returns 1 when merged (b is then freed), 0 when not, -1 when out of memory. */
static int merge_values(ms_selnode *n, ms_selnode *b)
{
    if (b->kind != SN_KEYLIST) return 0;
    size_t nk = n->kind == SN_OR ? n->nkids : 1;
    for (size_t i = 0; i < nk; i++) {
        ms_selnode *k = n->kind == SN_OR ? n->kids[i] : n;
        if (k->kind != SN_KEYLIST || k->kw != b->kw) continue;
        ms_selval *v = realloc(k->vals, (k->nvals + b->nvals) * sizeof *v);
        if (!v) return -1;
        memcpy(v + k->nvals, b->vals, b->nvals * sizeof *v);
        k->vals = v;
        k->nvals += b->nvals;
        b->nvals = 0;    /* the values (and their regexes) now belong to k */
        ms_selnode_free(b);
        return 1;
    }
    return 0;
}

/* The room allocated for a chain of n kids: chains grow through ms_grow, which doubles from
 * 16, so the room is a power of two of at least 16 and at least n. */
static size_t chain_capacity(size_t n)
{
    size_t cap = 16;
    while (cap < n) cap *= 2;
    return cap;
}

/* Append b to the and/or chain a (or start one), flattening chains of the same kind: and
 * and or are associative, and flat chains keep the evaluator's recursion shallow. */
static ms_selnode *join(parser *p, ms_node_kind k, ms_selnode *a, ms_selnode *b)
{
    if (k == SN_OR && (a->kind == SN_OR || a->kind == SN_KEYLIST) && b->kind != SN_OR) {
        int merged = merge_values(a, b);
        if (merged) return merged > 0 ? a : join_fail(p, a, b);
    }
    ms_selnode *n = a;
    size_t cap = a->kind == k ? chain_capacity(a->nkids) : 0;
    if (a->kind != k) {
        if (!(n = node_new(p, k)) || ms_grow((void **)&n->kids, &cap, 1, sizeof *n->kids)) {
            free(n);
            goto fail;
        }
        n->kids[n->nkids++] = a;
    }
    size_t add = b->kind == k ? b->nkids : 1;
    if (ms_grow((void **)&n->kids, &cap, n->nkids + add, sizeof *n->kids)) {
        a = n;
        goto fail;
    }
    if (b->kind == k) {
        memcpy(n->kids + n->nkids, b->kids, add * sizeof *b->kids);
        b->nkids = 0;
        ms_selnode_free(b);
    } else {
        n->kids[n->nkids] = b;
    }
    n->nkids += add;
    return n;
fail:
    ms_selnode_free(a);
    ms_selnode_free(b);
    return oom(p);
}

void ms_selnode_free(ms_selnode *n)
{
    if (!n) return;
    ms_selnode_free(n->a);
    ms_selnode_free(n->b);
    for (size_t i = 0; i < n->nkids; i++) ms_selnode_free(n->kids[i]);
    free(n->kids);
    for (size_t i = 0; i < n->nvals; i++) {
        free(n->vals[i].lo);
        free(n->vals[i].hi);
        if (n->vals[i].re) regfree(n->vals[i].re);
        free(n->vals[i].re);
    }
    free(n->vals);
    free(n->s);
    free(n);
}

/* The symbol a token names: a built-in keyword, or a macro (*macro set), or nothing. */
static const ms_selkw *symbol(const ms_tok *t, int *macro)
{
    *macro = 0;
    if (t->kind != TK_WORD || !t->ident) return NULL;
    const ms_selkw *k = ms_selkw_find(t->str);
    if (!k) *macro = ms_sel_macro_get(t->str, NULL, 0) >= 0;
    return k;
}

/* A value word of a keyword list: a word that names nothing, a number or a string. */
static int is_value(const ms_tok *t)
{
    int macro;
    switch (t->kind) {
    case TK_INT: case TK_FLOAT: case TK_SQ: case TK_DQ: return 1;
    case TK_WORD: return symbol(t, &macro) == NULL && !macro;
    default: return 0;
    }
}

/* Can this token begin a selection (for a singleword's implicit and)? */
static int starts_selection(const ms_tok *t)
{
    switch (t->kind) {
    case TK_LPAREN: case TK_NOT: case TK_WITHIN: case TK_EXWITHIN: case TK_PBWITHIN:
    case TK_WITHINBONDS: case TK_SAME: case TK_INT: case TK_FLOAT: case TK_WORD: case TK_SQ:
    case TK_DQ: case TK_SUB: case TK_ADD: case TK_MAXRINGSIZE: case TK_RINGSIZE:
    case TK_NEAREST:
        return 1;
    default:
        return 0;
    }
}

static int is_compare_op(ms_tok_kind k) { return k >= TK_NLT && k <= TK_MATCH; }
static int is_arith_op(ms_tok_kind k) { return k >= TK_ADD && k <= TK_POW; }

static int enter(parser *p)
{
    if (++p->depth > MAX_DEPTH) {
        fail_at(p, tok(p)->pos, "selection nested too deeply at position %zu", tok(p)->pos);
        return -1;
    }
    return 0;
}

/* ---------------------------------------------------------------- keyword lists */

/* Values after a keyword or string function: word | word to word, at least one. */
static ms_selnode *parse_values(parser *p, ms_selnode *n)
{
    size_t cap = 0;
    do {
        const ms_tok *lo = tok(p), *hi = NULL;
        if (spend(p, 1)) {
            ms_selnode_free(n);
            return NULL;
        }
        p->i++;
        if (kind(p) == TK_THROUGH) {
            p->i++;
            if (!is_value(tok(p))) {
                ms_selnode_free(n);
                return syntax_error(p);
            }
            hi = tok(p);
            p->i++;
        }
        if (ms_grow((void **)&n->vals, &cap, n->nvals + 1, sizeof *n->vals)) {
            ms_selnode_free(n);
            return oom(p);
        }
        ms_selval *v = &n->vals[n->nvals++];
        memset(v, 0, sizeof *v);
        v->kind = hi ? SV_RANGE : lo->kind == TK_DQ ? SV_REGEX : SV_EXACT;
        v->lo = ms_strdup(lo->str);
        if (!v->lo || (hi && !(v->hi = ms_strdup(hi->str)))) {
            ms_selnode_free(n);
            return oom(p);
        }
    } while (is_value(tok(p)));
    return n;
}

/* Compile the regular expressions of a keyword list (string keywords only: VMD reads
 * "quoted" numbers as numbers). */
static ms_selnode *compile_regexes(parser *p, ms_selnode *n, int anchored, size_t pos)
{
    for (size_t i = 0; i < n->nvals; i++) {
        ms_selval *v = &n->vals[i];
        int want = anchored ? v->kind == SV_REGEX : 1;
        if (!want) continue;
        if (!(v->re = malloc(sizeof *v->re))) {
            ms_selnode_free(n);
            return oom(p);
        }
        char pat[4096];
        if (!anchored && v->kind == SV_RANGE)   /* sequence: "X to Y" means X.*Y */
            snprintf(pat, sizeof pat, "%s.*%s", v->lo, v->hi);
        else
            snprintf(pat, sizeof pat, "%s", v->lo);
        ms_error e = {{0}};
        if (ms_sel_regcomp(v->re, pat, anchored, anchored, &e)) {
            free(v->re);
            v->re = NULL;
            ms_selnode_free(n);
            return fail_at(p, pos, "%s", e.msg);
        }
    }
    return n;
}

static ms_selnode *parse_keylist(parser *p, const ms_selkw *k)
{
    size_t pos = tok(p)->pos;
    ms_selnode *n = node_new(p, SN_KEYLIST);
    if (!n) return NULL;
    n->kw = k;
    p->uses_coords |= k->coords;
    p->i++;
    if (!(n = parse_values(p, n))) return NULL;
    return k->kind == SK_STRING ? compile_regexes(p, n, 1, pos) : n;
}

/* ---------------------------------------------------------------- string functions */

static int append(char *buf, size_t size, size_t *len, const char *s)
{
    size_t n = strlen(s);
    if (*len + n + 1 > size) return -1;
    memcpy(buf + *len, s, n + 1);
    *len += n;
    return 0;
}

/* One field of a rasmol primitive as a VMD regular expression: * and ? become .* and .?,
 * letters are upper-cased; a field that is just "*" is dropped. */
static void rasmol_field(const char *b, const char *e, char *out, size_t size)
{
    size_t o = 0;
    out[0] = '\0';
    if (e - b == 1 && *b == '*') return;
    for (const char *s = b; s < e && o + 3 < size; s++) {
        if (*s == '*' || *s == '?') out[o++] = '.';
        out[o++] = (char)toupper((unsigned char)*s);
    }
    out[o] = '\0';
}

/* The selection text VMD builds for a rasmol primitive [resname]resid:chain.name. */
static int rasmol_text(const char *w, char *out, size_t size)
{
    const char *rn0 = w, *rn1, *rid0;
    if (*rn0 == '*') {
        rn1 = rn0 + 1;
        rid0 = rn1;
    } else if (*rn0 == '[') {
        rn1 = ++rn0;
        while (*rn1 && *rn1 != ']') rn1++;
        rid0 = *rn1 == ']' ? rn1 + 1 : rn1;
    } else {
        rn1 = rn0;
        while (isalpha((unsigned char)*rn1) || *rn1 == '?') rn1++;
        rid0 = rn1;
    }
    const char *rid1 = rid0;
    if (*rid1 == '*') rid1++;
    else while (isdigit((unsigned char)*rid1)) rid1++;
    const char *ch0 = *rid1 == ':' ? rid1 + 1 : rid1, *ch1 = ch0;
    while (*ch1 && *ch1 != '.') ch1++;
    const char *nm0 = *ch1 == '.' ? ch1 + 1 : ch1, *nm1 = nm0 + strlen(nm0);
    char f[4][256];
    rasmol_field(rn0, rn1, f[0], sizeof f[0]);
    rasmol_field(rid0, rid1, f[1], sizeof f[1]);
    rasmol_field(ch0, ch1, f[2], sizeof f[2]);
    rasmol_field(nm0, nm1, f[3], sizeof f[3]);
    const char *keys[4] = {"resname", "resid", strlen(f[2]) > 1 ? "segname" : "chain", "name"};
    size_t len = 0;
    out[0] = '\0';
    for (int k = 0; k < 4; k++) {
        if (!f[k][0]) continue;
        if ((len && append(out, size, &len, " and ")) || append(out, size, &len, keys[k]) ||
            append(out, size, &len, " \"") || append(out, size, &len, f[k]) ||
            append(out, size, &len, "\""))
            return -1;
    }
    return len ? 0 : append(out, size, &len, "all");
}

/* rasmol "w1" "w2": each primitive becomes a selection; all must hold (as VMD does). */
static ms_selnode *expand_rasmol(parser *p, ms_selnode *vals)
{
    ms_selnode *result = NULL;
    for (size_t i = 0; i < vals->nvals; i++) {
        char text[2048];
        if (rasmol_text(vals->vals[i].lo, text, sizeof text)) {
            ms_selnode_free(result);
            return fail_at(p, tok(p)->pos, "rasmol: primitive '%s' is too long",
                           vals->vals[i].lo);
        }
        ms_error e = {{0}};
        ms_selnode *sub = ms_sel_parse_text(text, p->macros, p->nmacros, p->depth,
                                            &p->uses_coords, p->budget, &e);
        if (!sub) {
            ms_selnode_free(result);
            if (p->budget->exceeded) return too_large(p);
            return fail_at(p, tok(p)->pos, "rasmol: cannot understand '%s': %s",
                           vals->vals[i].lo, e.msg);
        }
        result = result ? join(p, SN_AND, result, sub) : sub;
        if (!result) return NULL;
    }
    return result;
}

static ms_selnode *parse_sfunc(parser *p, const ms_selkw *k)
{
    size_t pos = tok(p)->pos;
    p->i++;
    if (!is_value(tok(p))) return syntax_error(p);
    ms_selnode *n = node_new(p, SN_SEQUENCE);
    if (!n) return NULL;
    if (!(n = parse_values(p, n))) return NULL;
    if (!strcmp(k->name, "sequence")) return compile_regexes(p, n, 0, pos);
    ms_selnode *r = expand_rasmol(p, n);
    ms_selnode_free(n);
    return r;
}

/* ---------------------------------------------------------------- macros */

/* Has this compilation used macro `name` before? Remembers it when not; -1 when out of
 * memory. */
static int used_before(ms_selbudget *b, const char *name)
{
    for (size_t i = 0; i < b->nseen; i++)
        if (!strcmp(b->seen[i], name)) return 1;
    char *copy = ms_strdup(name);
    if (!copy || ms_grow((void **)&b->seen, &b->cap, b->nseen + 1, sizeof *b->seen)) {
        free(copy);
        return -1;
    }
    b->seen[b->nseen++] = copy;
    return 0;
}

/* Parse a macro's text in place of its name, with the name on the recursion stack. */
static ms_selnode *parse_macro_text(parser *p, const ms_tok *t, const char *text,
                                    ms_error *e)
{
    const char **stack = malloc((size_t)(p->nmacros + 1) * sizeof *stack);
    int again = used_before(p->budget, t->str);
    if (!stack || again < 0) {
        free(stack);
        return oom(p);
    }
    if (p->nmacros) memcpy(stack, p->macros, (size_t)p->nmacros * sizeof *stack);
    stack[p->nmacros] = t->str;
    ms_selnode *n = NULL;
    p->budget->repeated += again;
    if (p->nmacros + 1 > 64)
        ms_error_set(e, "macros nested too deeply");
    else
        n = ms_sel_parse_text(text, stack, p->nmacros + 1, p->depth, &p->uses_coords,
                              p->budget, e);
    p->budget->repeated -= again;
    free(stack);
    return n;
}

static ms_selnode *expand_macro(parser *p, const ms_tok *t)
{
    for (int i = 0; i < p->nmacros; i++)
        if (!strcmp(p->macros[i], t->str))
            return fail_at(p, t->pos, "macro '%s' refers to itself", t->str);
    char *text = ms_sel_macro_text(t->str);
    if (!text) return oom(p);
    ms_error e = {{0}};
    ms_selnode *n = parse_macro_text(p, t, text, &e);
    free(text);
    if (n) return n;
    if (p->budget->exceeded) return too_large(p);
    if (p->errpos == (size_t)-1) return NULL;
    if (strstr(e.msg, "refers to itself")) return fail_at(p, t->pos, "%s", e.msg);
    return fail_at(p, t->pos, "in macro '%s': %s", t->str, e.msg);
}

/* ---------------------------------------------------------------- selections */

/* A singleword or macro, then (implicit and) a selection if one follows. */
static ms_selnode *parse_singleword(parser *p, const ms_selkw *k)
{
    const ms_tok *t = tok(p);
    ms_selnode *n;
    if (k) {
        if ((n = node_new(p, SN_SINGLE))) n->kw = k;
    } else {
        n = expand_macro(p, t);
    }
    if (!n) return NULL;
    p->i++;
    if (!starts_selection(tok(p))) return n;
    ms_selnode *rest = parse_or(p);
    if (!rest) {
        ms_selnode_free(n);
        return NULL;
    }
    return join(p, SN_AND, n, rest);
}

static int read_number(parser *p, int integer_only, double *out)
{
    ms_tok_kind k = kind(p);
    if (k != TK_INT && (integer_only || k != TK_FLOAT)) {
        syntax_error(p);
        return -1;
    }
    *out = tok(p)->num;
    p->i++;
    return 0;
}

static int expect(parser *p, ms_tok_kind k)
{
    if (kind(p) != k) {
        syntax_error(p);
        return -1;
    }
    p->i++;
    return 0;
}

/* within d of S, exwithin, pbwithin, withinbonds n of S */
static ms_selnode *parse_within(parser *p)
{
    ms_tok_kind k = kind(p);
    ms_node_kind nk = k == TK_WITHIN ? SN_WITHIN : k == TK_EXWITHIN ? SN_EXWITHIN
                    : k == TK_PBWITHIN ? SN_PBWITHIN : SN_WITHINBONDS;
    double d;
    p->i++;
    if (read_number(p, nk == SN_WITHINBONDS, &d) || expect(p, TK_OF)) return NULL;
    ms_selnode *child = parse_or(p);
    if (!child) return NULL;
    ms_selnode *n = node2(p, nk, child, NULL);
    if (!n) return NULL;
    n->d = d;
    n->count = d > 2e9 ? 2000000000L : (long)d;
    if (nk != SN_WITHINBONDS) p->uses_coords = 1;
    return n;
}

static ms_selnode *parse_same(parser *p)
{
    p->i++;
    int macro;
    const ms_selkw *k = symbol(tok(p), &macro);
    if (!k || k->kind > SK_STRING) {
        if (kind(p) == TK_WORD)
            return fail_at(p, tok(p)->pos, "same: '%s' at position %zu is not a keyword",
                           tok(p)->str, tok(p)->pos);
        return syntax_error(p);
    }
    p->i++;
    if (expect(p, TK_AS)) return NULL;
    ms_selnode *child = parse_or(p);
    if (!child) return NULL;
    ms_selnode *n = node2(p, SN_SAME, child, NULL);
    if (n) n->kw = k;
    p->uses_coords |= k->coords;
    return n;
}

/* ( selection ) or an arithmetic expression in parentheses. */
static ms_selnode *parse_paren(parser *p)
{
    size_t save = p->i;
    p->i++;
    ms_selnode *n = parse_or(p);
    if (n && kind(p) == TK_RPAREN) {
        p->i++;
        if (!is_compare_op(kind(p)) && !is_arith_op(kind(p))) return n;
    } else if (n) {
        syntax_error(p);
    }
    ms_selnode_free(n);
    if (p->errpos == (size_t)-1) return NULL;    /* out of memory: no retry */
    p->i = save;
    return parse_compare(p);
}

static ms_selnode *parse_word(parser *p)
{
    int macro;
    const ms_tok *t = tok(p);
    const ms_selkw *k = symbol(t, &macro);
    if (macro || (k && k->kind == SK_SINGLE)) return parse_singleword(p, k);
    if (k && k->kind == SK_SFUNC) return parse_sfunc(p, k);
    if (k && k->kind <= SK_STRING && is_value(&p->t[p->i + 1])) return parse_keylist(p, k);
    if (!k && t->ident && !is_compare_op(peek(p, 1)) && !is_arith_op(peek(p, 1)))
        return fail_at(p, t->pos, "unknown keyword or macro '%s' at position %zu", t->str,
                       t->pos);
    return parse_compare(p);
}

static ms_selnode *parse_primary(parser *p)
{
    switch (kind(p)) {
    case TK_LPAREN: return parse_paren(p);
    case TK_WITHIN: case TK_EXWITHIN: case TK_PBWITHIN: case TK_WITHINBONDS:
        return parse_within(p);
    case TK_SAME: return parse_same(p);
    case TK_MAXRINGSIZE: case TK_RINGSIZE: case TK_NEAREST: case TK_WHERE:
        return fail_at(p, tok(p)->pos, "'%s' at position %zu is not supported",
                       ms_sel_tok_name(kind(p)), tok(p)->pos);
    case TK_WORD: return parse_word(p);
    case TK_INT: case TK_FLOAT: case TK_SQ: case TK_DQ: case TK_SUB: case TK_ADD:
        return parse_compare(p);
    default:
        return syntax_error(p);
    }
}

static ms_selnode *parse_unary(parser *p)
{
    if (enter(p)) return NULL;
    ms_selnode *n;
    if (kind(p) == TK_NOT) {
        /* not not a is a: a chain of nots never nests more than one deep */
        int nots = 0;
        for (; kind(p) == TK_NOT; p->i++) nots ^= 1;
        ms_selnode *c = parse_unary(p);
        n = c && nots ? node2(p, SN_NOT, c, NULL) : c;
    } else {
        n = parse_primary(p);
    }
    p->depth--;
    return n;
}

static ms_selnode *parse_and(parser *p)
{
    ms_selnode *n = parse_unary(p);
    while (n && kind(p) == TK_AND) {
        p->i++;
        ms_selnode *r = parse_unary(p);
        if (!r) {
            ms_selnode_free(n);
            return NULL;
        }
        n = join(p, SN_AND, n, r);
    }
    return n;
}

static ms_selnode *parse_or(parser *p)
{
    if (enter(p)) return NULL;
    ms_selnode *n = parse_and(p);
    while (n && kind(p) == TK_OR) {
        p->i++;
        ms_selnode *r = parse_and(p);
        if (!r) {
            ms_selnode_free(n);
            n = NULL;
            break;
        }
        n = join(p, SN_OR, n, r);
    }
    p->depth--;
    return n;
}

/* ---------------------------------------------------------------- expressions */

static ms_selnode *parse_atom_expr(parser *p)
{
    const ms_tok *t = tok(p);
    ms_selnode *n;
    int macro;
    switch (t->kind) {
    case TK_INT: case TK_FLOAT:
        if (!(n = node_new(p, EN_NUM))) return NULL;
        n->d = t->num;
        n->is_int = t->kind == TK_INT;
        p->i++;
        return n;
    case TK_SQ: case TK_DQ: case TK_WORD: {
        const ms_selkw *k = symbol(t, &macro);
        if (macro || (k && k->kind == SK_SINGLE) || (k && k->kind == SK_SFUNC))
            return fail_at(p, t->pos, "'%s' at position %zu cannot be used in an expression",
                           t->str, t->pos);
        if (k && k->kind == SK_FUNC) {
            p->i++;
            if (expect(p, TK_LPAREN)) return NULL;
            ms_selnode *arg = parse_expr(p);
            if (!arg) return NULL;
            if (expect(p, TK_RPAREN)) {
                ms_selnode_free(arg);
                return NULL;
            }
            if ((n = node2(p, EN_FUNC, arg, NULL))) n->kw = k;
            return n;
        }
        if (!(n = node_new(p, k ? EN_KEY : EN_STR))) return NULL;
        if (k) {
            n->kw = k;
            p->uses_coords |= k->coords;
        } else if (!(n->s = ms_strdup(t->str))) {
            ms_selnode_free(n);
            return oom(p);
        }
        p->i++;
        return n;
    }
    case TK_LPAREN: {
        p->i++;
        ms_selnode *e = parse_expr(p);
        if (e && expect(p, TK_RPAREN)) {
            ms_selnode_free(e);
            return NULL;
        }
        return e;
    }
    default:
        return syntax_error(p);
    }
}

static ms_selnode *parse_unary_expr(parser *p)
{
    if (enter(p)) return NULL;
    ms_selnode *n;
    if (kind(p) == TK_SUB || kind(p) == TK_ADD) {
        int neg = kind(p) == TK_SUB;
        p->i++;
        n = parse_unary_expr(p);
        if (n && neg) n = node2(p, EN_NEG, n, NULL);
    } else {
        n = parse_atom_expr(p);
    }
    p->depth--;
    return n;
}

/* One level of left-associative binary operators. A chain of n operators nests n deep in
 * the tree, so it counts against the nesting limit. */
static ms_selnode *parse_binary(parser *p, int level)
{
    static const ms_tok_kind ops[3][3] = {{TK_ADD, TK_SUB, TK_END},
                                          {TK_MUL, TK_DIV, TK_MOD},
                                          {TK_POW, TK_END, TK_END}};
    int depth0 = p->depth;
    ms_selnode *n = level == 2 ? parse_unary_expr(p) : parse_binary(p, level + 1);
    for (;;) {
        ms_tok_kind k = kind(p);
        if (!n || k == TK_END || (k != ops[level][0] && k != ops[level][1] && k != ops[level][2]))
            break;
        if (enter(p)) {
            ms_selnode_free(n);
            n = NULL;
            break;
        }
        p->i++;
        ms_selnode *r = level == 2 ? parse_unary_expr(p) : parse_binary(p, level + 1);
        if (!r) {
            ms_selnode_free(n);
            n = NULL;
            break;
        }
        ms_node_kind nk = k == TK_ADD ? EN_ADD : k == TK_SUB ? EN_SUB : k == TK_MUL ? EN_MUL
                        : k == TK_DIV ? EN_DIV : k == TK_MOD ? EN_MOD : EN_POW;
        n = node2(p, nk, n, r);
    }
    p->depth = depth0;
    return n;
}

static ms_selnode *parse_expr(parser *p)
{
    if (enter(p)) return NULL;
    ms_selnode *n = parse_binary(p, 0);
    p->depth--;
    return n;
}

static ms_selnode *parse_compare(parser *p)
{
    ms_selnode *l = parse_expr(p);
    if (!l) return NULL;
    ms_tok_kind op = kind(p);
    if (!is_compare_op(op)) {
        ms_selnode_free(l);
        return syntax_error(p);
    }
    p->i++;
    ms_selnode *r = parse_expr(p);
    if (!r) {
        ms_selnode_free(l);
        return NULL;
    }
    ms_selnode *n = node2(p, SN_COMPARE, l, r);
    if (!n) return NULL;
    n->op = op;
    if (op != TK_MATCH || r->kind != EN_STR) return n;
    /* A constant pattern is compiled now: a bad one is a compile error. */
    regex_t *re = malloc(sizeof *re);
    if (!re || !(n->vals = calloc(1, sizeof *n->vals))) {
        free(re);
        ms_selnode_free(n);
        return oom(p);
    }
    ms_error e = {{0}};
    if (ms_sel_regcomp(re, r->s, 0, 1, &e)) {
        free(re);
        ms_selnode_free(n);
        return fail_at(p, tok(p)->pos, "%s", e.msg);
    }
    n->vals[0].re = re;     /* nvals counts it only now, so a failure above frees nothing */
    n->nvals = 1;
    return n;
}

/* ---------------------------------------------------------------- entry points */

static void budget_free(ms_selbudget *b)
{
    for (size_t i = 0; i < b->nseen; i++) free(b->seen[i]);
    free(b->seen);
}

ms_selnode *ms_sel_parse_text(const char *text, const char **macros, int nmacros, int depth,
                              int *uses_coords, ms_selbudget *budget, ms_error *err)
{
    ms_selbudget own = {0};
    parser p = {.text = text, .macros = macros, .nmacros = nmacros, .depth = depth,
                .budget = budget ? budget : &own, .err = err};
    err->msg[0] = '\0';
    long n = ms_sel_lex(text, &p.t, err);
    if (n < 0) return NULL;
    p.ntok = (size_t)n;
    ms_selnode *root = NULL;
    if (p.t[0].kind == TK_END) {
        ms_error_set(err, "empty selection");
    } else if ((root = parse_or(&p)) && kind(&p) != TK_END) {
        ms_selnode_free(root);
        root = NULL;
        err->msg[0] = '\0';
        syntax_error(&p);
    }
    ms_sel_free_tokens(p.t, p.ntok);
    budget_free(&own);
    if (root && uses_coords) *uses_coords |= p.uses_coords;
    return root;
}

ms_selexpr *ms_sel_compile(const char *text, ms_error *err)
{
    ms_error local = {{0}};
    if (!err) err = &local;
    if (!text) text = "";
    ms_selexpr *e = calloc(1, sizeof *e);
    if (!e || !(e->text = ms_strdup(text))) {
        free(e);
        ms_error_set(err, "out of memory compiling the selection");
        return NULL;
    }
    e->root = ms_sel_parse_text(text, NULL, 0, 0, &e->uses_coords, NULL, err);
    if (!e->root) {
        ms_sel_free(e);
        return NULL;
    }
    return e;
}

void ms_sel_free(ms_selexpr *e)
{
    if (!e) return;
    ms_selnode_free(e->root);
    free(e->text);
    free(e);
}

const char *ms_sel_text(const ms_selexpr *e) { return e->text; }
int ms_sel_uses_coords(const ms_selexpr *e) { return e->uses_coords; }
