/* options.h: molscope's command line, VMD's options: -dispdev, -e, -python, -eofexit, -args, -size,
 * -pos, -startup, -m/-f, -<type> file, -nt, -dist, -height, -h. */
#ifndef MS_OPTIONS_H
#define MS_OPTIONS_H

typedef struct ms_cmdfile {
    const char *path;
    const char *type;   /* forced with -<type>, else NULL */
    int new_molecule;   /* -m mode, or the first file */
} ms_cmdfile;

typedef struct ms_options {
    const char *dispdev;
    const char *escript;
    int python;              /* -python: escript is a Python script */
    const char *startup;
    int eofexit;
    int width, height;       /* 0 = default */
    int help, version;
    ms_cmdfile *files;
    int nfiles;
    int tcl_argc;            /* after -args */
    char **tcl_argv;
} ms_options;

/* Parse argv. Returns 0, or -1 after printing why to stderr. `is_type(name)` says whether
 * `-name` names a file type (a plugin). */
int ms_options_parse(int argc, char **argv, int (*is_type)(void *, const char *), void *ud,
                     ms_options *o);
void ms_options_free(ms_options *o);
void ms_options_usage(const char *argv0);

#endif
