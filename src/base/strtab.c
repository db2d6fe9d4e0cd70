/* strtab.c: interned strings in one arena with an open-addressing hash index. */
#include "config.h"
#include "base/strtab.h"
#include "base/base.h"

#include <stdlib.h>
#include <string.h>

struct ms_strtab {
    char *arena;           /* NUL-terminated strings back to back */
    size_t arena_len, arena_cap;
    uint32_t *offset;      /* offset[id] into arena */
    size_t count, offset_cap;
    uint32_t *slot;        /* hash slots hold id+1, 0 = empty */
    size_t nslots;         /* power of two */
};

static uint64_t strtab_hash(const char *s, size_t len)
{
    uint64_t h = 1469598103934665603ull;
    for (size_t i = 0; i < len; i++) {
        h ^= (unsigned char)s[i];
        h *= 1099511628211ull;
    }
    return h ^ (h >> 29);
}

static int strtab_rehash(ms_strtab *t, size_t nslots)
{
    uint32_t *slot = calloc(nslots, sizeof *slot);
    if (!slot) return -1;
    for (size_t id = 0; id < t->count; id++) {
        const char *s = t->arena + t->offset[id];
        size_t i = strtab_hash(s, strlen(s)) & (nslots - 1);
        while (slot[i]) i = (i + 1) & (nslots - 1);
        slot[i] = (uint32_t)id + 1;
    }
    free(t->slot);
    t->slot = slot;
    t->nslots = nslots;
    return 0;
}

ms_strtab *ms_strtab_new(void)
{
    ms_strtab *t = calloc(1, sizeof *t);
    if (!t) return NULL;
    if (strtab_rehash(t, 64) || ms_strtab_intern(t, "", 0) != 0) {
        ms_strtab_free(t);
        return NULL;
    }
    return t;
}

void ms_strtab_free(ms_strtab *t)
{
    if (!t) return;
    free(t->arena);
    free(t->offset);
    free(t->slot);
    free(t);
}

static int strtab_same(const ms_strtab *t, uint32_t id, const char *s, size_t len)
{
    const char *a = t->arena + t->offset[id];
    /* strncmp stops at the stored string's end: it may be shorter than len. */
    return strncmp(a, s, len) == 0 && a[len] == '\0';
}

ms_str ms_strtab_intern(ms_strtab *t, const char *s, size_t len)
{
    if (memchr(s, '\0', len)) len = strlen(s);
    size_t i = strtab_hash(s, len) & (t->nslots - 1);
    while (t->slot[i]) {
        if (strtab_same(t, t->slot[i] - 1, s, len)) return t->slot[i] - 1;
        i = (i + 1) & (t->nslots - 1);
    }
    if (t->count >= 0xfffffff0u) return MS_STR_NONE;
    if (ms_grow((void **)&t->arena, &t->arena_cap, t->arena_len + len + 1, 1) ||
        ms_grow((void **)&t->offset, &t->offset_cap, t->count + 1, sizeof *t->offset))
        return MS_STR_NONE;
    if (t->arena_len + len + 1 > 0xffffffffu) return MS_STR_NONE;
    uint32_t id = (uint32_t)t->count++;
    t->offset[id] = (uint32_t)t->arena_len;
    memcpy(t->arena + t->arena_len, s, len);
    t->arena[t->arena_len + len] = '\0';
    t->arena_len += len + 1;
    t->slot[i] = id + 1;
    if (t->count * 2 > t->nslots && strtab_rehash(t, t->nslots * 2) &&
        t->count + 1 >= t->nslots) {
        /* Out of memory with the index full: forget the string just added so the
         * table stays consistent (every probe sequence still ends at an empty slot). */
        t->slot[i] = 0;
        t->count--;
        t->arena_len -= len + 1;
        return MS_STR_NONE;
    }
    return id;
}

ms_str ms_strtab_intern_cstr(ms_strtab *t, const char *s)
{
    return ms_strtab_intern(t, s, strlen(s));
}

ms_str ms_strtab_find(const ms_strtab *t, const char *s)
{
    size_t len = strlen(s);
    size_t i = strtab_hash(s, len) & (t->nslots - 1);
    while (t->slot[i]) {
        if (strtab_same(t, t->slot[i] - 1, s, len)) return t->slot[i] - 1;
        i = (i + 1) & (t->nslots - 1);
    }
    return MS_STR_NONE;
}

const char *ms_strtab_get(const ms_strtab *t, ms_str id)
{
    return id < t->count ? t->arena + t->offset[id] : "";
}

uint32_t ms_strtab_count(const ms_strtab *t) { return (uint32_t)t->count; }

size_t ms_strtab_bytes(const ms_strtab *t)
{
    return t->arena_cap + t->offset_cap * sizeof(uint32_t) + t->nslots * sizeof(uint32_t);
}
