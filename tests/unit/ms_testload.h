/* ms_testload.h: for unit tests that link the readers: a registry of the built-in plugins
 * (the test's main registers them in reg) and load(), which reads tests/data/<name> with
 * every frame, reporting a failed load as a failed check. */
#ifndef MS_TESTLOAD_H
#define MS_TESTLOAD_H

#include "builtin/builtin.h"
#include "fileio/load.h"
#include "ms_test.h"

static ms_registry reg;

static ms_molecule *load(const char *name) __attribute__((unused));
static ms_molecule *load(const char *name)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", t_data(), name);
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    ms_error err = {{0}};
    ms_molecule *m = ms_load_new(&reg, path, &o, &err);
    if (!m) t_ok(0, "load %s: %s", name, err.msg);
    return m;
}

#endif
