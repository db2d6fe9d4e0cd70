/* cmd_memory.c: ::molscope::memory, molscope's own memory report (not VMD's): the bytes each
 * data structure holds, summed from its real allocations, for one molecule or for all of
 * them: the molecule's atoms, strings, bonds, topology and frames, the reps' caches, their
 * display lists with the QuickSurf reps' (surfaces) apart, what the last TachyonInternal
 * render held (Embree's acceleration structures and buffers, the arrays made for them, the
 * frame buffers, the image), and the process's resident set now and at its peak. */
#include "config.h"
#include "app/app.h"
#include "commands/args.h"
#include "commands/commands.h"
#include "rep/rep.h"
#include "rt/rt.h"

#include <string.h>

/* The sums a report lists, in its order. */
enum {
    K_ATOMS, K_STRINGS, K_BONDS, K_TOPOLOGY, K_FRAMES, K_OTHER, K_REPS, K_LISTS, K_SURFACES,
    K_EMBREE, K_WORLD, K_FRAMEBUF, K_IMAGE, K_RSS, K_PEAK, K_NKEYS
};
static const char *const key_names[K_NKEYS] = {
    "atoms", "strings", "bonds", "topology", "frames", "other", "reps", "displaylists",
    "surfaces", "tracer_bvh", "tracer_world", "tracer_frame", "image", "rss", "peak"};

/* A molecule's structures and its reps' into sum. */
static void add_molecule(ms_app *app, ms_molecule *m, size_t sum[K_NKEYS])
{
    ms_mol_memory mm;
    ms_mol_memory_of(m, &mm);
    sum[K_ATOMS] += mm.atoms;
    sum[K_STRINGS] += mm.strings;
    sum[K_BONDS] += mm.bonds;
    sum[K_TOPOLOGY] += mm.topology;
    sum[K_FRAMES] += mm.frames;
    sum[K_OTHER] += mm.other;
    size_t nreps = ms_rep_count(app->world.reps, m);
    int qsurf = ms_rep_method_find("QuickSurf");
    for (size_t i = 0; i < nreps; i++) {
        const ms_rep *r = ms_rep_get(app->world.reps, m, (long)i);
        sum[K_REPS] += ms_rep_cache_bytes(r);
        sum[r->style.method == qsurf ? K_SURFACES : K_LISTS] += ms_dl_bytes(ms_rep_list(r));
    }
}

/* ::molscope::memory ?<molid>?: "key bytes ..." for that molecule or for all. */
static int cmd_memory(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    size_t sum[K_NKEYS];
    memset(sum, 0, sizeof sum);
    if (objc == 2) {
        ms_molecule *m = ms_cmd_mol(app, interp, objv[1], "::molscope::memory");
        if (!m) return TCL_ERROR;
        add_molecule(app, m, sum);
    } else {
        for (size_t i = 0; i < app->mols.n; i++) add_molecule(app, app->mols.mols[i], sum);
    }
    ms_rt_memory rt;
    ms_rt_last_memory(&rt);
    sum[K_EMBREE] = rt.embree;
    sum[K_WORLD] = rt.world;
    sum[K_FRAMEBUF] = rt.frame;
    sum[K_IMAGE] = rt.image;
    sum[K_RSS] = ms_rss();
    sum[K_PEAK] = ms_peak_rss();
    Tcl_Obj *out = Tcl_NewListObj(0, NULL);
    for (int k = 0; k < K_NKEYS; k++) {
        Tcl_ListObjAppendElement(NULL, out, Tcl_NewStringObj(key_names[k], -1));
        Tcl_ListObjAppendElement(NULL, out, Tcl_NewWideIntObj((Tcl_WideInt)sum[k]));
    }
    Tcl_SetObjResult(interp, out);
    return TCL_OK;
}

void ms_cmd_memory_register(ms_app *app)
{
    static const ms_subcmd spec = {"::molscope::memory", cmd_memory, 0, 1, "?<molid>?"};
    ms_cmd_create(app, &spec);
}
