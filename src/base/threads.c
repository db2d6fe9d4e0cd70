/* threads.c: the worker pool behind ms_parallel_for. Workers sleep on a condition variable
 * between loops; each loop bumps a generation counter and workers pull chunks from an atomic
 * cursor until the range is exhausted. */
#include "config.h"
#include "base/threads.h"
#include "base/base.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdlib.h>
#include <unistd.h>

typedef struct pool_job {
    ms_range_fn fn;
    void *ctx;
    size_t n, chunk;
    int nactive;             /* threads that take part (the others only check in) */
    atomic_size_t next;
    atomic_int pending;      /* workers still inside this job */
} pool_job;

static struct {
    pthread_once_t once;
    pthread_mutex_t lock;
    pthread_cond_t wake, done;
    int nthreads;            /* including the caller */
    unsigned long generation;
    pool_job *job;
    int started;
    int limit;               /* 0 = all of the pool */
} pool = {.once = PTHREAD_ONCE_INIT,
          .lock = PTHREAD_MUTEX_INITIALIZER,
          .wake = PTHREAD_COND_INITIALIZER,
          .done = PTHREAD_COND_INITIALIZER};

static _Thread_local int in_pool_loop;
/* One loop at a time uses the pool; a second caller thread runs its loop serially. */
static pthread_mutex_t call_lock = PTHREAD_MUTEX_INITIALIZER;

int ms_cpu_count(void)
{
    long n = sysconf(_SC_NPROCESSORS_ONLN);
    return n > 0 ? (int)n : 1;
}

static void run_chunks(pool_job *job, int tid)
{
    for (;;) {
        size_t b = atomic_fetch_add(&job->next, job->chunk);
        if (b >= job->n) break;
        size_t e = b + job->chunk < job->n ? b + job->chunk : job->n;
        job->fn(job->ctx, b, e, tid);
    }
}

static void *worker_main(void *arg)
{
    int tid = (int)(intptr_t)arg;
    unsigned long seen = 0;
    in_pool_loop = 1;
    pthread_mutex_lock(&pool.lock);
    for (;;) {
        while (pool.generation == seen) pthread_cond_wait(&pool.wake, &pool.lock);
        seen = pool.generation;
        pool_job *job = pool.job;
        pthread_mutex_unlock(&pool.lock);
        if (tid < job->nactive) run_chunks(job, tid);
        pthread_mutex_lock(&pool.lock);
        if (atomic_fetch_sub(&job->pending, 1) == 1) pthread_cond_signal(&pool.done);
    }
    return NULL;
}

static void pool_init(void)
{
    int n = ms_cpu_count();
    const char *env = getenv("MOLSCOPE_THREADS");
    if (env && *env) {
        int v = atoi(env);
        if (v >= 1 && v <= 1024) n = v;
    }
    pool.nthreads = 1;
    for (int i = 1; i < n; i++) {
        pthread_t th;
        pthread_attr_t attr;
        pthread_attr_init(&attr);
        pthread_attr_setdetachstate(&attr, PTHREAD_CREATE_DETACHED);
        if (pthread_create(&th, &attr, worker_main, (void *)(intptr_t)i) == 0) pool.nthreads++;
        pthread_attr_destroy(&attr);
    }
}

static int pool_size(void)
{
    pthread_once(&pool.once, pool_init);
    return pool.nthreads;
}

int ms_threads_count(void)
{
    int n = pool_size();
    return pool.limit > 0 && pool.limit < n ? pool.limit : n;
}

int ms_threads_set_limit(int n)
{
    int before = pool.limit;
    pool.limit = n > 0 ? n : 0;
    return before;
}

void ms_parallel_for(size_t n, size_t chunk, ms_range_fn fn, void *ctx)
{
    if (n == 0) return;
    if (chunk == 0) chunk = 1;
    int nt = ms_threads_count();
    if (nt == 1 || n <= chunk || in_pool_loop || pthread_mutex_trylock(&call_lock) != 0) {
        fn(ctx, 0, n, 0);
        return;
    }
    pool_job job = {.fn = fn, .ctx = ctx, .n = n, .chunk = chunk, .nactive = nt};
    atomic_init(&job.next, 0);
    atomic_init(&job.pending, pool_size() - 1);
    pthread_mutex_lock(&pool.lock);
    pool.job = &job;
    pool.generation++;
    pthread_cond_broadcast(&pool.wake);
    pthread_mutex_unlock(&pool.lock);

    in_pool_loop = 1;
    run_chunks(&job, 0);
    in_pool_loop = 0;

    pthread_mutex_lock(&pool.lock);
    while (atomic_load(&job.pending) > 0) pthread_cond_wait(&pool.done, &pool.lock);
    pthread_mutex_unlock(&pool.lock);
    pthread_mutex_unlock(&call_lock);
}
