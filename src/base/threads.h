/* threads.h: a persistent pool of worker threads for parallel loops. All cores are used by
 * default; MOLSCOPE_THREADS=N overrides. Work is handed out dynamically in chunks, so loops
 * with uneven work balance themselves. */
#ifndef MS_THREADS_H
#define MS_THREADS_H

#include <stddef.h>

/* fn(ctx, begin, end, thread) is called for disjoint ranges covering [0, n). thread is in
 * [0, ms_threads_count()). The call returns when every range is done. Nested calls run
 * serially in the calling thread. */
typedef void (*ms_range_fn)(void *ctx, size_t begin, size_t end, int thread);
void ms_parallel_for(size_t n, size_t chunk, ms_range_fn fn, void *ctx);

/* Number of threads ms_parallel_for uses (workers plus the caller), within the limit. */
int ms_threads_count(void);
/* Use at most n threads (at least 1) in later loops; 0 lifts the limit. Returns the limit
 * before (0 for none). The pool keeps its threads: several MPI ranks on one node each take
 * their share of the cores, and a rank working while the others wait takes them all. Call
 * it from the thread that runs the loops, between loops. */
int ms_threads_set_limit(int n);
/* Number of online processors. */
int ms_cpu_count(void);

#endif
