/* msdump.c: a test tool that loads files as `mol new` and `mol addfile` do (every frame,
 * the plugins linked in) and prints what it read as tab-separated lines, for cross-checks
 * against independent readers:
 *   natoms  N
 *   nframes F
 *   atom    i name resname resid segname chain      (once per atom, 0-based i)
 *   cell    k a b c alpha beta gamma                (once per frame)
 *   xyz     k i x y z                               (per frame and atom)
 *   volume  v n0 n1 n2 ox oy oz d00 d01 ... d22 min max mean  (once per volume)
 * and with -f (first on the line) also the force-field side:
 *   prop    i type charge mass atomicnumber         (once per atom)
 *   bond    i j                                     (once per bond, i < j)
 *   term    kind a b c [d]                          (angle, dihedral, improper)
 *   vel     k i vx vy vz                            (per frame and atom, with velocities)
 *   time    k t                                     (once per frame)
 * usage: msdump [-f] [-o out] [-a assembly] [-s step] [-t type] file [[-t type] file ...]: the
 * first file makes the molecule, the others are added to it (every step-th frame of those
 * after -s); with -o the molecule (every frame) is written to `out` instead, in the format
 * its extension names (a volume format writes the first volume); -a builds a biological
 * assembly from the first file. Exit status 1 with the error on stderr
 * when a load or the write fails. */
#include "config.h"
#include "builtin/builtin.h"
#include "fileio/load.h"
#include "fileio/write.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* The -f lines: types, charges, masses, atomic numbers, bonds, terms, velocities, times. */
static void dump_full(const ms_molecule *m)
{
    const ms_atoms *a = &m->atoms;
    for (size_t i = 0; i < a->n; i++)
        printf("prop\t%zu\t%s\t%.9g\t%.9g\t%d\n", i, ms_mol_str(m, a->type[i]),
               (double)a->charge[i], (double)a->mass[i], a->atomicnumber[i]);
    for (size_t i = 0; m->has_bonds && i < a->n; i++)
        for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++)
            if (m->bonds.to[k] > i) printf("bond\t%zu\t%u\n", i, m->bonds.to[k]);
    static const char *const kinds[MS_TERM_KINDS] = {"angle", "dihedral", "improper"};
    for (int kind = 0; kind < MS_TERM_KINDS; kind++) {
        const ms_terms *t = &m->terms[kind];
        size_t w = ms_term_width(kind);
        for (size_t k = 0; k < t->n; k++) {
            printf("term\t%s", kinds[kind]);
            for (size_t q = 0; q < w; q++) printf("\t%u", t->atoms[k * w + q]);
            printf("\n");
        }
    }
    for (size_t k = 0; k < m->nframes; k++) {
        const ms_frame *f = &m->frames[k];
        printf("time\t%zu\t%.9g\n", k, f->time);
        for (size_t i = 0; f->vel && i < a->n; i++)
            printf("vel\t%zu\t%zu\t%.9g\t%.9g\t%.9g\n", k, i, (double)f->vel[3 * i],
                   (double)f->vel[3 * i + 1], (double)f->vel[3 * i + 2]);
    }
}

static void dump(const ms_molecule *m)
{
    const ms_atoms *a = &m->atoms;
    printf("natoms\t%zu\nnframes\t%zu\n", a->n, m->nframes);
    for (size_t i = 0; i < a->n; i++)
        printf("atom\t%zu\t%s\t%s\t%d\t%s\t%s\n", i, ms_mol_str(m, a->name[i]),
               ms_mol_str(m, a->resname[i]), a->resid[i], ms_mol_str(m, a->segname[i]),
               ms_mol_str(m, a->chain[i]));
    for (size_t k = 0; k < m->nframes; k++) {
        const ms_frame *f = &m->frames[k];
        printf("cell\t%zu", k);
        for (int c = 0; c < 6; c++) printf("\t%.9g", (double)f->cell[c]);
        printf("\n");
        for (size_t i = 0; i < a->n; i++)
            printf("xyz\t%zu\t%zu\t%.9g\t%.9g\t%.9g\n", k, i, (double)f->pos[3 * i],
                   (double)f->pos[3 * i + 1], (double)f->pos[3 * i + 2]);
    }
    for (size_t k = 0; k < m->nvolumes; k++) {
        const ms_volume *v = &m->volumes[k];
        printf("volume\t%zu\t%d\t%d\t%d", k, v->n[0], v->n[1], v->n[2]);
        for (int d = 0; d < 3; d++) printf("\t%.9g", (double)v->origin[d]);
        for (int d = 0; d < 9; d++) printf("\t%.9g", (double)v->delta[d / 3][d % 3]);
        printf("\t%.9g\t%.9g\t%.9g\n", (double)v->min, (double)v->max, (double)v->mean);
    }
}

int main(int argc, char **argv)
{
    ms_registry reg;
    ms_registry_init(&reg);
    if (ms_test_add_builtin(&reg)) {
        fprintf(stderr, "msdump: out of memory\n");
        return 1;
    }
    ms_molecule *m = NULL;
    ms_error err = {{0}};
    const char *type = NULL, *out = NULL, *assembly = NULL;
    long step = 1;
    int status = 0, full = argc > 1 && !strcmp(argv[1], "-f");
    for (int i = 1 + full; i < argc && status == 0; i++) {
        if (!strcmp(argv[i], "-t") && i + 1 < argc) {
            type = argv[++i];
            continue;
        }
        if (!strcmp(argv[i], "-o") && i + 1 < argc) {
            out = argv[++i];
            continue;
        }
        if (!strcmp(argv[i], "-a") && i + 1 < argc) {
            assembly = argv[++i];
            continue;
        }
        if (!strcmp(argv[i], "-s") && i + 1 < argc) {
            step = strtol(argv[++i], NULL, 10);
            continue;
        }
        ms_load_opts o;
        ms_load_opts_default(&o);
        o.waitfor = -1;
        o.step = step > 0 ? step : 1;
        o.type = type;
        o.assembly = m ? NULL : assembly;
        type = NULL;
        int failed = m ? ms_load_add(&reg, m, argv[i], &o, &err) != 0
                       : (m = ms_load_new(&reg, argv[i], &o, &err)) == NULL;
        if (failed) {
            fprintf(stderr, "msdump: %s: %s\n", argv[i], err.msg);
            status = 1;
        }
    }
    if (!m && status == 0) {
        fprintf(stderr, "usage: msdump [-f] [-o out] [-a assembly] [-s step] [-t type] file "
                        "[[-t type] file ...]\n");
        status = 1;
    }
    if (status == 0 && out) {
        ms_write_opts wo;
        ms_write_opts_default(&wo);
        const ms_plugin *wp = ms_registry_for_path(&reg, out);
        int vol = wp && (wp->caps & MS_CAN_WRITE_VOLUME) && m->nvolumes;
        if (vol ? ms_write_volume(&reg, &m->volumes[0], out, NULL, &err) < 0
                : ms_write_file(&reg, m, out, &wo, &err) < 0) {
            fprintf(stderr, "msdump: %s: %s\n", out, err.msg);
            status = 1;
        }
    } else if (status == 0) {
        dump(m);
        if (full) dump_full(m);
    }
    ms_mol_free(m);
    ms_registry_free(&reg);
    return status;
}
