/* mctable.c: the marching cubes case tables, derived here from a rule instead of typed in.
 * For each of the 256 inside/outside patterns of a cell's corners, each face of the cell
 * gets the segments that separate its inside corners from its outside ones; on a face with
 * two diagonal inside corners the inside corners are kept apart. The rule depends only on
 * the face, so the two cells sharing a face always draw the same segments there, and
 * surfaces are closed. The segments join into loops around the cell, each loop becomes a
 * fan of triangles, oriented counter-clockwise seen from the outside. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <pthread.h>

/* Edge e runs along axis e / 4; the two other axes' offsets are bits of e % 4. */
const uint8_t ms_qsurf_mc_edge_from[12] = {
    0, 2, 4, 6,    /* x edges: (0,dy,dz) with dy = k & 1, dz = k >> 1 */
    0, 1, 4, 5,    /* y edges: (dx,0,dz) */
    0, 1, 2, 3     /* z edges: (dx,dy,0) */
};

static ms_qsurf_mctab table;
static pthread_once_t table_once = PTHREAD_ONCE_INIT;

/* The edge joining corners a and b (neighbours along one axis). */
static int edge_between(int a, int b)
{
    int lo = a < b ? a : b, axis = (a ^ b) == 1 ? 0 : (a ^ b) == 2 ? 1 : 2;
    for (int k = 0; k < 4; k++)
        if (ms_qsurf_mc_edge_from[axis * 4 + k] == lo) return axis * 4 + k;
    return -1;
}

/* The four corners of face (axis, side) in counter-clockwise order seen from outside:
 * with u x v = the outward normal, the order is (0,0) (1,0) (1,1) (0,1) in (u, v). */
static void face_corners(int axis, int side, int out[4])
{
    int b = (axis + 1) % 3, c = (axis + 2) % 3;
    int u = side ? b : c, v = side ? c : b;
    static const int uv[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    for (int i = 0; i < 4; i++)
        out[i] = (side << axis) | (uv[i][0] << u) | (uv[i][1] << v);
}

/* Segments of one face for corner pattern `in`: next[e] = the edge a segment leaving the
 * crossing on edge e goes to. Walking the face counter-clockwise, a segment runs from a
 * crossing entering the inside to the next crossing leaving it, so the inside is on its
 * right seen from outside the cell. */
static void face_segments(int in, int axis, int side, int next[12])
{
    int c[4], enter[4], ne = 0, nl = 0, order[4], kind[4];
    face_corners(axis, side, c);
    for (int i = 0; i < 4; i++) {
        int a = (in >> c[i]) & 1, b = (in >> c[(i + 1) % 4]) & 1;
        order[i] = edge_between(c[i], c[(i + 1) % 4]);
        kind[i] = a == b ? 0 : b ? 1 : 2;   /* 1: enters the inside, 2: leaves it */
    }
    for (int i = 0; i < 4; i++) {
        if (kind[i] == 1) enter[ne++] = i;
        nl += kind[i] == 2;
    }
    for (int k = 0; k < ne && nl; k++) {
        int i = enter[k], j = (i + 1) % 4;
        while (kind[j] != 2) j = (j + 1) % 4;
        next[order[i]] = order[j];
    }
}

/* Whether two crossing edges lie on a common face of the cell. A triangle side between
 * them would lie in that face, where the neighbouring cell may draw it too. */
static int share_face(int e1, int e2)
{
    int a1 = e1 >> 2, a2 = e2 >> 2, c1 = ms_qsurf_mc_edge_from[e1], c2 = ms_qsurf_mc_edge_from[e2];
    for (int b = 0; b < 3; b++)
        if (b != a1 && b != a2 && ((c1 >> b) & 1) == ((c2 >> b) & 1)) return 1;
    return 0;
}

typedef struct loop_tri {
    const int *v;            /* the loop's edges in order */
    uint8_t *out;
    int nt;
} loop_tri;

/* Triangulate the polygon v[i..j] (v[i]-v[j] already a side), with no inner side lying in
 * a cell face; backtracks over the apex k. */
static int triangulate(loop_tri *t, int i, int j)
{
    if (j - i < 2) return 1;
    for (int k = i + 1; k < j; k++) {
        if ((k > i + 1 && share_face(t->v[i], t->v[k])) ||
            (k < j - 1 && share_face(t->v[k], t->v[j])))
            continue;
        int saved = t->nt;
        if (t->nt >= MS_QSURF_MC_MAXTRI) return 0;
        uint8_t *o = t->out + 3 * t->nt++;
        o[0] = (uint8_t)t->v[i], o[1] = (uint8_t)t->v[k], o[2] = (uint8_t)t->v[j];
        if (triangulate(t, i, k) && triangulate(t, k, j)) return 1;
        t->nt = saved;
    }
    return 0;
}

static void build_case(int in)
{
    int next[12], seen[12] = {0};
    loop_tri t = {.out = table.tri[in], .nt = 0};
    for (int e = 0; e < 12; e++) next[e] = -1;
    for (int axis = 0; axis < 3; axis++)
        for (int side = 0; side < 2; side++) face_segments(in, axis, side, next);
    for (int e = 0; e < 12; e++) {
        if (next[e] < 0 || seen[e]) continue;
        int loop[12], m = 0;
        for (int f = e; f >= 0 && !seen[f] && m < 12; f = next[f]) {
            seen[f] = 1;
            loop[m++] = f;
        }
        t.v = loop;
        if (!triangulate(&t, 0, m - 1)) table.bad++;
    }
    table.ntri[in] = (uint8_t)t.nt;
}

/* The case's distinct edges in order of first use, and its corners as indices into them. */
static void distinct_edges(int in)
{
    int slot[12];
    for (int e = 0; e < 12; e++) slot[e] = -1;
    for (int k = 0; k < 3 * table.ntri[in]; k++) {
        int e = table.tri[in][k];
        if (slot[e] < 0) {
            slot[e] = table.nedge[in]++;
            table.edges[in][slot[e]] = (uint8_t)e;
        }
        table.corner[in][k] = (uint8_t)slot[e];
    }
}

/* Each point owns the edges to its +x and +y neighbours and to its -z neighbour, so the
 * owner of a cell's z edge is its corner at dz = 1. */
static void owners(void)
{
    for (int e = 0; e < 12; e++) {
        int from = ms_qsurf_mc_edge_from[e], axis = e >> 2;
        int dx = from & 1, dy = from >> 1 & 1, dz = (from >> 2 & 1) + (axis == 2);
        table.owner[e] = (uint8_t)(dx | (dy + 2 * dz) << 1 | axis << 3);
    }
}

static void build_tables(void)
{
    for (int in = 0; in < 256; in++) {
        build_case(in);
        distinct_edges(in);
    }
    owners();
}

const ms_qsurf_mctab *ms_qsurf_mc_table(void)
{
    pthread_once(&table_once, build_tables);
    return &table;
}
