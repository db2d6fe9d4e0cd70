/* parallel.h: molscope across MPI ranks: start-up and shutdown, who we are, collectives on
 * byte buffers, a dynamically balanced loop (ms_par_for) and broadcast loading of
 * molecules. Every function also works without MPI (a build without it, MOLSCOPE_NOMPI set,
 * or no launcher): then the job is one rank and the collectives are trivial.
 *
 * Start-up: ms_par_init calls MPI_Init_thread (MPI_THREAD_SERIALIZED: rank 0's for-loop
 * server thread makes MPI calls while the main thread computes) when a launcher started
 * the process: mpirun/mpiexec of OpenMPI or MPICH (Hydra), PMI or PMIx launchers, srun.
 * A process started by hand is a job of one rank and does not pay MPI's start-up time;
 * MOLSCOPE_MPI=1 makes it an MPI singleton anyway, MOLSCOPE_NOMPI=1 never uses MPI.
 *
 * Shutdown: ms_par_exit(status) finalizes MPI when this code initialised it; a non-zero
 * status on any rank of a job of several aborts the whole job (MPI_Abort), so an error on
 * one rank never leaves the others waiting in a collective.
 *
 * Each copy of this code (molscope itself, the molscope::parallel Tcl package loaded into
 * a plain tclsh) keeps its own duplicate of MPI_COMM_WORLD, so their messages never mix. */
#ifndef MS_PARALLEL_H
#define MS_PARALLEL_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"

/* Start MPI when a launcher started us (see above). Safe to call when MPI is already
 * initialised (then this copy uses it but does not finalize it) and more than once.
 * Returns 0; -1 when MPI failed to start (err says why). */
int ms_par_init(int *argc, char ***argv, ms_error *err);
/* Whether MPI is in use, this copy initialised it, and the job's shape. */
int ms_par_using_mpi(void);
int ms_par_owner(void);
int ms_par_rank(void);
int ms_par_size(void);
/* Ranks sharing this node (1 without MPI). */
int ms_par_local_size(void);
/* Give this rank's thread pool its share of the node's cores (ms_threads_set_limit) when
 * several ranks share the node and MOLSCOPE_THREADS is not set. (In bcastload.c with the
 * other parts that only molscope itself has, not the Tcl package's copy.) */
void ms_par_share_cores(void);
/* The processor (host) name. */
const char *ms_par_nodename(void);
/* The MPI thread level provided (0 without MPI). */
int ms_par_thread_level(void);

/* End of the program: finalize MPI (when this copy started it) after a zero status; abort
 * every rank after a non-zero one when the job has several. Returns status. */
int ms_par_exit(int status);
/* End the whole job now: print "molscope: rank R: <message>" on stderr and abort every
 * rank (MPI_Abort); with one rank, exit(status). Does not return. */
void ms_par_abort(int status, const char *fmt, ...)
    __attribute__((format(printf, 2, 3), noreturn));

/* ---- collectives: every rank of the job must call them in the same order ---- */

int ms_par_barrier(ms_error *err);
/* Broadcast bytes bytes from rank 0 into buf on every rank (any size: sent in pieces). */
int ms_par_bcast(void *buf, size_t bytes, ms_error *err);
/* The same for a small message that rank 0 may be slow to send (a line it is still
 * reading): the others wait without spinning on a core. */
int ms_par_bcast_small(void *buf, size_t bytes, ms_error *err);
/* Broadcast rank 0's buffer of any length: the other ranks get a malloc'd copy in *buf
 * (rank 0's *buf is untouched). */
int ms_par_bcast_buffer(void **buf, size_t *len, ms_error *err);

/* Every rank's byte string, in rank order: part r is data + off[r], len[r] bytes. */
typedef struct ms_par_parts {
    char *data;
    size_t *off, *len;
    int n;
} ms_par_parts;
void ms_par_parts_free(ms_par_parts *p);
/* Gather every rank's bytes on every rank (total below 2 GiB). */
int ms_par_allgather(const void *buf, size_t len, ms_par_parts *out, ms_error *err);
/* Gather every rank's bytes on rank 0 only (the others get n = 0). */
int ms_par_gather0(const void *buf, size_t len, ms_par_parts *out, ms_error *err);

/* Do all ranks pass the same key? Sets *same to 1 or 0 on every rank. Waits at most
 * timeout seconds for every rank to arrive (<= 0: forever); -1 with err when they do not
 * (the caller should then end the job: the others may never come). */
int ms_par_agree(uint64_t key, double timeout, int *same, ms_error *err);

/* ---- the dynamically balanced loop ---- */

/* One work item; returns 0, or -1 after filling err. */
typedef int (*ms_par_item_fn)(void *ctx, long index, ms_error *err);
/* Call fn for every index in [first, last] (inclusive) exactly once across the job; rank 0's
 * first and last decide. Indices are handed out one at a time on request, so faster ranks
 * take more; rank 0 computes too. Every rank returns once every index is done. With one
 * rank: a plain loop that stops at the first failure (-1, err). With several, a failure
 * ends the whole job with the item's message (the others cannot go on without it). */
int ms_par_for(long first, long last, ms_par_item_fn fn, void *ctx, ms_error *err);
/* Told on rank 0 that index is done (its item returned, on whichever rank ran it). Called
 * from rank 0's server thread or its main thread, so it must be thread-safe, quick, and
 * make no MPI call. Never called on the other ranks. */
typedef void (*ms_par_done_fn)(void *ctx, long index);
/* ms_par_for with an observer of completions (the movie driver feeds its encoder in frame
 * order as frames complete). done may be NULL. A failed item on one of several ranks ends
 * the job with "<what>: <the item's message>" (what NULL: "parallel for: index <i>: ..."),
 * for items whose messages name what they were. */
int ms_par_for_observed(long first, long last, ms_par_item_fn fn, void *ctx,
                        ms_par_done_fn done, void *done_ctx, const char *what, ms_error *err);

/* ---- loading a molecule once and broadcasting it (bcastload.c) ---- */

struct ms_registry;
struct ms_load_opts;
struct ms_molecule;
/* Whether broadcast loading is in effect: several ranks and MOLSCOPE_NOBCAST unset. */
int ms_par_bcast_enabled(void);
/* Collective `mol new`: rank 0 reads the file and broadcasts the structure, then every
 * frame in batches as it reads them (all frames: waitfor does not apply); the others build
 * the same molecule without touching the file. Every rank returns the same outcome (a
 * molecule, or NULL with rank 0's error message). */
struct ms_molecule *ms_par_load_new(const struct ms_registry *r, const char *path,
                                    const struct ms_load_opts *o, ms_error *err);
/* Collective `mol addfile` into m (the same molecule on every rank). */
int ms_par_load_add(const struct ms_registry *r, struct ms_molecule *m, const char *path,
                    const struct ms_load_opts *o, ms_error *err);

#endif
