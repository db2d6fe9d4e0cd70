/* bench_snapshot.c: issue 5's benchmark: `render snapshot` of a 1M-atom VDW and a 1M-atom
 * Licorice scene (1tii replicated) at 1024x1024, whole: the display lists into GL buffers,
 * every pass, the readback and the PNG, each phase timed, on every OpenGL back-end that
 * starts (OSMesa's llvmpipe, EGL surfaceless, EGL on a GPU). The camera, lights, material and
 * depth cue are VMD's defaults for an OpenGL display, the view resetview's.
 *
 * usage: bench_snapshot [data folder] [copies] [size] [frames] [egl|osmesa|all] */
#include "config.h"
#include "bench_system.h"
#include "assemble/view.h"
#include "gl/gl.h"
#include "vecmath/vecf.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

static void vmd_scene(ms_scene *sc, int size)
{
    ms_scene_init(sc);
    sc->width = sc->height = size;
    ms_camera *c = &sc->settings.cam;
    c->projection = MS_PROJ_PERSPECTIVE;
    c->eye[2] = 2;
    c->dir[2] = -1;
    c->up[1] = 1;
    c->height = 6;
    c->distance = -2;
    c->near_clip = 0.5f;
    c->far_clip = 10;
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        sc->settings.lights[i].on = i < 2;
        memcpy(sc->settings.lights[i].pos, ms_view_default_light(i), 3 * sizeof(float));
        sc->settings.lights[i].color[0] = sc->settings.lights[i].color[1] = sc->settings.lights[i].color[2] = 1;
    }
    sc->settings.depthcue = 1;
    sc->settings.cuemode = MS_CUE_EXP2;
    sc->settings.cue_start = 0.5f;
    sc->settings.cue_end = 10;
    sc->settings.cue_density = 0.32f;
}

/* resetview: centre on the box, largest extent 1.5 units. */
static void resetview(const bench_sys *s, float xform[16])
{
    float ext = 0, t[16], sc[16];
    for (int k = 0; k < 3; k++) ext = MS_MAX(ext, s->hi[k] - s->lo[k]);
    ms_mat4_translation(t, -0.5f * (s->lo[0] + s->hi[0]), -0.5f * (s->lo[1] + s->hi[1]),
                        -0.5f * (s->lo[2] + s->hi[2]));
    ms_mat4_scaling(sc, 1.5f / ext);
    ms_mat4_mul(sc, t, xform);
}

/* CPU seconds of every thread of the process (llvmpipe's included): a measure the other
 * jobs of a shared machine disturb less than the wall clock. */
static double cpu_seconds(void)
{
    struct rusage ru;
    getrusage(RUSAGE_SELF, &ru);
    return (double)ru.ru_utime.tv_sec + ru.ru_utime.tv_usec * 1e-6 + (double)ru.ru_stime.tv_sec +
           ru.ru_stime.tv_usec * 1e-6;
}

/* Frames of one scene on one back-end; prints the first and the best frame. */
static void run(ms_gl *g, const char *what, const ms_scene *sc, int frames, const char *png)
{
    double best[6] = {1e9, 1e9, 1e9, 1e9, 1e9, 1e9};
    const char *name = ms_gl_kind_name(ms_gl_kind_of(g));
    for (int f = 0; f < frames; f++) {
        ms_gl_times t;
        ms_image img;
        ms_error err = {{0}};
        double t0 = ms_now(), c0 = cpu_seconds();
        if (ms_gl_render(g, sc, &img, &t, &err)) {
            printf("  %-9s %-8s failed: %s\n", what, name, err.msg);
            return;
        }
        double t1 = ms_now();
        int rc = ms_image_write(&img, png, &err);
        double t2 = ms_now();
        ms_image_free(&img);
        if (rc) printf("  PNG failed: %s\n", err.msg);
        double ph[6] = {t.upload, t.draw, t.readback, t2 - t1, t2 - t0, cpu_seconds() - c0};
        if (f == 0) printf("  %-9s %-7s first frame %.3f s\n", what, name, ph[4]);
        if (ph[4] < best[4]) memcpy(best, ph, sizeof best);
    }
    printf("  %-9s %-7s best of %d: upload %.3f  draw %.3f  readback %.3f  PNG %.3f  "
           "whole %.3f s (CPU %.3f s)\n", what, name, frames, best[0], best[1], best[2], best[3],
           best[4], best[5]);
}

static void bench_backend(ms_gl_kind k, const bench_sys *s, int size, int frames)
{
    ms_error err = {{0}};
    ms_gl *g = ms_gl_open(k, &err);
    if (!g) {
        printf("%s: does not start: %s\n", ms_gl_kind_name(k), err.msg);
        return;
    }
    printf("%s\n", ms_gl_info(g));
    ms_material mat = {"Opaque", 0, 0, .5f, .65f, 40, 0, 1, 0, 0, 0};
    ms_materials mats = {&mat, 1, 1, 1, 0};
    float xform[16];
    resetview(s, xform);
    for (int lic = 0; lic < 2; lic++) {
        ms_displaylist dl;
        ms_dl_init(&dl);
        ms_scene sc;
        vmd_scene(&sc, size);
        if ((lic ? bench_licorice_list(s, &dl, &err) : bench_vdw_list(s, &dl, &err)) ||
            ms_scene_add(&sc, &dl, xform, &mats, &err)) {
            printf("  %s\n", err.msg);
        } else {
            char png[64];
            snprintf(png, sizeof png, "bench-out/snapshot_%s_%s.png", lic ? "licorice" : "vdw",
                     ms_gl_kind_name(k));
            run(g, lic ? "Licorice" : "VDW", &sc, frames, png);
        }
        ms_scene_free(&sc);
        ms_dl_free(&dl);
    }
    ms_gl_close(g);
}

int main(int argc, char **argv)
{
    const char *data = argc > 1 ? argv[1] : "tests/data";
    int copies = argc > 2 ? atoi(argv[2]) : 176;
    int size = argc > 3 ? atoi(argv[3]) : 1024;
    int frames = argc > 4 ? atoi(argv[4]) : 3;
    const char *which = argc > 5 ? argv[5] : "all";
    bench_sys s;
    if (copies < 1 || size < 1 || frames < 1 || bench_system_make(data, copies, &s)) return 1;
    printf("system: %zu atoms, %u bonds (1tii x %d); image %dx%d\n", s.n, s.bstart[s.n] / 2,
           copies, size, size);
    for (int k = 0; k < MS_GL_NKINDS; k++)
        if (!strcmp(which, "all") || !strcmp(which, ms_gl_kind_name((ms_gl_kind)k)))
            bench_backend((ms_gl_kind)k, &s, size, frames);
    bench_system_free(&s);
    return 0;
}
