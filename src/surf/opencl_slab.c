/* opencl_slab.c: one slab of QuickSurf on the OpenCL device, from density to mesh, with
 * the kernels of kernels.cl: the slab's density planes (those the slab before left on the
 * device are moved to the front, not computed again), then marching cubes on them where
 * they are: counts per work-item, their prefix sum (the slab's vertex and triangle totals
 * are the only numbers read back before the mesh), vertices and triangles written at
 * their final places, and the slab's part of the mesh read into the host mesh. The first
 * vertices of the slab's top plane stay on the device for the next slab. Any error leaves
 * the host mesh as it was; the caller falls back to the CPU. */
#include "config.h"
#include "surf/qsurf_impl.h"

#ifdef MS_HAVE_OPENCL
#include "surf/opencl_impl.h"

/* Kernel arguments set in order; the first error is kept. */
typedef struct args {
    cl_kernel k;
    cl_uint n;
    cl_int e;
} args;

static void arg(args *a, size_t size, const void *v)
{
    if (a->e == CL_SUCCESS) a->e = clSetKernelArg(a->k, a->n, size, v);
    a->n++;
}
#define ARG(a, v) arg((a), sizeof(v), &(v))

static size_t round_up(size_t n, size_t m)
{
    return (n + m - 1) / m * m;
}

static cl_int run(ms_qsurf_cl *cl, cl_kernel k, cl_uint dims, const size_t *global,
                  const size_t *local)
{
    return clEnqueueNDRangeKernel(cl->queue, k, dims, NULL, global, local, 0, NULL, NULL);
}

static int injected(ms_qsurf_cl *cl, int stage, const char *what, cl_int code, ms_error *err)
{
    if (cl->fail_stage != stage) return 0;
    cl->fail_stage = -1;
    ms_error_set(err, "OpenCL: %s failed (%d, injected fault)", what, (int)code);
    return 1;
}

/* ---------------------------------------------------------------- density */

/* Planes the device holds from the slab before that this slab needs are moved to the front
 * of the buffers (where source and destination overlap, they are computed again, to the
 * same bits). Returns the first plane still to compute. */
static int keep_planes(ms_qsurf_cl *cl, const ms_qsurf_slab *s, cl_int *e)
{
    int zb = s->zb, last = MS_MIN(cl->held_ze, s->ze);
    if (zb < cl->held_zb || last < zb) return zb;
    size_t plane = (size_t)cl->nx * cl->ny * sizeof(float);
    size_t src = (size_t)(zb - cl->held_zb) * plane, n = (size_t)(last - zb + 1) * plane;
    if (src > 0 && src < n) return zb;
    cl_mem bufs[4] = {cl->dens, cl->rgb[0], cl->rgb[1], cl->rgb[2]};
    for (int b = 0; src > 0 && b < (cl->colored ? 4 : 1) && *e == CL_SUCCESS; b++)
        *e = clEnqueueCopyBuffer(cl->queue, bufs[b], bufs[b], src, 0, n, 0, NULL, NULL);
    return last + 1;
}

static cl_int density_kernel(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, const ms_qsurf_slab *s,
                             int nz, int cz)
{
    cl_int4 nc = {{ag->nc[0], ag->nc[1], ag->nc[2], 0}}, dims = {{s->nx, s->ny, nz, s->zb}};
    cl_float4 cw = {{ag->cw[0], ag->cw[1], ag->cw[2], 0.0f}};
    cl_int colored = cl->colored, from = cz, ze = s->ze;
    args a = {.k = cl->k[K_DENSITY]};
    ARG(&a, cl->atoms), ARG(&a, cl->colors), ARG(&a, cl->cells), ARG(&a, nc), ARG(&a, cw);
    ARG(&a, ag->cutmax), ARG(&a, ag->elim), ARG(&a, dims), ARG(&a, from), ARG(&a, ze);
    ARG(&a, colored), ARG(&a, cl->dens);
    for (int k = 0; k < 3; k++) ARG(&a, cl->rgb[k]);
    if (a.e != CL_SUCCESS) return a.e;
    size_t local[3] = {8, 8, 2};
    size_t global[3] = {round_up((size_t)s->nx, 8), round_up((size_t)s->ny, 8),
                        (size_t)(ze - cz + 8) / 8 * 2};
    return run(cl, a.k, 3, global, local);
}

static int density(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, const ms_qsurf_slab *s, int nz,
                   ms_error *err)
{
    cl_int e = CL_SUCCESS;
    int cz = keep_planes(cl, s, &e);
    cl->held_ze = cl->held_zb - 1;
    if (e != CL_SUCCESS) return ms_cl_fail(err, "keeping the shared planes", e);
    if (injected(cl, MS_QSURF_CL_FAIL_DENSITY, "the density kernel", CL_OUT_OF_RESOURCES, err))
        return -1;
    if (cz <= s->ze && (e = density_kernel(cl, ag, s, nz, cz)) != CL_SUCCESS)
        return ms_cl_fail(err, "the density kernel", e);
    if ((e = clFinish(cl->queue)) != CL_SUCCESS)
        return ms_cl_fail(err, "running the density kernel", e);
    cl->held_zb = s->zb, cl->held_ze = s->ze;
    return 0;
}

/* ---------------------------------------------------------------- marching cubes */

/* What every marching-cubes kernel is told: the grid and the slab. */
typedef struct mc_shape {
    cl_int4 dims;            /* nx, ny, nz, first plane held */
    cl_int4 span;            /* z0, z1, work-items per row */
    cl_float iso;
    size_t global[3], local[3];
} mc_shape;

static void shape_of(const ms_qsurf_extract *mc, const ms_qsurf_slab *s, int z0, int z1,
                     mc_shape *sh)
{
    int nix = ms_qsurf_cl_items(mc->n[0]);
    sh->dims = (cl_int4){{mc->n[0], mc->n[1], mc->n[2], s->zb}};
    sh->span = (cl_int4){{z0, z1, nix, 0}};
    sh->iso = mc->iso;
    sh->local[0] = 2, sh->local[1] = 8, sh->local[2] = 8;
    sh->global[0] = round_up((size_t)nix, 2);
    sh->global[1] = round_up((size_t)mc->n[1], 8);
    sh->global[2] = round_up((size_t)(z1 - z0 + 1), 8);
}

static cl_int count(ms_qsurf_cl *cl, mc_shape *sh)
{
    args a = {.k = cl->k[K_COUNT]};
    ARG(&a, cl->dens), ARG(&a, sh->dims), ARG(&a, sh->span), ARG(&a, sh->iso);
    ARG(&a, cl->ntri), ARG(&a, cl->level[0]);
    return a.e != CL_SUCCESS ? a.e : run(cl, a.k, 3, sh->global, sh->local);
}

/* Exclusive prefix sums of the n counts in level 0, in place; their totals into *total. */
static cl_int scan(ms_qsurf_cl *cl, size_t n, cl_uint total[2])
{
    size_t ls = cl->scan_local, per = 4 * ls, size[MS_QSURF_CL_LEVELS];
    cl_uint uper = (cl_uint)per;
    int top = 0;
    size[0] = n;
    for (;; top++) {
        size_t groups = (size[top] + per - 1) / per, global = groups * ls;
        cl_uint un = (cl_uint)size[top];
        args a = {.k = cl->k[K_SCAN]};
        ARG(&a, cl->level[top]), ARG(&a, un), ARG(&a, cl->level[top + 1]);
        arg(&a, ls * sizeof(cl_uint2), NULL);
        if (a.e != CL_SUCCESS || (a.e = run(cl, a.k, 1, &global, &ls)) != CL_SUCCESS) return a.e;
        size[top + 1] = groups;
        if (groups == 1 || top + 2 >= MS_QSURF_CL_LEVELS) break;
    }
    if (size[top + 1] != 1) return CL_INVALID_BUFFER_SIZE;
    for (int l = top - 1; l >= 0; l--) {
        cl_uint un = (cl_uint)size[l];
        args a = {.k = cl->k[K_SCAN_ADD]};
        ARG(&a, cl->level[l]), ARG(&a, un), ARG(&a, uper), ARG(&a, cl->level[l + 1]);
        if (a.e != CL_SUCCESS || (a.e = run(cl, a.k, 1, &size[l], NULL)) != CL_SUCCESS)
            return a.e;
    }
    return clEnqueueReadBuffer(cl->queue, cl->level[top + 1], CL_TRUE, 0, 2 * sizeof(cl_uint),
                               total, 0, NULL, NULL);
}

/* Mesh buffers for nv vertices and nt triangles, grown with a quarter to spare. */
static int grow_mesh(ms_qsurf_cl *cl, size_t nv, size_t nt, ms_error *err)
{
    cl_int e = CL_SUCCESS;
    if (injected(cl, MS_QSURF_CL_FAIL_ALLOC, "growing the mesh buffers",
                 CL_MEM_OBJECT_ALLOCATION_FAILURE, err))
        return -1;
    if (nv > cl->vcap) {
        size_t cap = nv + nv / 4 + 1024;
        ms_qsurf_cl_free_mem(&cl->pos), ms_qsurf_cl_free_mem(&cl->normal);
        ms_qsurf_cl_free_mem(&cl->color);
        cl->vcap = 0;
        cl->pos = ms_qsurf_cl_buffer(cl, CL_MEM_WRITE_ONLY, cap * 3 * sizeof(float), NULL, &e);
        cl->normal = ms_qsurf_cl_buffer(cl, CL_MEM_WRITE_ONLY, cap * 3, NULL, &e);
        cl->color = ms_qsurf_cl_buffer(cl, CL_MEM_WRITE_ONLY, cap * 4, NULL, &e);
        if (e == CL_SUCCESS) cl->vcap = cap;
    }
    if (nt > cl->tcap && e == CL_SUCCESS) {
        size_t cap = nt + nt / 4 + 1024;
        ms_qsurf_cl_free_mem(&cl->index);
        cl->tcap = 0;
        cl->index = ms_qsurf_cl_buffer(cl, CL_MEM_WRITE_ONLY, cap * 3 * sizeof(cl_uint), NULL, &e);
        if (e == CL_SUCCESS) cl->tcap = cap;
    }
    return e == CL_SUCCESS ? 0 : ms_cl_fail(err, "allocating the mesh buffers", e);
}

static cl_int vertices(ms_qsurf_cl *cl, const ms_qsurf_extract *mc, mc_shape *sh, cl_uint vfirst)
{
    cl_float4 origin = {{(float)mc->origin[0], (float)mc->origin[1], (float)mc->origin[2],
                         (float)mc->axis[0][0]}};
    cl_float4 solid = {{mc->solid[0], mc->solid[1], mc->solid[2], 1.0f}};
    cl_int colored = mc->colored;
    args a = {.k = cl->k[K_VERTICES]};
    ARG(&a, cl->dens);
    for (int k = 0; k < 3; k++) ARG(&a, cl->rgb[k]);
    ARG(&a, sh->dims), ARG(&a, sh->span), ARG(&a, sh->iso), ARG(&a, origin), ARG(&a, colored);
    ARG(&a, solid), ARG(&a, cl->level[0]), ARG(&a, vfirst), ARG(&a, cl->vbase);
    ARG(&a, cl->pos), ARG(&a, cl->normal), ARG(&a, cl->color);
    return a.e != CL_SUCCESS ? a.e : run(cl, a.k, 3, sh->global, sh->local);
}

static cl_int triangles(ms_qsurf_cl *cl, mc_shape *sh)
{
    args a = {.k = cl->k[K_TRIANGLES]};
    ARG(&a, cl->dens), ARG(&a, sh->dims), ARG(&a, sh->span), ARG(&a, sh->iso);
    ARG(&a, cl->ntri), ARG(&a, cl->tri), ARG(&a, cl->edge_from), ARG(&a, cl->level[0]);
    ARG(&a, cl->vbase), ARG(&a, cl->index);
    return a.e != CL_SUCCESS ? a.e : run(cl, a.k, 3, sh->global, sh->local);
}

static cl_int read_buffer(ms_qsurf_cl *cl, cl_mem from, size_t bytes, void *to)
{
    if (bytes == 0) return CL_SUCCESS;
    return clEnqueueReadBuffer(cl->queue, from, CL_TRUE, 0, bytes, to, 0, NULL, NULL);
}

/* The slab's nv vertices and nt triangles appended to the host mesh. */
static int read_mesh(ms_qsurf_cl *cl, ms_qsurf_mesh *m, size_t nv, size_t nt, ms_error *err)
{
    size_t v0 = m->nv, t0 = m->nt;
    if (ms_qsurf_mesh_resize(m, v0 + nv, t0 + nt) < 0) {
        ms_error_set(err, "out of memory for a mesh of %zu vertices and %zu triangles", v0 + nv,
                     t0 + nt);
        return -1;
    }
    cl_int e = read_buffer(cl, cl->pos, nv * 3 * sizeof(float), m->pos + 3 * v0);
    if (e == CL_SUCCESS) e = read_buffer(cl, cl->normal, nv * 3, m->normal + 3 * v0);
    if (e == CL_SUCCESS) e = read_buffer(cl, cl->color, nv * 4, m->color + 4 * v0);
    int rc = e == CL_SUCCESS ? 0 : ms_cl_fail(err, "reading the mesh back", e);
    if (rc == 0 && injected(cl, MS_QSURF_CL_FAIL_READ, "reading the triangles back",
                            CL_OUT_OF_RESOURCES, err))
        rc = -1;
    if (rc == 0 && (e = read_buffer(cl, cl->index, nt * 3 * sizeof(cl_uint), m->index + 3 * t0)))
        rc = ms_cl_fail(err, "reading the triangles back", e);
    if (rc < 0) m->nv = v0, m->nt = t0;      /* the arrays stay valid, a little larger */
    return rc;
}

/* Marching cubes on the slab's planes as ms_qsurf_extract_slab does on the host. */
static int extract(ms_qsurf_cl *cl, const ms_qsurf_slab *s, ms_qsurf_extract *mc, int z0,
                   int z1, ms_error *err)
{
    mc_shape sh;
    cl_uint total[2];
    ms_qsurf_mesh *m = mc->mesh;
    shape_of(mc, s, z0, z1, &sh);
    size_t items = (size_t)sh.span.s[2] * mc->n[1] * (size_t)(z1 - z0 + 1);
    cl_int e = count(cl, &sh);
    if (e == CL_SUCCESS) e = scan(cl, items, total);
    if (e != CL_SUCCESS) return ms_cl_fail(err, "counting the slab's triangles", e);
    if (m->nv + total[0] > UINT32_MAX || m->nt + total[1] > UINT32_MAX) {
        ms_error_set(err, "the surface has more than %u vertices or triangles", UINT32_MAX);
        return -1;
    }
    if (ms_qsurf_mesh_fits(mc, m->nv + total[0], m->nt + total[1], err) < 0) return -1;
    if (grow_mesh(cl, total[0], total[1], err) < 0) return -1;
    e = vertices(cl, mc, &sh, (cl_uint)m->nv);
    if (e == CL_SUCCESS) e = triangles(cl, &sh);
    if (e != CL_SUCCESS) return ms_cl_fail(err, "the marching cubes kernels", e);
    if (read_mesh(cl, m, total[0], total[1], err) < 0) return -1;
    /* The first vertices of plane z1 are those of the next slab's plane z0. */
    size_t plane = (size_t)mc->n[0] * mc->n[1] * sizeof(cl_uint);
    e = clEnqueueCopyBuffer(cl->queue, cl->vbase, cl->vbase, (size_t)(z1 - z0) * plane, 0, plane,
                            0, NULL, NULL);
    return e == CL_SUCCESS ? 0 : ms_cl_fail(err, "keeping the top plane", e);
}

int ms_qsurf_cl_slab(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, const ms_qsurf_slab *s,
                     ms_qsurf_extract *mc, int z0, int z1, double t[2], ms_error *err)
{
    size_t v0 = mc->mesh->nv, t0 = mc->mesh->nt;
    int fail = ms_qsurf_cl_fail_after >= 0 && ms_qsurf_cl_fail_after-- == 0;
    cl->fail_stage = fail ? ms_qsurf_cl_fail_stage : -1;
    if (s->nx != cl->nx || s->ny != cl->ny || s->ze - s->zb + 1 > cl->planes) {
        ms_error_set(err, "OpenCL: slab %d..%d does not fit the device buffers", z0, z1);
        return -1;
    }
    double t1 = ms_now();
    if (density(cl, ag, s, mc->n[2], err) < 0) return -1;
    double t2 = ms_now();
    int rc = extract(cl, s, mc, z0, z1, err);
    t[0] = t2 - t1, t[1] = ms_now() - t2;
    if (rc < 0) mc->mesh->nv = v0, mc->mesh->nt = t0;
    return rc;
}

#else /* no OpenCL at build time */

int ms_qsurf_cl_slab(ms_qsurf_cl *cl, const ms_qsurf_atomgrid *ag, const ms_qsurf_slab *s,
                     ms_qsurf_extract *mc, int z0, int z1, double t[2], ms_error *err)
{
    ms_error_set(err, "molscope was built without OpenCL");
    return -1;
}

#endif
