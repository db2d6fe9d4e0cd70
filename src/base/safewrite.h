/* safewrite.h: opening an output file so that writing it never destroys what its name
 * refers to. Every writer in molscope (images, scene exports, structure and volume files,
 * movie frames and videos, the OpenCL binary cache) goes through this one family:
 *
 *   a regular file, or a name that     a temporary file is created in the same folder (an
 *   does not exist yet                 unpredictable name, O_CREAT|O_EXCL, so a symlink
 *                                      planted under any name is never followed) with the
 *                                      permissions a plain creation would have, or those of
 *                                      the file it replaces; commit renames it over the
 *                                      file, abort removes it: the file is replaced whole
 *                                      or not at all
 *   a symlink (or a chain of them)     followed to its final target, which is replaced (or
 *                                      created, when the link dangles) as above; the link
 *                                      stays the same link
 *   anything else: a device, a FIFO,   opened with O_WRONLY and written in place (never
 *   a socket, /dev/stdout,             created, truncated, renamed or removed); a
 *   /proc/self/fd/N                    descriptor link to a regular file (/dev/stdout
 *                                      redirected to a file) is appended to
 *
 * Every error names the path the caller gave and the problem ("/dev/full: write error: No
 * space left on device"). While a FIFO, pipe or socket is written, SIGPIPE is blocked in the
 * calling thread (a reader that went away is the error EPIPE): open, write and finish an
 * output in one thread. */
#ifndef MS_SAFEWRITE_H
#define MS_SAFEWRITE_H

#include <stddef.h>
#include <stdio.h>

#include "base/base.h"

typedef struct ms_ofile ms_ofile;

/* Open the output for path by the rules above. NULL with err set when it cannot be opened
 * (a missing or unwritable folder, a read-only file, a folder named). Opening a FIFO waits
 * for its reader, as a shell's redirection does. */
ms_ofile *ms_ofile_open(const char *path, ms_error *err);

/* A log: a file that must hold what was written at every moment, so that a process that
 * dies leaves it (the command log). The name is followed through its symlinks as above; a
 * regular file or a missing name is truncated or created in place (O_NOFOLLOW: never
 * through a symlink planted there meanwhile), a device or FIFO written in place. Each ms_ofile_write goes
 * straight to the file; commit closes it, abort closes it and keeps what was written. */
ms_ofile *ms_ofile_open_log(const char *path, ms_error *err);

/* The descriptor to write to (the temporary file, or the output itself). */
int ms_ofile_fd(const ms_ofile *o);
/* A buffered stream over the descriptor, made on the first call (libpng and fprintf
 * writers); NULL with err set on failure. Write through one of the stream or the
 * descriptor, not both. */
FILE *ms_ofile_stream(ms_ofile *o, ms_error *err);
/* ms_ofile_open and ms_ofile_stream in one: the stream, with the output in *out; NULL with
 * err set and nothing left open. */
FILE *ms_ofile_open_stream(const char *path, ms_ofile **out, ms_error *err);
/* Write n bytes (through the stream when there is one); 0, or -1 with err set. */
int ms_ofile_write(ms_ofile *o, const void *data, size_t n, ms_error *err);
/* "/dev/fd/N" for the descriptor: a name for code that opens its output by name (file
 * format plugins); on Linux opening it reaches exactly this file, whatever the names in the
 * folder become meanwhile. */
const char *ms_ofile_fd_name(const ms_ofile *o);
/* The temporary file's name, for a program that writes the output itself (ffmpeg, a
 * renderer): it exists, is empty and belongs to this output. NULL when the output is
 * written in place (a device or a FIFO). */
const char *ms_ofile_temp_name(const ms_ofile *o);
/* The path the output was opened for. */
const char *ms_ofile_path(const ms_ofile *o);

/* Flush the stream and report a write that failed so far (with the system's reason, kept
 * from the first failure): 0, or -1 with err set. */
int ms_ofile_check(ms_ofile *o, ms_error *err);
/* Finish: flush and close, report any write error, and put the temporary file in place of
 * the target. On any failure the target is left as it was and no temporary file remains.
 * 0, or -1 with err set. Frees o. */
int ms_ofile_commit(ms_ofile *o, ms_error *err);
/* Give up: close, and remove the temporary file; the target is left exactly as it was (an
 * output written in place keeps what was written). Frees o; NULL is allowed. */
void ms_ofile_abort(ms_ofile *o);
/* Commit when ok, else abort and return -1 (err left as the caller set it). */
int ms_ofile_finish(ms_ofile *o, int ok, ms_error *err);

/* Whether the file name `name` (a base name, no folder) is one of the temporary names
 * ms_ofile_open makes for a target whose base name is `target`, or a temporary made for
 * one of those: for removing what a killed process left. */
int ms_ofile_is_temp(const char *name, const char *target);

#endif
