/* macros.c: selection macros, global as in VMD. The table starts with VMD's defaults (its
 * atomselmacros.dat, in that order); `atomselect macro` adds or replaces, `delmacro`
 * removes. A lock guards the table: selections may be compiled from any thread. */
#include "config.h"
#include "select/selint.h"

#include <ctype.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

static const char *const default_macros[][2] = {
    {"at", "resname ADE A THY T"},
    {"acidic", "resname ASP GLU"},
    {"cyclic", "resname HIS PHE PRO TRP TYR"},
    {"acyclic", "protein and not cyclic"},
    {"aliphatic", "resname ALA GLY ILE LEU VAL"},
    {"alpha", "protein and name CA"},
    {"amino", "protein"},
    {"aromatic", "resname HIS PHE TRP TYR"},
    {"basic", "resname ARG HIS LYS HSP"},
    {"bonded", "numbonds > 0"},
    {"buried", "resname ALA LEU VAL ILE PHE CYS MET TRP"},
    {"cg", "resname CYT C GUA G"},
    {"charged", "basic or acidic"},
    {"hetero", "not (protein or nucleic)"},
    {"hydrophobic", "resname ALA LEU VAL ILE PRO PHE MET TRP"},
    {"small", "resname ALA GLY SER"},
    {"medium", "resname VAL THR ASP ASN PRO CYS ASX PCA HYP"},
    {"large", "protein and not (small or medium)"},
    {"neutral", "resname VAL PHE GLN TYR HIS CYS MET TRP ASX GLX PCA HYP"},
    {"polar", "protein and not hydrophobic"},
    {"purine", "resname ADE A GUA G"},
    {"pyrimidine", "resname CYT C THY T URA U"},
    {"surface", "protein and not buried"},
    {"lipid", "resname DLPE DMPC DPPC GPC LPPC PALM PC PGCL POPC POPE POPG"},
    {"lipids", "lipid"},
    {"ion", "resname AL BA CA CAL CD CES CLA CL CO CS CU CU1 CUA HG IN IOD K LIT MG MN3 MO3 "
            "MO4 MO5 MO6 NA NAW OC7 PB POT PT RB SOD TB TL WO4 YB ZN ZN1 ZN2"},
    {"ions", "ion"},
    {"sugar", "resname AGLC"},
    {"solvent", "not (protein or sugar or nucleic or lipid)"},
    {"glycan", "resname NAG BGLN FUC AFUC MAN AMAN BMA BMAN"},
    {"carbon", "name \"C.*\" and not ion"},
    {"hydrogen", "name \"[0-9]?H.*\""},
    {"nitrogen", "name \"N.*\""},
    {"oxygen", "name \"O.*\""},
    {"sulfur", "name \"S.*\" and not ion"},
    {"noh", "not hydrogen"},
    {"heme", "resname HEM HEME"},
    {"conformationall", "altloc \"\""},
    {"conformationA", "altloc \"\" or altloc \"A\""},
    {"conformationB", "altloc \"\" or altloc \"B\""},
    {"conformationC", "altloc \"\" or altloc \"C\""},
    {"conformationD", "altloc \"\" or altloc \"D\""},
    {"conformationE", "altloc \"\" or altloc \"E\""},
    {"conformationF", "altloc \"\" or altloc \"F\""},
    {"drude", "type DRUD or type LP"},
};

typedef struct macro {
    char *name, *text;
} macro;

static struct {
    pthread_mutex_t lock;
    pthread_once_t once;
    macro *items;
    size_t n, cap;
    int oom;               /* the defaults could not all be stored */
} table = {PTHREAD_MUTEX_INITIALIZER, PTHREAD_ONCE_INIT, NULL, 0, 0, 0};

static long find_locked(const char *name)
{
    for (size_t i = 0; i < table.n; i++)
        if (table.items[i].name[0] == name[0] && !strcmp(table.items[i].name, name))
            return (long)i;
    return -1;
}

/* Store (or replace) a macro; the caller holds the lock. */
static int store_locked(const char *name, const char *text)
{
    char *t = ms_strdup(text);
    if (!t) return -1;
    long i = find_locked(name);
    if (i >= 0) {
        free(table.items[i].text);
        table.items[i].text = t;
        return 0;
    }
    char *nm = ms_strdup(name);
    if (!nm || ms_grow((void **)&table.items, &table.cap, table.n + 1, sizeof *table.items)) {
        free(nm);
        free(t);
        return -1;
    }
    table.items[table.n].name = nm;
    table.items[table.n++].text = t;
    return 0;
}

static void load_defaults(void)
{
    pthread_mutex_lock(&table.lock);
    for (size_t i = 0; i < MS_COUNTOF(default_macros); i++)
        if (store_locked(default_macros[i][0], default_macros[i][1])) table.oom = 1;
    pthread_mutex_unlock(&table.lock);
}

static void ensure_defaults(void) { pthread_once(&table.once, load_defaults); }

char *ms_sel_macro_text(const char *name)
{
    ensure_defaults();
    pthread_mutex_lock(&table.lock);
    long i = find_locked(name);
    char *t = i >= 0 ? ms_strdup(table.items[i].text) : NULL;
    pthread_mutex_unlock(&table.lock);
    return t;
}

long ms_sel_macro_get(const char *name, char *buf, size_t bufsize)
{
    ensure_defaults();
    pthread_mutex_lock(&table.lock);
    long i = find_locked(name), len = -1;
    if (i >= 0) {
        len = (long)strlen(table.items[i].text);
        if (buf && (size_t)len < bufsize) memcpy(buf, table.items[i].text, (size_t)len + 1);
    }
    pthread_mutex_unlock(&table.lock);
    return len;
}

void ms_sel_macro_foreach(void (*fn)(void *ud, const char *name, const char *text), void *ud)
{
    ensure_defaults();
    pthread_mutex_lock(&table.lock);
    size_t n = table.n;
    macro *copy = ms_alloc_array(n, sizeof *copy);
    for (size_t i = 0; copy && i < n; i++) {
        copy[i].name = ms_strdup(table.items[i].name);
        copy[i].text = ms_strdup(table.items[i].text);
    }
    pthread_mutex_unlock(&table.lock);
    /* fn runs unlocked (it may compile selections); the copies keep it safe */
    for (size_t i = 0; copy && i < n; i++) {
        if (copy[i].name && copy[i].text) fn(ud, copy[i].name, copy[i].text);
        free(copy[i].name);
        free(copy[i].text);
    }
    free(copy);
}

/* A macro name must be a plain word that is not a keyword or a reserved word. */
static int check_name(const char *name, ms_error *err)
{
    ms_tok *t;
    long n = ms_sel_lex(name, &t, err);
    if (n < 0) return -1;
    int plain = n == 2 && t[0].kind == TK_WORD && t[0].ident && t[0].len == strlen(name);
    int reserved = n == 2 && t[0].kind != TK_WORD && t[1].kind == TK_END &&
                   t[0].len == strlen(name) && name[0] && isalpha((unsigned char)name[0]);
    ms_sel_free_tokens(t, (size_t)n);
    if (reserved) {
        ms_error_set(err, "'%s' is a reserved word", name);
        return -1;
    }
    if (!plain) {
        ms_error_set(err, "'%s' is not a valid macro name (letters, digits and _ only)", name);
        return -1;
    }
    if (ms_selkw_find(name)) {
        ms_error_set(err, "'%s' is a built-in keyword and cannot be redefined", name);
        return -1;
    }
    return 0;
}

int ms_sel_macro_define(const char *name, const char *text, ms_error *err)
{
    ensure_defaults();
    if (check_name(name, err)) return -1;
    /* It must compile, and must not refer to itself, directly or through other macros. */
    const char *stack[1] = {name};
    ms_error e = {{0}};
    ms_selnode *tree = ms_sel_parse_text(text, stack, 1, 0, NULL, NULL, &e);
    if (!tree) {
        ms_error_set(err, "macro '%s': %s", name, e.msg);
        return -1;
    }
    ms_selnode_free(tree);
    pthread_mutex_lock(&table.lock);
    int rc = store_locked(name, text);
    pthread_mutex_unlock(&table.lock);
    if (rc) ms_error_set(err, "out of memory defining macro '%s'", name);
    return rc;
}

int ms_sel_macro_delete(const char *name, ms_error *err)
{
    ensure_defaults();
    pthread_mutex_lock(&table.lock);
    long i = find_locked(name);
    if (i >= 0) {
        free(table.items[i].name);
        free(table.items[i].text);
        memmove(table.items + i, table.items + i + 1,
                (table.n - (size_t)i - 1) * sizeof *table.items);
        table.n--;
    }
    pthread_mutex_unlock(&table.lock);
    if (i < 0) ms_error_set(err, "no macro named '%s'", name);
    return i < 0 ? -1 : 0;
}
