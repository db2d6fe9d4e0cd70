/* measure.h: the numbers behind VMD's `measure` command, computed over atoms of a molecule:
 * centers, extents, radius of gyration, RMSD and optimal superposition, inertia, averages
 * and fluctuations over frames, contacts and hydrogen bonds, solvent-accessible surface
 * area, and radial distribution functions. Pair searches go through a uniform cell grid, so
 * they are linear in the number of atoms; the heavy loops run on all cores.
 *
 * Every function takes atoms as an ms_atomset (molecule, frame, ascending atom indices),
 * returns 0 or -1 with err filled, and knows nothing about Tcl. Weights, where taken, are
 * one per atom of the set (NULL = all 1). */
#ifndef MS_MEASURE_H
#define MS_MEASURE_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"
#include "molecule/molecule.h"

/* Atoms of one frame of a molecule. */
typedef struct ms_atomset {
    const ms_molecule *mol;
    size_t frame;            /* must be < mol->nframes */
    const uint32_t *atoms;   /* ascending, each < mol->atoms.n */
    size_t n;
} ms_atomset;

/* Check that the frame exists and has its coordinates in memory (a streamed frame is read);
 * -1 with "molecule N has no frame F" or the read error otherwise. */
int ms_atomset_check(const ms_atomset *s, ms_error *err);
/* Coordinates of the set's frame (x y z per atom of the molecule). */
static inline const float *ms_atomset_pos(const ms_atomset *s)
{
    return s->mol->frames[s->frame].pos;
}

/* ---- per-atom values usable as weights */

/* Is `keyword` a floating-point atom keyword (mass charge beta occupancy radius user user2
 * user3 user4 x y z vx vy vz)? Integer and string keywords (index, resid, name...) are
 * recognised separately so a caller can say why they cannot be weights. */
int ms_measure_is_float_keyword(const char *keyword);
int ms_measure_is_atom_keyword(const char *keyword);
/* The keyword's value for each atom of the set (n values). */
int ms_measure_atom_values(const ms_atomset *s, const char *keyword, double *out,
                           ms_error *err);
double ms_measure_sumweights(const double *w, size_t n);

/* ---- one set */

/* Weighted mean position; fails when the weights sum to zero (or the set is empty). */
int ms_measure_center(const ms_atomset *s, const double *w, double c[3], ms_error *err);
/* Bounding box of the atom centres, or of the spheres with -withradii. Fails when empty. */
int ms_measure_minmax(const ms_atomset *s, int with_radii, double lo[3], double hi[3],
                      ms_error *err);
/* sqrt(sum w |r - c|^2 / sum w) about the weighted center c. */
int ms_measure_rgyr(const ms_atomset *s, const double *w, double *rgyr, ms_error *err);

typedef struct ms_inertia {
    double com[3];           /* center of mass */
    double axes[3][3];       /* principal axes (unit rows), largest moment first */
    double tensor[3][3];     /* the inertia tensor about the center of mass */
    double moments[3];       /* its eigenvalues, decreasing */
} ms_inertia;
/* Mass-weighted inertia (always masses, as VMD does); fails when the total mass is zero. */
int ms_measure_inertia(const ms_atomset *s, ms_inertia *out, ms_error *err);

/* ---- two sets, atom i of a paired with atom i of b */

/* sqrt(sum w |a_i - b_i|^2 / sum w), without fitting. */
int ms_measure_rmsd(const ms_atomset *a, const ms_atomset *b, const double *w, double *rmsd,
                    ms_error *err);
/* The rigid motion (rotation then translation, never a reflection) that moves a onto b with
 * the least weighted RMSD, as a row-major 4x4 matrix. order, when not NULL, pairs atom i of
 * a with atom order[i] of b (indices into the set, 0 .. n-1). */
int ms_measure_fit(const ms_atomset *a, const ms_atomset *b, const double *w,
                   const uint32_t *order, double m[16], ms_error *err);
/* The same for plain points: x and y are n points (3n doubles), x is moved onto y. Horn's
 * quaternion method: the largest eigenvector of a 4x4 symmetric matrix built from the
 * weighted covariance. */
int ms_measure_fit_points(size_t n, const double *x, const double *y, const double *w,
                          double m[16], ms_error *err);

/* ---- frames of one molecule */

typedef struct ms_frame_range {
    size_t first, last, step;     /* inclusive, step >= 1, last < nframes */
} ms_frame_range;
/* VMD's first/last/step with last = -1 meaning the last frame; -1 when the range is empty
 * or outside the molecule's frames. */
int ms_frame_range_make(const ms_molecule *m, long first, long last, long step,
                        ms_frame_range *r, ms_error *err);
/* Average position of each atom over the frames (3 n values). */
int ms_measure_avpos(const ms_molecule *m, const uint32_t *atoms, size_t n,
                     const ms_frame_range *r, double *avpos, ms_error *err);
/* RMS fluctuation of each atom about its average position over the frames (n values). */
int ms_measure_rmsf(const ms_molecule *m, const uint32_t *atoms, size_t n,
                    const ms_frame_range *r, double *rmsf, ms_error *err);

/* ---- pairs */

/* Atom index pairs, a[k] with b[k]. */
typedef struct ms_pairs {
    uint32_t *a, *b;
    size_t n, cap;
} ms_pairs;
void ms_pairs_free(ms_pairs *p);

/* Pairs of an atom of a and an atom of b closer than or at cutoff, sorted by (a, b), as VMD
 * reports them: with b == NULL (or the same atoms of the same frame) each unordered pair
 * once with a < b, skipping atoms at the same place; with two sets of one molecule a pair
 * of atoms in both sets once; bonded pairs of one molecule are left out. */
int ms_measure_contacts(const ms_atomset *a, const ms_atomset *b, double cutoff,
                        ms_pairs *out, ms_error *err);

typedef struct ms_hbonds {
    uint32_t *donor, *acceptor, *hydrogen;
    size_t n, cap;
} ms_hbonds;
void ms_hbonds_free(ms_hbonds *h);
/* Hydrogen bonds D-H...A: D in donors and A in acceptors (both from `donors` when acceptors
 * is NULL), neither a hydrogen, not bonded to each other, D-A distance <= cutoff, H a
 * hydrogen bonded to D, and the angle between D->H and H->A below `angle` degrees (0 for a
 * straight bond). Sorted by donor, acceptor, hydrogen. The sets must share molecule and
 * frame, and the molecule needs bonds to have any hydrogen bonds. */
int ms_measure_hbonds(const ms_atomset *donors, const ms_atomset *acceptors, double cutoff,
                      double angle, ms_hbonds *out, ms_error *err);

/* ---- surfaces */

typedef struct ms_sasa_opts {
    double srad;                   /* probe radius added to every atom radius */
    int samples;                   /* points per sphere (VMD's default 500) */
    const uint32_t *restrict_to;   /* only these atoms contribute (ascending); NULL = all */
    size_t nrestrict;
    int want_points;               /* also return the exposed points */
} ms_sasa_opts;
/* Shrake-Rupley solvent-accessible area of the set, alone (atoms outside it do not bury
 * anything): each sphere of radius r + srad carries the same golden-spiral point set, a
 * point is exposed unless it lies within r' + srad of another atom of the set. With
 * want_points, *points gets the exposed points of the contributing atoms (3 floats each,
 * malloc'd) in atom order. */
int ms_measure_sasa(const ms_atomset *s, const ms_sasa_opts *o, double *area, float **points,
                    size_t *npoints, ms_error *err);
/* The k-th of n golden-spiral points on the unit sphere. */
void ms_sphere_point(size_t k, size_t n, double p[3]);

/* ---- radial distribution: g(r) accumulated frame by frame, with VMD's normalisation */

typedef struct ms_gofr ms_gofr;
/* Bins of width delta up to rmax ((int)(rmax / delta + 1) bins, centred at (i + 0.5)
 * delta); usepbc takes minimum-image distances in each frame's unit cell. */
ms_gofr *ms_gofr_new(double delta, double rmax, int usepbc, ms_error *err);
void ms_gofr_free(ms_gofr *g);
/* Add one frame: pairs of an atom of a and a different atom of b. Fails on a periodic
 * frame without a usable cell. A frame where either set is empty is counted as skipped. */
int ms_gofr_add_frame(ms_gofr *g, const ms_molecule *m, size_t frame, const uint32_t *a,
                      size_t na, const uint32_t *b, size_t nb, ms_error *err);

typedef struct ms_gofr_result {
    size_t nbins;
    const double *r, *gofr, *numint, *hist;   /* averaged over the frames added */
    long frames_total, frames_skipped, frames_done;
} ms_gofr_result;
/* The averages so far (pointers stay valid until the next call or ms_gofr_free). */
void ms_gofr_get(ms_gofr *g, ms_gofr_result *res);

#endif
