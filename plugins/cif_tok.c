/* cif_tok.c: the CIF tokenizer and category tables (cif_tok.h). */
#include "cif_tok.h"

#include <errno.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

typedef struct tok {
    char *s;               /* NUL-terminated value */
    int kind;              /* T_VALUE, T_NULL, T_TAG, T_LOOP, T_DATA, T_OTHER */
    long line;
} tok;

enum { T_END, T_VALUE, T_NULL, T_TAG, T_LOOP, T_DATA, T_OTHER };

typedef struct lexer {
    char *p, *end;
    long line;
    int bol;               /* at the beginning of a line */
} lexer;

static int is_loop(const char *p)
{
    static const char w[] = "loop_";
    for (int k = 0; k < 5; k++)
        if ((p[k] | (k < 4 ? 32 : 0)) != w[k]) return 0;
    return p[5] == '\0';
}

static int is_space(char c) { return c == ' ' || c == '\t' || c == '\n' || c == '\r'; }

/* The next token; T_END at the end; -1 with err set on an unterminated value. */
static int next_tok(lexer *lx, tok *t, ms_perr *err)
{
    for (;;) {
        while (lx->p < lx->end && is_space(*lx->p)) {
            if (*lx->p == '\n') lx->line++, lx->bol = 1;
            else if (*lx->p != '\r') lx->bol = 0;
            lx->p++;
        }
        if (lx->p >= lx->end) return t->kind = T_END;
        if (*lx->p != '#') break;
        while (lx->p < lx->end && *lx->p != '\n') lx->p++;
    }
    char *p = lx->p;
    t->line = lx->line;
    if (*p == ';' && lx->bol) {
        /* Text field: up to a line that starts with ';'. */
        char *q = p + 1;
        for (;;) {
            char *nl = memchr(q, '\n', (size_t)(lx->end - q));
            if (!nl) return ms_perr_set(err, "line %ld: unterminated text field", t->line);
            lx->line++;
            if (nl + 1 < lx->end && nl[1] == ';') {
                *nl = '\0';
                if (nl > p + 1 && nl[-1] == '\r') nl[-1] = '\0';
                t->s = p + 1;
                lx->p = nl + 2;
                lx->bol = 0;
                return t->kind = T_VALUE;
            }
            q = nl + 1;
        }
    }
    lx->bol = 0;
    if (*p == '\'' || *p == '"') {
        char qc = *p, *q = p + 1;
        while (q < lx->end && *q != '\n' && !(*q == qc && (q + 1 >= lx->end || is_space(q[1]))))
            q++;
        if (q >= lx->end || *q != qc)
            return ms_perr_set(err, "line %ld: unterminated quoted value", t->line);
        *q = '\0';
        t->s = p + 1;
        lx->p = q + 1;
        return t->kind = T_VALUE;
    }
    char *q = p;
    while (q < lx->end && !is_space(*q)) q++;
    if (q < lx->end) {
        if (*q == '\n') lx->line++, lx->bol = 1;
        *q = '\0';
        lx->p = q + 1;
    } else {
        lx->p = q; /* the file ends here: the caller's buffer has a spare NUL */
    }
    t->s = p;
    if (*p == '_') return t->kind = T_TAG;
    if ((p[0] == '.' || p[0] == '?') && p[1] == '\0') return t->kind = T_NULL;
    if (is_loop(p)) return t->kind = T_LOOP;
    if (!strncmp(p, "data_", 5)) return t->kind = T_DATA;
    if (!strncmp(p, "save_", 5) || !strcmp(p, "global_") || !strcmp(p, "stop_"))
        return t->kind = T_OTHER;
    return t->kind = T_VALUE;
}

/* ---------------------------------------------------------------- tables */

typedef struct builder {
    cif_file *f;
    size_t tcap;
    size_t vcap, ccap;     /* of the table being built */
} builder;

static cif_table *new_table(builder *b, char *name, long line, ms_perr *err)
{
    cif_file *f = b->f;
    if (f->ntables == b->tcap) {
        size_t nc = b->tcap ? 2 * b->tcap : 32;
        cif_table *nt = realloc(f->tables, nc * sizeof *nt);
        if (!nt) return ms_perr_set(err, "out of memory"), NULL;
        f->tables = nt;
        b->tcap = nc;
    }
    cif_table *t = &f->tables[f->ntables++];
    memset(t, 0, sizeof *t);
    t->name = name;
    t->line = line;
    b->vcap = b->ccap = 0;
    return t;
}

static int push(void ***arr, size_t *cap, size_t n, void *v)
{
    if (n == *cap) {
        size_t nc = *cap ? 2 * *cap : 16;
        void **na = realloc(*arr, nc * sizeof *na);
        if (!na) return -1;
        *arr = na;
        *cap = nc;
    }
    (*arr)[n] = v;
    return 0;
}

/* Split "_cat.item" in place into category and item ("" when there is no dot). */
static char *split_tag(char *tag, char **item)
{
    char *dot = strchr(tag, '.');
    if (!dot) {
        *item = tag + strlen(tag);
        return tag + 1;
    }
    *dot = '\0';
    *item = dot + 1;
    return tag + 1;
}

static int read_loop(builder *b, lexer *lx, tok *t, ms_perr *err)
{
    long line = t->line;
    cif_table *tb = NULL;
    int rc;
    while ((rc = next_tok(lx, t, err)) == T_TAG) {
        char *item, *cat = split_tag(t->s, &item);
        if (!tb && !(tb = new_table(b, cat, line, err))) return -1;
        if (strcmp(tb->name, cat) != 0)
            return ms_perr_set(err, "line %ld: loop mixes categories %s and %s", t->line, tb->name,
                               cat);
        if (push((void ***)&tb->cols, &b->ccap, tb->ncols, item)) goto oom;
        tb->ncols++;
    }
    if (rc < 0) return -1;
    if (!tb) return ms_perr_set(err, "line %ld: loop_ without tags", line);
    size_t nv = 0;
    while (rc == T_VALUE || rc == T_NULL) {
        if (push((void ***)&tb->vals, &b->vcap, nv++, rc == T_NULL ? NULL : t->s)) goto oom;
        rc = next_tok(lx, t, err);
    }
    if (rc < 0) return -1;
    if (nv % tb->ncols)
        return ms_perr_set(err, "line %ld: the %s loop has %zu values, not a multiple of its %zu "
                           "columns", line, tb->name, nv, tb->ncols);
    tb->nrows = nv / tb->ncols;
    return rc;
oom:
    return ms_perr_set(err, "out of memory");
}

/* A tag and its value, added to the current single-row table of that category. */
static int read_item(builder *b, lexer *lx, tok *t, cif_table **cur, ms_perr *err)
{
    long line = t->line;
    char *item, *cat = split_tag(t->s, &item);
    int rc = next_tok(lx, t, err);
    if (rc < 0) return -1;
    if (rc != T_VALUE && rc != T_NULL)
        return ms_perr_set(err, "line %ld: tag _%s.%s has no value", line, cat, item);
    cif_table *tb = *cur ? &b->f->tables[b->f->ntables - 1] : NULL;
    if (!tb || strcmp(tb->name, cat) != 0) {
        if (!(tb = new_table(b, cat, line, err))) return -1;
        tb->nrows = 1;
        *cur = tb; /* only tested for NULL: the table is always the last one */
    }
    if (push((void ***)&tb->cols, &b->ccap, tb->ncols, item) ||
        push((void ***)&tb->vals, &b->vcap, tb->ncols, rc == T_NULL ? NULL : t->s))
        return ms_perr_set(err, "out of memory");
    tb->ncols++;
    return next_tok(lx, t, err);
}

int cif_parse(cif_file *f, char *text, size_t len, ms_perr *err)
{
    memset(f, 0, sizeof *f);
    f->text = text;
    f->len = len;
    builder b = {f, 0, 0, 0};
    lexer lx = {text, text + len, 1, 1};
    tok t;
    int rc = next_tok(&lx, &t, err), blocks = 0;
    cif_table *cur = NULL;
    while (rc > T_END) {
        if (rc == T_DATA) {
            if (blocks++) break; /* the first data block only */
            rc = next_tok(&lx, &t, err);
        } else if (rc == T_LOOP) {
            cur = NULL;
            rc = read_loop(&b, &lx, &t, err);
        } else if (rc == T_TAG) {
            rc = read_item(&b, &lx, &t, &cur, err);
        } else if (rc == T_OTHER) {
            rc = next_tok(&lx, &t, err);
        } else {
            return ms_perr_set(err, "line %ld: value '%.32s' without a tag", t.line, t.s);
        }
    }
    if (rc < 0) return MS_PLUGIN_ERROR;
    return MS_PLUGIN_OK;
}

int cif_read(cif_file *f, const char *path, ms_perr *err)
{
    memset(f, 0, sizeof *f);
    FILE *fp = fopen(path, "rb");
    if (!fp) return ms_perr_set(err, "%s", strerror(errno));
    if (fseeko(fp, 0, SEEK_END) != 0) {
        fclose(fp);
        return ms_perr_set(err, "cannot seek");
    }
    long long size = ftello(fp);
    rewind(fp);
    char *text = size >= 0 && (unsigned long long)size < ((size_t)-1) / 2 ? malloc((size_t)size + 1) : NULL;
    if (!text) {
        fclose(fp);
        return ms_perr_set(err, "out of memory for a file of %lld bytes", size);
    }
    size_t got = fread(text, 1, (size_t)size, fp);
    fclose(fp);
    if (got != (size_t)size) {
        free(text);
        return ms_perr_set(err, "read error");
    }
    text[got] = '\0';
    int rc = cif_parse(f, text, got, err);
    if (rc != MS_PLUGIN_OK) cif_free(f);
    return rc;
}

void cif_free(cif_file *f)
{
    for (size_t k = 0; k < f->ntables; k++) {
        free(f->tables[k].cols);
        free(f->tables[k].vals);
    }
    free(f->tables);
    free(f->text);
    memset(f, 0, sizeof *f);
}

const cif_table *cif_find(const cif_file *f, const char *category)
{
    for (size_t k = 0; k < f->ntables; k++)
        if (!strcmp(f->tables[k].name, category)) return &f->tables[k];
    return NULL;
}

int cif_col(const cif_table *t, const char *item)
{
    for (size_t c = 0; c < t->ncols; c++)
        if (!strcmp(t->cols[c], item)) return (int)c;
    return -1;
}
