/* bench_scene.c: how fast display lists fill, for the representation builders that come next
 * (targets for a 1M-atom system: VDW 0.1 s, Licorice 0.3 s, NewCartoon 0.5 s), and how fast
 * the Tachyon exporter writes. The system is 1tii replicated on a grid to ~1M atoms, with its
 * real bonds; colours come from a per-atom table as a colouring method would give them.
 *
 * usage: bench_scene [data folder] [copies]     (run by `make bench`) */
#include "config.h"
#include "bench_system.h"
#include "base/threads.h"
#include "render/render.h"
#include "scene/displaylist.h"
#include "vecmath/vecf.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* NewCartoon-like: a tube mesh of `ring` vertices per spline point. */
typedef struct tube {
    ms_displaylist *dl;
    size_t v0, t0, ring;
    const float *path;        /* spline points */
} tube;

static void fill_tube(void *ctx, size_t b, size_t e, int t)
{
    tube *u = ctx;
    ms_dl_mesh *m = &u->dl->mesh;
    for (size_t p = b; p < e; p++) {
        for (size_t r = 0; r < u->ring; r++) {
            size_t v = u->v0 + p * u->ring + r;
            float ang = 6.2831853f * (float)r / (float)u->ring, c = 1 - ang * ang / 2, s = ang;
            m->xyz[3 * v] = u->path[3 * p] + 0.3f * c;
            m->xyz[3 * v + 1] = u->path[3 * p + 1] + 0.3f * s;
            m->xyz[3 * v + 2] = u->path[3 * p + 2];
            m->normal[3 * v] = ms_normal_quantize(c);
            m->normal[3 * v + 1] = ms_normal_quantize(s);
            m->normal[3 * v + 2] = 0;
            m->color[v] = (ms_rgba8){166, 0, 166, 255};
            if (p == 0) continue;
            size_t tt = u->t0 + 2 * ((p - 1) * u->ring + r);
            uint32_t a = (uint32_t)v, bb = (uint32_t)(v - u->ring);
            uint32_t a1 = (uint32_t)(u->v0 + p * u->ring + (r + 1) % u->ring);
            uint32_t b1 = a1 - (uint32_t)u->ring;
            uint32_t *tri = m->tri + 3 * tt;
            tri[0] = bb; tri[1] = b1; tri[2] = a;
            tri[3] = a; tri[4] = b1; tri[5] = a1;
        }
    }
}

static double now(void) { return ms_now(); }

static void bench_vdw(const bench_sys *s, ms_error *err)
{
    ms_displaylist dl;
    ms_dl_init(&dl);
    double t = now();
    for (size_t i = 0; i < s->n; i++) ms_dl_sphere(&dl, s->pos + 3 * i, s->radius[i], s->color[i], 12);
    double t_single = now() - t;
    /* reserve + parallel fill, into the memory of the last build (a rebuild) and fresh */
    ms_dl_clear(&dl);
    t = now();
    bench_vdw_list(s, &dl, err);
    double t_rebuild = now() - t;
    ms_dl_free(&dl);
    t = now();
    bench_vdw_list(s, &dl, err);
    double t_fresh = now() - t;
    printf("VDW       %8zu spheres: single appends %.3f s, block fill %.3f s fresh, %.3f s rebuild\n",
           s->n, t_single, t_fresh, t_rebuild);
    ms_dl_free(&dl);
}

static void bench_licorice(const bench_sys *s, ms_error *err)
{
    ms_displaylist dl;
    ms_dl_init(&dl);
    double t = now();
    bench_licorice_list(s, &dl, err);
    printf("Licorice  %8zu spheres + %zu cylinders: %.3f s fresh\n", s->n, dl.cylinders.n, now() - t);
    ms_dl_free(&dl);
}

/* NewCartoon-like: 10 spline points per residue (1/8 of the atoms), a ring of 12. */
static void bench_cartoon(const bench_sys *s, ms_error *err)
{
    size_t npts = s->n / 8 * 10, ring = 12;
    float *path = malloc(3 * npts * sizeof(float));
    if (!path) return;
    for (size_t p = 0; p < npts; p++) {
        path[3 * p] = 0.38f * (float)p;
        path[3 * p + 1] = path[3 * p + 2] = 0;
    }
    ms_displaylist dl;
    ms_dl_init(&dl);
    double t[2];
    for (int pass = 0; pass < 2; pass++) {
        ms_dl_clear(&dl);
        double t0 = now();
        tube u = {&dl, 0, 0, ring, path};
        ms_dl_mesh_extend(&dl, npts * ring, 2 * (npts - 1) * ring, &u.v0, &u.t0, err);
        ms_parallel_for(npts, 4096, fill_tube, &u);
        t[pass] = now() - t0;
    }
    printf("NewCartoon-like mesh %zu vertices %zu triangles: %.3f s fresh, %.3f s rebuild\n",
           dl.mesh.nverts, dl.mesh.ntris, t[0], t[1]);
    free(path);
    ms_dl_free(&dl);
}

/* The Tachyon exporter on the first 200k spheres. */
static void bench_export(const bench_sys *s, ms_error *err)
{
    ms_displaylist dl;
    ms_dl_init(&dl);
    bench_sys part = *s;
    part.n = MS_MIN(s->n, (size_t)200000);
    size_t n = part.n;
    bench_vdw_list(&part, &dl, err);
    ms_scene sc;
    ms_scene_init(&sc);
    sc.width = sc.height = 512;
    sc.settings.cam.eye[2] = 2;
    sc.settings.cam.dir[2] = -1;
    sc.settings.cam.up[1] = 1;
    sc.settings.cam.height = 6;
    sc.settings.cam.distance = -2;
    ms_material mat = {"Opaque", 0, 0, .5f, .65f, 40, 0, 1, 0, 0, 0};
    ms_materials mats = {&mat, 1, 1, 1, 0};
    float xform[16];
    ms_mat4_scaling(xform, 0.01f);
    ms_scene_add(&sc, &dl, xform, &mats, err);
    const char *tmp = "bench_scene_out.dat";
    double t = now();
    int rc = ms_render_tachyon.write(&sc, tmp, err);
    printf("Tachyon export %zu spheres: %.3f s (%s)\n", n, now() - t, rc ? err->msg : "ok");
    remove(tmp);
    ms_scene_free(&sc);
    ms_dl_free(&dl);
}

int main(int argc, char **argv)
{
    const char *data = argc > 1 ? argv[1] : "tests/data";
    int copies = argc > 2 ? atoi(argv[2]) : 176;
    bench_sys s;
    if (copies < 1 || bench_system_make(data, copies, &s)) return 1;
    printf("system: %zu atoms, %u bonds (1tii x %d), %d threads\n", s.n, s.bstart[s.n] / 2,
           copies, ms_threads_count());
    ms_error err = {{0}};
    bench_vdw(&s, &err);
    bench_licorice(&s, &err);
    bench_cartoon(&s, &err);
    bench_export(&s, &err);
    bench_system_free(&s);
    return 0;
}
