/* cif_tok.h: a CIF 1.1 tokenizer and table reader for the PDBx/mmCIF plugin. The whole file
 * is read into memory and split into tokens in place (each value NUL-terminated where it
 * ends): bare words, 'single' and "double" quoted values (a quote closes only when followed
 * by white space), semicolon text fields (a line starting with ';' up to the next such
 * line), comments, data_ blocks, loop_ and tags. Items are gathered into categories: a
 * loop's tags and rows, or the single-valued items of a category as a one-row table. */
#ifndef MS_CIF_TOK_H
#define MS_CIF_TOK_H

#include <stddef.h>

#include "ms_plugin.h"

typedef struct cif_table {
    char *name;             /* category, without the leading '_' (e.g. "atom_site") */
    size_t ncols, nrows;
    char **cols;            /* item names (after the '.') */
    char **vals;            /* nrows * ncols values, row-major; NULL for '.' and '?' */
    long line;              /* line where the category starts */
} cif_table;

typedef struct cif_file {
    char *text;
    size_t len;
    cif_table *tables;
    size_t ntables;
} cif_file;

/* Read and tokenize the first data block of a file. */
int cif_read(cif_file *f, const char *path, ms_perr *err);
/* The same over text in memory (malloc'd, with a NUL at text[len]; taken over: freed by
 * cif_free). */
int cif_parse(cif_file *f, char *text, size_t len, ms_perr *err);
void cif_free(cif_file *f);
const cif_table *cif_find(const cif_file *f, const char *category);
/* Column index of an item, -1 when absent. */
int cif_col(const cif_table *t, const char *item);
/* Value of row r, column c (NULL when c < 0 or the value is null). */
static inline const char *cif_val(const cif_table *t, size_t r, int c)
{
    return c < 0 ? NULL : t->vals[r * t->ncols + (size_t)c];
}

#endif
