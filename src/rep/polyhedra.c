/* polyhedra.c: VMD's Polyhedra method (distance cutoff, 3.0): for every selected atom, the
 * convex hull of the atoms bonded to it no farther than the cutoff (its coordination
 * polyhedron), drawn as flat triangles in the atom's colour. Three neighbours make one
 * triangle; fewer make nothing. The hull is found face by face: a triangle of neighbours is
 * a face when every other neighbour lies on its inner side; a face with more than three
 * neighbours in its plane (a square of an octahedron seen from outside, a cube's face) is
 * drawn once, as a fan from its lowest neighbour over the face's boundary edges. At most
 * MAX_NEIGH neighbours, the nearest, are used. */
#include "config.h"
#include "rep/rep_int.h"

#include <math.h>

#define MAX_NEIGH 32

typedef struct hull {
    float p[MAX_NEIGH][3];
    int n;
    float eps;
} hull;

static void sub(const float a[3], const float b[3], float o[3])
{
    for (int k = 0; k < 3; k++) o[k] = a[k] - b[k];
}

static float dot(const float a[3], const float b[3])
{
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

static void cross(const float a[3], const float b[3], float o[3])
{
    o[0] = a[1] * b[2] - a[2] * b[1];
    o[1] = a[2] * b[0] - a[0] * b[2];
    o[2] = a[0] * b[1] - a[1] * b[0];
}

/* The unit normal of the plane through i, j, k; 0 when they are (nearly) collinear. */
static int plane(const hull *h, int i, int j, int k, float nrm[3])
{
    float u[3], v[3];
    sub(h->p[j], h->p[i], u);
    sub(h->p[k], h->p[i], v);
    cross(u, v, nrm);
    float l = sqrtf(dot(nrm, nrm));
    if (l <= h->eps * h->eps) return 0;
    for (int c = 0; c < 3; c++) nrm[c] /= l;
    return 1;
}

/* Is the edge j-k of the face (normal nrm) on the face's boundary: every point of the face
 * on one side of it, within the plane? */
static int boundary_edge(const hull *h, const float nrm[3], const int *face, int nface, int j,
                         int k)
{
    float e[3], out[3];
    sub(h->p[k], h->p[j], e);
    cross(e, nrm, out);
    int pos = 0, neg = 0;
    for (int f = 0; f < nface; f++) {
        float d[3];
        sub(h->p[face[f]], h->p[j], d);
        float s = dot(d, out);
        pos += s > h->eps;
        neg += s < -h->eps;
    }
    return !(pos && neg);
}

/* Triangle i < j < k: 1 (and *flip when its winding points inwards) when it is drawn. */
static int face(const hull *h, int i, int j, int k, float nrm[3], int *flip)
{
    if (!plane(h, i, j, k, nrm)) return 0;
    int face[MAX_NEIGH], nface = 0, pos = 0, neg = 0;
    for (int m = 0; m < h->n; m++) {
        float d[3];
        sub(h->p[m], h->p[i], d);
        float s = dot(d, nrm);
        if (s > h->eps) pos++;
        else if (s < -h->eps) neg++;
        else face[nface++] = m;
    }
    if (pos && neg) return 0;
    *flip = pos > 0;
    if (nface == 3) return 1;
    /* a face of more points: a fan from its lowest (i) over the boundary edges j-k */
    return face[0] == i && boundary_edge(h, nrm, face, nface, j, k);
}

static int emit(ms_displaylist *dl, const hull *h, int i, int j, int k, const float nrm[3],
                int flip, ms_rgba8 col)
{
    int v[3] = {i, flip ? k : j, flip ? j : k};
    float p[9], n[9];
    for (int c = 0; c < 3; c++)
        for (int d = 0; d < 3; d++) {
            p[3 * c + d] = h->p[v[c]][d];
            n[3 * c + d] = flip ? -nrm[d] : nrm[d];
        }
    ms_rgba8 cc[3] = {col, col, col};
    return ms_dl_triangle(dl, p, n, cc);
}

static int draw_hull(ms_displaylist *dl, const hull *h, ms_rgba8 col, ms_error *err)
{
    for (int i = 0; i < h->n; i++)
        for (int j = i + 1; j < h->n; j++)
            for (int k = j + 1; k < h->n; k++) {
                float nrm[3];
                int flip;
                if (face(h, i, j, k, nrm, &flip) && emit(dl, h, i, j, k, nrm, flip, col)) {
                    ms_error_set(err, "out of memory");
                    return -1;
                }
            }
    return 0;
}

/* Put q (at squared distance r2) among the nearest MAX_NEIGH kept in order in h. */
static void keep_nearest(hull *h, float *d2, const float q[3], float r2)
{
    int at = h->n;
    if (at == MAX_NEIGH) {
        if (r2 >= d2[MAX_NEIGH - 1]) return;
        at--;
    } else {
        h->n++;
    }
    for (; at > 0 && d2[at - 1] > r2; at--) {
        d2[at] = d2[at - 1];
        for (int k = 0; k < 3; k++) h->p[at][k] = h->p[at - 1][k];
    }
    d2[at] = r2;
    for (int k = 0; k < 3; k++) h->p[at][k] = q[k];
}

/* The neighbours of atom a: bonded, within the cutoff, the nearest MAX_NEIGH. */
static void neighbours(const ms_rep_build *b, uint32_t a, float cutoff, hull *h)
{
    const ms_bonds *bd = &b->m->bonds;
    const float *c = ms_rep_xyz(b, a);
    float d2[MAX_NEIGH];
    h->n = 0;
    for (uint32_t e = bd->start[a]; e < bd->start[a + 1]; e++) {
        const float *q = ms_rep_xyz(b, bd->to[e]);
        float d[3];
        sub(q, c, d);
        float r2 = dot(d, d);
        if (r2 <= cutoff * cutoff) keep_nearest(h, d2, q, r2);
    }
    h->eps = 1e-3f * (h->n ? sqrtf(d2[h->n - 1]) : 1.0f);
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    float cutoff = b->p[0];
    if (!(cutoff > 0) || !b->m->has_bonds) return 0;
    hull h;
    for (size_t s = 0; s < b->nsel; s++) {
        uint32_t a = b->idx[s];
        neighbours(b, a, cutoff, &h);
        if (h.n >= 3 && draw_hull(dl, &h, ms_rep_rgba(b, a), err)) return -1;
    }
    return 0;
}

const ms_rep_method ms_rep_polyhedra = {"Polyhedra", 1, {{"distance cutoff", 3.0f}}, 0, build};
