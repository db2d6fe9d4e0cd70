/* base.c: error reports, checked array growth, time and environment helpers. */
#include "config.h"
#include "base/base.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>
#include <time.h>
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

size_t ms_peak_rss(void)
{
    struct rusage ru;
    if (getrusage(RUSAGE_SELF, &ru) != 0) return 0;
    return (size_t)ru.ru_maxrss * 1024u;
}

size_t ms_mem_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f) return 0;
    char line[256];
    unsigned long long kb = 0;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %llu kB", &kb) == 1) break;
    fclose(f);
    return (size_t)kb * 1024u;
}
