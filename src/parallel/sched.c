/* sched.c: ms_par_for, the dynamically balanced loop behind `parallel for` and the movie
 * driver (which also learns on rank 0 when each frame is done: ms_par_for_observed).
 *
 * Protocol, on the layer's own communicator, two tags:
 *   ASK  (worker -> rank 0, no payload): "give me an index"
 *   GIVE (rank 0 -> worker, two int64): {1, index}: do this index; {0, 0}: nothing is
 *        left, stop
 * A worker loops: send ASK, receive GIVE, stop on "stop", else do the item. It has one
 * request in flight at a time and its last message from rank 0 is always its stop, so nothing is
 * left in flight when a loop ends and the next loop's messages cannot be confused with
 * this one's. Rank 0 answers requests from a server thread (Iprobe with back-off, so it
 * uses no core while idle) and meanwhile works on indices itself, taking them from the
 * same counter under a mutex; the main thread makes no MPI call while the server runs
 * (MPI_THREAD_SERIALIZED). Where MPI gives less than that, rank 0 answers the requests
 * between its own items instead. Every index is handed out exactly once, by that counter.
 * Rank 0 finishes when it has no index left and every worker has had its stop; then all
 * ranks meet in a barrier, so the loop returns everywhere only when every item is done.
 *
 * Completion: a worker sends its next ASK only after its previous item returned, so an ASK
 * from rank r tells rank 0 that the index it last gave r is done; rank 0's own items are
 * done when its call returns. The observer is told of each from wherever rank 0 learns it
 * (its server thread or its main thread), with no extra message.
 *
 * A failing item ends the job (ms_par_abort) when there are several ranks: the index it
 * held could only be redone by a protocol much less simple than this one. */
#include "config.h"
#include "parallel/parallel.h"
#include "parallel/internal.h"

#include <limits.h>
#include <pthread.h>
#include <stdio.h>
#include <stdlib.h>

static int serial_loop(long first, long last, ms_par_item_fn fn, void *ctx,
                       ms_par_done_fn done, void *done_ctx, ms_error *err)
{
    for (long i = first; i <= last; i++) {
        if (fn(ctx, i, err)) return -1;
        if (done) done(done_ctx, i);
        if (i == LONG_MAX) break;
    }
    return 0;
}

#ifdef MS_HAVE_MPI
typedef struct sched {
    ms_par_item_fn fn;
    void *ctx;
    ms_par_done_fn done;   /* the observer (may be NULL) */
    void *done_ctx;
    const char *what;      /* names a failure; NULL: "parallel for: index <i>" */
    long *held;            /* per worker rank: the index it works on */
    uint8_t *holding;      /* per worker rank: whether held[] is valid */
    long next, last;       /* the next index to hand out; the last one */
    int exhausted;         /* every index was handed out (also when last is LONG_MAX) */
    int workers_left;      /* workers that have not yet had their stop */
    pthread_mutex_t lock;  /* the counter, and (with a server thread) all MPI calls */
} sched;

enum { TAG_ASK = 7101, TAG_GIVE = 7102 };

/* The next index in *i; 0 when none is left. Caller holds the lock. */
static int take(sched *s, long *i)
{
    if (s->exhausted || s->next > s->last) return 0;
    *i = s->next;
    if (s->next == s->last) s->exhausted = 1;
    else s->next++;
    return 1;
}

/* Answer every request waiting now. Returns how many were answered. */
static int serve_pending(sched *s)
{
    MPI_Comm comm = ms_par_comm();
    int served = 0;
    for (;;) {
        int flag = 0;
        MPI_Status st;
        MPI_Iprobe(MPI_ANY_SOURCE, TAG_ASK, comm, &flag, &st);
        if (!flag) return served;
        MPI_Recv(NULL, 0, MPI_BYTE, st.MPI_SOURCE, TAG_ASK, comm, MPI_STATUS_IGNORE);
        int r = st.MPI_SOURCE;
        if (s->holding[r] && s->done) s->done(s->done_ctx, s->held[r]);
        long i = 0;
        int64_t give[2] = {take(s, &i), 0};
        give[1] = i;
        s->holding[r] = (uint8_t)give[0];
        s->held[r] = i;
        if (!give[0]) s->workers_left--;
        MPI_Send(give, 2, MPI_INT64_T, st.MPI_SOURCE, TAG_GIVE, comm);
        served++;
    }
}

static void *server_main(void *arg)
{
    sched *s = arg;
    int spins = 0;
    for (;;) {
        pthread_mutex_lock(&s->lock);
        int served = serve_pending(s), left = s->workers_left;
        pthread_mutex_unlock(&s->lock);
        if (left == 0) return NULL;
        if (served) spins = 0;
        else ms_par_backoff(&spins);
    }
}

static void item_failed(sched *s, long i, ms_error *err)
{
    /* Hold the lock so the server thread is not inside MPI while we abort. */
    pthread_mutex_lock(&s->lock);
    const char *msg = err->msg[0] ? err->msg : "failed";
    if (s->what) ms_par_abort(1, "%s: %s", s->what, msg);
    ms_par_abort(1, "parallel for: index %ld: %s", i, msg);
}

/* Rank 0: compute alongside the server (thread, or polling between items). */
static void rank0_loop(sched *s, ms_error *err)
{
    pthread_t th;
    int threaded = ms_par_thread_level() >= MPI_THREAD_SERIALIZED &&
                   pthread_create(&th, NULL, server_main, s) == 0;
    for (;;) {
        long i = 0;
        pthread_mutex_lock(&s->lock);
        if (!threaded) serve_pending(s);
        int more = take(s, &i);
        pthread_mutex_unlock(&s->lock);
        if (!more) break;
        if (s->fn(s->ctx, i, err)) item_failed(s, i, err);
        if (s->done) s->done(s->done_ctx, i);
    }
    if (threaded) {
        pthread_join(th, NULL);
        return;
    }
    int spins = 0;
    while (s->workers_left > 0) {
        if (serve_pending(s)) spins = 0;
        else ms_par_backoff(&spins);
    }
}

static void worker_loop(sched *s, ms_error *err)
{
    MPI_Comm comm = ms_par_comm();
    for (;;) {
        int64_t give[2];
        MPI_Request req;
        MPI_Send(NULL, 0, MPI_BYTE, 0, TAG_ASK, comm);
        MPI_Irecv(give, 2, MPI_INT64_T, 0, TAG_GIVE, comm, &req);
        ms_par_wait(&req, 0);
        if (!give[0]) return;
        if (s->fn(s->ctx, (long)give[1], err)) item_failed(s, (long)give[1], err);
    }
}
#endif

int ms_par_for_observed(long first, long last, ms_par_item_fn fn, void *ctx,
                        ms_par_done_fn done, void *done_ctx, const char *what, ms_error *err)
{
    if (ms_par_size() == 1) return serial_loop(first, last, fn, ctx, done, done_ctx, err);
#ifdef MS_HAVE_MPI
    int n = ms_par_size();
    sched s = {.fn = fn, .ctx = ctx, .done = done, .done_ctx = done_ctx, .what = what,
               .next = first, .last = last, .workers_left = n - 1};
    s.held = calloc((size_t)n, sizeof *s.held);
    s.holding = calloc((size_t)n, 1);
    if (!s.held || !s.holding) /* every rank must take part: end the job */
        ms_par_abort(1, "parallel for: out of memory");
    pthread_mutex_init(&s.lock, NULL);
    if (ms_par_rank() == 0) rank0_loop(&s, err);
    else worker_loop(&s, err);
    pthread_mutex_destroy(&s.lock);
    free(s.held);
    free(s.holding);
    return ms_par_barrier(err);
#else
    (void)what;
    return serial_loop(first, last, fn, ctx, done, done_ctx, err);
#endif
}

int ms_par_for(long first, long last, ms_par_item_fn fn, void *ctx, ms_error *err)
{
    return ms_par_for_observed(first, last, fn, ctx, NULL, NULL, NULL, err);
}
