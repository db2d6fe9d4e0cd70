/* plugin_util.h: what text-format plugins share: a fast buffered line reader that counts
 * lines and byte offsets, fixed-column field extraction, strict number parsing that reports
 * what was wrong, hybrid-36 numbers, and checked output. Compiled into each plugin. */
#ifndef MS_PLUGIN_UTIL_H
#define MS_PLUGIN_UTIL_H

#include <stddef.h>
#include <stdio.h>
#include <stdint.h>

#include "ms_plugin.h"

/* ---------------------------------------------------------------- line reader */

typedef struct ms_lines {
    FILE *fp;
    char *buf;
    size_t cap, len, pos;   /* buffered bytes [pos, len) */
    long long offset;       /* file offset of buf[0] */
    long line_no;           /* number of the line last returned (1-based) */
    char *line;             /* the line last returned, NUL-terminated, no newline */
    size_t line_len;
    char *long_line;        /* storage for lines that straddle buffer refills */
    size_t long_cap;
    int eof, error;
} ms_lines;

int ms_lines_open(ms_lines *r, const char *path, ms_perr *err);
void ms_lines_close(ms_lines *r);
/* A reader's state: `size` zeroed bytes of a struct whose first member is an ms_lines, with
 * it opened on path. NULL with err set. */
void *ms_lines_create(size_t size, const char *path, ms_perr *err);
/* Close the ms_lines at the start of a reader's state and free the state. */
void ms_lines_destroy(void *reader);
/* The next line, or NULL at the end of the file (r->error set on a read error). The
 * returned text stays valid until the next call. */
const char *ms_lines_next(ms_lines *r);
/* File offset of the start of the line last returned / of the next line. */
long long ms_lines_tell_next(const ms_lines *r);
/* Reposition at a file offset (from ms_lines_tell_next); line numbering restarts at
 * line_no. */
int ms_lines_seek(ms_lines *r, long long offset, long line_no);

/* Bytes of the file after the line last returned (from the file's size when it was opened
 * and what has been read), or -1 when the size is unknown (not a regular file). */
long long ms_lines_left(const ms_lines *r);

/* ---------------------------------------------------------------- declared sizes */

/* A header declares `count` items (atoms, bonds, grid values) that the rest of the file
 * must hold, each taking at least min_bytes there (the last may lack its newline, so one
 * byte of slack). MS_PLUGIN_OK when left (bytes after the header; < 0: unknown) has room,
 * else MS_PLUGIN_ERROR with the message "<claim> but the file holds only <left> bytes after
 * it (room for at most <n> <unit>)", claim being a printf format ("line 2: the header
 * declares %ld atoms"). Readers call it before they (or the host) allocate for the count. */
int ms_check_room(ms_perr *err, double count, double min_bytes, long long left,
                  const char *unit, const char *claim, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 6, 7)))
#endif
    ;
/* Memory the system can still give (MemAvailable), in bytes; -1 when unknown. For sizes a
 * file cannot bound (a trajectory header with no frame to vouch for its atom count). */
long long ms_plugin_mem_available(void);

/* ---------------------------------------------------------------- fields */

/* Copy columns [c0, c1) (0-based, end exclusive) of a line of length len into out (size
 * >= c1 - c0 + 1), trimmed of blanks. Missing columns read as blanks. */
void ms_field(const char *line, size_t len, size_t c0, size_t c1, char *out);

/* Parse columns [c0, c1) as a float / int. Returns 1 on success, 0 when the field is blank
 * (value untouched), -1 when it is not a number. */
int ms_field_float(const char *line, size_t len, size_t c0, size_t c1, float *v);
int ms_field_int(const char *line, size_t len, size_t c0, size_t c1, int *v);

/* Parse a whole token (no surrounding blanks) as a number; 1 ok, -1 bad. */
int ms_parse_float(const char *s, size_t n, float *v);
int ms_parse_double(const char *s, size_t n, double *v);
int ms_parse_long(const char *s, size_t n, long *v);

/* 1 when v is a whole number in [lo, hi] (never NaN): check before casting a parsed double
 * to an integer type, since casting an out-of-range value is undefined. */
int ms_whole_in(double v, double lo, double hi);

/* Hybrid-36 (the PDB convention for serials > 99999 and resids > 9999): decode a field of
 * `width` characters (blanks trimmed). Returns 1 ok, 0 blank, -1 invalid. */
int ms_hy36_decode(const char *s, size_t width, long *v);
/* Encode into exactly `width` characters plus NUL; returns 0, or -1 when out of range. */
int ms_hy36_encode(long v, size_t width, char *out);

/* Split a line into whitespace-separated tokens; returns the count (at most max). */
int ms_tokens(char *line, char **tok, int max);

/* ---------------------------------------------------------------- elements */

/* Copy the symbol of element z into out (size >= 4); 0 when z is out of range. */
int ms_plugin_symbol_of(long z, char out[4]);
/* The atomic number of a symbol in its usual case ("C", "Cl"), 0 when it is none. */
int ms_plugin_element_number(const char *sym);
/* "C", "Cl": a symbol in its usual case is taken as an element; "CA" or "CL" (an atom name
 * in capitals) is left for the host to guess from the name. */
int ms_plugin_element_like(const char *s);

/* ---------------------------------------------------------------- volume data */

/* Read n whitespace-separated numbers from the lines that follow (and the rest of `first`,
 * when not NULL: the unread part of the current line) into dst. An error names the line
 * and the token, or says how many values were found before the file ended. */
int ms_read_floats(ms_lines *in, const char *first, float *dst, size_t n, ms_perr *err);
/* Reorder a grid stored with z fastest (OpenDX, cube) into x fastest (molscope's order):
 * value (i, j, k) is src[(i n1 + j) n2 + k] and becomes dst[(k n1 + j) n0 + i]. */
void ms_grid_zfast_to_xfast(const float *src, float *dst, const long n[3]);
/* The reverse, for writers. */
void ms_grid_xfast_to_zfast(const float *src, float *dst, const long n[3]);

/* ---------------------------------------------------------------- binary input */

/* A binary file opened for reading, with its size in bytes; NULL with err set (the
 * system's reason) when it cannot be opened or its size read. */
FILE *ms_open_sized(const char *path, long long *size, ms_perr *err);

/* ---------------------------------------------------------------- output */

/* fprintf that remembers failure; check with ms_out_close. */
typedef struct ms_out {
    FILE *fp;
    int failed;
} ms_out;

int ms_out_open(ms_out *o, const char *path, ms_perr *err);
/* A writer's state: `size` zeroed bytes of a struct whose first member is an ms_out, with
 * that output opened at path. NULL with err set. */
void *ms_out_create(size_t size, const char *path, ms_perr *err);
/* Close the ms_out at the start of a writer's state (ms_out_close) and free the state;
 * returns what the close returned. */
int ms_out_destroy(void *writer, ms_perr *err);
void ms_out_printf(ms_out *o, const char *fmt, ...)
#if defined(__GNUC__)
    __attribute__((format(printf, 2, 3)))
#endif
    ;
void ms_out_write(ms_out *o, const void *data, size_t n);
/* Flush and close; MS_PLUGIN_ERROR with a message when anything failed (a full disk). */
int ms_out_close(ms_out *o, ms_perr *err);

#endif
