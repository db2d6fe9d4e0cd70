/* options.c: parsing molscope's command line the way VMD parses its own. Options are
 * matched case-insensitively; -args hands every later word to Tcl. */
#include "config.h"
#include "app/options.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

void ms_options_usage(const char *argv0)
{
    printf("usage: %s [options] [files...]\n"
           "  -dispdev text|none|osmesa|egl|opengl|openglpbuffer|win\n"
           "                     display device (text and none need no display)\n"
           "  -e <script>        run a Tcl script after startup\n"
           "  -python            the -e script is Python (built with Python only)\n"
           "  -eofexit           exit when standard input ends\n"
           "  -args ...          pass every later argument to Tcl's argv\n"
           "  -size <w> <h>      display size in pixels (default 512 512)\n"
           "  -pos <x> <y>       window position (accepted; no windows are opened)\n"
           "  -startup <file>    run this file instead of .molscoperc / .vmdrc\n"
           "  -m                 each later file becomes a molecule of its own\n"
           "  -f                 later files go into one molecule (the default)\n"
           "  -<type> <file>     read the file as this type (-pdb, -psf, -dcd, ...)\n"
           "  -nt, -dist <d>, -height <h>\n"
           "                     accepted for VMD compatibility\n"
           "  -h, --help         this message\n"
           "  --version          print the version\n"
           "Startup: the Tcl library's init.tcl, the files named here, the first of\n"
           "./.molscoperc and ~/.molscoperc (else ./.vmdrc or ~/.vmdrc), then the -e script.\n",
           argv0);
}

static int need_args(int i, int n, int argc, const char *opt)
{
    if (i + n < argc) return 0;
    fprintf(stderr, "molscope: option %s needs %d argument%s\n", opt, n, n > 1 ? "s" : "");
    return -1;
}

static int parse_size(const char *s, int *out, const char *what)
{
    char *end;
    long v = strtol(s, &end, 10);
    if (*s == '\0' || *end != '\0' || v < 1 || v > 32768) {
        fprintf(stderr, "molscope: -size: bad %s '%s' (1 to 32768 pixels)\n", what, s);
        return -1;
    }
    *out = (int)v;
    return 0;
}

int ms_options_parse(int argc, char **argv, int (*is_type)(void *, const char *), void *ud,
                     ms_options *o)
{
    memset(o, 0, sizeof *o);
    o->files = calloc((size_t)argc + 1, sizeof *o->files);
    if (!o->files) return -1;
    int new_each = 0;
    const char *forced = NULL;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i];
        if (a[0] != '-' || a[1] == '\0') {
            ms_cmdfile *f = &o->files[o->nfiles];
            f->path = a;
            f->type = forced;
            f->new_molecule = new_each || o->nfiles == 0;
            o->nfiles++;
            forced = NULL;
            continue;
        }
        const char *opt = a + 1;
        if (opt[0] == '-') opt++; /* --help, --version */
        if (!strcasecmp(opt, "args")) {
            o->tcl_argc = argc - i - 1;
            o->tcl_argv = argv + i + 1;
            break;
        } else if (!strcasecmp(opt, "dispdev")) {
            if (need_args(i, 1, argc, a)) return -1;
            o->dispdev = argv[++i];
        } else if (!strcasecmp(opt, "e")) {
            if (need_args(i, 1, argc, a)) return -1;
            o->escript = argv[++i];
        } else if (!strcasecmp(opt, "startup")) {
            if (need_args(i, 1, argc, a)) return -1;
            o->startup = argv[++i];
        } else if (!strcasecmp(opt, "eofexit")) {
            o->eofexit = 1;
        } else if (!strcasecmp(opt, "size")) {
            if (need_args(i, 2, argc, a) || parse_size(argv[i + 1], &o->width, "width") ||
                parse_size(argv[i + 2], &o->height, "height"))
                return -1;
            i += 2;
        } else if (!strcasecmp(opt, "pos")) {
            if (need_args(i, 2, argc, a)) return -1;
            i += 2;
        } else if (!strcasecmp(opt, "dist") || !strcasecmp(opt, "height")) {
            if (need_args(i, 1, argc, a)) return -1;
            i++;
        } else if (!strcasecmp(opt, "nt")) {
            /* no window title: nothing to do without windows */
        } else if (!strcasecmp(opt, "m")) {
            new_each = 1;
        } else if (!strcasecmp(opt, "f")) {
            new_each = 0;
        } else if (!strcasecmp(opt, "h") || !strcasecmp(opt, "help")) {
            o->help = 1;
        } else if (!strcasecmp(opt, "version")) {
            o->version = 1;
        } else if (!strcasecmp(opt, "python")) {
#ifdef MS_HAVE_PYTHON
            o->python = 1;
#else
            fprintf(stderr, "molscope: -python: this molscope was built without Python "
                            "(configure --with-python)\n");
            return -1;
#endif
        } else if (is_type && is_type(ud, opt)) {
            if (need_args(i, 1, argc, a)) return -1;
            forced = opt;
        } else {
            fprintf(stderr, "molscope: unknown option %s (see -h)\n", a);
            return -1;
        }
    }
    if (forced) {
        fprintf(stderr, "molscope: -%s needs a file name\n", forced);
        return -1;
    }
    return 0;
}

void ms_options_free(ms_options *o)
{
    free(o->files);
    memset(o, 0, sizeof *o);
}
