/* bitset.c: word-wise set operations. The bits past nbits in the last word stay clear. */
#include "config.h"
#include "base/bitset.h"

#include <stdlib.h>
#include <string.h>

int ms_bitset_init(ms_bitset *b, size_t nbits)
{
    b->nbits = nbits;
    b->words = calloc(ms_bitset_nwords(b) ? ms_bitset_nwords(b) : 1, sizeof *b->words);
    if (!b->words) {
        b->nbits = 0;
        return -1;
    }
    return 0;
}

void ms_bitset_free(ms_bitset *b)
{
    free(b->words);
    b->words = NULL;
    b->nbits = 0;
}

int ms_bitset_copy(ms_bitset *dst, const ms_bitset *src)
{
    if (ms_bitset_init(dst, src->nbits)) return -1;
    memcpy(dst->words, src->words, ms_bitset_nwords(src) * sizeof *src->words);
    return 0;
}

static void trim_tail(ms_bitset *b)
{
    size_t rem = b->nbits & 63;
    if (rem) b->words[b->nbits >> 6] &= (1ull << rem) - 1;
}

void ms_bitset_fill(ms_bitset *b, int value)
{
    memset(b->words, value ? 0xff : 0, ms_bitset_nwords(b) * sizeof *b->words);
    trim_tail(b);
}

void ms_bitset_and(ms_bitset *dst, const ms_bitset *src)
{
    for (size_t i = 0, n = ms_bitset_nwords(dst); i < n; i++) dst->words[i] &= src->words[i];
}

void ms_bitset_or(ms_bitset *dst, const ms_bitset *src)
{
    for (size_t i = 0, n = ms_bitset_nwords(dst); i < n; i++) dst->words[i] |= src->words[i];
}

void ms_bitset_andnot(ms_bitset *dst, const ms_bitset *src)
{
    for (size_t i = 0, n = ms_bitset_nwords(dst); i < n; i++) dst->words[i] &= ~src->words[i];
}

void ms_bitset_not(ms_bitset *b)
{
    for (size_t i = 0, n = ms_bitset_nwords(b); i < n; i++) b->words[i] = ~b->words[i];
    trim_tail(b);
}

size_t ms_bitset_count(const ms_bitset *b)
{
    size_t c = 0;
    for (size_t i = 0, n = ms_bitset_nwords(b); i < n; i++)
        c += (size_t)__builtin_popcountll(b->words[i]);
    return c;
}

size_t ms_bitset_indices(const ms_bitset *b, uint32_t *out)
{
    size_t c = 0;
    for (size_t i = 0, n = ms_bitset_nwords(b); i < n; i++) {
        uint64_t w = b->words[i];
        if (w == ~(uint64_t)0) {   /* a whole word: 64 indices in a row */
            for (uint32_t k = 0; k < 64; k++) out[c + k] = (uint32_t)(i * 64) + k;
            c += 64;
            continue;
        }
        while (w) {
            out[c++] = (uint32_t)(i * 64 + (size_t)__builtin_ctzll(w));
            w &= w - 1;
        }
    }
    return c;
}
