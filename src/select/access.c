/* access.c: reading and writing keyword values of chosen atoms, for `$sel get/set` and for
 * commands that take a keyword: numbers of int and float keywords, strings of string
 * keywords, 0/1 of singlewords. Setting a name interns it; setting `structure` changes the
 * whole residue, as VMD does. */
#include "config.h"
#include "select/selint.h"
#include "molecule/elements.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static int check_indices(const ms_molecule *m, const uint32_t *idx, size_t n, ms_error *err)
{
    for (size_t j = 0; j < n; j++)
        if (idx[j] >= m->atoms.n) {
            ms_error_set(err, "atom index %u out of range (molecule has %zu atoms)", idx[j],
                         m->atoms.n);
            return -1;
        }
    return 0;
}

int ms_sel_get_numbers(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, double *out, ms_error *err)
{
    if (k->kind != SK_INT && k->kind != SK_FLOAT && k->kind != SK_SINGLE) {
        ms_error_set(err, "'%s' has no numeric value per atom", k->name);
        return -1;
    }
    if (check_indices(m, idx, n, err)) return -1;
    ms_selctx c;
    if (ms_selctx_init(&c, m, frame, err)) return -1;
    int rc = ms_selkw_prepare(k, &c);
    for (size_t j = 0; rc == 0 && j < n; j++) {
        if (k->kind == SK_SINGLE) {
            uint64_t bit;
            ms_selkw_single(k, &c, idx[j], 1, &bit);
            out[j] = (double)(bit & 1);
        } else {
            ms_selkw_numbers(k, &c, idx[j], 1, &out[j]);
        }
    }
    ms_selctx_free(&c);
    return rc;
}

int ms_sel_get_strings(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, const char **out, ms_error *err)
{
    if (k->kind != SK_STRING) {
        ms_error_set(err, "'%s' is not a string keyword", k->name);
        return -1;
    }
    if (check_indices(m, idx, n, err)) return -1;
    ms_selctx c;
    if (ms_selctx_init(&c, m, frame, err)) return -1;
    if (ms_selkw_prepare(k, &c)) {
        ms_selctx_free(&c);
        return -1;
    }
    for (size_t j = 0; j < n; j++) {
        uint32_t buf;
        const uint32_t *cls = ms_selkw_classes(k, &c, idx[j], 1, &buf);
        out[j] = ms_selkw_class_str(k, m, cls[0]);
    }
    ms_selctx_free(&c);
    return 0;
}

/* ---------------------------------------------------------------- setting numbers */

static int32_t to_int32(double v)
{
    if (!(v == v)) return 0;
    if (v > 2147483647.0) return 2147483647;
    if (v < -2147483648.0) return INT32_MIN;
    return (int32_t)v;
}

/* The float array a keyword writes, allocating user fields and velocities on first use. */
static float *float_target(const ms_selkw *k, ms_molecule *m, long frame, size_t *stride,
                           ms_error *err)
{
    const char *nm = k->name;
    ms_atoms *a = &m->atoms;
    *stride = 1;
    if (!strcmp(nm, "radius")) return a->radius;
    if (!strcmp(nm, "mass")) return a->mass;
    if (!strcmp(nm, "charge")) return a->charge;
    if (!strcmp(nm, "beta")) return a->beta;
    if (!strcmp(nm, "occupancy")) return a->occupancy;
    if (!strncmp(nm, "user", 4)) {
        int u = nm[4] ? nm[4] - '1' : 0;
        if (!m->user[u] && !(m->user[u] = ms_calloc_array(a->n, sizeof(float)))) {
            ms_error_set(err, "out of memory for %s", nm);
            return NULL;
        }
        return m->user[u];
    }
    long f = ms_sel_resolve_frame(m, frame);
    if (f < 0) {
        ms_error_set(err, "cannot set %s: molecule %d has no frames", nm, m->id);
        return NULL;
    }
    ms_frame *fr = ms_mol_frame_pin(m, (size_t)f, err);   /* a changed frame stays */
    if (!fr) return NULL;
    *stride = 3;
    if (nm[0] != 'v') return fr->pos + (nm[0] - 'x');
    if (!fr->vel && !(fr->vel = ms_calloc_array(a->n * 3, sizeof(float)))) {
        ms_error_set(err, "out of memory for velocities");
        return NULL;
    }
    return fr->vel + (nm[1] - 'x');
}

static void set_ints(const ms_selkw *k, ms_molecule *m, const uint32_t *idx, size_t n,
                     const double *vals)
{
    ms_atoms *a = &m->atoms;
    for (size_t j = 0; j < n; j++) {
        int32_t v = to_int32(vals[j]);
        uint32_t i = idx[j];
        if (!strcmp(k->name, "resid")) {
            a->resid[i] = v;
        } else if (!strcmp(k->name, "atomicnumber")) {
            a->atomicnumber[i] = (uint8_t)(v < 0 ? 0 : v > 255 ? 255 : v);
        } else {   /* flag0..flag7 */
            uint16_t bit = (uint16_t)(1u << (MS_AF_USER_FLAGS + (k->name[4] - '0')));
            a->flags[i] = (uint16_t)(v ? a->flags[i] | bit : a->flags[i] & ~bit);
        }
    }
}

int ms_sel_set_numbers(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, const double *vals, ms_error *err)
{
    if (!k->settable || (k->kind != SK_INT && k->kind != SK_FLOAT)) {
        ms_error_set(err, "'%s' cannot be set to numbers", k->name);
        return -1;
    }
    if (check_indices(m, idx, n, err)) return -1;
    if (k->kind == SK_INT) {
        set_ints(k, m, idx, n, vals);
        return 0;
    }
    size_t stride;
    float *dst = float_target(k, m, frame, &stride, err);
    if (!dst) return -1;
    for (size_t j = 0; j < n; j++) dst[stride * idx[j]] = (float)vals[j];
    return 0;
}

/* ---------------------------------------------------------------- setting strings */

/* A secondary structure code from a value as VMD reads it: a name (helix, sheet, 310...) or
 * its first letter. */
static char ss_code(const char *s)
{
    static const struct {
        const char *name;
        char code;
    } names[] = {
        {"helix", 'H'}, {"alpha", 'H'}, {"alpha_helix", 'H'}, {"alphahelix", 'H'},
        {"alpha helix", 'H'}, {"pi", 'I'}, {"pi_helix", 'I'}, {"pihelix", 'I'},
        {"pi helix", 'I'}, {"310", 'G'}, {"310_helix", 'G'}, {"3_10", 'G'}, {"3", 'G'},
        {"310 helix", 'G'}, {"3_10_helix", 'G'}, {"3_10 helix", 'G'}, {"3 10 helix", 'G'},
        {"helix_3_10", 'G'}, {"helix 3 10", 'G'}, {"helix3_10", 'G'}, {"helix310", 'G'},
        {"beta", 'E'}, {"betasheet", 'E'}, {"beta_sheet", 'E'}, {"beta sheet", 'E'},
        {"sheet", 'E'}, {"strand", 'E'}, {"beta_strand", 'E'}, {"beta strand", 'E'},
        {"turn", 'T'}, {"coil", 'C'}, {"unknown", 'C'},
    };
    char c = s[0];
    if (strlen(s) > 1) {
        c = 'X';
        for (size_t i = 0; i < MS_COUNTOF(names); i++)
            if (!strcasecmp(s, names[i].name)) c = names[i].code;
    }
    switch (toupper((unsigned char)c)) {
    case 'H': return 'H';
    case '3': case 'G': return 'G';
    case 'P': case 'I': return 'I';
    case 'S': case 'E': return 'E';
    case 'B': return 'B';
    case 'T': return 'T';
    default: return 'C';   /* C, L and anything unknown */
    }
}

static void set_structure(ms_molecule *m, uint32_t i, const char *v)
{
    char code = ss_code(v);
    int32_t r = m->atoms.residue[i];
    if (m->res_start && r >= 0 && (size_t)r < m->nresidues) {
        for (uint32_t k = m->res_start[r]; k < m->res_start[r + 1]; k++) m->atoms.ss[k] = code;
    } else {
        m->atoms.ss[i] = code;
    }
    m->ss_known = 1;
}

static ms_str *interned_target(const ms_selkw *k, ms_atoms *a)
{
    if (!strcmp(k->name, "name")) return a->name;
    if (!strcmp(k->name, "type")) return a->type;
    if (!strcmp(k->name, "resname")) return a->resname;
    if (!strcmp(k->name, "chain")) return a->chain;
    if (!strcmp(k->name, "segname") || !strcmp(k->name, "segid")) return a->segname;
    return NULL;
}

int ms_sel_set_strings(const ms_selkw *k, ms_molecule *m, long frame, const uint32_t *idx,
                       size_t n, const char *const *vals, ms_error *err)
{
    if (!k->settable || k->kind != SK_STRING) {
        ms_error_set(err, "'%s' cannot be set to strings", k->name);
        return -1;
    }
    if (check_indices(m, idx, n, err)) return -1;
    ms_atoms *a = &m->atoms;
    ms_str *dst = interned_target(k, a);
    for (size_t j = 0; j < n; j++) {
        uint32_t i = idx[j];
        if (dst) {
            ms_str id = ms_strtab_intern_cstr(m->strings, vals[j]);
            if (id == MS_STR_NONE) {
                ms_error_set(err, "out of memory setting %s", k->name);
                return -1;
            }
            dst[i] = id;
        } else if (!strcmp(k->name, "altloc")) {
            a->altloc[i] = vals[j][0] == ' ' ? '\0' : vals[j][0];
        } else if (!strcmp(k->name, "element")) {
            a->atomicnumber[i] = (uint8_t)ms_element_from_symbol(vals[j]);
        } else {
            set_structure(m, i, vals[j]);
        }
    }
    (void)frame;
    return 0;
}
