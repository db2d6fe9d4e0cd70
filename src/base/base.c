/* base.c: error reports, checked array growth, time and environment helpers. */
#include "config.h"
#include "base/base.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
#include <sys/mman.h>
#include <sys/resource.h>

void ms_error_set(ms_error *err, const char *fmt, ...)
{
    if (!err) return;
    va_list ap;
    va_start(ap, fmt);
    vsnprintf(err->msg, sizeof err->msg, fmt, ap);
    va_end(ap);
}

void ms_error_prefix(ms_error *err, const char *fmt, ...)
{
    if (!err) return;
    char buf[sizeof err->msg * 2];
    va_list ap;
    va_start(ap, fmt);
    int n = vsnprintf(buf, sizeof err->msg, fmt, ap);
    va_end(ap);
    if (n < 0) return;
    size_t len = strlen(buf);
    memcpy(buf + len, ": ", 3);
    len += 2;
    size_t old = strnlen(err->msg, sizeof err->msg - 1);
    memcpy(buf + len, err->msg, old);
    len += old;
    if (len >= sizeof err->msg) len = sizeof err->msg - 1;
    memcpy(err->msg, buf, len);
    err->msg[len] = '\0';
}

int ms_mul_size(size_t a, size_t b, size_t *out)
{
    if (a && b > SIZE_MAX / a) return -1;
    *out = a * b;
    return 0;
}

int ms_grow(void **ptr, size_t *cap, size_t need, size_t elsize)
{
    if (need <= *cap) return 0;
    size_t ncap = *cap ? *cap : 16;
    while (ncap < need) {
        if (ncap > SIZE_MAX / 2) return -1;
        ncap *= 2;
    }
    size_t bytes;
    if (ms_mul_size(ncap, elsize, &bytes)) return -1;
    void *p = realloc(*ptr, bytes);
    if (!p) return -1;
    *ptr = p;
    *cap = ncap;
    return 0;
}

void *ms_alloc_array(size_t n, size_t elsize)
{
    size_t bytes;
    if (ms_mul_size(n, elsize, &bytes)) return NULL;
    return malloc(bytes ? bytes : 1);
}

void *ms_calloc_array(size_t n, size_t elsize)
{
    return calloc(n ? n : 1, elsize ? elsize : 1);
}

void ms_advise_huge(void *p, size_t bytes)
{
#ifdef MADV_HUGEPAGE
    const uintptr_t huge = (uintptr_t)2 << 20;
    uintptr_t a = ((uintptr_t)p + huge - 1) & ~(huge - 1), e = ((uintptr_t)p + bytes) & ~(huge - 1);
    if (p && e > a) madvise((void *)a, e - a, MADV_HUGEPAGE);
#else
    (void)p, (void)bytes;
#endif
}

void ms_prefault(void *p, size_t bytes)
{
#ifdef MADV_POPULATE_WRITE
    const uintptr_t page = 4096;
    uintptr_t a = ((uintptr_t)p + page - 1) & ~(page - 1), e = ((uintptr_t)p + bytes) & ~(page - 1);
    if (p && bytes >= ((size_t)1 << 20) && e > a) madvise((void *)a, e - a, MADV_POPULATE_WRITE);
#else
    (void)p, (void)bytes;
#endif
}

char *ms_strdup(const char *s)
{
    size_t n = strlen(s) + 1;
    char *d = malloc(n);
    if (d) memcpy(d, s, n);
    return d;
}

double ms_now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

int ms_env_flag(const char *name)
{
    const char *v = getenv(name);
    return v && *v && strcmp(v, "0") != 0;
}

int ms_word_eq(const char *word, const char *name)
{
    return strncasecmp(word, name, 15) == 0;
}

/* A "Name: N kB" line of a /proc file, in bytes; 0 when absent. */
static size_t proc_kb(const char *path, const char *name)
{
    FILE *f = fopen(path, "r");
    if (!f) return 0;
    char line[256];
    unsigned long long kb = 0;
    size_t len = strlen(name);
    while (fgets(line, sizeof line, f))
        if (strncmp(line, name, len) == 0 && line[len] == ':' &&
            sscanf(line + len + 1, "%llu", &kb) == 1)
            break;
    fclose(f);
    return (size_t)kb * 1024u;
}

size_t ms_rss(void) { return proc_kb("/proc/self/status", "VmRSS"); }

size_t ms_peak_rss(void)
{
    size_t hwm = proc_kb("/proc/self/status", "VmHWM");
    struct rusage ru;
    if (hwm || getrusage(RUSAGE_SELF, &ru) != 0) return hwm;
    return (size_t)ru.ru_maxrss * 1024u;
}

/* A number from the first line of a file; 0 when absent or not a number ("max"). */
static size_t file_number(const char *path)
{
    FILE *f = fopen(path, "r");
    unsigned long long v = 0;
    if (!f) return 0;
    if (fscanf(f, "%llu", &v) != 1) v = 0;
    fclose(f);
    return (size_t)v;
}

/* a < b, where 0 means unknown (larger than anything) */
static size_t min_known(size_t a, size_t b) { return !a ? b : !b ? a : MS_MIN(a, b); }

size_t ms_mem_available(void)
{
    size_t avail = proc_kb("/proc/meminfo", "MemAvailable");
    /* a batch job's memory limit (cgroup v2) may be lower than the machine's */
    size_t max = file_number("/sys/fs/cgroup/memory.max");
    size_t cur = file_number("/sys/fs/cgroup/memory.current");
    if (max) avail = min_known(avail, max > cur ? max - cur : 1);
    /* and so may the address-space limit (ulimit -v), less what is mapped already */
    struct rlimit rl;
    if (getrlimit(RLIMIT_AS, &rl) == 0 && rl.rlim_cur != RLIM_INFINITY) {
        size_t mapped = proc_kb("/proc/self/status", "VmSize");
        avail = min_known(avail, (size_t)rl.rlim_cur > mapped ? (size_t)rl.rlim_cur - mapped : 1);
    }
    return avail;
}
