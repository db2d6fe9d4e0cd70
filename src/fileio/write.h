/* write.h: writing molecules (all atoms or a selection, a range of frames) through plugins.
 * Output goes to a temporary file beside the target and is renamed into place only when
 * complete, so a failed write never leaves a partial file. */
#ifndef MS_WRITE_H
#define MS_WRITE_H

#include "fileio/registry.h"
#include "molecule/molecule.h"

typedef struct ms_write_opts {
    const char *type;         /* plugin name; NULL = from the extension */
    const uint32_t *atoms;    /* indices to write, ascending; NULL = all */
    size_t natoms;            /* with atoms != NULL */
    long first, last, step;   /* frames, inclusive; last < 0 = the last frame */
    const char *options;      /* writer options for the plugin (ms_struct_view.options) */
} ms_write_opts;

void ms_write_opts_default(ms_write_opts *o);

/* Returns the number of frames written, or -1 with err set. */
long ms_write_file(const ms_registry *r, ms_molecule *m, const char *path,
                   const ms_write_opts *o, ms_error *err);

/* Write one volume through a plugin that writes volumes (type NULL: from the extension),
 * through a temporary file renamed into place. Returns 0 or -1 with err set. */
int ms_write_volume(const ms_registry *r, const ms_volume *v, const char *path,
                    const char *type, ms_error *err);

#endif
