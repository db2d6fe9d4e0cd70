/* bench_rt.c: the TachyonInternal benchmark scene and its timings. 1tii replicated to about a
 * million atoms (bench_system.h): every other copy drawn VDW (atom radii), the others Licorice
 * (0.3 A spheres and a tube a bond, coloured by atom up to its middle, as the Licorice rep
 * emits it since issue 17), and a transparent surface: a smooth tessellated sphere (VMD's
 * Transparent material) enclosing the middle of the lattice. VMD's default view, lights, shadows and ambient occlusion (12
 * samples). The scene is exported with the Tachyon device (for Debian's tachyon, run by
 * bench_rt.sh on the same file), then rendered by TachyonInternal at each sample count given,
 * printing build and trace times and rays per second.
 *
 * usage: bench_rt data-folder copies size out-folder spp...   (bench_rt.sh runs it)
 * Switches for experiments (environment): BENCH_RT_NOEXPORT (no .dat), BENCH_RT_NOSHELL,
 * BENCH_RT_OPAQUESHELL, BENCH_RT_STACKS=n (a shell of 4 n^2 triangles; default 500),
 * BENCH_RT_NOAO, BENCH_RT_NOSHADOWS, BENCH_RT_TRACERS="rt ocl" (which tracers render each sample count, in that
 * order: rt TachyonInternal, ocl TachyonLOpenCLInternal; default "rt"), BENCH_RT_OWNBVH (the
 * OpenCL tracer's BVH from its own SAH builder instead of rtcBuildBVH). The tracers' own
 * variables apply as in a render (doc/rt.md: MOLSCOPE_RT_ORDER, MOLSCOPE_RT_LEAVES, ...). */
#include "config.h"
#include "assemble/view.h"
#include "base/threads.h"
#include "render/render.h"
#include "oclrt/oclrt.h"
#include "rt/rt.h"
#include "scene/displaylist.h"
#include "vecmath/vecf.h"
#include "scene/material.h"
#include "bench_system.h"

#include <math.h>
#include <sys/resource.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>

/* Even copies as VDW spheres, odd copies as Licorice. */
static int fill_molecule(const bench_sys *s, ms_displaylist *vdw, ms_displaylist *lic, ms_error *err)
{
    size_t copies = s->n / s->n0;
    for (size_t c = 0; c < copies; c++) {
        ms_displaylist *dl = c % 2 ? lic : vdw;
        for (size_t i = c * s->n0; i < (c + 1) * s->n0; i++) {
            const float *p = s->pos + 3 * i;
            if (ms_dl_sphere(dl, p, c % 2 ? 0.3f : s->radius[i], s->color[i], 12)) goto oom;
            if (!(c % 2)) continue;
            for (uint32_t k = s->bstart[i]; k < s->bstart[i + 1]; k++) {
                size_t j = s->bto[k];
                if (j < i) continue;
                const float *q = s->pos + 3 * j;
                float mid[3] = {0.5f * (p[0] + q[0]), 0.5f * (p[1] + q[1]), 0.5f * (p[2] + q[2])};
                /* one tube a bond, its colour changing at the joint, as Licorice emits it */
                if (ms_dl_bond(dl, p, mid, q, 0.3f, s->color[i], s->color[j], MS_CYL_INWARD, 12))
                    goto oom;
            }
        }
    }
    return 0;
oom:
    ms_error_set(err, "out of memory");
    return -1;
}

/* A UV sphere of stacks x slices quads around c: smooth outward normals, triangles wound
 * counter-clockwise seen from outside (Tachyon shades the side the winding faces). */
static int fill_shell(ms_displaylist *dl, const float c[3], float r, int stacks, int slices,
                      ms_error *err)
{
    size_t nv = (size_t)(stacks + 1) * (size_t)slices, nt = 2 * (size_t)stacks * (size_t)slices, v0, t0;
    if (ms_dl_mesh_extend(dl, nv, nt, &v0, &t0, err)) return -1;
    ms_dl_mesh *m = &dl->mesh;
    for (int i = 0; i <= stacks; i++)
        for (int j = 0; j < slices; j++) {
            double th = M_PI * i / stacks, ph = 2 * M_PI * j / slices;
            float n[3] = {(float)(sin(th) * cos(ph)), (float)cos(th), (float)(sin(th) * sin(ph))};
            size_t v = v0 + (size_t)i * (size_t)slices + (size_t)j;
            for (int k = 0; k < 3; k++) {
                m->xyz[3 * v + k] = c[k] + r * n[k];
                m->normal[3 * v + k] = ms_normal_quantize(n[k]);
            }
            m->color[v] = (ms_rgba8){200, 200, 220, 255};
        }
    uint32_t *t = m->tri + 3 * t0;
    for (int i = 0; i < stacks; i++)
        for (int j = 0; j < slices; j++) {
            uint32_t a = (uint32_t)(v0 + (size_t)i * slices + j), b = (uint32_t)(v0 + (size_t)i * slices + (j + 1) % slices);
            uint32_t c2 = a + (uint32_t)slices, d = b + (uint32_t)slices;
            t[0] = a, t[1] = b, t[2] = c2, t[3] = b, t[4] = d, t[5] = c2;   /* CCW from outside */
            t += 6;
        }
    return 0;
}

/* VMD's default view of the system: centred, largest extent 1.5 units. */
static void default_view(const bench_sys *s, float xform[16], float centre[3], float *extent)
{
    float lo[3] = {INFINITY, INFINITY, INFINITY}, hi[3] = {-INFINITY, -INFINITY, -INFINITY};
    for (size_t i = 0; i < s->n; i++)
        for (int k = 0; k < 3; k++) {
            lo[k] = fminf(lo[k], s->pos[3 * i + k]);
            hi[k] = fmaxf(hi[k], s->pos[3 * i + k]);
        }
    *extent = 0;
    for (int k = 0; k < 3; k++) {
        centre[k] = 0.5f * (lo[k] + hi[k]);
        *extent = fmaxf(*extent, hi[k] - lo[k]);
    }
    float t[16], sc[16];
    ms_mat4_translation(t, -centre[0], -centre[1], -centre[2]);
    ms_mat4_scaling(sc, 1.5f / *extent);
    ms_mat4_mul(sc, t, xform);
}

static void scene_settings(ms_scene *sc, int size)
{
    sc->width = sc->height = size;
    ms_camera *c = &sc->settings.cam;
    c->projection = MS_PROJ_PERSPECTIVE;
    c->eye[2] = 2, c->dir[2] = -1, c->up[1] = 1;
    c->height = 6, c->distance = -2, c->near_clip = 0.5f, c->far_clip = 10;
    c->dof_fnumber = 64, c->dof_focaldist = 0.7f;
    for (int i = 0; i < 2; i++) {
        sc->settings.lights[i].on = 1;
        memcpy(sc->settings.lights[i].pos, ms_view_default_light(i), 3 * sizeof(float));
        sc->settings.lights[i].color[0] = sc->settings.lights[i].color[1] = sc->settings.lights[i].color[2] = 1;
    }
    sc->settings.shadows = sc->settings.ao = 1;
    sc->settings.ao_ambient = 0.8f, sc->settings.ao_direct = 0.3f;
    sc->settings.cue_start = 0.5f, sc->settings.cue_end = 10, sc->settings.cue_density = 0.32f;
}

/* CPU seconds of the process so far (all threads): timings on a shared machine. */
static double cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return ru.ru_utime.tv_sec + ru.ru_stime.tv_sec + 1e-6 * (ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

static void run(const ms_scene *sc, int spp, int ocl, const char *out, ms_error *err)
{
    ms_rt_options o;
    ms_rt_options_default(&o);
    o.aasamples = spp - 1;
    o.aosamples = 12;
    if (ms_rt_options_from_env(&o, err)) {     /* MOLSCOPE_RT_ORDER, _LEAVES, ... (doc/rt.md) */
        printf("%s\n", err->msg);
        return;
    }
    ms_rt_stats st;
    char path[1024];
    const char *tag = ocl ? "ocl" : "rt";
    snprintf(path, sizeof path, "%s/%s_%d.png", out, tag, spp);
    double cpu = cpu_seconds();
    int fell_back = 0;
    if (ocl ? ms_oclrt_write(sc, &o, path, &st, &fell_back, err) || fell_back : ms_rt_write(sc, &o, path, &st, err)) {
        printf("%s %d spp: %s\n", ocl ? "TachyonLOpenCLInternal" : "TachyonInternal", spp,
               fell_back ? "fell back to TachyonInternal" : err->msg);
        return;
    }
    uint64_t rays = ms_rt_stats_rays(&st);
    printf("%s spp=%d build=%.3f trace=%.3f total=%.3f rays=%llu primary=%llu shadow=%llu "
           "ao=%llu secondary=%llu mrays=%.2f cpu=%.3f build_cpu=%.3f trace_cpu=%.3f\n", tag, spp, st.build_s, st.trace_s, st.build_s + st.trace_s,
           (unsigned long long)rays, (unsigned long long)st.rays[MS_RT_PRIMARY],
           (unsigned long long)st.rays[MS_RT_SHADOW], (unsigned long long)st.rays[MS_RT_AO],
           (unsigned long long)st.rays[MS_RT_SECONDARY], rays / st.trace_s / 1e6,
           cpu_seconds() - cpu, st.build_cpu_s, st.trace_cpu_s);
    if (ocl) printf("ocl device: %s\n", ms_oclrt_device_name());
    fflush(stdout);
}

int main(int argc, char **argv)
{
    if (argc < 6) {
        fprintf(stderr, "usage: bench_rt data-folder copies size out-folder spp...\n");
        return 2;
    }
    int copies = atoi(argv[2]), size = atoi(argv[3]);
    bench_sys s;
    memset(&s, 0, sizeof s);
    if (copies < 2 || size < 1 || bench_system_make(argv[1], copies, &s)) return 1;
    ms_error err = {{0}};
    ms_displaylist vdw, lic, shell;
    ms_dl_init(&vdw);
    ms_dl_init(&lic);
    ms_dl_init(&shell);
    float xform[16], centre[3], extent;
    default_view(&s, xform, centre, &extent);
    ms_materials *mats = ms_materials_new(&err);
    int stacks = getenv("BENCH_RT_STACKS") ? atoi(getenv("BENCH_RT_STACKS")) : 500;
    if (stacks < 2) stacks = 2;
    shell.material = 1;                                   /* VMD's Transparent */
    if (!mats || fill_molecule(&s, &vdw, &lic, &err) ||
        fill_shell(&shell, centre, 0.3f * extent, stacks, 2 * stacks, &err)) {
        fprintf(stderr, "bench_rt: %s\n", err.msg);
        return 1;
    }
    ms_scene sc;
    ms_scene_init(&sc);
    scene_settings(&sc, size);
    ms_scene_add(&sc, &vdw, xform, mats, &err);
    if (!getenv("BENCH_RT_VDWONLY")) ms_scene_add(&sc, &lic, xform, mats, &err);
    if (!getenv("BENCH_RT_NOSHELL") && !getenv("BENCH_RT_VDWONLY")) ms_scene_add(&sc, &shell, xform, mats, &err);
    if (getenv("BENCH_RT_NOAO")) sc.settings.ao = 0;
    if (getenv("BENCH_RT_NOSHADOWS")) sc.settings.shadows = 0;
    if (getenv("BENCH_RT_OPAQUESHELL")) sc.items[sc.nitems - 1].mat.opacity = 1;
    printf("scene: %zu atoms (1tii x %d): %zu VDW spheres, %zu Licorice spheres + %zu cylinders, "
           "%zu transparent triangles; %dx%d, %d threads\n", s.n, copies, vdw.spheres.n,
           lic.spheres.n, lic.cylinders.n, shell.mesh.ntris, size, size, ms_threads_count());
    char path[1024];
    snprintf(path, sizeof path, "%s/rt_scene.dat", argv[4]);
    double t = ms_now();
    if (!getenv("BENCH_RT_NOEXPORT")) {
        if (ms_render_tachyon.write(&sc, path, &err)) fprintf(stderr, "bench_rt: %s\n", err.msg);
        printf("exported %s in %.2f s\n", path, ms_now() - t);
    }
    fflush(stdout);
    const char *tracers = getenv("BENCH_RT_TRACERS") ? getenv("BENCH_RT_TRACERS") : "rt";
    ms_oclrt_own_bvh = getenv("BENCH_RT_OWNBVH") != NULL;
    for (int i = 5; i < argc; i++) {
        int spp = atoi(argv[i]) < 1 ? 1 : atoi(argv[i]);
        for (const char *p = tracers; *p; p++) {
            if (!strncmp(p, "rt", 2)) run(&sc, spp, 0, argv[4], &err);
            if (!strncmp(p, "ocl", 3)) run(&sc, spp, 1, argv[4], &err);
        }
    }
    ms_scene_free(&sc);
    ms_dl_free(&vdw);
    ms_dl_free(&lic);
    ms_dl_free(&shell);
    ms_materials_free(mats);
    bench_system_free(&s);
    return 0;
}
