/* bitset.h: a fixed-size set of atom indices as 64-bit words: what a selection evaluates to.
 * Whole-word operations make and/or/not linear in atoms/64. */
#ifndef MS_BITSET_H
#define MS_BITSET_H

#include <stddef.h>
#include <stdint.h>

typedef struct ms_bitset {
    uint64_t *words;
    size_t nbits;
} ms_bitset;

/* All bits clear. Returns 0, or -1 when memory runs out (b is then empty). */
int ms_bitset_init(ms_bitset *b, size_t nbits);
void ms_bitset_free(ms_bitset *b);
int ms_bitset_copy(ms_bitset *dst, const ms_bitset *src);

static inline size_t ms_bitset_nwords(const ms_bitset *b) { return (b->nbits + 63) / 64; }
static inline int ms_bitset_get(const ms_bitset *b, size_t i)
{
    return (int)((b->words[i >> 6] >> (i & 63)) & 1u);
}
static inline void ms_bitset_set(ms_bitset *b, size_t i) { b->words[i >> 6] |= 1ull << (i & 63); }
static inline void ms_bitset_clear(ms_bitset *b, size_t i)
{
    b->words[i >> 6] &= ~(1ull << (i & 63));
}

void ms_bitset_fill(ms_bitset *b, int value);       /* all set or all clear */
void ms_bitset_and(ms_bitset *dst, const ms_bitset *src);
void ms_bitset_or(ms_bitset *dst, const ms_bitset *src);
void ms_bitset_andnot(ms_bitset *dst, const ms_bitset *src);
void ms_bitset_not(ms_bitset *b);
size_t ms_bitset_count(const ms_bitset *b);
/* Write the set indices in ascending order to out (room for ms_bitset_count); returns the
 * count. */
size_t ms_bitset_indices(const ms_bitset *b, uint32_t *out);

#endif
