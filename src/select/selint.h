/* selint.h: the selection module's internals, shared by its files and by no one else: the
 * tokens of the lexer, the nodes of the compiled tree, the keyword table, the evaluation
 * context, and the cell grid. The public API is select.h. */
#ifndef MS_SELINT_H
#define MS_SELINT_H

#include <regex.h>

#include "select/select.h"

/* ---------------------------------------------------------------- tokens (lexer.c) */

typedef enum {
    TK_END, TK_LPAREN, TK_RPAREN, TK_AND, TK_OR, TK_NOT,
    TK_WITHIN, TK_EXWITHIN, TK_PBWITHIN, TK_WITHINBONDS, TK_MAXRINGSIZE, TK_RINGSIZE,
    TK_NEAREST, TK_WHERE, TK_OF, TK_FROM, TK_SAME, TK_AS, TK_THROUGH, TK_RANGE,
    TK_INT, TK_FLOAT,
    TK_WORD,                 /* a bare word: CA, C5', 1A, $x */
    TK_SQ, TK_DQ,            /* 'single-quoted' and "double-quoted" strings */
    TK_NLT, TK_NLE, TK_NEQ, TK_NGE, TK_NGT, TK_NNE,
    TK_SLT, TK_SLE, TK_SEQ, TK_SGE, TK_SGT, TK_SNE, TK_MATCH,
    TK_ADD, TK_SUB, TK_MUL, TK_DIV, TK_MOD, TK_POW
} ms_tok_kind;

typedef struct ms_tok {
    ms_tok_kind kind;
    size_t pos, len;         /* where it is in the text (0-based bytes) */
    char *str;               /* words and strings: the value, unescaped; else NULL */
    double num;              /* TK_INT, TK_FLOAT */
    int ident;               /* a word that may name a keyword: letters, digits, _ only */
} ms_tok;

/* Split text into tokens, ending with TK_END. Returns the count, or -1 with err set (a bad
 * character or an unterminated string, with its position). */
long ms_sel_lex(const char *text, ms_tok **out, ms_error *err);
void ms_sel_free_tokens(ms_tok *t, size_t n);
const char *ms_sel_tok_name(ms_tok_kind k);

/* ---------------------------------------------------------------- keywords (keywords.c) */

typedef enum {
    SK_INT, SK_FLOAT, SK_STRING,   /* keywords with a value per atom */
    SK_SINGLE,                     /* singlewords: a boolean per atom */
    SK_FUNC,                       /* sqr, sqrt, ... */
    SK_SFUNC                       /* sequence, rasmol */
} ms_sk_kind;

struct ms_selkw {
    const char *name;
    unsigned char kind;      /* ms_sk_kind */
    unsigned char field;     /* which attribute (keywords.c) */
    unsigned char coords;    /* value depends on the frame's coordinates */
    unsigned char settable;
};

/* Built-in symbol by name (not macros); NULL when unknown. */
const ms_selkw *ms_selkw_find(const char *name);

/* Evaluation context: one molecule, one frame, plus what keywords compute lazily. */
typedef struct ms_selctx {
    ms_molecule *m;
    size_t n;                /* atoms */
    long frame;              /* resolved frame, -1 when the molecule has none */
    const float *pos, *vel;  /* the frame's coordinates (NULL without frames) and velocities */
    const float *cell;       /* a b c alpha beta gamma of the frame, or NULL */
    ms_bitset all;           /* every atom set */
    double *phi, *psi;       /* per residue, on first use */
    uint8_t *sidechain;      /* per atom, on first use */
    ms_error *err;
} ms_selctx;

int ms_selctx_init(ms_selctx *c, ms_molecule *m, long frame, ms_error *err);
void ms_selctx_free(ms_selctx *c);

/* Compute what keyword k needs before atoms are read in parallel (polymer fragments,
 * phi/psi, sidechain; secondary structure through ms_ss_ensure when the molecule has none
 * yet). Returns 0 or -1 with c->err set. */
int ms_selkw_prepare(const ms_selkw *k, ms_selctx *c);
/* Values derived from the whole structure (derived.c): per-residue phi and psi from the
 * backbone atoms and bonds, and VMD's sidechain atoms grown from each CA. Computed into the
 * context once. */
int ms_sel_phipsi(ms_selctx *c);
int ms_sel_sidechain(ms_selctx *c);
/* Numeric values (int and float keywords) of atoms [begin, begin+len). */
void ms_selkw_numbers(const ms_selkw *k, const ms_selctx *c, size_t begin, size_t len,
                      double *out);
/* String keywords are read as classes: a small integer per atom naming its string, so a
 * comparison or regular expression runs once per distinct string. */
uint32_t ms_selkw_nclasses(const ms_selkw *k, const ms_molecule *m);
const char *ms_selkw_class_str(const ms_selkw *k, const ms_molecule *m, uint32_t cls);
/* Classes of atoms [begin, begin+len): a pointer into the molecule or into buf. */
const uint32_t *ms_selkw_classes(const ms_selkw *k, const ms_selctx *c, size_t begin,
                                 size_t len, uint32_t *buf);
/* Singleword truth of atoms [begin, begin+len) (begin a multiple of 64) into out words. */
void ms_selkw_single(const ms_selkw *k, const ms_selctx *c, size_t begin, size_t len,
                     uint64_t *out);
/* A math function (sqr, sqrt, ...) applied in place. */
void ms_selkw_func(const ms_selkw *k, double *v, size_t len);

/* ---------------------------------------------------------------- the tree (parser.c) */

typedef enum {
    SN_AND, SN_OR,           /* kids[0..nkids): and/or chains are flat */
    SN_NOT,                  /* a */
    SN_SINGLE,               /* kw: a built-in singleword (all and none included) */
    SN_KEYLIST,              /* kw with a list of values */
    SN_WITHIN, SN_EXWITHIN, SN_PBWITHIN, /* d, a */
    SN_WITHINBONDS,          /* count, a */
    SN_SAME,                 /* kw, a */
    SN_SEQUENCE,             /* vals: regular expressions over one-letter codes */
    SN_COMPARE,              /* op (a TK_ comparison), a, b: expressions */
    /* expressions */
    EN_NUM, EN_STR, EN_KEY, EN_FUNC, EN_NEG,
    EN_ADD, EN_SUB, EN_MUL, EN_DIV, EN_MOD, EN_POW
} ms_node_kind;

typedef enum { SV_EXACT, SV_REGEX, SV_RANGE } ms_selval_kind;

/* One value of a keyword list: `CA`, `"C.*"`, `1 to 10`. */
typedef struct ms_selval {
    ms_selval_kind kind;
    char *lo, *hi;           /* the text (hi for ranges) */
    regex_t *re;             /* SV_REGEX, and sequence patterns */
} ms_selval;

typedef struct ms_selnode ms_selnode;
struct ms_selnode {
    ms_node_kind kind;
    int op;                  /* SN_COMPARE: the operator token */
    const ms_selkw *kw;
    ms_selnode *a, *b;
    ms_selnode **kids;
    size_t nkids;
    double d;                /* within distance; EN_NUM value */
    long count;              /* withinbonds depth */
    int is_int;              /* EN_NUM written as an integer */
    char *s;                 /* EN_STR */
    ms_selval *vals;
    size_t nvals;
};

struct ms_selexpr {
    char *text;
    ms_selnode *root;
    int uses_coords;
};

void ms_selnode_free(ms_selnode *n);
/* The most nodes and keyword values that repeated uses of macros may add to one selection
 * (parser.c: a macro's first use is not counted; doc/commands.md states the limit). */
#define MS_SEL_MACRO_NODES 100000
typedef struct ms_selbudget ms_selbudget;
/* Parse text into a tree; macros[0..nmacros) are being expanded (a recursion check) and
 * depth is the nesting already used. Sets *uses_coords when coordinates are read. budget is
 * what the whole compilation has spent on macros (NULL: this text starts a compilation). */
ms_selnode *ms_sel_parse_text(const char *text, const char **macros, int nmacros, int depth,
                              int *uses_coords, ms_selbudget *budget, ms_error *err);
/* Compile a regular expression the way VMD's selections do: POSIX extended syntax plus \d
 * and \D; anchored as ^(...)$ when asked. err names the pattern and the problem. */
int ms_sel_regcomp(regex_t *re, const char *pattern, int anchored, int nosub, ms_error *err);

/* ---------------------------------------------------------------- macros (macros.c) */

/* Copy of a macro's text (malloc'd), or NULL when there is no such macro. */
char *ms_sel_macro_text(const char *name);

/* ---------------------------------------------------------------- evaluation */

/* Evaluate a selection node: out = the atoms of mask for which it holds (eval.c). */
int ms_sel_eval_node(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                     ms_bitset *out);
/* Comparisons of expressions (compare.c). */
int ms_sel_eval_compare(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                        ms_bitset *out);
/* A function over blocks of atoms, run in parallel: fn sets out's words for atoms
 * [begin, begin+len) where the mask words are set; scratch is per thread. */
#define MS_SEL_BLOCK 4096
typedef int (*ms_block_fn)(const ms_selctx *c, const void *data, size_t begin, size_t len,
                           const uint64_t *mask, uint64_t *out, void *scratch);
int ms_sel_for_blocks(ms_selctx *c, const ms_bitset *mask, ms_bitset *out, ms_block_fn fn,
                      const void *data, size_t scratch_bytes);

/* Distance search through a cell grid (grid.c): out = the atoms of cand within cutoff of an
 * atom of src, through the periodic cell when periodic is set. */
int ms_sel_within(ms_selctx *c, const ms_bitset *cand, const ms_bitset *src, double cutoff,
                  int periodic, ms_bitset *out);

/* same K as, withinbonds, sequence (relations.c). */
int ms_sel_eval_same(ms_selctx *c, const ms_selkw *k, const ms_bitset *src,
                     const ms_bitset *mask, ms_bitset *out);
int ms_sel_eval_withinbonds(ms_selctx *c, long depth, const ms_bitset *src,
                            const ms_bitset *mask, ms_bitset *out);
int ms_sel_eval_sequence(ms_selctx *c, const ms_selnode *nd, const ms_bitset *mask,
                         ms_bitset *out);

#endif
