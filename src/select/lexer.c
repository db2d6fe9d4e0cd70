/* lexer.c: splits a selection text into tokens the way VMD's lexer does: the longest match
 * wins, so `C5'`, `1A` and `3'A` are words, `5.` and `.5` are floats, `and`/`andrew` are an
 * operator and a word; "..." and '...' strings allow \" \' and \\ escapes. Every token
 * records its position for error messages. */
#include "config.h"
#include "select/selint.h"

#include <ctype.h>
#include <stdlib.h>
#include <string.h>

static const struct {
    const char *word;
    ms_tok_kind kind;
} reserved[] = {
    {"and", TK_AND},           {"or", TK_OR},           {"not", TK_NOT},
    {"within", TK_WITHIN},     {"exwithin", TK_EXWITHIN}, {"pbwithin", TK_PBWITHIN},
    {"withinbonds", TK_WITHINBONDS}, {"maxringsize", TK_MAXRINGSIZE},
    {"ringsize", TK_RINGSIZE}, {"of", TK_OF},           {"from", TK_FROM},
    {"same", TK_SAME},         {"as", TK_AS},           {"to", TK_THROUGH},
    {"where", TK_WHERE},       {"nearest", TK_NEAREST},
    {"lt", TK_SLT},            {"le", TK_SLE},          {"eq", TK_SEQ},
    {"ge", TK_SGE},            {"gt", TK_SGT},          {"ne", TK_SNE},
};

/* Operators, longest first so that "<=" wins over "<". */
static const struct {
    const char *text;
    ms_tok_kind kind;
} operators[] = {
    {"&&", TK_AND}, {"||", TK_OR},  {"...", TK_THROUGH}, {"<=", TK_NLE}, {"==", TK_NEQ},
    {">=", TK_NGE}, {"!=", TK_NNE}, {"=~", TK_MATCH},    {"**", TK_POW}, {"<", TK_NLT},
    {"=", TK_NEQ},  {">", TK_NGT},  {"+", TK_ADD},       {"-", TK_SUB},  {"/", TK_DIV},
    {"*", TK_MUL},  {"%", TK_MOD},  {"^", TK_POW},       {":", TK_RANGE},
    {"(", TK_LPAREN}, {"{", TK_LPAREN}, {")", TK_RPAREN}, {"}", TK_RPAREN},
};

const char *ms_sel_tok_name(ms_tok_kind k)
{
    for (size_t i = 0; i < MS_COUNTOF(reserved); i++)
        if (reserved[i].kind == k) return reserved[i].word;
    for (size_t i = 0; i < MS_COUNTOF(operators); i++)
        if (operators[i].kind == k) return operators[i].text;
    return "?";
}

static int is_alpha(int c) { return isalpha((unsigned char)c) || c == '_'; }
static int is_alnum(int c) { return isalnum((unsigned char)c) || c == '_'; }
static int is_weird(int c) { return c == '\'' || c == '"'; }

/* Length of a float at s: [0-9]+\. | [0-9]*\.[0-9]+([eE][-+]?[0-9]+)? ; 0 if none. */
static size_t match_float(const char *s)
{
    size_t i = 0;
    while (isdigit((unsigned char)s[i])) i++;
    size_t digits = i;
    if (s[i] != '.') return 0;
    i++;
    size_t frac = i;
    while (isdigit((unsigned char)s[i])) i++;
    if (i == frac) return digits ? i : 0;   /* "5." is a float, "." is not */
    if (s[i] == 'e' || s[i] == 'E') {
        size_t j = i + 1;
        if (s[j] == '+' || s[j] == '-') j++;
        if (isdigit((unsigned char)s[j])) {
            while (isdigit((unsigned char)s[j])) j++;
            i = j;
        }
    }
    return i;
}

/* Words: 1A-like (digits then letters or quotes), C5'-like (letters then a quote), plain
 * identifiers, $name and @name. Sets *ident for plain identifiers. */
static size_t match_word(const char *s, int *ident)
{
    size_t i = 0;
    *ident = 0;
    if (isdigit((unsigned char)s[0])) {
        while (isdigit((unsigned char)s[i])) i++;
        if (!is_alpha(s[i]) && !is_weird(s[i])) return 0;
        while (is_alnum(s[i]) || is_weird(s[i])) i++;
        return i;
    }
    if (s[0] == '$' || s[0] == '@') {
        i = 1;
        while (is_alnum(s[i])) i++;
        return i;
    }
    if (!is_alpha(s[0])) return 0;
    while (is_alnum(s[i])) i++;
    if (!is_weird(s[i])) {
        *ident = 1;
        return i;
    }
    while (is_alnum(s[i]) || is_weird(s[i])) i++;
    return i;
}

/* A quoted string starting at s[0] (the quote). Returns its length including both quotes,
 * or 0 when it is not terminated. An escaped quote or backslash does not end it; when that
 * reading finds no end, the first closing quote does (as a longest match would). */
static size_t match_quoted(const char *s)
{
    char q = s[0];
    for (size_t i = 1; s[i]; i++) {
        if (s[i] == '\\' && (s[i + 1] == q || s[i + 1] == '\\')) {
            i++;
            continue;
        }
        if (s[i] == q) return i + 1;
    }
    const char *end = strchr(s + 1, q);
    return end ? (size_t)(end - s) + 1 : 0;
}

/* The value of a quoted string of length len: \q becomes q and \\ becomes \. */
static char *unquote(const char *s, size_t len)
{
    char *out = malloc(len);
    if (!out) return NULL;
    char q = s[0];
    size_t o = 0;
    for (size_t i = 1; i + 1 < len; i++) {
        if (s[i] == '\\' && i + 2 < len && (s[i + 1] == q || s[i + 1] == '\\')) i++;
        out[o++] = s[i];
    }
    out[o] = '\0';
    return out;
}

static char *copy_n(const char *s, size_t n)
{
    char *d = malloc(n + 1);
    if (!d) return NULL;
    memcpy(d, s, n);
    d[n] = '\0';
    return d;
}

/* Read one token at s (not whitespace, not the end) into t. */
static int lex_one(const char *text, size_t pos, ms_tok *t, ms_error *err)
{
    const char *s = text + pos;
    memset(t, 0, sizeof *t);
    t->pos = pos;
    if (*s == '"' || *s == '\'') {
        size_t n = match_quoted(s);
        if (!n) {
            ms_error_set(err, "unterminated %s-quoted string at position %zu",
                         *s == '"' ? "double" : "single", pos);
            return -1;
        }
        t->kind = *s == '"' ? TK_DQ : TK_SQ;
        t->len = n;
        return (t->str = unquote(s, n)) ? 0 : -1;
    }
    int ident;
    size_t fl = match_float(s), wl = match_word(s, &ident), il = 0;
    while (isdigit((unsigned char)s[il])) il++;
    if (fl && fl >= wl) {
        t->kind = TK_FLOAT;
        t->len = fl;
        t->num = strtod(s, NULL);
        return (t->str = copy_n(s, fl)) ? 0 : -1;
    }
    if (wl && wl > il) {
        t->kind = TK_WORD;
        t->len = wl;
        t->ident = ident;
        if (!(t->str = copy_n(s, wl))) return -1;
        for (size_t k = 0; ident && k < MS_COUNTOF(reserved); k++)
            if (!strcmp(t->str, reserved[k].word)) t->kind = reserved[k].kind;
        return 0;
    }
    if (il) {
        t->kind = TK_INT;
        t->len = il;
        t->num = strtod(s, NULL);
        return (t->str = copy_n(s, il)) ? 0 : -1;
    }
    for (size_t k = 0; k < MS_COUNTOF(operators); k++) {
        size_t n = strlen(operators[k].text);
        if (!strncmp(s, operators[k].text, n)) {
            t->kind = operators[k].kind;
            t->len = n;
            return 0;
        }
    }
    if (isprint((unsigned char)*s))
        ms_error_set(err, "bad character '%c' at position %zu", *s, pos);
    else
        ms_error_set(err, "bad character (byte %u) at position %zu", (unsigned char)*s, pos);
    return -1;
}

void ms_sel_free_tokens(ms_tok *t, size_t n)
{
    if (!t) return;
    for (size_t i = 0; i < n; i++) free(t[i].str);
    free(t);
}

long ms_sel_lex(const char *text, ms_tok **out, ms_error *err)
{
    ms_tok *t = NULL;
    size_t n = 0, cap = 0, pos = 0;
    *out = NULL;
    for (;;) {
        while (text[pos] == ' ' || text[pos] == '\t' || text[pos] == '\n' || text[pos] == '\r')
            pos++;
        if (ms_grow((void **)&t, &cap, n + 1, sizeof *t)) goto oom;
        if (!text[pos]) {
            memset(&t[n], 0, sizeof t[n]);
            t[n].kind = TK_END;
            t[n++].pos = pos;
            break;
        }
        err->msg[0] = '\0';
        if (lex_one(text, pos, &t[n], err)) {
            if (!err->msg[0]) goto oom;
            ms_sel_free_tokens(t, n);
            return -1;
        }
        pos += t[n++].len;
    }
    *out = t;
    return (long)n;
oom:
    ms_sel_free_tokens(t, n);
    ms_error_set(err, "out of memory reading the selection");
    return -1;
}
