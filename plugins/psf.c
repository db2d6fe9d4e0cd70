/* psf.c: the PSF plugin (CHARMM, NAMD and X-PLOR protein structure files). Reads the
 * !NATOM section in CHARMM's fixed columns (standard and EXT), NAMD's space-separated form
 * with long names, CHEQ and Drude extra columns, and X-PLOR type names; reads !NBOND (a PSF
 * lists every bond). Writes atoms and bonds, switching to EXT or NAMD layout when names or
 * counts need it. A PSF holds no coordinates. */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct psf_reader {
    ms_lines in;
    int ext;           /* "EXT" flag: wide columns */
    long natoms;
    long long size;    /* file size, to bound the atom count hint */
} psf_reader;

/* Column layout of an atom line up to the name: the id field width and the string width. */
typedef struct psf_cols {
    size_t id_w, str_w;
} psf_cols;

static const psf_cols psf_standard = {8, 4}, psf_extended = {10, 8};

static void *psf_open_read(const char *path, long *natoms, ms_perr *err)
{
    psf_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    struct stat sb;
    r->size = fstat(fileno(r->in.fp), &sb) == 0 ? (long long)sb.st_size : 0;
    const char *l = ms_lines_next(&r->in);
    if (!l || strncmp(l, "PSF", 3) != 0) {
        ms_lines_destroy(r);
        ms_perr_set(err, "line 1: not a PSF file (it does not start with 'PSF')");
        return NULL;
    }
    char head[256];
    snprintf(head, sizeof head, "%s", l + 3);
    char *tok[16];
    int nt = ms_tokens(head, tok, 16);
    for (int k = 0; k < nt; k++)
        if (!strcmp(tok[k], "EXT")) r->ext = 1;
    *natoms = -1;
    return r;
}

static void psf_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* The count before a "!NAME" section tag, or -1 when the line is not that section's
 * header; -2 when it is but the count is not a number. */
static long section_count(const char *line, const char *tag)
{
    const char *bang = strstr(line, tag);
    if (!bang) return -1;
    size_t tl = strlen(tag);
    char c = bang[tl];
    if (c && c != ':' && c != ' ' && c != '\t') return -1; /* !NBONDS... is not !NBOND */
    const char *p = line;
    while (*p == ' ' || *p == '\t') p++;
    const char *e = p;
    while (*e >= '0' && *e <= '9') e++;
    long v;
    if (e == p || e > bang || ms_parse_long(p, (size_t)(e - p), &v) < 0 || v < 0) return -2;
    return v;
}

/* Title lines up to the !NATOM header; returns the atom count or MS_PLUGIN_ERROR. */
static long read_title(psf_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    const char *l;
    while ((l = ms_lines_next(&r->in))) {
        long n = section_count(l, "!NATOM");
        if (n == -2) return ms_perr_set(err, "line %ld: bad !NATOM count", r->in.line_no);
        if (n >= 0) return n;
        const char *p = l;
        while (*p == ' ') p++;
        if ((!strncmp(p, "REMARKS", 7) || *p == '*') && sink->add_remark(sink, p))
            return ms_perr_set(err, "out of memory");
    }
    if (r->in.error) return ms_perr_set(err, "read error after line %ld", r->in.line_no);
    return ms_perr_set(err, "no !NATOM section (file ends at line %ld)", r->in.line_no);
}

/* A residue number with an optional insertion letter: "12", "-3", "12A". */
static int parse_resid(const char *s, int *resid, char *ins)
{
    size_t n = strlen(s);
    *ins = ' ';
    if (n >= 2 && ((s[n - 1] >= 'A' && s[n - 1] <= 'Z') || (s[n - 1] >= 'a' && s[n - 1] <= 'z'))) {
        *ins = s[n - 1];
        n--;
    }
    long v;
    if (ms_parse_long(s, n, &v) < 0) return -1;
    *resid = (int)v;
    return 0;
}

/* Do the fixed columns of this layout fit the line: blank separators after the id and each
 * string field, and a number in the id field? */
static int fixed_fits(const char *l, size_t len, psf_cols c)
{
    size_t end = c.id_w + 4 * (c.str_w + 1);
    if (len <= end) return 0;
    for (int k = 0; k < 5; k++)
        if (l[c.id_w + (size_t)k * (c.str_w + 1)] != ' ') return 0;
    int id;
    return ms_field_int(l, len, 0, c.id_w, &id) == 1;
}

typedef struct psf_fields {
    char seg[64], resid[64], resname[64], name[64], type[64];
    const char *charge, *mass;
} psf_fields;

static void copy_tok(char *dst, const char *src)
{
    snprintf(dst, 64, "%s", src);
}

/* Split an atom line (modified in place) into its fields. */
static int split_atom_line(psf_reader *r, char *l, size_t len, psf_fields *f, ms_perr *err)
{
    char *tok[16];
    psf_cols c = r->ext ? psf_extended : psf_standard;
    if (!fixed_fits(l, len, c)) c = r->ext ? psf_standard : psf_extended;
    if (fixed_fits(l, len, c)) {
        char *field[4] = {f->seg, f->resid, f->resname, f->name};
        for (size_t k = 0; k < 4; k++) {
            size_t c0 = c.id_w + 1 + k * (c.str_w + 1);
            ms_field(l, len, c0, c0 + c.str_w, field[k]);
        }
        int nt = ms_tokens(l + c.id_w + 4 * (c.str_w + 1), tok, 16);
        if (nt < 3)
            return ms_perr_set(err, "line %ld: atom record lacks type, charge or mass",
                               r->in.line_no);
        copy_tok(f->type, tok[0]);
        f->charge = tok[1];
        f->mass = tok[2];
        return MS_PLUGIN_OK;
    }
    /* NAMD's space-separated form: id seg resid resname name type charge mass ... */
    int nt = ms_tokens(l, tok, 16);
    if (nt < 8)
        return ms_perr_set(err, "line %ld: atom record has %d fields, expected at least 8",
                           r->in.line_no, nt);
    copy_tok(f->seg, tok[1]);
    copy_tok(f->resid, tok[2]);
    copy_tok(f->resname, tok[3]);
    copy_tok(f->name, tok[4]);
    copy_tok(f->type, tok[5]);
    f->charge = tok[6];
    f->mass = tok[7];
    return MS_PLUGIN_OK;
}

static int parse_atom_line(psf_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    ms_lines *in = &r->in;
    psf_fields f;
    memset(&f, 0, sizeof f);
    if (split_atom_line(r, in->line, in->line_len, &f, err) != MS_PLUGIN_OK)
        return MS_PLUGIN_ERROR;
    ms_atom_in a;
    memset(&a, 0, sizeof a);
    if (parse_resid(f.resid, &a.resid, &a.insertion))
        return ms_perr_set(err, "line %ld: bad residue number '%s'", in->line_no, f.resid);
    if (ms_parse_float(f.charge, strlen(f.charge), &a.charge) < 0)
        return ms_perr_set(err, "line %ld: bad charge '%.32s'", in->line_no, f.charge);
    if (ms_parse_float(f.mass, strlen(f.mass), &a.mass) < 0)
        return ms_perr_set(err, "line %ld: bad mass '%.32s'", in->line_no, f.mass);
    a.has = MS_HAS_CHARGE | MS_HAS_MASS;
    a.segname = f.seg;
    a.resname = f.resname;
    a.name = f.name;
    a.type = f.type;
    a.chain = "";
    a.altloc = ' ';
    if (sink->add_atom(sink, &a)) return ms_perr_set(err, "out of memory at line %ld", in->line_no);
    r->natoms++;
    return MS_PLUGIN_OK;
}

static int read_atoms(psf_reader *r, ms_struct_sink *sink, long count, ms_perr *err)
{
    ms_lines *in = &r->in;
    /* An atom line is at least eight fields (16 bytes): the file bounds the count. */
    if (ms_check_room(err, (double)count, 16, ms_lines_left(in), "atoms",
                      "line %ld: !NATOM declares %ld atoms", in->line_no, count))
        return MS_PLUGIN_ERROR;
    /* A usual atom line is at least 40 bytes: the file size bounds the hint. */
    long long most = r->size / 40 + 16;
    sink->reserve(sink, (size_t)(count < most ? count : most));
    for (long k = 0; k < count; k++) {
        const char *l = ms_lines_next(in);
        if (!l) {
            if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
            return ms_perr_set(err, "!NATOM says %ld, found %ld at the end of the file (line %ld)",
                               count, k, in->line_no);
        }
        const char *p = l + strspn(l, " \t");
        if (*p == '\0' || strchr(l, '!'))
            return ms_perr_set(err, "line %ld: !NATOM says %ld, found %ld", in->line_no, count, k);
        if (parse_atom_line(r, sink, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    }
    return MS_PLUGIN_OK;
}

/* Integers of one bond line: fixed fields of width w when they parse, else tokens. Returns
 * the count of values stored in v (at most max), or -1 when the line is not numbers. */
static int bond_line_values(char *l, size_t len, size_t w, long *v, int max)
{
    int n = 0, fixed = 1;
    for (size_t c = 0; c < len && n < max; c += w) {
        int x;
        int rc = ms_field_int(l, len, c, c + w, &x);
        if (rc < 0) {
            fixed = 0;
            break;
        }
        if (rc == 1) v[n++] = x;
    }
    if (fixed) return n;
    char *tok[64];
    int nt = ms_tokens(l, tok, 64);
    for (n = 0; n < nt && n < max; n++)
        if (ms_parse_long(tok[n], strlen(tok[n]), &v[n]) < 0) return -1;
    return n;
}

/* The sections of connectivity after the atoms, in the order a PSF has them. */
static const struct psf_section {
    const char *tag, *what;
    int width, kind; /* kind -1: bonds, else MS_PTERM_* */
} psf_sections[] = {{"!NBOND", "bond", 2, -1},
                    {"!NTHETA", "angle", 3, MS_PTERM_ANGLE},
                    {"!NPHI", "dihedral", 4, MS_PTERM_DIHEDRAL},
                    {"!NIMPHI", "improper", 4, MS_PTERM_IMPROPER}};

/* Which connectivity section a header line opens (its count in *count), -1 for another
 * section, -2 for a bad count. */
static int which_section(const char *l, long *count)
{
    for (int k = 0; k < (int)(sizeof psf_sections / sizeof psf_sections[0]); k++) {
        long c = section_count(l, psf_sections[k].tag);
        if (c == -2) return -2;
        if (c >= 0) {
            *count = c;
            return k;
        }
    }
    return -1;
}

/* Hand one record of a section to the sink (v: 1-based atom numbers). */
static int emit_record(ms_struct_sink *sink, const struct psf_section *sec, const long *v)
{
    size_t at[4];
    for (int q = 0; q < sec->width; q++) at[q] = (size_t)(v[q] - 1);
    if (sec->kind < 0) return sink->add_bond(sink, at[0], at[1], 1.0f);
    return sink->add_term(sink, sec->kind, at, NULL);
}

/* The `count` records of one section, width atom numbers each, any number a line. */
static int read_records(psf_reader *r, ms_struct_sink *sink, const struct psf_section *sec,
                        long count, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    /* A record is width numbers, each a digit and a separator at the least. */
    char unit[24];
    snprintf(unit, sizeof unit, "%ss", sec->what);
    if (ms_check_room(err, (double)count, 2 * sec->width, ms_lines_left(in), unit,
                      "line %ld: %s declares %ld %s", in->line_no, sec->tag, count, unit))
        return MS_PLUGIN_ERROR;
    long found = 0, v[4];
    int have = 0;
    while (found < count) {
        if (!(l = ms_lines_next(in))) {
            if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
            return ms_perr_set(err, "%s says %ld, found %ld at the end of the file (line %ld)",
                               sec->tag, count, found, in->line_no);
        }
        if (strchr(l, '!') || l[strspn(l, " \t")] == '\0')
            return ms_perr_set(err, "line %ld: %s says %ld, found %ld", in->line_no, sec->tag,
                               count, found);
        long vals[64];
        int nv = bond_line_values(in->line, in->line_len, r->ext ? 10 : 8, vals, 64);
        if (nv < 0) return ms_perr_set(err, "line %ld: bad %s record", in->line_no, sec->what);
        for (int k = 0; k < nv && found < count; k++) {
            if (vals[k] < 1 || vals[k] > r->natoms)
                return ms_perr_set(err, "line %ld: %s names atom %ld, but there are %ld atoms",
                                   in->line_no, sec->what, vals[k], r->natoms);
            v[have++] = vals[k];
            if (have < sec->width) continue;
            if (emit_record(sink, sec, v)) return ms_perr_set(err, "out of memory");
            have = 0;
            found++;
        }
    }
    return MS_PLUGIN_OK;
}

/* Bonds, angles, dihedrals and impropers, each when the file has its section; reading
 * stops at the first other section (donors, acceptors ...) or the end of the file. */
static int read_connectivity(psf_reader *r, ms_struct_sink *sink, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    int next = 0;
    while ((l = ms_lines_next(in))) {
        const char *p = l + strspn(l, " \t");
        if (*p == '\0' || !strchr(l, '!')) continue;
        long count = 0;
        int k = which_section(l, &count);
        if (k == -2) return ms_perr_set(err, "line %ld: bad section count", in->line_no);
        if (k < next) break; /* another section, or one out of order: the rest is not ours */
        if (read_records(r, sink, &psf_sections[k], count, err) != MS_PLUGIN_OK)
            return MS_PLUGIN_ERROR;
        if (k == 0) sink->bonds_complete(sink);
        next = k + 1;
    }
    if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
    return MS_PLUGIN_OK;
}

static int psf_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    psf_reader *r = h;
    long count = read_title(r, sink, err);
    if (count < 0) return MS_PLUGIN_ERROR;
    if (count == 0) return ms_perr_set(err, "line %ld: !NATOM says 0 atoms", r->in.line_no);
    if (read_atoms(r, sink, count, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
    return read_connectivity(r, sink, err);
}

/* ---------------------------------------------------------------- writing */

typedef struct psf_writer {
    ms_out out;
} psf_writer;

static void *psf_open_write(const char *path, long natoms, ms_perr *err)
{
    psf_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    return w;
}

enum { PSF_STANDARD, PSF_EXT, PSF_NAMD };

static void resid_text(const ms_atom_in *a, char out[24])
{
    char ins = a->insertion && a->insertion != ' ' ? a->insertion : '\0';
    snprintf(out, 24, "%d%c", a->resid, ins);
}

static const char *or_blank(const char *s, const char *dflt) { return s && *s ? s : dflt; }

static size_t max_len(size_t w, const char *s)
{
    size_t n = strlen(s);
    return n > w ? n : w;
}

/* Which layout holds every field: CHARMM's standard columns, EXT, or NAMD's free form.
 * *xplor is set when some type is not a number. */
static int choose_layout(const ms_struct_view *v, int *xplor)
{
    size_t widest = 0, type_w = 0;
    *xplor = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        char resid[24];
        v->get_atom(v, i, &a);
        resid_text(&a, resid);
        const char *s[4] = {or_blank(a.segname, ""), resid, or_blank(a.resname, ""),
                            or_blank(a.name, "")};
        for (int k = 0; k < 4; k++) widest = max_len(widest, s[k]);
        const char *t = or_blank(a.type, "X");
        type_w = max_len(type_w, t);
        long dummy;
        if (ms_parse_long(t, strlen(t), &dummy) < 0) *xplor = 1;
    }
    if (widest > 8 || type_w > 6) return PSF_NAMD;
    if (widest > 4 || type_w > 4 || v->natoms > 9999999) return PSF_EXT;
    return PSF_STANDARD;
}

static void write_atoms(ms_out *o, const ms_struct_view *v, int layout, const char *idfmt)
{
    ms_out_printf(o, idfmt, (long)v->natoms);
    ms_out_printf(o, " !NATOM\n");
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        char resid[24];
        v->get_atom(v, i, &a);
        resid_text(&a, resid);
        const char *seg = or_blank(a.segname, layout == PSF_NAMD ? "X" : ""),
                   *rn = or_blank(a.resname, "X"), *nm = or_blank(a.name, "X"),
                   *ty = or_blank(a.type, "X");
        if (layout == PSF_STANDARD)
            ms_out_printf(o, "%8zu %-4s %-4s %-4s %-4s %-4s %14.6f%14.6f%8d\n", i + 1, seg,
                          resid, rn, nm, ty, (double)a.charge, (double)a.mass, 0);
        else if (layout == PSF_EXT)
            ms_out_printf(o, "%10zu %-8s %-8s %-8s %-8s %-6s %14.6f%14.6f%8d\n", i + 1, seg,
                          resid, rn, nm, ty, (double)a.charge, (double)a.mass, 0);
        else
            ms_out_printf(o, "%10zu %s %s %s %s %s %.6f %.4f 0\n", i + 1, seg, resid, rn, nm, ty,
                          (double)a.charge, (double)a.mass);
    }
    ms_out_printf(o, "\n");
}

/* Every bond once (i < j), four pairs a line. */
static void write_bonds(ms_out *o, const ms_struct_view *v, const char *idfmt)
{
    size_t nb = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const unsigned *to;
        size_t n = v->get_bonds(v, i, &to);
        for (size_t k = 0; k < n; k++) nb += to[k] > i;
    }
    ms_out_printf(o, idfmt, (long)nb);
    ms_out_printf(o, " !NBOND: bonds\n");
    size_t col = 0;
    for (size_t i = 0; i < v->natoms; i++) {
        const unsigned *to;
        size_t n = v->get_bonds(v, i, &to);
        for (size_t k = 0; k < n; k++) {
            if (to[k] <= i) continue;
            ms_out_printf(o, idfmt, (long)i + 1);
            ms_out_printf(o, idfmt, (long)to[k] + 1);
            if (++col == 4) {
                ms_out_printf(o, "\n");
                col = 0;
            }
        }
    }
    ms_out_printf(o, col || nb == 0 ? "\n\n" : "\n");
}

/* The angles (3 atoms, three a line), dihedrals or impropers (4 atoms, two a line) of the
 * view, as CHARMM lays them out. */
static void write_terms(ms_out *o, const ms_struct_view *v, int kind, const char *name,
                        const char *idfmt)
{
    size_t n = v->count_terms ? v->count_terms(v, kind) : 0, width = kind ? 4 : 3;
    size_t per_line = kind ? 2 : 3;
    ms_out_printf(o, idfmt, (long)n);
    ms_out_printf(o, " %s\n", name);
    for (size_t k = 0; k < n; k++) {
        size_t at[4];
        const char *type;
        v->get_term(v, kind, k, at, &type);
        for (size_t q = 0; q < width; q++) ms_out_printf(o, idfmt, (long)at[q] + 1);
        if ((k + 1) % per_line == 0 || k + 1 == n) ms_out_printf(o, "\n");
    }
    ms_out_printf(o, "\n\n");
}

static int psf_write_structure(void *h, const ms_struct_view *v, ms_perr *err)
{
    psf_writer *w = h;
    ms_out *o = &w->out;
    int xplor;
    int layout = choose_layout(v, &xplor);
    const char *idfmt = layout == PSF_STANDARD ? "%8ld" : "%10ld";
    ms_out_printf(o, "PSF%s%s%s\n\n", layout != PSF_STANDARD ? " EXT" : "",
                  layout == PSF_NAMD ? " NAMD" : "", xplor ? " XPLOR" : "");
    ms_out_printf(o, idfmt, 1L);
    ms_out_printf(o, " !NTITLE\n REMARKS written by molscope\n\n");
    write_atoms(o, v, layout, idfmt);
    write_bonds(o, v, idfmt);
    static const char *const names[] = {"!NTHETA: angles", "!NPHI: dihedrals",
                                        "!NIMPHI: impropers"};
    for (int kind = 0; kind < 3; kind++) write_terms(o, v, kind, names[kind], idfmt);
    /* Empty sections, so readers that expect them find them. */
    static const char *const rest[] = {"!NDON: donors", "!NACC: acceptors"};
    for (size_t k = 0; k < sizeof rest / sizeof rest[0]; k++) {
        ms_out_printf(o, idfmt, 0L);
        ms_out_printf(o, " %s\n\n\n", rest[k]);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int psf_close_write(void *h, ms_perr *err)
{
    psf_writer *w = h;
    return ms_out_destroy(w, err);
}

static const ms_plugin psf_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "psf",
    .description = "CHARMM, NAMD and X-PLOR protein structure file",
    .extensions = "psf",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_WRITE_STRUCTURE,
    .open_read = psf_open_read,
    .read_structure = psf_read_structure,
    .close_read = psf_close_read,
    .open_write = psf_open_write,
    .write_structure = psf_write_structure,
    .close_write = psf_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &psf_plugin; }
