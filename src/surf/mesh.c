/* mesh.c: the QuickSurf mesh: exact-size growth (realloc, which for large blocks remaps
 * pages instead of copying; the vertex arrays keep one spare vertex, MS_QSURF_MESH_VCAP)
 * within the surface's memory budget, release, memory and area. */
#include "config.h"
#include "surf/qsurf_impl.h"

#include <stdlib.h>
#include <string.h>

static int resize(void **p, size_t n, size_t elsize)
{
    size_t bytes;
    if (ms_mul_size(n, elsize, &bytes)) return -1;
    void *q = realloc(*p, bytes ? bytes : 1);
    if (!q) return -1;
    *p = q;
    return 0;
}

int ms_qsurf_mesh_resize(ms_qsurf_mesh *m, size_t nv, size_t nt)
{
    /* one spare vertex: a display list adopting the arrays hands pos to Embree as it is */
    if (resize((void **)&m->pos, nv + 1, 3 * sizeof *m->pos) < 0 ||
        resize((void **)&m->normal, nv + 1, 3 * sizeof *m->normal) < 0 ||
        resize((void **)&m->color, nv + 1, 4 * sizeof *m->color) < 0 ||
        resize((void **)&m->index, nt, 3 * sizeof *m->index) < 0)
        return -1;
    m->nv = nv, m->nt = nt;
    return 0;
}

int ms_qsurf_mesh_fits(ms_qsurf_extract *mc, size_t nv, size_t nt, ms_error *err)
{
    double bytes = (double)nv * MS_QSURF_VERTEX_BYTES + (double)nt * 3 * sizeof(uint32_t);
    if (!mc->budget || bytes <= (double)mc->mesh_room) return 0;
    mc->over_budget = 1;
    ms_error_set(err, "the mesh needs %.1f MB (%zu vertices and %zu triangles so far), more "
                 "than the %.1f MB the memory budget of %.1f MB leaves it beside the density "
                 "slabs (MOLSCOPE_QUICKSURF_MEMLIMIT or the memory available; a coarser grid "
                 "spacing makes a smaller mesh)", bytes / 1048576, nv, nt,
                 (double)mc->mesh_room / 1048576, (double)mc->budget / 1048576);
    return -1;
}

void ms_qsurf_mesh_free(ms_qsurf_mesh *m)
{
    free(m->pos);
    free(m->normal);
    free(m->color);
    free(m->index);
    memset(m, 0, sizeof *m);
}

size_t ms_qsurf_mesh_bytes(const ms_qsurf_mesh *m)
{
    return m->nv * MS_QSURF_VERTEX_BYTES + m->nt * 3 * sizeof(uint32_t);
}

double ms_qsurf_mesh_area(const ms_qsurf_mesh *m)
{
    double area = 0.0;
    for (size_t t = 0; t < m->nt; t++) {
        const uint32_t *i = m->index + 3 * t;
        double e1[3], e2[3];
        for (int d = 0; d < 3; d++) {
            e1[d] = (double)m->pos[3 * i[1] + d] - (double)m->pos[3 * i[0] + d];
            e2[d] = (double)m->pos[3 * i[2] + d] - (double)m->pos[3 * i[0] + d];
        }
        double cx = e1[1] * e2[2] - e1[2] * e2[1], cy = e1[2] * e2[0] - e1[0] * e2[2],
               cz = e1[0] * e2[1] - e1[1] * e2[0];
        area += 0.5 * sqrt(cx * cx + cy * cy + cz * cz);
    }
    return area;
}
