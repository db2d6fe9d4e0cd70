/* qsurfbench.c: the QuickSurf benchmark driver. Loads a structure through the core (the
 * PDB plugin linked in), colours it by element, computes its surface and prints one line
 * of key=value measurements per run: grid, slabs, density and marching-cubes time,
 * triangles, bytes per vertex, and the peak memory the surface added above the loaded
 * molecule (VmHWM reset through /proc/self/clear_refs before the run).
 *
 *   qsurfbench [-h spacing] [-q quality] [-r radscale] [-i iso] [-n runs] [-solid]
 *              [-beads] [-hash] [-b cpu|opencl|auto] file.pdb
 * -hash adds a hash of the mesh arrays, to check that a change leaves the mesh alone. */
#include "config.h"
#include "base/threads.h"
#include "fileio/load.h"
#include "surf/qsurf.h"

#include <malloc.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <sys/resource.h>

#include "builtin/builtin.h"

typedef struct bench_opts {
    ms_qsurf_params p;
    int runs, solid, beads, hash;
    const char *path;
} bench_opts;

static int parse(int argc, char **argv, bench_opts *o)
{
    ms_qsurf_params_default(&o->p);
    o->runs = 1;
    for (int i = 1; i < argc; i++) {
        const char *a = argv[i], *v = i + 1 < argc ? argv[i + 1] : NULL;
        if (!strcmp(a, "-solid")) o->solid = 1;
        else if (!strcmp(a, "-beads")) o->beads = 1;
        else if (!strcmp(a, "-hash")) o->hash = 1;
        else if (!v) o->path = a;
        else if (!strcmp(a, "-h")) o->p.gridspacing = (float)atof(v), i++;
        else if (!strcmp(a, "-q")) o->p.quality = atoi(v), i++;
        else if (!strcmp(a, "-r")) o->p.radscale = (float)atof(v), i++;
        else if (!strcmp(a, "-i")) o->p.isovalue = (float)atof(v), i++;
        else if (!strcmp(a, "-n")) o->runs = atoi(v), i++;
        else if (!strcmp(a, "-b")) {
            o->p.backend = !strcmp(v, "cpu") ? MS_QSURF_CPU : !strcmp(v, "opencl") ? MS_QSURF_OPENCL
                                                                                  : MS_QSURF_AUTO;
            i++;
        } else o->path = a;
    }
    return o->path ? 0 : -1;
}

/* A line of /proc/self/status in kB, as bytes. */
static size_t status_kb(const char *key)
{
    FILE *f = fopen("/proc/self/status", "r");
    char line[256];
    size_t kb = 0, n = strlen(key);
    while (f && fgets(line, sizeof line, f))
        if (!strncmp(line, key, n)) kb = strtoull(line + n + 1, NULL, 10);
    if (f) fclose(f);
    return kb * 1024;
}

static void reset_peak(void)
{
    FILE *f = fopen("/proc/self/clear_refs", "w");
    if (f) {
        fputs("5", f);
        fclose(f);
    }
}

/* CPU seconds this process has used (all threads). */
static double cpu_seconds(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return 0.0;
    return (double)ru.ru_utime.tv_sec + 1e-6 * (double)ru.ru_utime.tv_usec +
           (double)ru.ru_stime.tv_sec + 1e-6 * (double)ru.ru_stime.tv_usec;
}

static void element_rgb(int z, float *c)
{
    static const float cyan[3] = {0.25f, 0.75f, 0.75f}, blue[3] = {0, 0, 1}, red[3] = {1, 0, 0},
                       yellow[3] = {1, 1, 0}, other[3] = {0.6f, 0.6f, 0.6f};
    const float *s = z == 6 ? cyan : z == 7 ? blue : z == 8 ? red : z == 16 ? yellow : other;
    memcpy(c, s, 3 * sizeof(float));
}

/* FNV-1a over the mesh's arrays. */
static uint64_t mesh_hash(const ms_qsurf_mesh *m)
{
    const void *parts[4] = {m->pos, m->normal, m->color, m->index};
    size_t sizes[4] = {m->nv * 3 * sizeof *m->pos, m->nv * 3 * sizeof *m->normal,
                       m->nv * 4 * sizeof *m->color, m->nt * 3 * sizeof *m->index};
    uint64_t h = 14695981039346656037u;
    for (int k = 0; k < 4; k++)
        for (size_t i = 0; i < sizes[k]; i++)
            h = (h ^ ((const uint8_t *)parts[k])[i]) * 1099511628211u;
    return h;
}

static void run_once(const ms_qsurf_atoms *a, const bench_opts *o)
{
    ms_qsurf_mesh m = {0};
    ms_qsurf_stats st;
    ms_error err = {{0}};
    size_t base = status_kb("VmRSS:");
    reset_peak();
    double t0 = ms_now(), c0 = cpu_seconds();
    if (ms_qsurf_surface(a, &o->p, &m, &st, &err) < 0) {
        printf("error=\"%s\"\n", err.msg);
        return;
    }
    double total = ms_now() - t0, cpu = cpu_seconds() - c0;
    size_t peak = status_kb("VmHWM:"), mesh = ms_qsurf_mesh_bytes(&m);
    size_t added = peak > base ? peak - base : 0;
    size_t slab = st.plan_bytes;
    printf("atoms=%zu h=%g grid=%dx%dx%d slabs=%d layers=%d kernel=%s opencl=%d setup_s=%.3f "
           "density_s=%.3f mc_s=%.3f total_s=%.3f cpu_s=%.3f vertices=%zu triangles=%zu "
           "vertex_bytes=%zu mesh_bytes_per_vertex=%.1f mesh_mb=%.1f plan_mb=%.1f peak_mb=%.1f "
           "peak_over_target=%.2f\n",
           st.grid.natoms, st.grid.h, st.grid.n[0], st.grid.n[1], st.grid.n[2], st.nslabs,
           st.slab_layers, st.kernel, st.opencl, st.t_setup, st.t_density, st.t_mc, total, cpu,
           m.nv, m.nt, (size_t)MS_QSURF_VERTEX_BYTES, m.nv ? (double)mesh / (double)m.nv : 0.0,
           mesh / 1048576.0, slab / 1048576.0, added / 1048576.0,
           (double)added / (1.5 * (double)mesh + (double)slab));
    if (o->hash) printf("hash=%016llx\n", (unsigned long long)mesh_hash(&m));
    if (st.note[0]) printf("note=\"%s\"\n", st.note);
    fflush(stdout);
    ms_qsurf_mesh_free(&m);
}

int main(int argc, char **argv)
{
    bench_opts o = {0};
    ms_registry reg;
    ms_load_opts lo;
    ms_error err = {{0}};
    mallopt(M_MMAP_THRESHOLD, 256 * 1024);
    if (parse(argc, argv, &o) < 0) {
        fprintf(stderr, "usage: qsurfbench [-h spacing] [-q quality] [-r radscale] [-i iso] "
                        "[-n runs] [-solid] [-beads] [-hash] [-b cpu|opencl|auto] file.pdb\n");
        return 2;
    }
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    ms_load_opts_default(&lo);
    lo.autobonds = 0;
    lo.waitfor = -1;
    double t0 = ms_now();
    ms_molecule *mol = ms_load_new(&reg, o.path, &lo, &err);
    if (!mol) {
        fprintf(stderr, "qsurfbench: %s\n", err.msg);
        return 1;
    }
    size_t n = mol->atoms.n;
    float *rgb = o.solid ? NULL : malloc(3 * n * sizeof(float));
    for (size_t i = 0; rgb && i < n; i++) element_rgb(mol->atoms.atomicnumber[i], rgb + 3 * i);
    ms_qsurf_atoms a = {.n = n, .pos = ms_mol_pos(mol), .radius = mol->atoms.radius, .rgb = rgb,
                        .solid = {0.25f, 0.75f, 0.75f}};
    ms_qsurf_radius_range(mol->atoms.radius, n, NULL, 0, &a.minrad, &a.maxrad);
    ms_qsurf_beads beads = {0};
    if (o.beads && ms_qsurf_beads_build(&a, mol->atoms.residue, &beads, &err) == 0)
        ms_qsurf_beads_atoms(&beads, &a);
    printf("loaded=%s atoms=%zu load_s=%.2f threads=%d\n", o.path, n, ms_now() - t0,
           ms_threads_count());
    for (int r = 0; r < o.runs; r++) run_once(&a, &o);
    ms_qsurf_beads_free(&beads);
    free(rgb);
    ms_mol_free(mol);
    ms_registry_free(&reg);
    return 0;
}
