/* elements.h: the periodic table (symbols, masses, van der Waals radii) and VMD's rules for
 * guessing an element, mass and radius from an atom name when a file gives none. */
#ifndef MS_ELEMENTS_H
#define MS_ELEMENTS_H

#define MS_NUM_ELEMENTS 119   /* 0 = unknown ("X"), 1..118 */

const char *ms_element_symbol(int z);       /* "X" for 0 or out of range */
float ms_element_mass(int z);               /* standard atomic weight; 0 for unknown */
float ms_element_vdw_radius(int z);         /* Angstrom; 1.5 for unknown */
/* Atomic number of a symbol ("C", "Cl", "CL", "cl"), 0 when not an element. */
int ms_element_from_symbol(const char *sym);
/* Guess the atomic number from an atom name for files without an element column: leading
 * digits are skipped; an atom named like its residue takes the two-letter element (ions:
 * NA in NA, CL in CL, ZN in ZN); otherwise the first letter when it is an element, else the
 * first two letters. 0 when nothing matches. */
int ms_element_guess(const char *name, const char *resname);
/* VMD's name-based radius when no element is known: first letter after leading digits,
 * H 1.0, C 1.5, N 1.4, O 1.3, F 1.2, S 1.9, otherwise 1.5. */
float ms_element_radius_from_name(const char *name);

#endif
