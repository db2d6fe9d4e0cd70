/* xyz.c: the XYZ plugin. Each frame is an atom count line, a comment line and one line per
 * atom, "name x y z" (more columns are ignored); frames follow one another. Names come from
 * the first column (an atomic number there becomes the element's symbol) and elements are
 * guessed from them. Writes element symbols (the name when the element is unknown). */
#include "ms_plugin.h"
#include "plugin_util.h"

#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>

typedef struct xyz_reader {
    ms_lines in;
    long natoms;
    long long size;
} xyz_reader;

static void *xyz_open_read(const char *path, long *natoms, ms_perr *err)
{
    xyz_reader *r = ms_lines_create(sizeof *r, path, err);
    if (!r) return NULL;
    struct stat sb;
    r->size = fstat(fileno(r->in.fp), &sb) == 0 ? (long long)sb.st_size : 0;
    *natoms = -1;
    return r;
}

static void xyz_close_read(void *h)
{
    ms_lines_destroy(h);
}

/* The count line of the next frame: MS_PLUGIN_EOF when only blank lines remain. */
static int read_count(xyz_reader *r, long *n, ms_perr *err)
{
    ms_lines *in = &r->in;
    const char *l;
    while ((l = ms_lines_next(in)) && l[strspn(l, " \t")] == '\0') {}
    if (!l) return in->error ? ms_perr_set(err, "read error after line %ld", in->line_no)
                             : MS_PLUGIN_EOF;
    char *tok[2];
    int nt = ms_tokens(in->line, tok, 2);
    if (nt < 1 || ms_parse_long(tok[0], strlen(tok[0]), n) < 0 || *n < 1)
        return ms_perr_set(err, "line %ld: bad atom count '%.32s'", in->line_no,
                           nt ? tok[0] : "");
    if (!ms_lines_next(in))
        return ms_perr_set(err, "line %ld: the file ends before the frame's comment line",
                           in->line_no);
    return MS_PLUGIN_OK;
}

/* One atom line: name and coordinates. name may be NULL when only coordinates matter. */
static int read_atom(xyz_reader *r, long k, long n, char name[64], float xyz[3], ms_perr *err)
{
    ms_lines *in = &r->in;
    if (!ms_lines_next(in)) {
        if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
        return ms_perr_set(err, "line %ld: the file ends after %ld of %ld atoms", in->line_no, k,
                           n);
    }
    char *tok[4];
    if (ms_tokens(in->line, tok, 4) < 4)
        return ms_perr_set(err, "line %ld: expected 'name x y z'", in->line_no);
    static const char *const axis[3] = {"x", "y", "z"};
    for (int d = 0; d < 3; d++)
        if (ms_parse_float(tok[1 + d], strlen(tok[1 + d]), &xyz[d]) < 0)
            return ms_perr_set(err, "line %ld: bad %s coordinate '%.32s'", in->line_no, axis[d],
                               tok[1 + d]);
    if (name) snprintf(name, 64, "%s", tok[0]);
    return MS_PLUGIN_OK;
}

static int xyz_read_structure(void *h, ms_struct_sink *sink, ms_perr *err)
{
    xyz_reader *r = h;
    long n;
    int rc = read_count(r, &n, err);
    if (rc == MS_PLUGIN_EOF) return ms_perr_set(err, "empty file");
    if (rc != MS_PLUGIN_OK) return rc;
    /* an atom line ("C 0 0 0") is at least 8 bytes: the file bounds the count */
    if (ms_check_room(err, (double)n, 8, ms_lines_left(&r->in), "atoms",
                      "line %ld: the header declares %ld atoms", r->in.line_no - 1, n))
        return MS_PLUGIN_ERROR;
    long long most = r->size / 8 + 16;
    sink->reserve(sink, (size_t)(n < most ? n : most));
    for (long k = 0; k < n; k++) {
        char name[64], sym[4];
        ms_atom_in a;
        memset(&a, 0, sizeof a);
        float p[3];
        if (read_atom(r, k, n, name, p, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        long z;
        if (ms_parse_long(name, strlen(name), &z) == 1 && ms_plugin_symbol_of(z, sym)) {
            snprintf(name, sizeof name, "%s", sym);
            a.atomicnumber = (int)z;
            a.has |= MS_HAS_ATOMICNUMBER;
        }
        a.name = a.type = name;
        a.element = ms_plugin_element_like(name) ? name : NULL;
        a.resid = 1;
        a.x = p[0];
        a.y = p[1];
        a.z = p[2];
        a.has |= MS_HAS_POS;
        if (sink->add_atom(sink, &a))
            return ms_perr_set(err, "out of memory at line %ld", r->in.line_no);
    }
    r->natoms = n;
    return MS_PLUGIN_OK;
}

static int xyz_read_frame(void *h, long natoms, ms_frame_out *fr, ms_perr *err)
{
    xyz_reader *r = h;
    long n;
    int rc = read_count(r, &n, err);
    if (rc != MS_PLUGIN_OK) return rc;
    if (n != natoms)
        return ms_perr_set(err, "line %ld: frame has %ld atoms, expected %ld", r->in.line_no - 1,
                           n, natoms);
    for (long k = 0; k < n; k++) {
        float p[3];
        if (read_atom(r, k, n, NULL, p, err) != MS_PLUGIN_OK) return MS_PLUGIN_ERROR;
        if (fr->pos) memcpy(fr->pos + 3 * k, p, sizeof p);
    }
    return MS_PLUGIN_OK;
}

/* ---------------------------------------------------------------- writing */

typedef struct xyz_writer {
    ms_out out;
} xyz_writer;

static void *xyz_open_write(const char *path, long natoms, ms_perr *err)
{
    xyz_writer *w = ms_out_create(sizeof *w, path, err);
    if (!w) return NULL;
    return w;
}

static int xyz_write_frame(void *h, const ms_struct_view *v, const ms_frame_in *f, ms_perr *err)
{
    xyz_writer *w = h;
    ms_out *o = &w->out;
    ms_out_printf(o, "%zu\n molscope frame %d\n", v->natoms, f->index);
    for (size_t i = 0; i < v->natoms; i++) {
        ms_atom_in a;
        char sym[4];
        v->get_atom(v, i, &a);
        const char *label = a.atomicnumber > 0 && ms_plugin_symbol_of(a.atomicnumber, sym) ? sym
                            : a.name && a.name[0]                               ? a.name
                                                                                 : "X";
        const float *p = f->pos + 3 * i;
        ms_out_printf(o, "%-4s %14.6f %14.6f %14.6f\n", label, (double)p[0], (double)p[1],
                      (double)p[2]);
    }
    return o->failed ? ms_perr_set(err, "write failed") : MS_PLUGIN_OK;
}

static int xyz_close_write(void *h, ms_perr *err)
{
    xyz_writer *w = h;
    return ms_out_destroy(w, err);
}

static const ms_plugin xyz_plugin = {
    .abi = MS_PLUGIN_ABI,
    .name = "xyz",
    .description = "XYZ coordinates (XMol)",
    .extensions = "xyz",
    .caps = MS_CAN_READ_STRUCTURE | MS_CAN_READ_FRAMES | MS_CAN_WRITE_FRAMES,
    .open_read = xyz_open_read,
    .read_structure = xyz_read_structure,
    .read_frame = xyz_read_frame,
    .close_read = xyz_close_read,
    .open_write = xyz_open_write,
    .write_frame = xyz_write_frame,
    .close_write = xyz_close_write,
};

const ms_plugin *ms_plugin_entry(void) { return &xyz_plugin; }
