/* bench_ss.c: how long ms_ss_compute (DSSP over every protein residue) takes on a loaded
 * structure, the median and best of R runs, and a check that a replicated system (copies
 * told apart by segment name, as scripts/bench/replicate.py writes them) gets the same
 * assignment in every copy.
 *
 * usage: bench_ss file.pdb [repeats]      (run by scripts/bench/bench_ss.sh) */
#include "config.h"
#include "base/threads.h"
#include "fileio/load.h"
#include "ss/ss.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

#include "builtin/builtin.h"

static int cmp_double(const void *a, const void *b)
{
    double x = *(const double *)a, y = *(const double *)b;
    return x < y ? -1 : x > y;
}

/* Residues whose code differs from the same residue of the first copy (same position in
 * the copy's run of residues). */
static size_t copy_mismatches(const ms_molecule *m, size_t *ncopies)
{
    size_t per = 0, bad = 0;
    ms_str seg0 = m->atoms.segname[0];
    while (per < m->nresidues && m->atoms.segname[m->res_start[per]] == seg0) per++;
    *ncopies = per ? m->nresidues / per : 0;
    for (size_t r = per; r < m->nresidues; r++)
        bad += m->atoms.ss[m->res_start[r]] != m->atoms.ss[m->res_start[r % per]];
    return bad;
}

int main(int argc, char **argv)
{
    if (argc < 2) {
        fprintf(stderr, "usage: bench_ss file.pdb [repeats]\n");
        return 2;
    }
    int repeats = argc > 2 ? atoi(argv[2]) : 5;
    if (repeats < 1) repeats = 1;
    ms_registry reg;
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    ms_load_opts o;
    ms_load_opts_default(&o);
    o.waitfor = -1;
    ms_error err = {{0}};
    double t0 = ms_now();
    ms_molecule *m = ms_load_new(&reg, argv[1], &o, &err);
    if (!m) {
        fprintf(stderr, "bench_ss: %s: %s\n", argv[1], err.msg);
        return 1;
    }
    double tload = ms_now() - t0, *t = calloc((size_t)repeats, sizeof *t);
    double *cpu = calloc((size_t)repeats, sizeof *cpu);
    for (int k = 0; k < repeats; k++) {
        clock_t c0 = clock();
        t0 = ms_now();
        if (ms_ss_compute(m, -1, &err)) {
            fprintf(stderr, "bench_ss: %s\n", err.msg);
            return 1;
        }
        t[k] = ms_now() - t0;
        cpu[k] = (double)(clock() - c0) / CLOCKS_PER_SEC;
    }
    qsort(t, (size_t)repeats, sizeof *t, cmp_double);
    qsort(cpu, (size_t)repeats, sizeof *cpu, cmp_double);
    size_t counts[256] = {0}, ncopies, bad = copy_mismatches(m, &ncopies);
    for (size_t r = 0; r < m->nresidues; r++) counts[(unsigned char)m->atoms.ss[m->res_start[r]]]++;
    printf("%s: %zu atoms, %zu residues, loaded in %.2f s, %d threads\n", argv[1], m->atoms.n,
           m->nresidues, tload, ms_threads_count());
    printf("  ms_ss_compute: wall median %.1f ms, best %.1f ms; CPU median %.1f ms (%d runs)\n",
           1e3 * t[repeats / 2], 1e3 * t[0], 1e3 * cpu[repeats / 2], repeats);
    printf("  residues H %zu G %zu I %zu E %zu B %zu T %zu C %zu; %zu copies, %zu residues "
           "differ from the first copy\n", counts['H'], counts['G'], counts['I'], counts['E'],
           counts['B'], counts['T'], counts['C'], ncopies, bad);
    free(t);
    free(cpu);
    ms_mol_free(m);
    ms_registry_free(&reg);
    return bad ? 1 : 0;
}
