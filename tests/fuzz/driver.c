/* driver.c: the main() of a fuzz target when it is not built with libFuzzer: the test
 * suite's smoke run. It feeds LLVMFuzzerTestOneInput every file of a seed-corpus folder,
 * then deterministic mutations of them: every truncation length on a stride, then byte
 * flips, byte overwrites with characters that matter to parsers, insertions and deletions
 * drawn from a fixed-seed PRNG, until MS_FUZZ_RUNS inputs (default 3000) or MS_FUZZ_SECONDS
 * (default 2.5) are spent. It prints PASS lines; a crash or a sanitizer report aborts the
 * program, which the test runner counts as a failure.
 *
 * usage: fuzz_<fmt> corpus-folder */
#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

/* Sanitizer settings: stop at the first report; a huge allocation fails instead of
 * aborting (readers must handle that). */
__attribute__((used)) const char *__asan_default_options(void);
__attribute__((used)) const char *__asan_default_options(void)
{
    return "allocator_may_return_null=1:detect_leaks=1";
}
__attribute__((used)) const char *__ubsan_default_options(void);
__attribute__((used)) const char *__ubsan_default_options(void)
{
    return "halt_on_error=1:print_stacktrace=1";
}

typedef struct seed {
    char *name;
    uint8_t *data;
    size_t size;
} seed;

static uint64_t prng_state = 0x9e3779b97f4a7c15ull;

static uint64_t prng(void)
{
    uint64_t x = prng_state;
    x ^= x << 13;
    x ^= x >> 7;
    x ^= x << 17;
    return prng_state = x;
}

static double now(void)
{
    struct timespec ts;
    clock_gettime(CLOCK_MONOTONIC, &ts);
    return (double)ts.tv_sec + 1e-9 * (double)ts.tv_nsec;
}

static int cmp_seed(const void *a, const void *b)
{
    return strcmp(((const seed *)a)->name, ((const seed *)b)->name);
}

static int read_file(const char *path, seed *s)
{
    FILE *f = fopen(path, "rb");
    if (!f) return -1;
    size_t cap = 4096, n = 0, got;
    uint8_t *buf = malloc(cap);
    while (buf && (got = fread(buf + n, 1, cap - n, f)) > 0) {
        n += got;
        if (n == cap) {
            uint8_t *nb = realloc(buf, 2 * cap);
            if (!nb) {
                free(buf);
                buf = NULL;
                break;
            }
            buf = nb;
            cap *= 2;
        }
    }
    fclose(f);
    if (!buf) return -1;
    s->data = buf;
    s->size = n;
    return 0;
}

/* Every regular file of the folder, sorted by name so runs repeat exactly. */
static seed *load_corpus(const char *dir, size_t *count)
{
    DIR *d = opendir(dir);
    if (!d) return NULL;
    seed *s = NULL;
    size_t n = 0;
    struct dirent *e;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        seed one = {strdup(e->d_name), NULL, 0};
        seed *ns = realloc(s, (n + 1) * sizeof *s);
        if (!ns || !one.name || read_file(path, &one)) {
            free(one.name);
            if (ns) s = ns;
            continue;
        }
        s = ns;
        s[n++] = one;
    }
    closedir(d);
    if (n) qsort(s, n, sizeof *s, cmp_seed);
    *count = n;
    return s;
}

/* Bytes that change how text and binary readers branch. */
static uint8_t interesting(void)
{
    static const uint8_t v[] = {'\n', ' ', '\0', '-', '.', '9', '0', 'E', '!', 0x7f, 0x80, 0xff,
                                'A', '+', '\t', '\r'};
    return v[prng() % sizeof v];
}

/* One random edit of a copy of s into buf (capacity s->size + 1); returns the new size. */
static size_t mutate(const seed *s, uint8_t *buf, int *kind)
{
    size_t n = s->size;
    memcpy(buf, s->data, n);
    size_t pos = n ? (size_t)(prng() % n) : 0;
    *kind = (int)(prng() % 4);
    switch (*kind) {
    case 0: /* flip a bit */
        if (n) buf[pos] ^= (uint8_t)(1u << (prng() % 8));
        return n;
    case 1: /* overwrite with an interesting or random byte */
        if (n) buf[pos] = prng() % 2 ? interesting() : (uint8_t)prng();
        return n;
    case 2: /* insert */
        memmove(buf + pos + 1, buf + pos, n - pos);
        buf[pos] = prng() % 2 ? interesting() : (uint8_t)prng();
        return n + 1;
    default: /* delete */
        if (!n) return 0;
        memmove(buf + pos, buf + pos + 1, n - pos - 1);
        return n - 1;
    }
}

static const char *base_name(const char *p)
{
    const char *s = strrchr(p, '/');
    return s ? s + 1 : p;
}

int main(int argc, char **argv)
{
    const char *me = base_name(argv[0]);
    if (argc < 2) {
        fprintf(stderr, "usage: %s corpus-folder\n", me);
        return 2;
    }
    size_t nseeds = 0;
    seed *seeds = load_corpus(argv[1], &nseeds);
    if (!seeds || nseeds == 0) {
        printf("FAIL: %s: no seed files in %s\n", me, argv[1]);
        return 1;
    }
    long max_runs = getenv("MS_FUZZ_RUNS") ? atol(getenv("MS_FUZZ_RUNS")) : 3000;
    double budget = getenv("MS_FUZZ_SECONDS") ? atof(getenv("MS_FUZZ_SECONDS")) : 2.5;
    double t0 = now();
    size_t biggest = 0;
    for (size_t i = 0; i < nseeds; i++) {
        LLVMFuzzerTestOneInput(seeds[i].data, seeds[i].size);
        if (seeds[i].size > biggest) biggest = seeds[i].size;
    }
    printf("PASS: %s: %zu seed files load without a crash\n", me, nseeds);

    uint8_t *buf = malloc(biggest + 1);
    if (!buf) return 1;
    long runs = 0, counts[5] = {0};
    /* Truncations: about 48 lengths per seed, always including the empty file. */
    for (size_t i = 0; i < nseeds && runs < max_runs / 3 && now() - t0 < budget; i++) {
        size_t stride = seeds[i].size / 48 + 1;
        for (size_t len = 0; len < seeds[i].size; len += stride, runs++, counts[4]++)
            LLVMFuzzerTestOneInput(seeds[i].data, len);
    }
    while (runs < max_runs && now() - t0 < budget) {
        const seed *s = &seeds[prng() % nseeds];
        int kind;
        size_t n = mutate(s, buf, &kind);
        LLVMFuzzerTestOneInput(buf, n);
        counts[kind]++;
        runs++;
    }
    printf("PASS: %s: %ld mutated inputs in %.1f s without a crash (%ld truncations, %ld bit "
           "flips, %ld overwrites, %ld insertions, %ld deletions)\n",
           me, runs, now() - t0, counts[4], counts[0], counts[1], counts[2], counts[3]);
    free(buf);
    for (size_t i = 0; i < nseeds; i++) {
        free(seeds[i].name);
        free(seeds[i].data);
    }
    free(seeds);
    return 0;
}
