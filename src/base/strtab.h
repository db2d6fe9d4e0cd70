/* strtab.h: an interned string table. Every distinct string is stored once and named by a
 * 32-bit id; id 0 is always "". Atom names, types, residue names, chains and segment names
 * are ids into one table per molecule, so comparing them is comparing integers and a
 * regular expression is matched once per distinct string, not once per atom. */
#ifndef MS_STRTAB_H
#define MS_STRTAB_H

#include <stddef.h>
#include <stdint.h>

typedef uint32_t ms_str;
#define MS_STR_NONE ((ms_str)0xffffffffu)

typedef struct ms_strtab ms_strtab;

ms_strtab *ms_strtab_new(void);
void ms_strtab_free(ms_strtab *t);

/* The id of s (of length len), adding it if new; MS_STR_NONE when memory runs out. */
ms_str ms_strtab_intern(ms_strtab *t, const char *s, size_t len);
ms_str ms_strtab_intern_cstr(ms_strtab *t, const char *s);
/* The id of s if present, else MS_STR_NONE. */
ms_str ms_strtab_find(const ms_strtab *t, const char *s);
const char *ms_strtab_get(const ms_strtab *t, ms_str id);
uint32_t ms_strtab_count(const ms_strtab *t);
size_t ms_strtab_bytes(const ms_strtab *t);

#endif
