/* assembly.h: biological assemblies built at load time (`mol new file.cif assembly 1`): the
 * generators a structure reader reports (index ranges of the file's atoms and the operators
 * that copy them), the choice of one assembly, and the expansion of atoms, coordinates and
 * file bonds into its copies. Used by load.c. */
#ifndef MS_ASSEMBLY_H
#define MS_ASSEMBLY_H

#include "molecule/molecule.h"

typedef struct ms_asm_gen {
    char *id;                /* the assembly this generator belongs to */
    size_t nranges, nops;
    size_t (*ranges)[2];     /* half-open ranges of file atom indices */
    double (*ops)[12];       /* 3x4 row-major [R | t] */
    size_t natoms;           /* atoms in one copy */
} ms_asm_gen;

typedef struct ms_asm_plan {
    ms_asm_gen *gen;
    size_t ngen;
    size_t nfile;            /* atoms in the file (the index space of the ranges) */
} ms_asm_plan;

void ms_asm_plan_free(ms_asm_plan *p);
/* Append a generator (copied). Returns 0 or -1 (out of memory). */
int ms_asm_plan_add(ms_asm_plan *p, const char *id, size_t nranges, const size_t (*ranges)[2],
                    size_t nops, const double (*ops)[12], ms_error *err);
/* The generators of assembly `id` among all (copied into *out, out->nfile = nfile); ranges
 * are clipped to the file's atoms. An error lists the assemblies the file has. */
int ms_asm_select(const ms_asm_plan *all, const char *id, size_t nfile, ms_asm_plan *out,
                  ms_error *err);
/* Atoms the assembly makes. */
size_t ms_asm_natoms(const ms_asm_plan *p);
/* Replace m's atoms (the file's, p->nfile of them) by the assembly's copies; each copy's
 * segname is its 1-based number. */
int ms_asm_expand_atoms(ms_molecule *m, const ms_asm_plan *p, ms_error *err);
/* Coordinates of the file's atoms (src, 3 per atom) to the assembly's (dst); vectors
 * (velocities) are rotated only. */
void ms_asm_expand_xyz(const ms_asm_plan *p, const float *src, float *dst, int vectors);
/* File bond pairs (2 uint32 each) to the assembly's: a bond is copied with its atoms when
 * both are in a generator. *out is malloc'd. */
int ms_asm_expand_pairs(const ms_asm_plan *p, const uint32_t *pairs, const float *orders,
                        size_t npairs, uint32_t **out, float **out_orders, size_t *nout,
                        ms_error *err);

#endif
