/* movie.h: making movies, in one process or across MPI ranks. The Tcl library
 * (tcl/movie.tcl, the `movie` command) sets the scene for each frame and renders it; this
 * module does the rest:
 *
 *   frames     frame i is <basename>.%05d.png, or .rgb (SGI, VMD's movie maker's frames);
 *              it is rendered to a temporary file that base/safewrite makes beside it and
 *              renamed once it is checked to be a complete image of the movie's size, so a
 *              file under a final name is always a whole frame (frames.c, run.c)
 *   resuming   before rendering, rank 0 lists the frames that are missing or not a complete
 *              image of the right size that decodes, removes the temporary files a killed job
 *              left, and only those frames are rendered (frames.c, run.c)
 *   the loop   the missing frames are handed out dynamically by rank 0 (ms_par_for_observed)
 *              and rank 0 learns as each one completes, on any rank (run.c)
 *   encoding   rank 0 pipes the frames, in order and as soon as the next one in order is
 *              done, as raw RGB into an ffmpeg subprocess (libx264, yuv420p) writing the
 *              temporary file base/safewrite makes beside the video (<stem>.tmp-XXXXXXXX<ext>;
 *              a device or FIFO is written in place), renamed when ffmpeg succeeds, so
 *              the video exists the moment the last frame is done (encoder.c, monitor.c).
 *              ffmpeg is GPL: it is only ever run as a program, never linked.
 *   progress   rank 0 prints frames done of total, frames per minute and the time left
 *              (monitor.c)
 *
 * Frames reach rank 0 through the file system: every rank writes into the frames' folder,
 * which must be shared by the ranks (it is on one node, and on a cluster's parallel file
 * system); rank 0 reads them back in order. A re-run re-encodes the whole video from the
 * frames, so the frames are removed (keep_frames 0) only after the video is complete. */
#ifndef MS_MOVIE_H
#define MS_MOVIE_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"

/* ---- frame files (frames.c) ---- */

/* The image format of the frames. */
typedef enum ms_movie_frames {
    MS_FRAMES_PNG,     /* .png: the default */
    MS_FRAMES_RGB      /* .rgb: SGI, as VMD's movie maker writes them */
} ms_movie_frames;

/* The extension of a frame format (".png", ".rgb"). */
const char *ms_movie_frame_ext(ms_movie_frames format);
/* The file of frame i: <basename>.%05d<ext>. malloc'd; NULL when memory runs out. */
char *ms_movie_frame_path(const char *basename, ms_movie_frames format, long i);
/* Whether path is a complete image of width x height in the format its extension names.
 * A PNG (any name but .rgb): the signature, an IHDR of that size, then chunks whose lengths
 * lead exactly to an IEND chunk at the end of the file (a truncated or overlong file
 * fails), and it decodes: libpng reads every row and the chunks after them, a CRC error in
 * any chunk failing it (a damaged byte of pixel data). An .rgb: an SGI header of that size
 * with three or four channels of one byte, a verbatim file exactly as long as its pixels,
 * and every row decodes (run-length encoded files included). 1 yes, 0 no. */
int ms_movie_frame_ok(const char *path, int width, int height);
/* Remove what a killed job left in the frames' folder: the temporary files of frames
 * <basename>.<digits><ext> (ms_ofile_is_temp; those of a renderer writing one included) and
 * the <basename>.<digits>.part<ext>* of earlier versions. Returns how many were removed. */
long ms_movie_remove_stale(const char *basename, ms_movie_frames format);
/* Remove what a killed encoder left beside the video: its temporary files, and the
 * <stem>.part<ext> of earlier versions. Returns how many were removed. */
long ms_movie_remove_stale_video(const char *video);
/* The frames among 0..n-1 that are missing or not ms_movie_frame_ok: malloc'd ascending
 * list in *missing (NULL when none), their count in *nmissing. 0, or -1 on no memory. */
int ms_movie_scan(const char *basename, ms_movie_frames format, long n, int width, int height,
                  long **missing, long *nmissing, ms_error *err);
/* Check that files can be created in the folder of path (creating the folder when it does
 * not exist): 0, or -1 with err naming the folder and the reason. */
int ms_movie_check_dir(const char *path, ms_error *err);

/* ---- the encoder: an ffmpeg subprocess (encoder.c) ---- */

typedef struct ms_movie_encoder ms_movie_encoder;

/* The ffmpeg program: MOLSCOPE_FFMPEG when set (a path or a name looked up on PATH; only
 * that), else ffmpeg on PATH, else the one configure found. malloc'd path, or NULL when it
 * is not there. */
char *ms_movie_find_ffmpeg(void);
/* Whether name is one of x264's presets (ultrafast ... veryslow, placebo). */
int ms_movie_preset_ok(const char *name);
/* Append one frame (3 * width * height bytes, top row first). 0, or -1 with err when
 * ffmpeg has gone (its last message is in err). */
int ms_movie_encoder_put(ms_movie_encoder *e, const uint8_t *rgb, ms_error *err);
/* End of input: wait for ffmpeg; when it succeeded and ok is set, commit the video's
 * output (the temporary file takes the video's place); otherwise abort it (ffmpeg is stopped when ok is 0). Frees e.
 * 0, or -1 with err (ffmpeg's status and last message; never written when ok is 0, so err
 * may then be NULL). */
int ms_movie_encoder_finish(ms_movie_encoder *e, int ok, ms_error *err);

/* ---- the whole job (monitor.c, run.c) ---- */

/* The video codecs ffmpeg encodes to (the container follows the video's extension). */
typedef enum ms_movie_codec {
    MS_CODEC_H264,     /* libx264 at constant quality crf, x264 preset: the default */
    MS_CODEC_MPEG1,    /* MPEG-1 video at bitrate (the fps must be an MPEG rate) */
    MS_CODEC_MPEG2,    /* MPEG-2 video at bitrate (likewise) */
    MS_CODEC_MPEG4,    /* MPEG-4 part 2 at bitrate */
    MS_CODEC_GIF       /* animated GIF, one palette made from all the frames */
} ms_movie_codec;

typedef struct ms_movie_opts {
    const char *basename;      /* frames are <basename>.%05d<ext of frame_format> */
    ms_movie_frames frame_format;
    long nframes;              /* frames 0 .. nframes-1 */
    int width, height;
    const char *video;         /* NULL or "": frames only */
    double fps;
    int crf;
    const char *preset;        /* x264's speed preset (NULL: veryfast) */
    ms_movie_codec codec;      /* the video's codec (0: H.264) */
    long bitrate;              /* bits per second of the MPEG codecs (<= 0: 8000000) */
    int keep_frames;           /* 0: remove the frames once the video is complete */
    int progress;              /* -1: in place on a terminal, else a line every 5 %; 0: off;
                                * 1: a line whenever frames complete */
    double started, script_done;  /* this rank's process start and end of script loading
                                   * (seconds since the epoch; < 0: unknown) */
} ms_movie_opts;

/* Start ffmpeg encoding o's width x height RGB frames at o's fps into o->video's output
 * opened by base/safewrite (a temporary file beside it, or a device or FIFO in place; the
 * container follows the video's extension, which it must have) with o's codec: H.264 with
 * libx264 at constant quality crf (0-51, lower is better) and the x264 preset, MPEG-1, -2
 * or -4 at o's bitrate, yuv420p (an odd width or height is padded by one black pixel), or
 * an animated GIF with one palette made from all the frames. NULL with err on failure. */
ms_movie_encoder *ms_movie_encoder_start(const char *ffmpeg, const struct ms_movie_opts *o,
                                         ms_error *err);

/* Render frame `frame` to the file tmp (an image of the movie's size in the format of tmp's
 * extension, the frames' format); 0, or -1 with err. */
typedef int (*ms_movie_frame_fn)(void *ctx, long frame, const char *tmp, ms_error *err);

typedef struct ms_movie_stats {
    long frames, rendered, reused;  /* the job's totals */
    int ranks;
    double script_s, script_max_s;  /* rank 0's phase times and the largest of any rank */
    double state_s, state_max_s;
    double render_s;                /* geometry and rendering: the loop, until the last
                                     * frame is done (rank 0's clock) */
    double encode_tail_s;           /* after the last frame, until the video is complete */
    double busy_max_s, busy_sum_s;  /* time in frame calls: the busiest rank, all ranks */
    double total_s;                 /* first process start to the video complete */
    int video_made;                 /* the video was written */
    char note[1024];                /* why there is no video (no ffmpeg ...), or "" */
} ms_movie_stats;

/* Make the movie: collective, every rank calls it with the same options. Rank 0 checks the
 * folder, removes stale temporary files and lists the missing frames; those are rendered
 * across the ranks through fn; rank 0 encodes the video as they complete, prints progress,
 * and removes the frames when asked. Every rank returns the same outcome and stats: 0, or
 * -1 with err (a frame that failed to render with one rank; with several, a failed frame
 * ends the whole job as `parallel for` does). A video that cannot be made (no ffmpeg, an
 * encoder error) is not an error of the movie: the frames are kept and stats->note says
 * why; an encoder error is returned as an error after all frames are rendered. */
int ms_movie_run(const ms_movie_opts *o, ms_movie_frame_fn fn, void *ctx,
                 ms_movie_stats *stats, ms_error *err);

/* When this process started, in seconds since the epoch (from /proc; -1 when unknown). */
double ms_movie_process_start(void);

/* The monitor on rank 0 (monitor.c, used by run.c): a thread that feeds the encoder in
 * frame order as frames complete and prints progress. */
typedef struct ms_movie_monitor ms_movie_monitor;
/* done[i] says whether frame i exists already; enc may be NULL (no video). */
ms_movie_monitor *ms_movie_monitor_start(const ms_movie_opts *o, const uint8_t *done,
                                         long todo, ms_movie_encoder *enc, ms_error *err);
/* Frame i is complete (thread-safe; the observer of the loop). */
void ms_movie_monitor_done(void *monitor, long i);
/* Wait for the thread: with ok, after it has fed every frame, and finish the encoder
 * (keeping the video); without, stop at once and drop the video. Frees m. Returns 0, or -1
 * with err when the encoder failed; *last_done_at receives when the last frame was done
 * (ms_now's clock; the start when there was none). err may be NULL. */
int ms_movie_monitor_finish(ms_movie_monitor *m, int ok, double *last_done_at,
                            ms_error *err);

#endif
