/* ms_testload.h: for unit tests that link the readers: a registry of the built-in plugins
 * (the test's main registers them in reg); load(), which reads tests/data/<name> with every
 * frame, reporting a failed load as a failed check; load_err(), the same load leaving the
 * error to the caller; and count(), the number of atoms a selection picks. */
#ifndef MS_TESTLOAD_H
#define MS_TESTLOAD_H

#include "builtin/builtin.h"
#include "fileio/load.h"
#include "ms_test.h"
#include "select/select.h"

static ms_registry reg;

/* tests/data/<name> with every frame, or NULL with the reason in *err. */
static ms_molecule *load_err(const char *name, ms_error *err) __attribute__((unused));
static ms_molecule *load_err(const char *name, ms_error *err)
{
    char path[1024];
    snprintf(path, sizeof path, "%s/%s", t_data(), name);
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    return ms_load_new(&reg, path, &o, err);
}

static ms_molecule *load(const char *name) __attribute__((unused));
static ms_molecule *load(const char *name)
{
    ms_error err = {{0}};
    ms_molecule *m = load_err(name, &err);
    if (!m) t_ok(0, "load %s: %s", name, err.msg);
    return m;
}

/* Number of atoms a selection picks in the current frame, or -1 on error (the error is
 * printed). */
static long count(ms_molecule *m, const char *text) __attribute__((unused));
static long count(ms_molecule *m, const char *text)
{
    ms_bitset b;
    ms_error err = {{0}};
    if (ms_sel_select(m, -1, text, &b, &err)) {
        printf("  (%s: %s)\n", text, err.msg);
        return -1;
    }
    long n = (long)ms_bitset_count(&b);
    ms_bitset_free(&b);
    return n;
}

#endif
