/* analysis.h: structure analysis after a load, as VMD does it: bonds by distance through a
 * cell grid (linear time), residues, fragments, protein/nucleic/water/hydrogen flags from
 * names and connectivity, secondary structure from file records. */
#ifndef MS_ANALYSIS_H
#define MS_ANALYSIS_H

#include "molecule/molecule.h"

/* Fill atom i's atomic number, mass and radius where the file gave none, and set its
 * hydrogen flag:
 * - element: from the file's symbol or number, else guessed from the name;
 * - mass: the element's, else 0;
 * - radius: the element's van der Waals radius when the file named the element, else VMD's
 *   name-based radius (H 1.0, C 1.5, N 1.4, O 1.3, F 1.2, S 1.9, others 1.5). */
void ms_analysis_atom_defaults(ms_molecule *m, size_t i, int have_mass, int have_radius,
                               int have_element);
/* The same for atoms first .. first+n-1 at once (a bulk load), each name and residue name
 * pair looked at once: an atom has an element when its atomicnumber is set (not 0). */
void ms_analysis_atoms_defaults(ms_molecule *m, size_t first, size_t n, int have_mass,
                                int have_radius);

/* Distance bonds for the given coordinates: d < 0.6 (r1 + r2), never H-H, never between
 * different non-blank altlocs. Pairs are appended to *pairs (2 uint32 each), *npairs counts
 * pairs. Returns 0 or -1 (out of memory). */
int ms_bond_search(const ms_molecule *m, const float *pos, uint32_t **pairs, size_t *npairs,
                   size_t *cap, ms_error *err);

/* Build the CSR bond table from undirected pairs (duplicates and self-pairs dropped). */
int ms_bonds_build(ms_molecule *m, const uint32_t *pairs, size_t npairs, const float *order,
                   ms_error *err);

/* Give the built bond table types: pair k (atoms pairs[2k], pairs[2k+1]) gets types[k]
 * (MS_STR_NONE leaves it as it is); bonds without a type read "". */
int ms_bonds_set_types(ms_molecule *m, const uint32_t *pairs, const ms_str *types,
                       size_t npairs, ms_error *err);

/* Residues (consecutive atoms sharing resid, insertion, chain and segname), fragments
 * (connected components), protein/nucleic/backbone/water flags. Needs bonds. */
int ms_analysis_classify(ms_molecule *m, ms_error *err);

/* Secondary structure ranges recorded at load time, applied to atoms by chain and resid. */
typedef struct ms_ss_range {
    char code, insertion0, insertion1;
    ms_str chain;
    int resid0, resid1;
} ms_ss_range;
void ms_analysis_apply_ss(ms_molecule *m, const ms_ss_range *r, size_t n);

/* Protein and nucleic fragments (pfrag, nfrag): computed on first use, -1 for atoms outside
 * any. Returns 0 or -1 on memory exhaustion. */
int ms_mol_polymer_fragments(ms_molecule *m, ms_error *err);

#endif
