/* isosurface.c: VMD's Isosurface method (isovalue, volid, box, style, step, thickness): the
 * surface where volume `volid` crosses the isovalue, from the surface engine's marching
 * cubes run on the volume's own grid (skewed axes too: vertices land in world coordinates)
 * at every step-th point. Styles: 0 a lit mesh; 1 the mesh's edges as lines of width
 * thickness; 2 its vertices as unlit points of size thickness, 3 the same points lit.
 * Box: 0 the surface alone, 1 the grid's bounding box alone, 2 both; the box is twelve
 * lines (the edges leaving the origin along x, y and z in the Axes colours, width 3, the
 * others in Display Foreground, width 1), and with box 1 and the solid style also its six
 * faces, lit, as VMD draws them. Colours: `Volume n` colours every vertex by volume n's
 * value through the colour scale; ColorID and Molecule give their colour; any other method
 * Display Foreground (VMD's rule for volumes). A volid the molecule no longer holds draws
 * nothing. */
#include "config.h"
#include "rep/rep_int.h"
#include "surf/qsurf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

_Static_assert(sizeof(ms_qsurf_pos_t) == sizeof(float) &&
                   sizeof(ms_qsurf_normal_t) == sizeof(int8_t) &&
                   sizeof(ms_qsurf_color_t) == sizeof(uint8_t),
               "the display list adopts the surface engine's mesh arrays as they are");

enum { STYLE_SOLID, STYLE_WIRE, STYLE_POINTS, STYLE_LITPOINTS };

typedef struct iso_params {
    float iso, thickness;
    int box, surface, style, step;
} iso_params;

/* VMD's reading of the numbers: step below the grid's size along every axis (1 at the
 * least), line width and point size whole pixels from 1. */
static iso_params read_params(const ms_rep_build *b, const ms_volume *v)
{
    iso_params ip;
    const float *p = b->p;
    int box = (int)p[2], style = (int)p[3];
    ip.iso = p[0];
    ip.box = box > 0;
    ip.surface = box == 0 || box == 2;
    ip.style = style >= STYLE_WIRE && style <= STYLE_LITPOINTS ? style : STYLE_SOLID;
    ip.step = p[4] >= 2.0f && p[4] < 1e6f ? (int)p[4] : 1;
    for (int k = 0; k < 3; k++)
        if (ip.step >= v->n[k]) ip.step = MS_MAX(v->n[k] - 1, 1);
    ip.thickness = p[5] >= 1.0f ? (p[5] < 255.0f ? floorf(p[5]) : 255.0f) : 1.0f;
    return ip;
}

/* ---------------------------------------------------------------- the box */

/* Corner c (bits: +x, +y, +z) of the grid's box. */
static void corner(const ms_volume *v, int c, float out[3])
{
    double g[3];
    for (int k = 0; k < 3; k++) g[k] = (c >> k & 1) ? (double)(v->n[k] - 1) : 0.0;
    ms_volume_point(v, g, out);
}

static int box_lines(const ms_rep_build *b, const ms_volume *v, ms_displaylist *dl)
{
    int rc = 0;
    for (int c = 0; c < 8; c++)
        for (int k = 0; k < 3; k++) {
            if (c >> k & 1) continue;   /* each edge once: from the corner without bit k */
            float a[3], e[3];
            corner(v, c, a);
            corner(v, c | 1 << k, e);
            int at_origin = c == 0;
            ms_rgba8 col = b->palette[at_origin ? b->vc.axis[k] : b->vc.box];
            rc |= ms_dl_line(dl, a, e, at_origin ? 3.0f : 1.0f, col, MS_LINE_SOLID);
        }
    return rc;
}

/* The six faces, each two triangles wound counter-clockwise seen from outside. */
static int box_faces(const ms_rep_build *b, const ms_volume *v, ms_displaylist *dl)
{
    ms_rgba8 col = b->palette[b->vc.solid];
    int rc = 0;
    for (int a = 0; a < 3; a++) {
        int u = (a + 1) % 3, w = (a + 2) % 3;
        float pu[3], pw[3], pa[3], o[3], n[3];
        corner(v, 0, o);
        corner(v, 1 << u, pu);
        corner(v, 1 << w, pw);
        corner(v, 1 << a, pa);
        float eu[3], ew[3], ea[3];
        for (int k = 0; k < 3; k++) eu[k] = pu[k] - o[k], ew[k] = pw[k] - o[k], ea[k] = pa[k] - o[k];
        n[0] = eu[1] * ew[2] - eu[2] * ew[1];
        n[1] = eu[2] * ew[0] - eu[0] * ew[2];
        n[2] = eu[0] * ew[1] - eu[1] * ew[0];
        float len = sqrtf(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
        if (!(len > 0.0f)) continue;
        float orient = n[0] * ea[0] + n[1] * ea[1] + n[2] * ea[2] < 0.0f ? -1.0f : 1.0f;
        for (int side = 0; side < 2; side++) {
            float s = side ? orient : -orient, nn[3], q[4][3];
            for (int k = 0; k < 3; k++) {
                nn[k] = s * n[k] / len;
                float base = o[k] + (side ? ea[k] : 0.0f);
                q[0][k] = base;
                q[1][k] = base + eu[k];
                q[2][k] = base + eu[k] + ew[k];
                q[3][k] = base + ew[k];
            }
            long id[4];
            for (int c = 0; c < 4; c++) {
                /* 0 1 2 3 turns about n: counter-clockwise from outside when s > 0 */
                int from = s > 0.0f ? c : 3 - c;
                id[c] = ms_dl_vertex(dl, q[from], nn, col);
                rc |= id[c] < 0;
            }
            if (rc) return -1;
            rc |= ms_dl_tri(dl, (uint32_t)id[0], (uint32_t)id[1], (uint32_t)id[2]);
            rc |= ms_dl_tri(dl, (uint32_t)id[0], (uint32_t)id[2], (uint32_t)id[3]);
        }
    }
    return rc;
}

/* ---------------------------------------------------------------- the surface */

/* The grid marching cubes runs on: the volume itself, or every step-th point (copied into
 * scratch). */
static int sampled_grid(const ms_rep_build *b, const ms_volume *v, int step, ms_qsurf_volume *q,
                        ms_error *err)
{
    memset(q, 0, sizeof *q);
    memcpy(q->origin, v->origin, sizeof q->origin);
    for (int d = 0; d < 3; d++) {
        q->n[d] = (v->n[d] - 1) / step + 1;
        for (int k = 0; k < 3; k++) q->axis[d][k] = v->delta[d][k] * (float)step;
    }
    if (step == 1) {
        q->data = v->data;
        return 0;
    }
    size_t n = (size_t)q->n[0] * (size_t)q->n[1] * (size_t)q->n[2];
    float *d = ms_rep_scratch_get(b->scratch, MS_SCR_EXTRA, n * sizeof *d, err);
    if (!d) return -1;
    size_t sy = (size_t)v->n[0], sz = sy * (size_t)v->n[1], o = 0;
    for (int k = 0; k < q->n[2]; k++)
        for (int j = 0; j < q->n[1]; j++)
            for (int i = 0; i < q->n[0]; i++)
                d[o++] = v->data[(size_t)i * step + (size_t)j * step * sy + (size_t)k * step * sz];
    q->data = d;
    return 0;
}

/* The mesh of the isosurface, its vertices coloured. */
static int surface_mesh(const ms_rep_build *b, const ms_volume *v, const iso_params *ip,
                        ms_qsurf_mesh *mesh, ms_error *err)
{
    ms_qsurf_volume q;
    if (sampled_grid(b, v, ip->step, &q, err)) return -1;
    ms_rgba8_to_float(b->palette[b->vc.solid], q.solid);
    if (ms_qsurf_mc(&q, ip->iso, mesh, err)) return -1;
    const ms_volume *cv = b->coloring->method == MS_COL_VOLUME ? ms_rep_volume(b, (float)b->coloring->index) : NULL;
    if (cv && mesh->nv) {
        float lo, hi;
        ms_rep_volume_range(b, cv, &lo, &hi);
        ms_rep_color_by_volume(b, cv, lo, hi, (const float *)mesh->pos, mesh->nv,
                               (ms_rgba8 *)mesh->color);
    }
    return 0;
}

/* Every edge of the mesh once: edges listed under their lower vertex, repeats dropped. */
static int wire_lines(const ms_rep_build *b, const ms_qsurf_mesh *mesh, float width,
                      ms_displaylist *dl, ms_error *err)
{
    size_t nv = mesh->nv, nt = mesh->nt;
    size_t *start = ms_rep_scratch_get(b->scratch, MS_SCR_COUNTS, (nv + 1) * sizeof *start, err);
    uint32_t *to = ms_rep_scratch_get(b->scratch, MS_SCR_BONDTO, (3 * nt + 1) * sizeof *to, err);
    if (!start || !to) return -1;
    memset(start, 0, (nv + 1) * sizeof *start);
    for (size_t e = 0; e < 3 * nt; e++) {
        uint32_t a = mesh->index[e], c = mesh->index[e % 3 == 2 ? e - 2 : e + 1];
        start[MS_MIN(a, c)]++;
    }
    ms_rep_scan(start, nv + 1);
    size_t *fill = ms_rep_scratch_get(b->scratch, MS_SCR_BONDSTART, (nv + 1) * sizeof *fill, err);
    if (!fill) return -1;
    memcpy(fill, start, (nv + 1) * sizeof *fill);
    for (size_t e = 0; e < 3 * nt; e++) {
        uint32_t a = mesh->index[e], c = mesh->index[e % 3 == 2 ? e - 2 : e + 1];
        to[fill[MS_MIN(a, c)]++] = MS_MAX(a, c);
    }
    const float *xyz = (const float *)mesh->pos;
    const ms_rgba8 *col = (const ms_rgba8 *)mesh->color;
    for (size_t a = 0; a < nv; a++)
        for (size_t k = start[a]; k < start[a + 1]; k++) {
            size_t seen = start[a];
            while (seen < k && to[seen] != to[k]) seen++;
            if (seen < k) continue;
            if (ms_dl_line(dl, xyz + 3 * a, xyz + 3 * (size_t)to[k], width, col[a], MS_LINE_SOLID)) {
                ms_error_set(err, "out of memory for the isosurface's lines");
                return -1;
            }
        }
    return 0;
}

static int vertex_points(const ms_qsurf_mesh *mesh, float size, ms_displaylist *dl,
                         ms_error *err)
{
    long first = ms_dl_extend(dl, MS_DL_POINTS, mesh->nv, err);
    if (first < 0) return -1;
    ms_dl_points *p = &dl->points;
    memcpy(p->xyz + 3 * (size_t)first, mesh->pos, 3 * mesh->nv * sizeof(float));
    memcpy(p->color + first, mesh->color, mesh->nv * sizeof(ms_rgba8));
    for (size_t i = 0; i < mesh->nv; i++) p->size[(size_t)first + i] = size;
    return 0;
}

static int draw_surface(const ms_rep_build *b, const ms_volume *v, const iso_params *ip,
                        ms_displaylist *dl, ms_error *err)
{
    ms_qsurf_mesh mesh;
    memset(&mesh, 0, sizeof mesh);
    if (surface_mesh(b, v, ip, &mesh, err)) return -1;
    int rc = 0;
    if (ip->style == STYLE_SOLID) {
        ms_dl_mesh_adopt(dl, (float *)mesh.pos, (int8_t *)mesh.normal, (ms_rgba8 *)mesh.color,
                         mesh.nv, MS_QSURF_MESH_VCAP(&mesh), mesh.index, mesh.nt);
        return 0;
    }
    if (ip->style == STYLE_WIRE) rc = wire_lines(b, &mesh, ip->thickness, dl, err);
    else rc = vertex_points(&mesh, ip->thickness, dl, err);
    ms_qsurf_mesh_free(&mesh);
    return rc;
}

static int build(const ms_rep_build *b, ms_displaylist *dl, ms_error *err)
{
    const ms_volume *v = ms_rep_volume(b, b->p[1]);
    if (!v) return 0;
    iso_params ip = read_params(b, v);
    dl->lit = ip.style == STYLE_SOLID || ip.style == STYLE_LITPOINTS;
    if (ip.box) {
        if (box_lines(b, v, dl) || (!ip.surface && ip.style == STYLE_SOLID && box_faces(b, v, dl))) {
            ms_error_set(err, "out of memory for the volume's box");
            return -1;
        }
    }
    return ip.surface ? draw_surface(b, v, &ip, dl, err) : 0;
}

const ms_rep_method ms_rep_isosurface = {
    "Isosurface", 6,
    {{"isovalue", 0.5f}, {"volid", 0.0f}, {"box", 2.0f}, {"style", 2.0f}, {"step", 1.0f},
     {"thickness", 1.0f}},
    MS_REP_VOLUME, build};
