/* fuzz.h: what every fuzz target does with an input: write the bytes to a scratch file, load
 * it through one plugin as `mol new ... waitfor all` would, write the molecule back out with
 * the same plugin when it can write, and free everything. A target is one line around
 * ms_fuzz_load (fuzz_<fmt>.c); driver.c or libFuzzer calls it. */
#ifndef MS_FUZZ_H
#define MS_FUZZ_H

#include "config.h"
#include "fileio/load.h"
#include "fileio/write.h"

#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

static char ms_fuzz_in[4096], ms_fuzz_out[4200];

static void ms_fuzz_cleanup(void)
{
    if (ms_fuzz_in[0]) unlink(ms_fuzz_in);
}

/* The scratch file, created once per process. */
static int ms_fuzz_scratch(void)
{
    if (ms_fuzz_in[0]) return 0;
    const char *dir = getenv("TMPDIR");
    snprintf(ms_fuzz_in, sizeof ms_fuzz_in, "%s/msfuzz_XXXXXX", dir && *dir ? dir : "/tmp");
    int fd = mkstemp(ms_fuzz_in);
    if (fd < 0) {
        perror("fuzz: mkstemp");
        ms_fuzz_in[0] = '\0';
        return -1;
    }
    close(fd);
    snprintf(ms_fuzz_out, sizeof ms_fuzz_out, "%s.out", ms_fuzz_in);
    atexit(ms_fuzz_cleanup);
    return 0;
}

/* The input into the scratch file, and a registry holding p alone. */
static void ms_fuzz_prepare(const ms_plugin *p, const uint8_t *data, size_t size,
                            ms_registry *reg, ms_load_opts *o)
{
    if (ms_fuzz_scratch()) abort();
    FILE *f = fopen(ms_fuzz_in, "wb");
    if (!f || fwrite(data, 1, size, f) != size || fclose(f) != 0) abort();
    ms_registry_init(reg);
    if (ms_registry_add(reg, p, NULL, NULL) < 0) abort();
    ms_load_opts_default(o);
    o->type = p->name;
    o->waitfor = -1;
}

/* Write m back with p when it can write, then free m and the registry. */
static void ms_fuzz_write_back(const ms_plugin *p, ms_registry *reg, ms_molecule *m)
{
    ms_error err = {{0}};
    if (m && p->open_write) {
        ms_write_opts w;
        ms_write_opts_default(&w);
        w.type = p->name;
        if (ms_write_file(reg, m, ms_fuzz_out, &w, &err) >= 0) unlink(ms_fuzz_out);
    }
    ms_mol_free(m);
    ms_registry_free(reg);
}

static inline int ms_fuzz_load(const ms_plugin *p, const uint8_t *data, size_t size)
{
    ms_registry reg;
    ms_load_opts o;
    ms_fuzz_prepare(p, data, size, &reg, &o);
    ms_error err = {{0}};
    ms_fuzz_write_back(p, &reg, ms_load_new(&reg, ms_fuzz_in, &o, &err));
    return 0;
}

/* For a format of frames alone that does not give the atom count (AMBER's crd): add the
 * input to a molecule of natoms blank atoms, as `mol addfile` after a structure does. */
static inline int ms_fuzz_load_frames(const ms_plugin *p, size_t natoms, const uint8_t *data,
                               size_t size)
{
    ms_registry reg;
    ms_load_opts o;
    ms_fuzz_prepare(p, data, size, &reg, &o);
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    if (!m) abort();
    for (size_t i = 0; i < natoms; i++)
        if (ms_mol_add_blank_atom(m, &err) < 0) abort();
    ms_load_add(&reg, m, ms_fuzz_in, &o, &err);
    ms_fuzz_write_back(p, &reg, m);
    return 0;
}

#endif
