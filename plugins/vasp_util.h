/* vasp_util.h: what the VASP plugins (poscar.c, xdatcar.c) share: the header every VASP
 * structure file starts with (comment, scale factor, three lattice vectors, the species line
 * of VASP 5 and the counts line) and the atom lines that follow it (Direct or Cartesian).
 *   - scale: one number (negative: the cell's volume in A^3), or three (per axis);
 *   - VASP 4 files have no species line: the species are read from the comment line when
 *     it starts with one element symbol per count, else they are named X1, X2 ...;
 *   - species "Fe_pv" or "Si/1a2b" (VASP 5.4 POTCAR hashes) are the element before the '_'.
 * Header-only (static functions), so each plugin stays one module with no extra link. */
#ifndef MS_VASP_UTIL_H
#define MS_VASP_UTIL_H

#include "ms_plugin.h"
#include "plugin_util.h"
#include "gmx_util.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

#define VASP_MAX_SPECIES 128

typedef struct vasp_head {
    double lat[3][3];      /* scaled lattice vectors (Angstrom), one per row */
    double scale[3];       /* what Cartesian positions are multiplied by */
    int nspecies;
    char species[VASP_MAX_SPECIES][16];
    long count[VASP_MAX_SPECIES];
    long natoms;
    int vasp5;             /* the file has a species line */
} vasp_head;

/* The next line that is not blank, or NULL at the end (an error names what was expected). */
static const char *vasp_line(ms_lines *in, const char *what, ms_perr *err)
{
    const char *l;
    while ((l = ms_lines_next(in)) && l[strspn(l, " \t\r")] == '\0') {}
    if (!l) {
        if (in->error) ms_perr_set(err, "read error after line %ld", in->line_no);
        else ms_perr_set(err, "line %ld: the file ends before the %s", in->line_no, what);
    }
    return l;
}

/* n numbers of the line just read; an error names the line and what they are. */
static int vasp_numbers(ms_lines *in, double *v, int min, int max, int *got, const char *what,
                        ms_perr *err)
{
    char *tok[8];
    int nt = ms_tokens(in->line, tok, max < 8 ? max : 8);
    if (nt < min)
        return ms_perr_set(err, "line %ld: expected %d numbers for the %s, found %d",
                           in->line_no, min, what, nt);
    for (int k = 0; k < nt; k++)
        if (ms_parse_double(tok[k], strlen(tok[k]), &v[k]) < 0 || !isfinite(v[k]) ||
            fabs(v[k]) > 1e9)
            return ms_perr_set(err, "line %ld: bad %s value '%.32s'", in->line_no, what, tok[k]);
    if (got) *got = nt;
    return MS_PLUGIN_OK;
}

static double vasp_det(const double m[3][3])
{
    return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
           m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
           m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
}

/* The scale line and the three lattice vectors. */
static int vasp_read_lattice(ms_lines *in, vasp_head *h, ms_perr *err)
{
    double s[3], v[3];
    int ns;
    if (!vasp_line(in, "scale factor", err) ||
        vasp_numbers(in, s, 1, 3, &ns, "scale factor", err) != MS_PLUGIN_OK)
        return MS_PLUGIN_ERROR;
    long scale_line = in->line_no;
    if (ns == 2) ns = 1;
    for (int k = 0; k < 3; k++) {
        if (!vasp_line(in, "lattice vectors", err) ||
            vasp_numbers(in, v, 3, 3, NULL, "lattice vector", err) != MS_PLUGIN_OK)
            return MS_PLUGIN_ERROR;
        memcpy(h->lat[k], v, sizeof v);
    }
    double vol = fabs(vasp_det(h->lat));
    if (!(vol > 1e-12)) return ms_perr_set(err, "line %ld: the lattice vectors span no volume",
                                           in->line_no);
    if (ns == 1 && s[0] < 0) s[0] = cbrt(-s[0] / vol); /* a negative scale is the volume */
    for (int d = 0; d < 3; d++) {
        h->scale[d] = ns == 3 ? s[d] : s[0];
        if (!(h->scale[d] > 0))
            return ms_perr_set(err, "line %ld: scale factor %g is not positive", scale_line,
                               h->scale[d]);
    }
    for (int k = 0; k < 3; k++)
        for (int d = 0; d < 3; d++) h->lat[k][d] *= h->scale[d];
    return MS_PLUGIN_OK;
}

/* "Fe_pv" -> "Fe", "Si/1a2b" -> "Si" (at most 15 characters). */
static void vasp_species_name(const char *tok, char out[16])
{
    size_t n = strcspn(tok, "_/:");
    if (n == 0) n = strlen(tok);
    if (n > 15) n = 15;
    memcpy(out, tok, n);
    out[n] = '\0';
}

/* VASP 4: species from the comment line when it names one element per count. */
static void vasp_species_from_comment(vasp_head *h, const char *comment)
{
    char buf[512], *tok[VASP_MAX_SPECIES];
    snprintf(buf, sizeof buf, "%s", comment);
    int nt = ms_tokens(buf, tok, VASP_MAX_SPECIES);
    int ok = nt >= h->nspecies;
    for (int k = 0; ok && k < h->nspecies; k++) {
        char name[16];
        vasp_species_name(tok[k], name);
        ok = ms_plugin_element_number(name) > 0;
    }
    for (int k = 0; k < h->nspecies; k++) {
        if (ok) vasp_species_name(tok[k], h->species[k]);
        else snprintf(h->species[k], sizeof h->species[k], "X%d", k + 1);
    }
}

/* The counts on the line just read. */
static int vasp_counts(ms_lines *in, vasp_head *h, ms_perr *err)
{
    char *tok[VASP_MAX_SPECIES + 1];
    int nt = ms_tokens(in->line, tok, VASP_MAX_SPECIES + 1);
    if (nt > VASP_MAX_SPECIES)
        return ms_perr_set(err, "line %ld: more than %d species", in->line_no, VASP_MAX_SPECIES);
    if (h->vasp5 && nt != h->nspecies)
        return ms_perr_set(err, "line %ld: %d counts for %d species", in->line_no, nt,
                           h->nspecies);
    h->nspecies = nt;
    h->natoms = 0;
    for (int k = 0; k < nt; k++) {
        long c;
        if (ms_parse_long(tok[k], strlen(tok[k]), &c) < 0 || c < 0 || c > 0x7fffffffL)
            return ms_perr_set(err, "line %ld: bad atom count '%.32s'", in->line_no, tok[k]);
        h->count[k] = c;
        h->natoms += c;
    }
    if (h->natoms < 1 || h->natoms > 0x7fffffffL)
        return ms_perr_set(err, "line %ld: the counts give %ld atoms", in->line_no, h->natoms);
    return MS_PLUGIN_OK;
}

/* The species line (VASP 5) and the counts line, after the lattice. */
static int vasp_read_species(ms_lines *in, vasp_head *h, const char *comment, ms_perr *err)
{
    if (!vasp_line(in, "atom counts", err)) return MS_PLUGIN_ERROR;
    const char *l = in->line + strspn(in->line, " \t");
    h->vasp5 = isalpha((unsigned char)*l) != 0;
    if (h->vasp5) {
        char *tok[VASP_MAX_SPECIES + 1];
        int nt = ms_tokens(in->line, tok, VASP_MAX_SPECIES + 1);
        if (nt > VASP_MAX_SPECIES)
            return ms_perr_set(err, "line %ld: more than %d species", in->line_no,
                               VASP_MAX_SPECIES);
        h->nspecies = nt;
        for (int k = 0; k < nt; k++) vasp_species_name(tok[k], h->species[k]);
        if (!vasp_line(in, "atom counts", err)) return MS_PLUGIN_ERROR;
    }
    if (vasp_counts(in, h, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    if (!h->vasp5) vasp_species_from_comment(h, comment);
    return MS_PLUGIN_OK;
}

/* The species of atom i (0-based). */
static const char *vasp_species_of(const vasp_head *h, long i)
{
    for (int k = 0; k < h->nspecies; k++) {
        if (i < h->count[k]) return h->species[k];
        i -= h->count[k];
    }
    return "X";
}

/* Atom k of n: its line's first three numbers, converted to Cartesian Angstrom. With
 * selective dynamics the three T/F flags must follow. */
static int vasp_read_atom(ms_lines *in, const vasp_head *h, int cartesian, int selective,
                          long k, float out[3], ms_perr *err)
{
    if (!ms_lines_next(in)) {
        if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
        return ms_perr_set(err, "line %ld: the file ends after %ld of %ld atoms", in->line_no, k,
                           h->natoms);
    }
    double v[3];
    char *tok[6];
    int nt = ms_tokens(in->line, tok, 6);
    if (nt < 3)
        return ms_perr_set(err, "line %ld: expected three coordinates for atom %ld", in->line_no,
                           k + 1);
    for (int d = 0; d < 3; d++)
        if (ms_parse_double(tok[d], strlen(tok[d]), &v[d]) < 0 || !isfinite(v[d]) ||
            fabs(v[d]) > 1e9)
            return ms_perr_set(err, "line %ld: bad coordinate '%.32s'", in->line_no, tok[d]);
    for (int d = 3; selective && d < 6; d++)
        if (d >= nt || !strchr("TFtf", tok[d][0]) || tok[d][1])
            return ms_perr_set(err, "line %ld: atom %ld lacks its three selective dynamics "
                               "flags (T or F)", in->line_no, k + 1);
    for (int d = 0; d < 3; d++)
        out[d] = cartesian ? (float)(v[d] * h->scale[d])
                           : (float)(v[0] * h->lat[0][d] + v[1] * h->lat[1][d] +
                                     v[2] * h->lat[2][d]);
    return MS_PLUGIN_OK;
}

/* The lattice as a b c alpha beta gamma (through gmx_util's box conversion, in nm). */
static void vasp_cell(const vasp_head *h, float cell[6])
{
    double v[9];
    for (int k = 0; k < 9; k++) v[k] = h->lat[k / 3][k % 3] / 10.0;
    ms_gmx_box_to_cell(v, cell);
}

/* The atom record of atom i of a header: its species as name, type and element. */
static void vasp_atom(const vasp_head *h, long i, const float p[3], ms_atom_in *a)
{
    memset(a, 0, sizeof *a);
    const char *s = vasp_species_of(h, i);
    a->name = a->type = s;
    a->element = ms_plugin_element_number(s) > 0 ? s : NULL;
    a->resid = 1;
    a->x = p[0];
    a->y = p[1];
    a->z = p[2];
    a->has = MS_HAS_POS;
}

#endif
