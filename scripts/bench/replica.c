/* replica.c: the benchmarks' million-atom system (replica.h). */
#include "config.h"
#include "fileio/load.h"
#include "replica.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

const ms_plugin *ms_plugin_entry(void);

int bench_sys_make(const char *data, int copies, bench_sys *s)
{
    ms_registry reg;
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry(), NULL, NULL);
    char path[1024];
    snprintf(path, sizeof path, "%s/1tii.pdb", data);
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    ms_error err = {{0}};
    ms_molecule *m = ms_load_new(&reg, path, &o, &err);
    if (!m) {
        fprintf(stderr, "bench: %s: %s\n", path, err.msg);
        return -1;
    }
    size_t n0 = m->atoms.n, nb0 = m->bonds.start[n0];
    s->n0 = n0;
    s->n = n0 * (size_t)copies;
    s->pos = malloc(3 * s->n * sizeof(float));
    s->radius = malloc(s->n * sizeof(float));
    s->color = malloc(s->n * sizeof(ms_rgba8));
    s->bstart = malloc((s->n + 1) * sizeof(uint32_t));
    s->bto = malloc(nb0 * (size_t)copies * sizeof(uint32_t));
    if (!s->pos || !s->radius || !s->color || !s->bstart || !s->bto) return -1;
    const float *p0 = ms_mol_pos(m);
    int side = 1;
    while (side * side * side < copies) side++;
    for (int c = 0; c < copies; c++) {
        float off[3] = {(float)(c % side) * 120.0f, (float)(c / side % side) * 120.0f,
                        (float)(c / side / side) * 180.0f};
        for (size_t i = 0; i < n0; i++) {
            size_t a = (size_t)c * n0 + i;
            for (int k = 0; k < 3; k++) s->pos[3 * a + k] = p0[3 * i + k] + off[k];
            s->radius[a] = m->atoms.radius[i];
            int z = m->atoms.atomicnumber[i];
            s->color[a] = z == 6 ? (ms_rgba8){64, 191, 191, 255} : z == 8 ? (ms_rgba8){255, 0, 0, 255}
                          : z == 7 ? (ms_rgba8){0, 0, 255, 255} : (ms_rgba8){255, 255, 0, 255};
            s->bstart[a] = (uint32_t)((size_t)c * nb0 + m->bonds.start[i]);
        }
        for (size_t b = 0; b < nb0; b++) s->bto[(size_t)c * nb0 + b] = m->bonds.to[b] + (uint32_t)((size_t)c * n0);
    }
    s->bstart[s->n] = (uint32_t)(nb0 * (size_t)copies);
    ms_mol_free(m);
    ms_registry_free(&reg);
    return 0;
}

void bench_sys_free(bench_sys *s)
{
    free(s->pos);
    free(s->radius);
    free(s->color);
    free(s->bstart);
    free(s->bto);
    memset(s, 0, sizeof *s);
}
