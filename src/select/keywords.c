/* keywords.c: the names of VMD's selection language (keywords, singlewords, functions, in
 * VMD's order) and how each reads a molecule: numbers for int and float keywords, classes
 * (one small integer per distinct string) for string keywords, bits for singlewords. */
#include "config.h"
#include "select/selint.h"
#include "molecule/analysis.h"
#include "molecule/elements.h"
#include "ss/ss.h"

#include <math.h>
#include <pthread.h>
#include <stdlib.h>
#include <string.h>

enum {
    F_NAME, F_TYPE, F_BBTYPE, F_RESTYPE, F_INDEX, F_SERIAL, F_ATOMICNUMBER, F_ELEMENT,
    F_RESIDUE, F_RESNAME, F_ALTLOC, F_RESID, F_INSERTION, F_CHAIN, F_SEGNAME, F_FRAGMENT,
    F_PFRAG, F_NFRAG, F_NUMBONDS, F_STRUCTURE, F_USER, F_USER2, F_USER3, F_USER4,
    F_X, F_Y, F_Z, F_VX, F_VY, F_VZ, F_UFX, F_UFY, F_UFZ, F_PHI, F_PSI,
    F_RADIUS, F_MASS, F_CHARGE, F_BETA, F_OCCUPANCY,
    F_FLAG0, F_FLAG7 = F_FLAG0 + 7, F_VOLINDEX0, F_VOL0 = F_VOLINDEX0 + 8,
    F_INTERPVOL0 = F_VOL0 + 8,
    /* singlewords */
    S_ALL = 100, S_NONE, S_BACKBONE, S_SIDECHAIN, S_PROTEIN, S_NUCLEIC, S_WATER, S_HYDROGEN,
    S_HELIX, S_ALPHA_HELIX, S_HELIX_3_10, S_PI_HELIX, S_SHEET, S_EXTENDED_BETA, S_BRIDGE_BETA,
    S_TURN, S_COIL,
    /* functions */
    FN_SQR = 150, FN_SQRT, FN_ABS, FN_FLOOR, FN_CEIL, FN_SIN, FN_COS, FN_TAN, FN_ATAN,
    FN_ASIN, FN_ACOS, FN_SINH, FN_COSH, FN_TANH, FN_EXP, FN_LOG, FN_LOG10,
    SF_SEQUENCE = 200, SF_RASMOL
};

#define KI(n, f, set) {n, SK_INT, f, 0, set}
#define KF(n, f, c, set) {n, SK_FLOAT, f, c, set}
#define KS(n, f, set) {n, SK_STRING, f, 0, set}
#define SW(n, f) {n, SK_SINGLE, f, 0, 0}
#define FN(n, f) {n, SK_FUNC, f, 0, 0}
#define VOL(k) KF("volindex" #k, F_VOLINDEX0 + k, 1, 0)
#define VAL(k) KF("vol" #k, F_VOL0 + k, 1, 0)
#define IVOL(k) KF("interpvol" #k, F_INTERPVOL0 + k, 1, 0)

static const ms_selkw keywords[] = {
    KS("name", F_NAME, 1), KS("type", F_TYPE, 1), KS("backbonetype", F_BBTYPE, 0),
    KS("residuetype", F_RESTYPE, 0), KI("index", F_INDEX, 0), KI("serial", F_SERIAL, 0),
    KI("atomicnumber", F_ATOMICNUMBER, 1), KS("element", F_ELEMENT, 1),
    KI("residue", F_RESIDUE, 0), KS("resname", F_RESNAME, 1), KS("altloc", F_ALTLOC, 1),
    KI("resid", F_RESID, 1), KS("insertion", F_INSERTION, 0), KS("chain", F_CHAIN, 1),
    KS("segname", F_SEGNAME, 1), KS("segid", F_SEGNAME, 1),
    SW("all", S_ALL), SW("none", S_NONE),
    KI("fragment", F_FRAGMENT, 0), KI("pfrag", F_PFRAG, 0), KI("nfrag", F_NFRAG, 0),
    KI("numbonds", F_NUMBONDS, 0),
    SW("backbone", S_BACKBONE), SW("sidechain", S_SIDECHAIN), SW("protein", S_PROTEIN),
    SW("nucleic", S_NUCLEIC), SW("water", S_WATER), SW("waters", S_WATER),
    SW("vmd_fast_hydrogen", S_HYDROGEN),
    SW("helix", S_HELIX), SW("alpha_helix", S_ALPHA_HELIX), SW("helix_3_10", S_HELIX_3_10),
    SW("pi_helix", S_PI_HELIX), SW("sheet", S_SHEET), SW("betasheet", S_SHEET),
    SW("beta_sheet", S_SHEET), SW("extended_beta", S_EXTENDED_BETA),
    SW("bridge_beta", S_BRIDGE_BETA), SW("turn", S_TURN), SW("coil", S_COIL),
    KS("structure", F_STRUCTURE, 1),
    KF("user", F_USER, 0, 1), KF("user2", F_USER2, 0, 1), KF("user3", F_USER3, 0, 1),
    KF("user4", F_USER4, 0, 1),
    KF("x", F_X, 1, 1), KF("y", F_Y, 1, 1), KF("z", F_Z, 1, 1),
    KF("vx", F_VX, 0, 1), KF("vy", F_VY, 0, 1), KF("vz", F_VZ, 0, 1),
    KF("ufx", F_UFX, 0, 0), KF("ufy", F_UFY, 0, 0), KF("ufz", F_UFZ, 0, 0),
    KF("phi", F_PHI, 1, 0), KF("psi", F_PSI, 1, 0),
    KF("radius", F_RADIUS, 0, 1), KF("mass", F_MASS, 0, 1), KF("charge", F_CHARGE, 0, 1),
    KF("beta", F_BETA, 0, 1), KF("occupancy", F_OCCUPANCY, 0, 1),
    KI("flag0", F_FLAG0, 1), KI("flag1", F_FLAG0 + 1, 1), KI("flag2", F_FLAG0 + 2, 1),
    KI("flag3", F_FLAG0 + 3, 1), KI("flag4", F_FLAG0 + 4, 1), KI("flag5", F_FLAG0 + 5, 1),
    KI("flag6", F_FLAG0 + 6, 1), KI("flag7", F_FLAG7, 1),
    {"sequence", SK_SFUNC, SF_SEQUENCE, 0, 0}, {"rasmol", SK_SFUNC, SF_RASMOL, 0, 0},
    FN("sqr", FN_SQR), FN("sqrt", FN_SQRT), FN("abs", FN_ABS), FN("floor", FN_FLOOR),
    FN("ceil", FN_CEIL), FN("sin", FN_SIN), FN("cos", FN_COS), FN("tan", FN_TAN),
    FN("atan", FN_ATAN), FN("asin", FN_ASIN), FN("acos", FN_ACOS), FN("sinh", FN_SINH),
    FN("cosh", FN_COSH), FN("tanh", FN_TANH), FN("exp", FN_EXP), FN("log", FN_LOG),
    FN("log10", FN_LOG10),
    VOL(0), VOL(1), VOL(2), VOL(3), VOL(4), VOL(5), VOL(6), VOL(7),
    VAL(0), VAL(1), VAL(2), VAL(3), VAL(4), VAL(5), VAL(6), VAL(7),
    IVOL(0), IVOL(1), IVOL(2), IVOL(3), IVOL(4), IVOL(5), IVOL(6), IVOL(7),
};

/* The keywords sorted by name, for lookups by binary search (the parser looks up every word
 * of a selection and of every macro it expands). Built once. */
static const ms_selkw *by_name[MS_COUNTOF(keywords)];
static pthread_once_t by_name_once = PTHREAD_ONCE_INIT;

static int cmp_kw(const void *a, const void *b)
{
    return strcmp((*(const ms_selkw *const *)a)->name, (*(const ms_selkw *const *)b)->name);
}

static void sort_by_name(void)
{
    for (size_t i = 0; i < MS_COUNTOF(keywords); i++) by_name[i] = &keywords[i];
    qsort(by_name, MS_COUNTOF(by_name), sizeof by_name[0], cmp_kw);
}

static int cmp_name_kw(const void *key, const void *elem)
{
    return strcmp(key, (*(const ms_selkw *const *)elem)->name);
}

const ms_selkw *ms_selkw_find(const char *name)
{
    pthread_once(&by_name_once, sort_by_name);
    const ms_selkw *const *k = bsearch(name, by_name, MS_COUNTOF(by_name), sizeof by_name[0],
                                       cmp_name_kw);
    return k ? *k : NULL;
}

/* ---------------------------------------------------------------- public lookups */

const ms_selkw *ms_sel_keyword(const char *name) { return ms_selkw_find(name); }
const char *ms_sel_keyword_name(const ms_selkw *k) { return k->name; }
int ms_sel_keyword_settable(const ms_selkw *k) { return k->settable; }
size_t ms_sel_keyword_count(void) { return MS_COUNTOF(keywords); }
const ms_selkw *ms_sel_keyword_at(size_t i)
{
    return i < MS_COUNTOF(keywords) ? &keywords[i] : NULL;
}

ms_selkw_type ms_sel_keyword_type(const ms_selkw *k)
{
    static const ms_selkw_type map[] = {MS_SELKW_INT, MS_SELKW_FLOAT, MS_SELKW_STRING,
                                        MS_SELKW_BOOL, MS_SELKW_FUNCTION,
                                        MS_SELKW_STRFUNCTION};
    return map[k->kind];
}

/* ---------------------------------------------------------------- context */

long ms_sel_resolve_frame(const ms_molecule *m, long frame)
{
    if (m->nframes == 0) return -1;
    long last = (long)m->nframes - 1;
    if (frame == -2 || frame > last) return last;
    if (frame < 0) return m->frame >= 0 && m->frame <= last ? m->frame : last;
    return frame;
}

int ms_selctx_init(ms_selctx *c, ms_molecule *m, long frame, ms_error *err)
{
    memset(c, 0, sizeof *c);
    c->m = m;
    c->n = m->atoms.n;
    c->err = err;
    c->frame = ms_sel_resolve_frame(m, frame);
    if (c->frame >= 0) {
        const ms_frame *f = ms_mol_frame(m, (size_t)c->frame, err);   /* streamed: read now */
        if (!f) return -1;
        c->pos = f->pos;
        c->vel = f->vel;
        c->cell = f->cell;
    }
    if (ms_bitset_init(&c->all, c->n)) {
        ms_error_set(err, "out of memory for a selection of %zu atoms", c->n);
        return -1;
    }
    ms_bitset_fill(&c->all, 1);
    return 0;
}

void ms_selctx_free(ms_selctx *c)
{
    ms_bitset_free(&c->all);
    free(c->phi);
    free(c->psi);
    free(c->sidechain);
}

/* Does k read atoms.ss (the structure keyword and the secondary structure singlewords)? */
static int reads_structure(const ms_selkw *k)
{
    return k->field == F_STRUCTURE || (k->field >= S_HELIX && k->field <= S_COIL);
}

int ms_selkw_prepare(const ms_selkw *k, ms_selctx *c)
{
    if (reads_structure(k)) return ms_ss_ensure(c->m, c->frame, c->err);
    if (k->kind == SK_SINGLE) return k->field == S_SIDECHAIN ? ms_sel_sidechain(c) : 0;
    if (k->kind != SK_INT && k->kind != SK_FLOAT) return 0;
    if (k->field == F_PFRAG || k->field == F_NFRAG)
        return ms_mol_polymer_fragments(c->m, c->err);
    if (k->field == F_PHI || k->field == F_PSI) return ms_sel_phipsi(c);
    return 0;
}

/* ---------------------------------------------------------------- numbers */

static double flag_bit(const ms_atoms *a, size_t i, int bit)
{
    return (a->flags[i] >> (MS_AF_USER_FLAGS + bit)) & 1u;
}

static double residue_angle(const ms_selctx *c, const double *angle, size_t i)
{
    return angle ? angle[c->m->atoms.residue[i]] : 0.0;
}

/* One atom's value of a numeric keyword (the per-atom switch the block loops share). */
static double number_at(const ms_selkw *k, const ms_selctx *c, size_t i)
{
    const ms_molecule *m = c->m;
    const ms_atoms *a = &m->atoms;
    int f = k->field;
    switch (f) {
    case F_INDEX: return (double)i;
    case F_SERIAL: return (double)i + 1;
    case F_ATOMICNUMBER: return a->atomicnumber[i];
    case F_RESIDUE: return a->residue[i];
    case F_RESID: return a->resid[i];
    case F_FRAGMENT: return a->fragment[i];
    case F_PFRAG: return m->pfrag ? m->pfrag[i] : -1;
    case F_NFRAG: return m->nfrag ? m->nfrag[i] : -1;
    case F_NUMBONDS:
        return m->has_bonds ? (double)(m->bonds.start[i + 1] - m->bonds.start[i]) : 0.0;
    case F_USER: case F_USER2: case F_USER3: case F_USER4:
        return m->user[f - F_USER] ? m->user[f - F_USER][i] : 0.0;
    case F_X: case F_Y: case F_Z: return c->pos ? c->pos[3 * i + (size_t)(f - F_X)] : 0.0;
    case F_VX: case F_VY: case F_VZ: return c->vel ? c->vel[3 * i + (size_t)(f - F_VX)] : 0.0;
    case F_PHI: return residue_angle(c, c->phi, i);
    case F_PSI: return residue_angle(c, c->psi, i);
    case F_RADIUS: return a->radius[i];
    case F_MASS: return a->mass[i];
    case F_CHARGE: return a->charge[i];
    case F_BETA: return a->beta[i];
    case F_OCCUPANCY: return a->occupancy[i];
    default:
        if (f >= F_FLAG0 && f <= F_FLAG7) return flag_bit(a, i, f - F_FLAG0);
        if (f >= F_VOLINDEX0 && f < F_INTERPVOL0 + 8) return NAN;  /* no volumetric data */
        return 0.0;                                                /* ufx ufy ufz */
    }
}

void ms_selkw_numbers(const ms_selkw *k, const ms_selctx *c, size_t begin, size_t len,
                      double *out)
{
    const ms_atoms *a = &c->m->atoms;
    switch (k->field) {   /* the common ones as plain loops */
    case F_INDEX: for (size_t j = 0; j < len; j++) out[j] = (double)(begin + j); return;
    case F_RESID: for (size_t j = 0; j < len; j++) out[j] = a->resid[begin + j]; return;
    case F_RESIDUE: for (size_t j = 0; j < len; j++) out[j] = a->residue[begin + j]; return;
    case F_X: case F_Y: case F_Z:
        if (c->pos) {
            const float *p = c->pos + 3 * begin + (k->field - F_X);
            for (size_t j = 0; j < len; j++) out[j] = p[3 * j];
            return;
        }
        break;
    default: break;
    }
    for (size_t j = 0; j < len; j++) out[j] = number_at(k, c, begin + j);
}

void ms_selkw_func(const ms_selkw *k, double *v, size_t len)
{
    static double (*const fns[])(double) = {NULL, sqrt, fabs, floor, ceil, sin, cos, tan, atan,
                                            asin, acos, sinh, cosh, tanh, exp, log, log10};
    if (k->field == FN_SQR) {
        for (size_t j = 0; j < len; j++) v[j] *= v[j];
        return;
    }
    double (*fn)(double) = fns[k->field - FN_SQR];
    for (size_t j = 0; j < len; j++) v[j] = fn(v[j]);
}

/* ---------------------------------------------------------------- string classes */

static char char_table[256][2];   /* "", "\001", ... "A", ...: one-character strings */

static void char_table_fill(void)
{
    for (unsigned i = 0; i < 256; i++) char_table[i][0] = (char)i;
}

static const char *char_str(unsigned c)
{
    static pthread_once_t once = PTHREAD_ONCE_INIT;
    pthread_once(&once, char_table_fill);
    return char_table[c & 255];
}

static const char *const bbtype_names[] = {"normal", "proteinback", "nucleicback", "hydrogen"};
static const char *const restype_names[] = {"nothing", "protein", "nucleic", "waters"};

static uint32_t bbtype_class(uint16_t fl)
{
    return fl & MS_AF_PROT_BB ? 1 : fl & MS_AF_NUC_BB ? 2 : fl & MS_AF_HYDROGEN ? 3 : 0;
}

static uint32_t restype_class(uint16_t fl)
{
    return fl & MS_AF_PROTEIN ? 1 : fl & MS_AF_NUCLEIC ? 2 : fl & MS_AF_WATER ? 3 : 0;
}

static const ms_str *interned_field(const ms_selkw *k, const ms_atoms *a)
{
    switch (k->field) {
    case F_NAME: return a->name;
    case F_TYPE: return a->type;
    case F_RESNAME: return a->resname;
    case F_CHAIN: return a->chain;
    case F_SEGNAME: return a->segname;
    default: return NULL;
    }
}

uint32_t ms_selkw_nclasses(const ms_selkw *k, const ms_molecule *m)
{
    if (interned_field(k, &m->atoms)) return ms_strtab_count(m->strings);
    if (k->field == F_BBTYPE || k->field == F_RESTYPE) return 4;
    return 256;   /* characters and atomic numbers */
}

const char *ms_selkw_class_str(const ms_selkw *k, const ms_molecule *m, uint32_t cls)
{
    switch (k->field) {
    case F_ELEMENT: return ms_element_symbol((int)cls);
    case F_BBTYPE: return bbtype_names[cls & 3];
    case F_RESTYPE: return restype_names[cls & 3];
    case F_ALTLOC: case F_INSERTION: case F_STRUCTURE: return char_str(cls);
    default: return ms_mol_str(m, cls);
    }
}

const uint32_t *ms_selkw_classes(const ms_selkw *k, const ms_selctx *c, size_t begin,
                                 size_t len, uint32_t *buf)
{
    const ms_atoms *a = &c->m->atoms;
    const ms_str *field = interned_field(k, a);
    if (field) return field + begin;
    for (size_t j = 0; j < len; j++) {
        size_t i = begin + j;
        switch (k->field) {
        case F_ELEMENT: buf[j] = a->atomicnumber[i]; break;
        case F_BBTYPE: buf[j] = bbtype_class(a->flags[i]); break;
        case F_RESTYPE: buf[j] = restype_class(a->flags[i]); break;
        case F_ALTLOC: buf[j] = (unsigned char)a->altloc[i]; break;
        case F_INSERTION: buf[j] = (unsigned char)a->insertion[i]; break;
        default: buf[j] = (unsigned char)a->ss[i]; break;   /* structure */
        }
    }
    return buf;
}

/* ---------------------------------------------------------------- singlewords */

static int ss_in(char s, const char *codes) { return s && strchr(codes, s) != NULL; }

static int single_at(const ms_selkw *k, const ms_selctx *c, size_t i)
{
    const ms_atoms *a = &c->m->atoms;
    uint16_t fl = a->flags[i];
    char s = a->ss[i];
    switch (k->field) {
    case S_ALL: return 1;
    case S_NONE: return 0;
    case S_BACKBONE: return (fl & (MS_AF_PROT_BB | MS_AF_NUC_BB)) != 0;
    case S_SIDECHAIN: return c->sidechain && c->sidechain[i];
    case S_PROTEIN: return (fl & MS_AF_PROTEIN) != 0;
    case S_NUCLEIC: return (fl & MS_AF_NUCLEIC) != 0;
    case S_WATER: return (fl & MS_AF_WATER) != 0;
    case S_HYDROGEN: return (fl & MS_AF_HYDROGEN) != 0;
    case S_HELIX: return ss_in(s, "HGI");
    case S_ALPHA_HELIX: return s == 'H';
    case S_HELIX_3_10: return s == 'G';
    case S_PI_HELIX: return s == 'I';
    case S_SHEET: return ss_in(s, "EB");
    case S_EXTENDED_BETA: return s == 'E';
    case S_BRIDGE_BETA: return s == 'B';
    case S_TURN: return s == 'T';
    default: return s == 'C';
    }
}

void ms_selkw_single(const ms_selkw *k, const ms_selctx *c, size_t begin, size_t len,
                     uint64_t *out)
{
    for (size_t w = 0; w * 64 < len; w++) {
        uint64_t bits = 0;
        size_t end = MS_MIN(len, w * 64 + 64);
        for (size_t j = w * 64; j < end; j++)
            bits |= (uint64_t)single_at(k, c, begin + j) << (j & 63);
        out[w] = bits;
    }
}
