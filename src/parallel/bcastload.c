/* bcastload.c: loading a file once and broadcasting the molecule, so N ranks do not read
 * the same file N times.
 *
 * Every rank calls the same function at the same point (a collective):
 *   1. all ranks check they load the same thing (a hash of the path, options and target
 *      atom count; ms_par_agree): a mismatch is an error on every rank, and a rank that
 *      never arrives ends the job after MOLSCOPE_BCAST_TIMEOUT seconds (default 300) rather
 *      than leave the others waiting;
 *   2. rank 0 reads the structure and first frame and broadcasts the outcome (its error
 *      message when it failed: every rank then fails with it);
 *   3. rank 0 broadcasts the structure as ms_molser blocks, straight from its arrays into
 *      the others' arrays;
 *   4. rank 0 reads the remaining frames in batches of about 64 MiB and broadcasts each
 *      batch after a control word (more / done / failed), so memory stays bounded and
 *      the others receive while rank 0 reads.
 * A failure that is not rank 0's read error (memory on some rank) ends the job: the others
 * are in the middle of the exchange and cannot be told otherwise. While rank 0 reads, the
 * others wait without spinning and rank 0's thread pool uses every core of the node.
 *
 * Also here, as it too belongs to molscope itself and not to the Tcl package's copy of the
 * layer: sharing a node's cores between its ranks. */
#include "config.h"
#include "parallel/parallel.h"
#include "base/threads.h"
#include "fileio/load.h"
#include "molecule/serialize.h"

#include <stdlib.h>
#include <string.h>
#include <unistd.h>

#define BATCH_BYTES ((size_t)64 << 20)

enum { CTL_DONE = 0, CTL_BATCH = 1, CTL_FAILED = 2 };

int ms_par_bcast_enabled(void)
{
    return ms_par_size() > 1 && !ms_env_flag("MOLSCOPE_NOBCAST");
}

void ms_par_share_cores(void)
{
    int local = ms_par_local_size();
    if (local <= 1 || getenv("MOLSCOPE_THREADS")) return;
    long cores = sysconf(_SC_NPROCESSORS_ONLN);
    ms_threads_set_limit(cores / local > 1 ? (int)(cores / local) : 1);
}

static uint64_t fnv(uint64_t h, const void *data, size_t n)
{
    const unsigned char *p = data;
    for (size_t i = 0; i < n; i++) {
        h ^= p[i];
        h *= 1099511628211ull;
    }
    return h;
}

/* Step 1: every rank loads the same file the same way. A rank that already failed
 * (failed != 0, its message in err) still takes part, with a key no other rank has, so
 * every rank returns an error and none waits for it. */
static int join(const char *what, const char *path, const ms_load_opts *o, size_t natoms,
                int failed, ms_error *err)
{
    uint64_t h = 1469598103934665603ull;
    long nums[5] = {o->first, o->last, o->step, o->filebonds, o->autobonds};
    uint64_t n = natoms;
    h = fnv(h, what, strlen(what) + 1);
    h = fnv(h, path, strlen(path) + 1);
    h = fnv(h, o->type ? o->type : "", strlen(o->type ? o->type : "") + 1);
    h = fnv(h, nums, sizeof nums);
    h = fnv(h, &n, sizeof n);
    if (failed) h ^= 0x9e3779b97f4a7c15ull * (uint64_t)(ms_par_rank() + 1);
    const char *env = getenv("MOLSCOPE_BCAST_TIMEOUT");
    double timeout = env && *env ? atof(env) : 300.0;
    int same;
    if (ms_par_agree(h, timeout, &same, err))
        ms_par_abort(1, "broadcast load of %s: %s (is it run on rank 0 only? load with bcast "
                        "only where every rank loads the same file)", path, err->msg);
    if (failed) return -1;
    if (!same) {
        ms_error_set(err, "the ranks do not all load this file with the same options (or into "
                          "molecules of the same size) at this point");
        return -1;
    }
    return 0;
}

/* Step 2: rank 0's outcome (rc, and its message on failure) on every rank. */
static int share_outcome(int rc, ms_error *err)
{
    int32_t v = rc;
    ms_par_bcast_small(&v, sizeof v, err); /* the others wait here while rank 0 reads */
    if (v != 0) ms_par_bcast(err->msg, sizeof err->msg, err);
    return v;
}

static void bcast_blocks(const ms_molser *s, ms_error *err)
{
    for (size_t k = 0; k < s->nblocks; k++) ms_par_bcast(s->block[k].data, s->block[k].bytes, err);
}

/* Step 3: the structure. Returns the molecule on every rank. */
static ms_molecule *share_structure(ms_molecule *m, ms_error *err)
{
    ms_molser s;
    void *head = NULL;
    size_t len = 0;
    if (ms_par_rank() == 0) {
        if (ms_molser_pack(m, &s, err)) ms_par_abort(1, "broadcast load: %s", err->msg);
        head = s.head;
        len = s.head_len;
        ms_par_bcast_buffer(&head, &len, err);
        bcast_blocks(&s, err);
        ms_molser_free(&s);
        return m;
    }
    ms_par_bcast_buffer(&head, &len, err);
    m = ms_molser_unpack(head, len, &s, err);
    free(head);
    if (!m) ms_par_abort(1, "broadcast load: %s", err->msg);
    bcast_blocks(&s, err);
    if (ms_molser_finish(m, &s, err)) ms_par_abort(1, "broadcast load: %s", err->msg);
    ms_molser_free(&s);
    return m;
}

/* One batch of frames: rank 0's frames [first, nframes) to the others' m (perhaps none:
 * every rank calls this whenever rank 0 does, whatever its own frame count). */
static void share_frames(ms_molecule *m, size_t first, ms_error *err)
{
    ms_molser s;
    void *head = NULL;
    size_t len = 0;
    if (ms_par_rank() == 0) {
        if (ms_molser_pack_frames(m, first, m->nframes - first, &s, err))
            ms_par_abort(1, "broadcast load: %s", err->msg);
        head = s.head;
        len = s.head_len;
        ms_par_bcast_buffer(&head, &len, err);
    } else {
        ms_par_bcast_buffer(&head, &len, err);
        int rc = ms_molser_unpack_frames(m, head, len, &s, err);
        free(head);
        if (rc) ms_par_abort(1, "broadcast load: %s", err->msg);
    }
    bcast_blocks(&s, err);
    ms_molser_free(&s);
}

static long batch_frames(const ms_molecule *m)
{
    size_t per = m->atoms.n * 3 * sizeof(float) * 2;
    return per ? (long)MS_MAX((size_t)1, BATCH_BYTES / per) : 1;
}

/* Step 4: rank 0 reads the pending frames batch by batch; all ranks receive them. Returns
 * 0, or -1 on every rank with rank 0's read error. */
static int share_pending(ms_molecule *m, ms_error *err)
{
    for (;;) {
        int32_t ctl = CTL_DONE;
        size_t before = m->nframes;
        if (ms_par_rank() == 0 && m->pending) {
            char *done = NULL;
            int rc = ms_loader_pump(m, batch_frames(m), &done, err);
            free(done);
            ctl = rc < 0 ? CTL_FAILED : m->nframes > before || rc > 0 ? CTL_BATCH : CTL_DONE;
        }
        ms_par_bcast_small(&ctl, sizeof ctl, err);
        if (ctl == CTL_FAILED) {
            ms_par_bcast(err->msg, sizeof err->msg, err);
            return -1;
        }
        if (ctl == CTL_DONE) break;
        share_frames(m, before, err);
    }
    /* Bonds by distance wait for the first frame: the others compute them as rank 0 did. */
    if (ms_par_rank() != 0 && ms_load_finish_bonds(m, err))
        ms_par_abort(1, "broadcast load: %s", err->msg);
    return 0;
}

/* Rank 0 reads while the others wait (without taking a core): give it the whole pool. */
static int rank0_all_cores(void)
{
    return ms_par_rank() == 0 && !getenv("MOLSCOPE_THREADS") ? ms_threads_set_limit(0) : -1;
}

static void rank0_share_again(int limit)
{
    if (limit >= 0) ms_threads_set_limit(limit);
}

static void load_opts_first(const ms_load_opts *o, ms_load_opts *first)
{
    *first = *o;
    first->waitfor = 1;
    first->bcast = 0;
}

/* Steps 2-4 of `mol new` after the join. */
static ms_molecule *load_new_joined(const ms_registry *r, const char *path,
                                    const ms_load_opts *o, ms_error *err)
{
    ms_molecule *m = NULL;
    int limit = rank0_all_cores();
    if (ms_par_rank() == 0) {
        ms_load_opts first;
        load_opts_first(o, &first);
        m = ms_load_new(r, path, &first, err);
    }
    if (share_outcome(m || ms_par_rank() != 0 ? 0 : -1, err)) {
        rank0_share_again(limit);
        return NULL;
    }
    m = share_structure(m, err);
    share_frames(m, 0, err); /* the frames read with the structure (rank 0 decides) */
    int rc = share_pending(m, err);
    rank0_share_again(limit);
    if (rc) {
        ms_mol_free(m);
        return NULL;
    }
    m->frame = m->nframes ? (int)m->nframes - 1 : -1;
    return m;
}

ms_molecule *ms_par_load_new(const ms_registry *r, const char *path, const ms_load_opts *o,
                             ms_error *err)
{
    err->msg[0] = '\0';
    if (join("new", path, o, 0, 0, err)) return NULL;
    return load_new_joined(r, path, o, err);
}

/* Undo a file added to m by rank 0's ms_load_add when its later frames fail. */
static void drop_last_file(ms_molecule *m, size_t frames_before, int frame_before)
{
    ms_loader_cancel(m);
    ms_mol_truncate_frames(m, frames_before);
    m->frame = frame_before;
    if (m->nfiles) {
        m->nfiles--;
        free(m->files[m->nfiles].path);
        free(m->files[m->nfiles].type);
    }
}

int ms_par_load_add(const ms_registry *r, ms_molecule *m, const char *path,
                    const ms_load_opts *o, ms_error *err)
{
    err->msg[0] = '\0';
    /* Files load in order: first the frames each rank is still reading for itself. */
    int failed = 0;
    if (m->pending) {
        char *done = NULL;
        failed = ms_loader_pump(m, -1, &done, err) < 0;
        free(done);
    }
    if (join("add", path, o, m->atoms.n, failed, err)) return -1;
    if (m->atoms.n == 0) {
        /* A structure into an empty molecule: load it as new, then move it in. */
        ms_molecule *src = load_new_joined(r, path, o, err);
        if (!src) return -1;
        ms_load_adopt(m, src);
        return 0;
    }
    size_t before = m->nframes;
    int frame_before = m->frame, rc = 0, limit = rank0_all_cores();
    if (ms_par_rank() == 0) {
        ms_load_opts first;
        load_opts_first(o, &first);
        rc = ms_load_add(r, m, path, &first, err);
    }
    rc = share_outcome(rc, err);
    if (rc) {
        rank0_share_again(limit);
        return -1;
    }
    /* The file record (its type is the plugin rank 0 chose). */
    void *type = ms_par_rank() == 0 ? m->files[m->nfiles - 1].type : NULL;
    size_t len = ms_par_rank() == 0 ? strlen(type) + 1 : 0;
    ms_par_bcast_buffer(&type, &len, err);
    if (ms_par_rank() != 0) {
        int bad = len == 0 || ((char *)type)[len - 1] != '\0' ||
                  ms_mol_add_file(m, path, type, err);
        free(type);
        if (bad) ms_par_abort(1, "broadcast load: %s", err->msg[0] ? err->msg : "bad file type");
    }
    share_frames(m, before, err);
    rc = share_pending(m, err);
    rank0_share_again(limit);
    if (rc) {
        drop_last_file(m, before, frame_before);
        return -1;
    }
    if (m->nframes > before) m->frame = (int)m->nframes - 1;
    return 0;
}
