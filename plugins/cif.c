/* cif.c: the PDBx/mmCIF plugin. Reads atom_site (label and auth identifiers: names and
 * residue names from label_atom_id/label_comp_id, resid and chain from auth_seq_id and
 * auth_asym_id as VMD does, label_asym_id as the segment name, type_symbol, occupancy,
 * B_iso_or_equiv, pdbx_formal_charge, label_alt_id, pdbx_PDB_ins_code; each
 * pdbx_PDB_model_num a frame), _cell, struct_conf (helix classes, turns) and
 * struct_sheet_range, and the biological assemblies of pdbx_struct_assembly_gen and
 * pdbx_struct_oper_list (operator expressions such as "1,2", "(1-60)", "(1-5)(6-10)"), on
 * the CIF tokenizer of cif_tok.c. Writes atom_site files (one model per frame). */
#include "ms_plugin.h"
#include "plugin_util.h"
#include "cif_tok.h"

#include <ctype.h>
#include <math.h>
#include <stdlib.h>
#include <string.h>

enum { C_GROUP, C_ID, C_TYPE, C_LATOM, C_ALT, C_LCOMP, C_LASYM, C_LSEQ, C_INS, C_X, C_Y, C_Z,
       C_OCC, C_B, C_CHARGE, C_ASEQ, C_AASYM, C_AATOM, C_ACOMP, C_MODEL, C_NCOLS };
static const char *const col_names[C_NCOLS] = {
    "group_PDB", "id", "type_symbol", "label_atom_id", "label_alt_id", "label_comp_id",
    "label_asym_id", "label_seq_id", "pdbx_PDB_ins_code", "Cartn_x", "Cartn_y", "Cartn_z",
    "occupancy", "B_iso_or_equiv", "pdbx_formal_charge", "auth_seq_id", "auth_asym_id",
    "auth_atom_id", "auth_comp_id", "pdbx_PDB_model_num"};

typedef struct cif_reader {
    cif_file f;
    const cif_table *as;
    int col[C_NCOLS];
    long natoms;           /* atoms of the first model */
    size_t next_row;       /* first row of the model read_frame returns next */
} cif_reader;

/* A number, allowing a trailing standard uncertainty "(12)". */
static int num(const char *s, double *v)
{
    if (!s) return 0;
    size_t n = strcspn(s, "(");
    return ms_parse_double(s, n, v) == 1;
}

static void cif_close_read(void *h)
{
    cif_reader *r = h;
    cif_free(&r->f);
    free(r);
}

static const char *val(const cif_reader *r, size_t row, int c)
{
    return cif_val(r->as, row, r->col[c]);
}

/* Rows of the model starting at row `from`: up to the next change of model number. */
static size_t model_rows(const cif_reader *r, size_t from)
{
    size_t n = r->as->nrows, k = from;
    const char *m0 = val(r, from, C_MODEL);
    while (k < n) {
        const char *m = val(r, k, C_MODEL);
        if ((m0 == NULL) != (m == NULL) || (m0 && strcmp(m0, m) != 0)) break;
        k++;
    }
    return k - from;
}

static void *cif_open_read(const char *path, long *natoms, ms_perr *err)
{
    cif_reader *r = calloc(1, sizeof *r);
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (cif_read(&r->f, path, err) != MS_PLUGIN_OK) {
        free(r);
        return NULL;
    }
    if (!(r->as = cif_find(&r->f, "atom_site")) || r->as->nrows == 0) {
        ms_perr_set(err, "no atom_site records");
        cif_close_read(r);
        return NULL;
    }
    for (int c = 0; c < C_NCOLS; c++) r->col[c] = cif_col(r->as, col_names[c]);
    if (r->col[C_X] < 0 || r->col[C_Y] < 0 || r->col[C_Z] < 0) {
        ms_perr_set(err, "atom_site (line %ld) has no Cartn_x, Cartn_y and Cartn_z columns",
                    r->as->line);
        cif_close_read(r);
        return NULL;
    }
    r->natoms = (long)model_rows(r, 0);
    *natoms = r->natoms;
    return r;
}

/* x y z of atom_site row `row`; an error names the row and the atom id. */
static int row_xyz(const cif_reader *r, size_t row, float xyz[3], ms_perr *err)
{
    static const char *const axis[3] = {"Cartn_x", "Cartn_y", "Cartn_z"};
    for (int d = 0; d < 3; d++) {
        const char *s = val(r, row, C_X + d);
        double v;
        if (!num(s, &v) || !(fabs(v) < 1e30)) {
            const char *id = val(r, row, C_ID);
            return ms_perr_set(err, "atom_site row %zu (id %s): bad %s '%.32s'", row + 1,
                               id ? id : "?", axis[d], s ? s : "?");
        }
        xyz[d] = (float)v;
    }
    return MS_PLUGIN_OK;
}

static const char *or_blank(const char *s) { return s ? s : ""; }

static int add_atom(cif_reader *r, size_t row, ms_struct_sink *sink, ms_perr *err)
{
    ms_atom_in a;
    memset(&a, 0, sizeof a);
    float xyz[3];
    if (row_xyz(r, row, xyz, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    a.x = xyz[0], a.y = xyz[1], a.z = xyz[2];
    a.has = MS_HAS_POS;
    const char *name = val(r, row, C_LATOM), *comp = val(r, row, C_LCOMP);
    a.name = a.type = name ? name : or_blank(val(r, row, C_AATOM));
    a.resname = comp ? comp : or_blank(val(r, row, C_ACOMP));
    const char *chain = val(r, row, C_AASYM);
    a.chain = chain ? chain : or_blank(val(r, row, C_LASYM));
    a.segname = or_blank(val(r, row, C_LASYM));
    a.element = or_blank(val(r, row, C_TYPE));
    const char *seq = val(r, row, C_ASEQ);
    if (!seq) seq = val(r, row, C_LSEQ);
    double v;
    if (seq && (!num(seq, &v) || !(fabs(v) <= 2e9)))
        return ms_perr_set(err, "atom_site row %zu: bad residue number '%.32s'", row + 1, seq);
    a.resid = seq ? (int)v : 0;
    const char *alt = val(r, row, C_ALT), *ins = val(r, row, C_INS), *g = val(r, row, C_GROUP);
    a.altloc = alt ? alt[0] : ' ';
    a.insertion = ins ? ins[0] : ' ';
    a.hetero = g && !strcmp(g, "HETATM");
    if (num(val(r, row, C_OCC), &v)) a.occupancy = (float)v, a.has |= MS_HAS_OCCUPANCY;
    if (num(val(r, row, C_B), &v)) a.beta = (float)v, a.has |= MS_HAS_BETA;
    if (num(val(r, row, C_CHARGE), &v)) a.charge = (float)v, a.has |= MS_HAS_CHARGE;
    if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory");
    return MS_PLUGIN_OK;
}

static int read_cell(const cif_file *f, ms_struct_sink *sink)
{
    const cif_table *t = cif_find(f, "cell");
    static const char *const items[6] = {"length_a", "length_b", "length_c", "angle_alpha",
                                         "angle_beta", "angle_gamma"};
    if (!t || t->nrows < 1) return 0;
    float cell[6];
    for (int k = 0; k < 6; k++) {
        double v;
        if (!num(cif_val(t, 0, cif_col(t, items[k])), &v)) return 0;
        cell[k] = (float)v;
    }
    if (cell[0] > 1.0f || cell[1] > 1.0f || cell[2] > 1.0f) sink->set_cell(sink, cell);
    return 0;
}

/* One range of struct_conf or struct_sheet_range by author chain and residue numbers. */
static int ss_range(const cif_table *t, size_t row, char code, ms_struct_sink *sink,
                    ms_perr *err)
{
    const char *ch = cif_val(t, row, cif_col(t, "beg_auth_asym_id"));
    const char *b = cif_val(t, row, cif_col(t, "beg_auth_seq_id"));
    const char *e = cif_val(t, row, cif_col(t, "end_auth_seq_id"));
    const char *ib = cif_val(t, row, cif_col(t, "pdbx_beg_PDB_ins_code"));
    const char *ie = cif_val(t, row, cif_col(t, "pdbx_end_PDB_ins_code"));
    double r0, r1;
    if (!ch) ch = cif_val(t, row, cif_col(t, "beg_label_asym_id"));
    if (!num(b, &r0) || !num(e, &r1))
        return ms_perr_set(err, "%s row %zu (line %ld): bad residue numbers", t->name, row + 1,
                           t->line);
    if (sink->add_ss_range(sink, code, or_blank(ch), (int)r0, ib ? ib[0] : ' ', (int)r1,
                           ie ? ie[0] : ' '))
        return ms_perr_set(err, "out of memory");
    return MS_PLUGIN_OK;
}

static int read_ss(const cif_file *f, ms_struct_sink *sink, ms_perr *err)
{
    const cif_table *t = cif_find(f, "struct_conf");
    for (size_t k = 0; t && k < t->nrows; k++) {
        const char *type = cif_val(t, k, cif_col(t, "conf_type_id"));
        const char *cls = cif_val(t, k, cif_col(t, "pdbx_PDB_helix_class"));
        char code;
        if (type && !strncmp(type, "HELX", 4)) {
            int c = cls ? atoi(cls) : 1;
            code = c == 5 ? MS_SS_310 : c == 3 ? MS_SS_PI : MS_SS_ALPHA;
        } else if (type && !strncmp(type, "TURN", 4)) {
            code = MS_SS_TURN;
        } else if (type && !strncmp(type, "STRN", 4)) {
            code = MS_SS_EXTENDED;
        } else {
            continue;
        }
        if (ss_range(t, k, code, sink, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    }
    t = cif_find(f, "struct_sheet_range");
    for (size_t k = 0; t && k < t->nrows; k++)
        if (ss_range(t, k, MS_SS_EXTENDED, sink, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- assemblies */

typedef struct op_list {
    const cif_table *t;
    int id, m[3][4];       /* columns */
} op_list;

/* The 3x4 matrix of operator `id`. */
static int find_op(const op_list *ol, const char *id, double out[12], ms_perr *err)
{
    for (size_t r = 0; r < ol->t->nrows; r++) {
        const char *v = cif_val(ol->t, r, ol->id);
        if (!v || strcmp(v, id)) continue;
        for (int i = 0; i < 3; i++)
            for (int j = 0; j < 4; j++)
                if (!num(cif_val(ol->t, r, ol->m[i][j]), &out[4 * i + j]))
                    return ms_perr_set(err, "pdbx_struct_oper_list: operator %s: bad %s[%d]%s",
                                       id, j < 3 ? "matrix" : "vector", i + 1,
                                       j < 3 ? (const char *[]){"[1]", "[2]", "[3]"}[j] : "");
        return MS_PLUGIN_OK;
    }
    return ms_perr_set(err, "pdbx_struct_assembly_gen: no operator '%s' in pdbx_struct_oper_list",
                       id);
}

/* a = a * b (3x4 affine maps: b applied first). */
static void compose(double a[12], const double b[12])
{
    double r[12];
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            double s = j == 3 ? a[4 * i + 3] : 0;
            for (int k = 0; k < 3; k++) s += a[4 * i + k] * b[4 * k + j];
            r[4 * i + j] = s;
        }
    memcpy(a, r, sizeof r);
}

typedef struct op_set {
    double (*m)[12];
    size_t n, cap;
} op_set;

static int op_push(op_set *s, const double m[12])
{
    if (s->n == s->cap) {
        size_t nc = s->cap ? 2 * s->cap : 16;
        if (nc > (1u << 20)) return -1;
        double(*nm)[12] = realloc(s->m, nc * sizeof *nm);
        if (!nm) return -1;
        s->m = nm;
        s->cap = nc;
    }
    memcpy(s->m[s->n++], m, 12 * sizeof(double));
    return 0;
}

/* The operators of one group "1,2,5-8" (parentheses stripped), in order. */
static int parse_group(const op_list *ol, const char *g, size_t len, op_set *out, ms_perr *err)
{
    char item[64];
    size_t i = 0;
    while (i < len) {
        size_t e = i;
        while (e < len && g[e] != ',') e++;
        size_t n = e - i;
        if (n == 0 || n >= sizeof item)
            return ms_perr_set(err, "pdbx_struct_assembly_gen: bad operator expression");
        memcpy(item, g + i, n);
        item[n] = '\0';
        char *dash = strchr(item + 1, '-');
        double m[12];
        if (dash) {
            *dash = '\0';
            long a, b;
            if (ms_parse_long(item, strlen(item), &a) < 0 ||
                ms_parse_long(dash + 1, strlen(dash + 1), &b) < 0 || b < a || b - a > 100000)
                return ms_perr_set(err, "pdbx_struct_assembly_gen: bad operator range '%s-%s'",
                                   item, dash + 1);
            for (long k = a; k <= b; k++) {
                char id[24];
                snprintf(id, sizeof id, "%ld", k);
                if (find_op(ol, id, m, err) || op_push(out, m)) goto fail;
            }
        } else if (find_op(ol, item, m, err) || op_push(out, m)) {
            goto fail;
        }
        i = e + 1;
    }
    return MS_PLUGIN_OK;
fail:
    if (!err->msg[0]) ms_perr_set(err, "out of memory");
    return MS_PLUGIN_ERROR;
}

/* An operator expression: one list, or parenthesised groups whose product is taken (the
 * first group's operator applied last, the last group's varying fastest). */
static int parse_expr(const op_list *ol, const char *expr, op_set *out, ms_perr *err)
{
    char buf[4096];
    size_t n = 0;
    for (const char *p = expr; *p && n + 1 < sizeof buf; p++)
        if (!isspace((unsigned char)*p)) buf[n++] = *p;
    buf[n] = '\0';
    static const double id[12] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0};
    if (op_push(out, id)) return ms_perr_set(err, "out of memory");
    const char *p = buf;
    while (*p) {
        const char *g = p, *e;
        size_t len;
        if (*p == '(') {
            if (!(e = strchr(p, ')')))
                return ms_perr_set(err, "pdbx_struct_assembly_gen: unbalanced '(' in '%s'", expr);
            g = p + 1;
            len = (size_t)(e - g);
            p = e + 1;
        } else {
            len = strlen(p);
            p += len;
        }
        op_set grp = {0}, prod = {0};
        if (parse_group(ol, g, len, &grp, err)) {
            free(grp.m);
            return MS_PLUGIN_ERROR;
        }
        for (size_t a = 0; a < out->n; a++)
            for (size_t b = 0; b < grp.n; b++) {
                double m[12];
                memcpy(m, out->m[a], sizeof m);
                compose(m, grp.m[b]);
                if (op_push(&prod, m)) {
                    free(grp.m);
                    free(prod.m);
                    return ms_perr_set(err, "too many assembly operators");
                }
            }
        free(grp.m);
        free(out->m);
        *out = prod;
    }
    return MS_PLUGIN_OK;
}

/* Ranges of the first model's atoms whose label_asym_id is in a comma-separated list. */
static size_t (*asym_ranges(const cif_reader *r, const char *list, size_t *nr))[2]
{
    size_t(*rg)[2] = NULL, cap = 0;
    *nr = 0;
    for (size_t i = 0; i < (size_t)r->natoms; i++) {
        const char *a = val(r, i, C_LASYM);
        int in = 0;
        size_t al = a ? strlen(a) : 0;
        for (const char *p = list; a && *p && !in;) {
            size_t l = strcspn(p, ",");
            while (l && isspace((unsigned char)p[l - 1])) l--;
            in = l == al && !strncmp(p, a, l);
            p += strcspn(p, ",");
            if (*p == ',') p++;
            while (isspace((unsigned char)*p)) p++;
        }
        if (!in) continue;
        if (*nr && rg[*nr - 1][1] == i) {
            rg[*nr - 1][1] = i + 1;
            continue;
        }
        if (*nr == cap) {
            size_t nc = cap ? 2 * cap : 16;
            size_t(*n2)[2] = realloc(rg, nc * sizeof *n2);
            if (!n2) {
                free(rg);
                *nr = 0;
                return NULL;
            }
            rg = n2;
            cap = nc;
        }
        rg[*nr][0] = i;
        rg[*nr][1] = i + 1;
        (*nr)++;
    }
    return rg;
}

static int read_assemblies(const cif_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    const cif_table *gen = cif_find(&r->f, "pdbx_struct_assembly_gen");
    const cif_table *ops = cif_find(&r->f, "pdbx_struct_oper_list");
    if (!gen || !ops) return MS_PLUGIN_OK;
    op_list ol = {ops, cif_col(ops, "id"), {{0}}};
    for (int i = 0; i < 3; i++)
        for (int j = 0; j < 4; j++) {
            char name[32];
            if (j < 3) snprintf(name, sizeof name, "matrix[%d][%d]", i + 1, j + 1);
            else snprintf(name, sizeof name, "vector[%d]", i + 1);
            ol.m[i][j] = cif_col(ops, name);
        }
    int ca = cif_col(gen, "assembly_id"), ce = cif_col(gen, "oper_expression"),
        cl = cif_col(gen, "asym_id_list");
    for (size_t k = 0; k < gen->nrows; k++) {
        const char *id = cif_val(gen, k, ca), *expr = cif_val(gen, k, ce), *list = cif_val(gen, k, cl);
        if (!id || !expr || !list) continue;
        op_set s = {0};
        size_t nr;
        if (parse_expr(&ol, expr, &s, err) != MS_PLUGIN_OK) {
            free(s.m);
            return MS_PLUGIN_ERROR;
        }
        size_t(*rg)[2] = asym_ranges(r, list, &nr);
        int rc = nr ? sink->add_assembly(sink, id, nr, (const size_t(*)[2])rg, s.n,
                                         (const double(*)[12])s.m) : 0;
        free(rg);
        free(s.m);
        if (rc) return ms_perr_set(err, "out of memory");
    }
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- structure and frames */

static int cif_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    cif_reader *r = h;
    sink->reserve(sink, (size_t)r->natoms);
    for (size_t i = 0; i < (size_t)r->natoms; i++)
        if (add_atom(r, i, sink, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    read_cell(&r->f, sink);
    if (read_ss(&r->f, sink, err) != MS_PLUGIN_OK || read_assemblies(r, sink, err) != MS_PLUGIN_OK)
        return MS_PLUGIN_ERROR;
    r->next_row = (size_t)r->natoms;
    return MS_PLUGIN_OK;
}

static int cif_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    cif_reader *r = h;
    if (r->next_row == 0 || r->next_row >= r->as->nrows) return MS_PLUGIN_EOF;
    size_t n = model_rows(r, r->next_row);
    const char *m = val(r, r->next_row, C_MODEL);
    if ((long)n != natoms)
        return ms_perr_set(err, "atom_site: model %s has %zu atoms, the first has %ld",
                           m ? m : "?", n, natoms);
    for (size_t i = 0; i < n; i++) {
        float xyz[3];
        if (row_xyz(r, r->next_row + i, xyz, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        if (fr->pos) memcpy(fr->pos + 3 * i, xyz, sizeof xyz);
    }
    r->next_row += n;
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct cif_writer {
    ms_out out;
} cif_writer;

static void *cif_open_write(const char *path, long natoms, ms_perr *err)
{
    (void)natoms;
    cif_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    return w;
}

/* A value as CIF wants it: '.' when empty, quoted when it holds blanks or quotes or starts
 * with a character CIF reserves. */
static const char *cif_word(const char *s, char *buf, size_t cap)
{
    if (!s || !*s) return ".";
    int plain = !strchr("_#$'\";[]", s[0]) && strcmp(s, ".") && strcmp(s, "?");
    for (const char *p = s; *p && plain; p++) plain = !isspace((unsigned char)*p);
    if (plain && strncmp(s, "data_", 5) && strncmp(s, "loop_", 5)) return s;
    snprintf(buf, cap, strchr(s, '\'') ? "\"%s\"" : "'%s'", s);
    return buf;
}

static int cif_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    cif_writer *w = h;
    ms_out *o = &w->out;
    if (f->index == 0) {
        ms_out_printf(o, "data_molscope\n#\n");
        if (f->cell[0] > 0 && f->cell[1] > 0 && f->cell[2] > 0)
            ms_out_printf(o, "_cell.length_a %.3f\n_cell.length_b %.3f\n_cell.length_c %.3f\n"
                             "_cell.angle_alpha %.2f\n_cell.angle_beta %.2f\n"
                             "_cell.angle_gamma %.2f\n#\n", f->cell[0], f->cell[1], f->cell[2],
                          f->cell[3], f->cell[4], f->cell[5]);
        ms_out_printf(o, "loop_\n");
        static const int order[] = {C_GROUP, C_ID, C_TYPE, C_LATOM, C_ALT, C_LCOMP, C_LASYM,
                                    C_INS, C_X, C_Y, C_Z, C_OCC, C_B, C_CHARGE, C_ASEQ,
                                    C_AASYM, C_MODEL};
        for (size_t k = 0; k < sizeof order / sizeof *order; k++)
            ms_out_printf(o, "_atom_site.%s\n", col_names[order[k]]);
    }
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        v->get_atom(v, i, &a);
        char b1[80], b2[80], b3[80], b4[80], b5[80];
        char alt[2] = {a.altloc && a.altloc != ' ' ? a.altloc : '\0', '\0'};
        char ins[2] = {a.insertion && a.insertion != ' ' ? a.insertion : '\0', '\0'};
        const float *p = f->pos + 3 * i;
        ms_out_printf(o, "%s %zu %s %s %s %s %s %s %.3f %.3f %.3f %.2f %.2f %d %d %s %d\n",
                      a.hetero ? "HETATM" : "ATOM", i + 1, cif_word(a.element, b1, sizeof b1),
                      cif_word(a.name, b2, sizeof b2), alt[0] ? alt : ".",
                      cif_word(a.resname, b3, sizeof b3), cif_word(a.segname, b4, sizeof b4),
                      ins[0] ? ins : "?", p[0], p[1], p[2], a.occupancy, a.beta,
                      (int)lrintf(a.charge), a.resid, cif_word(a.chain, b5, sizeof b5),
                      f->index + 1);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int cif_close_write(void *h, ms_perr *err)
{
    cif_writer *w = h;
    ms_out_printf(&w->out, "#\n");
    return ms_out_destroy(w, err);
}

static const ms_plugin cif_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "pdbx",
    .description = "PDBx/mmCIF",
    .extensions = "cif mmcif pdbx",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = cif_open_read,
    .read_structure = cif_read_structure,
    .read_frame = cif_read_frame,
    .close_read = cif_close_read,
    .open_write = cif_open_write,
    .write_frame = cif_write_frame,
    .close_write = cif_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &cif_plugin; }
