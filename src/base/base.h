/* base.h: small shared utilities every module uses: error reports, checked growth of
 * arrays, monotonic time, environment switches. Nothing here knows about molecules or Tcl. */
#ifndef MS_BASE_H
#define MS_BASE_H

#include <stddef.h>
#include <stdint.h>
#include <stdarg.h>

/* An error report travels up from the core to the Tcl binding, which prefixes the command
 * name. Functions that can fail take an ms_error* and return -1 (or NULL) after filling it. */
typedef struct ms_error {
    char msg[1024];
} ms_error;

void ms_error_set(ms_error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));
/* Prefix an existing message: "prefix: old message". */
void ms_error_prefix(ms_error *err, const char *fmt, ...)
    __attribute__((format(printf, 2, 3)));

/* Grow *ptr (an array of elsize-byte items with capacity *cap) to hold at least need items.
 * Returns 0, or -1 with *ptr unchanged when memory is exhausted or the size overflows. */
int ms_grow(void **ptr, size_t *cap, size_t need, size_t elsize);

/* Multiply two sizes; returns 0 and sets *out, or -1 on overflow. */
int ms_mul_size(size_t a, size_t b, size_t *out);

/* malloc/calloc that return NULL on a size that overflows. */
void *ms_alloc_array(size_t n, size_t elsize);
void *ms_calloc_array(size_t n, size_t elsize);

/* Ask for huge pages under the 2 MB-aligned part of a large buffer (a hint; no error): a
 * buffer about to be filled takes one page fault per 2 MB instead of one per 4 kB. */
void ms_advise_huge(void *p, size_t bytes);
/* Commit the pages of a large buffer the caller is about to write whole, in one call rather
 * than one page fault per 4 kB page (MADV_POPULATE_WRITE; a hint, no error, nothing on a
 * kernel without it). The molecule's arrays take this rather than huge pages: on a virtual
 * machine that hands freed memory back to its host, a fresh huge page is zeroed at a
 * fraction of the speed of small ones (doc/BENCHMARKS.md, issue 23). */
void ms_prefault(void *p, size_t bytes);

/* Duplicate a string (NULL on failure). */
char *ms_strdup(const char *s);

/* Seconds from a monotonic clock. */
double ms_now(void);

/* An environment variable that is set to anything but "" or "0". */
int ms_env_flag(const char *name);

/* Case-insensitive comparison of a Tcl subcommand word against a name, over at most 15
 * characters as VMD does: "newcartoon" matches "NewCartoon". */
int ms_word_eq(const char *word, const char *name);

/* Resident-set peak of this process in bytes (VmHWM of /proc/self/status, else getrusage). */
size_t ms_peak_rss(void);
/* Resident set of this process now, in bytes (VmRSS of /proc/self/status); 0 when unknown. */
size_t ms_rss(void);
/* Memory this process can still get, in bytes: MemAvailable in /proc/meminfo, or less when
 * the cgroup's memory limit or the address-space limit (RLIMIT_AS, `ulimit -v`, less what
 * is mapped already) leaves less; 0 when unknown. For sizes no file bounds: check them
 * before allocating. */
size_t ms_mem_available(void);

#define MS_MIN(a, b) ((a) < (b) ? (a) : (b))
#define MS_MAX(a, b) ((a) > (b) ? (a) : (b))
#define MS_COUNTOF(a) (sizeof(a) / sizeof((a)[0]))

#endif
