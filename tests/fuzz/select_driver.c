/* select_driver.c: a standalone driver for fuzz_select.c (kept apart from the file-format
 * fuzz driver). It runs every file of the seed corpus given as its argument, then a fixed
 * number of deterministic mutations of them (byte flips, deletions, duplications, splices,
 * insertions of selection words), within a time budget, and prints one PASS line. A crash or
 * sanitizer report ends the process with a failure, which the test runner counts. */
#include "config.h"

#include <dirent.h>
#include <stdint.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size);

#define FUZZ_MAX_INPUT 4096

typedef struct input {
    uint8_t *data;
    size_t size;
} input;

static const char *const words[] = {
    " and ", " or ", " not ", "(", ")", "{", "}", "within ", " of ", "exwithin ", "pbwithin ",
    "withinbonds ", "same ", " as ", "residue ", "fragment ", "\"", "'", " to ", "==", "=~",
    " eq ", " lt ", "+", "-", "*", "/", "%", "^", "**", "sqr(", "sqrt(", "x", "y", "name ",
    "resname ", "resid ", "CA ", "5", "1.5", ".5", "1e5", "protein", "water", "acidic ",
    "sequence ", "rasmol ", "\"[A-\"", "\"(.*)*\"", "C5'", "1A", "all", "none", "index ",
    "beta ", "structure ", "element ", " ... ", "999999999", "-0", "0.0", "\\", "nearest ",
};

static uint64_t rng = 0x9E3779B97F4A7C15ull;
static uint64_t next_rand(void)
{
    rng ^= rng << 13;
    rng ^= rng >> 7;
    rng ^= rng << 17;
    return rng;
}

static void insert(uint8_t *buf, size_t *n, size_t at, const void *src, size_t len)
{
    if (*n + len > FUZZ_MAX_INPUT) len = FUZZ_MAX_INPUT - *n;
    memmove(buf + at + len, buf + at, *n - at);
    memcpy(buf + at, src, len);
    *n += len;
}

/* One mutation of buf (size *n, capacity FUZZ_MAX_INPUT). */
static void mutate(uint8_t *buf, size_t *n, const input *corpus, size_t ncorpus)
{
    size_t at = *n ? next_rand() % (*n + 1) : 0;
    switch (next_rand() % 6) {
    case 0:
        if (*n) buf[next_rand() % *n] ^= (uint8_t)(1u << (next_rand() % 8));
        break;
    case 1:
        if (*n) {
            size_t len = next_rand() % (*n - (at < *n ? at : *n - 1) + 1);
            if (at >= *n) at = *n - 1;
            memmove(buf + at, buf + at + len, *n - at - len);
            *n -= len;
        }
        break;
    case 2: {
        const char *w = words[next_rand() % (sizeof words / sizeof words[0])];
        insert(buf, n, at, w, strlen(w));
        break;
    }
    case 3:
        if (*n && at < *n) {
            size_t len = next_rand() % (*n - at) + 1;
            uint8_t tmp[FUZZ_MAX_INPUT];
            memcpy(tmp, buf + at, len);
            insert(buf, n, at, tmp, len);
        }
        break;
    case 4: {
        const input *o = &corpus[next_rand() % ncorpus];
        size_t from = o->size ? next_rand() % o->size : 0;
        insert(buf, n, at, o->data + from, o->size - from);
        break;
    }
    default: {
        uint8_t c = (uint8_t)(next_rand() % 256);
        insert(buf, n, at, &c, 1);
        break;
    }
    }
}

static int load_corpus(const char *dir, input **out, size_t *n)
{
    DIR *d = opendir(dir);
    if (!d) return -1;
    struct dirent *e;
    size_t cap = 0;
    while ((e = readdir(d))) {
        if (e->d_name[0] == '.') continue;
        char path[4096];
        snprintf(path, sizeof path, "%s/%s", dir, e->d_name);
        FILE *f = fopen(path, "rb");
        if (!f) continue;
        uint8_t *buf = malloc(FUZZ_MAX_INPUT);
        size_t len = buf ? fread(buf, 1, FUZZ_MAX_INPUT, f) : 0;
        fclose(f);
        if (!buf) break;
        if (*n == cap) {
            cap = cap ? cap * 2 : 64;
            input *grown = realloc(*out, cap * sizeof **out);
            if (!grown) {
                free(buf);
                break;
            }
            *out = grown;
        }
        (*out)[(*n)++] = (input){buf, len};
    }
    closedir(d);
    return 0;
}

int main(int argc, char **argv)
{
    if (argc != 2) {
        fprintf(stderr, "usage: %s <corpus folder>\n", argv[0]);
        return 2;
    }
    input *corpus = NULL;
    size_t ncorpus = 0;
    if (load_corpus(argv[1], &corpus, &ncorpus) || ncorpus == 0) {
        printf("FAIL: fuzz/select: no seed corpus in %s\n", argv[1]);
        return 1;
    }
    for (size_t i = 0; i < ncorpus; i++) LLVMFuzzerTestOneInput(corpus[i].data, corpus[i].size);
    const char *env = getenv("MS_FUZZ_RUNS");
    long runs = env ? atol(env) : 50000, done = 0;
    double budget = 20.0;   /* seconds: the smoke run stays short */
    clock_t t0 = clock();
    uint8_t buf[FUZZ_MAX_INPUT];
    for (; done < runs; done++) {
        const input *s = &corpus[next_rand() % ncorpus];
        size_t n = s->size;
        memcpy(buf, s->data, n);
        for (int k = 1 + (int)(next_rand() % 4); k > 0; k--) mutate(buf, &n, corpus, ncorpus);
        LLVMFuzzerTestOneInput(buf, n);
        if ((done & 255) == 0 && (double)(clock() - t0) / CLOCKS_PER_SEC > budget) break;
    }
    printf("PASS: fuzz/select: %zu seeds and %ld mutations compiled and evaluated without a "
           "crash\n", ncorpus, done);
    for (size_t i = 0; i < ncorpus; i++) free(corpus[i].data);
    free(corpus);
    return 0;
}
