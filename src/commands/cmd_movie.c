/* cmd_movie.c: the C commands under the Tcl movie library (tcl/movie.tcl), in the
 * ::molscope::movie namespace. The user's command is `movie`, defined in Tcl.
 *
 *   ::molscope::movie::run <framecmd> -basename B -frames N -width W -height H
 *       ?-format png|rgb -video V -codec h264|mpeg1|mpeg2|mpeg4|gif -fps F -crf Q -preset P -bitrate B
 *       -keepframes 0|1 -progress -1|0|1 -started T -scriptdone T?
 *       Collective (every rank): makes the movie with ms_movie_run, calling
 *       `{*}framecmd <frame> <file>` to render each missing frame into <file>. Returns a
 *       dict: frames rendered reused ranks video note script script_max state state_max
 *       render encode_tail busy_max busy_sum total (seconds).
 *   ::molscope::movie::frameok <file> <W> <H>   1 when file is a complete W x H PNG (an
 *       SGI image when its name ends in .rgb)
 *   ::molscope::movie::convert <from> <to>      an image file written again in the format
 *       of to's extension (.png .tga .ppm .bmp .rgb), through base/safewrite
 *   ::molscope::movie::pose ?<pose>?            every molecule's transform and the axes'
 *       rotation as a list, or set them from one (molecules not in it keep theirs): a
 *       movie sets each frame's view absolutely from the same starting pose
 *   ::molscope::movie::started                  this process's start (epoch seconds; -1)
 *   ::molscope::movie::ffmpeg                   the ffmpeg a video would use, or "" */
#include "config.h"
#include "commands/commands.h"
#include "assemble/view.h"
#include "image/image.h"
#include "movie/movie.h"

#include <limits.h>
#include <stddef.h>
#include <stdlib.h>
#include <string.h>

/* While the movie loop runs, the collective forms of `parallel` (and `mol new ... bcast`)
 * are refused, as inside a `parallel for` callback: the ranks are not at the same point. */
#define BUSY_KEY "molscope::parallel::busy"

/* ---------------------------------------------------------------- run */

typedef struct frame_ctx {
    Tcl_Interp *interp;
    Tcl_Obj *cmd;
} frame_ctx;

static int call_frame(void *ctx, long frame, const char *tmp, ms_error *err)
{
    frame_ctx *c = ctx;
    Tcl_Obj *cmd = Tcl_DuplicateObj(c->cmd);
    Tcl_IncrRefCount(cmd);
    int rc = Tcl_ListObjAppendElement(c->interp, cmd, Tcl_NewLongObj(frame));
    if (rc == TCL_OK) rc = Tcl_ListObjAppendElement(c->interp, cmd, Tcl_NewStringObj(tmp, -1));
    if (rc == TCL_OK) rc = Tcl_EvalObjEx(c->interp, cmd, TCL_EVAL_GLOBAL);
    Tcl_DecrRefCount(cmd);
    if (rc == TCL_OK) return 0;
    ms_error_set(err, "%s", Tcl_GetStringResult(c->interp));
    return -1;
}

/* run's options: the movie's and -progress, read as a number */
typedef struct run_args {
    ms_movie_opts o;
    int progress;
    int codec;
    int format;
} run_args;

/* The codecs, in the order of ms_movie_codec. */
static const char *const codecs[] = {"h264", "mpeg1", "mpeg2", "mpeg4", "gif", NULL};
/* The frame formats, in the order of ms_movie_frames. */
static const char *const frame_formats[] = {"png", "rgb", NULL};

#define ROFF(f) offsetof(run_args, f)
#define COUNT(max) 0, max, MS_OPT_MIN | MS_OPT_MAX, NULL
static const ms_opt run_options[] = {
    {"-basename", MS_OPT_STRING, ROFF(o.basename), 0, 0, 0, NULL},
    {"-frames", MS_OPT_LONG, ROFF(o.nframes), COUNT(99999999)},
    {"-width", MS_OPT_INT, ROFF(o.width), COUNT(MS_IMAGE_MAX_SIDE)},
    {"-height", MS_OPT_INT, ROFF(o.height), COUNT(MS_IMAGE_MAX_SIDE)},
    {"-video", MS_OPT_STRING, ROFF(o.video), 0, 0, 0, NULL},
    {"-fps", MS_OPT_DOUBLE, ROFF(o.fps), 0, 1000, MS_OPT_ABOVE | MS_OPT_MAX, NULL},
    {"-crf", MS_OPT_INT, ROFF(o.crf), COUNT(51)},
    {"-preset", MS_OPT_STRING, ROFF(o.preset), 0, 0, 0, NULL},
    {"-codec", MS_OPT_ENUM, ROFF(codec), 0, 0, 0, codecs},
    {"-format", MS_OPT_ENUM, ROFF(format), 0, 0, 0, frame_formats},
    {"-bitrate", MS_OPT_LONG, ROFF(o.bitrate), 1000, 1000000000L, MS_OPT_MIN | MS_OPT_MAX, NULL},
    {"-keepframes", MS_OPT_INT, ROFF(o.keep_frames), COUNT(1)},
    {"-progress", MS_OPT_INT, ROFF(progress), 0, 0, 0, NULL},
    {"-started", MS_OPT_DOUBLE, ROFF(o.started), 0, 0, 0, NULL},
    {"-scriptdone", MS_OPT_DOUBLE, ROFF(o.script_done), 0, 0, 0, NULL},
    {NULL, 0, 0, 0, 0, 0, NULL}};

/* Parse the options of run into o; video and basename point into objv. */
static int run_opts(Tcl_Interp *interp, int objc, Tcl_Obj *const objv[], ms_movie_opts *o)
{
    run_args a = {*o, -1, MS_CODEC_H264, MS_FRAMES_PNG};
    a.o.nframes = -1;
    a.o.crf = 18;
    a.o.keep_frames = 1;
    if (ms_args_options(interp, objc, objv, 2, run_options, &a, NULL)) return TCL_ERROR;
    *o = a.o;
    if (!o->basename || !*o->basename || o->nframes < 0 || o->width < 1 || o->height < 1)
        return ms_cmd_error(interp, "movie: -basename, -frames, -width and -height are required");
    if (o->preset && !ms_movie_preset_ok(o->preset))
        return ms_cmd_error(interp, "movie: -preset: unknown x264 preset '%s'", o->preset);
    o->codec = (ms_movie_codec)a.codec;
    o->frame_format = (ms_movie_frames)a.format;
    o->progress = a.progress < 0 ? -1 : a.progress > 0;
    return TCL_OK;
}

static Tcl_Obj *stats_dict(const ms_movie_opts *o, const ms_movie_stats *s)
{
    Tcl_Obj *d = Tcl_NewDictObj();
    struct { const char *k; double v; } nums[] = {
        {"script", s->script_s}, {"script_max", s->script_max_s}, {"state", s->state_s},
        {"state_max", s->state_max_s}, {"render", s->render_s},
        {"encode_tail", s->encode_tail_s}, {"busy_max", s->busy_max_s},
        {"busy_sum", s->busy_sum_s}, {"total", s->total_s}};
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("frames", -1), Tcl_NewLongObj(s->frames));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("rendered", -1), Tcl_NewLongObj(s->rendered));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("reused", -1), Tcl_NewLongObj(s->reused));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("ranks", -1), Tcl_NewIntObj(s->ranks));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("video", -1),
                   Tcl_NewStringObj(s->video_made ? o->video : "", -1));
    Tcl_DictObjPut(NULL, d, Tcl_NewStringObj("note", -1), Tcl_NewStringObj(s->note, -1));
    for (size_t i = 0; i < MS_COUNTOF(nums); i++)
        Tcl_DictObjPut(NULL, d, Tcl_NewStringObj(nums[i].k, -1), Tcl_NewDoubleObj(nums[i].v));
    return d;
}

static int movie_run(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (Tcl_GetAssocData(interp, BUSY_KEY, NULL))
        return ms_cmd_error(interp, "movie: not allowed inside a parallel for or movie frame "
                                    "callback (the other ranks are not at the same point)");
    ms_movie_opts o = {.fps = 30, .started = -1, .script_done = -1};
    if (run_opts(interp, objc, objv, &o) != TCL_OK) return TCL_ERROR;
    frame_ctx c = {interp, objv[1]};
    ms_movie_stats st;
    ms_error err = {{0}};
    Tcl_SetAssocData(interp, BUSY_KEY, NULL, (ClientData)1);
    int rc = ms_movie_run(&o, call_frame, &c, &st, &err);
    Tcl_DeleteAssocData(interp, BUSY_KEY);
    if (rc) return ms_cmd_error(interp, "movie make: %s", err.msg);
    Tcl_SetObjResult(interp, stats_dict(&o, &st));
    return TCL_OK;
}

/* ---------------------------------------------------------------- helpers */

static int movie_frameok(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    int w, h;
    if (ms_arg_int(interp, objv[2], "width", INT_MIN, INT_MAX, &w) ||
        ms_arg_int(interp, objv[3], "height", INT_MIN, INT_MAX, &h))
        return TCL_ERROR;
    Tcl_SetObjResult(interp, Tcl_NewBooleanObj(ms_movie_frame_ok(Tcl_GetString(objv[1]), w, h)));
    return TCL_OK;
}

static int movie_convert(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_image img = {0};
    ms_error err = {{0}};
    int rc = ms_image_read(Tcl_GetString(objv[1]), &img, &err);
    if (rc == 0) rc = ms_image_write(&img, Tcl_GetString(objv[2]), &err);
    ms_image_free(&img);
    if (rc) return ms_cmd_error(interp, "movie convert: %s", err.msg);
    return TCL_OK;
}

static int movie_started(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    Tcl_SetObjResult(interp, Tcl_NewDoubleObj(ms_movie_process_start()));
    return TCL_OK;
}

static int movie_ffmpeg(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    char *p = ms_movie_find_ffmpeg();
    Tcl_SetObjResult(interp, Tcl_NewStringObj(p ? p : "", -1));
    free(p);
    return TCL_OK;
}

/* ---------------------------------------------------------------- pose */

static Tcl_Obj *floats(const float *v, int n)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    for (int i = 0; i < n; i++) Tcl_ListObjAppendElement(NULL, l, Tcl_NewDoubleObj(v[i]));
    return l;
}

static int get_floats(Tcl_Interp *interp, Tcl_Obj *o, int n, float *out)
{
    Tcl_Obj **e;
    int len;
    if (Tcl_ListObjGetElements(NULL, o, &len, &e) != TCL_OK || len != n)
        return ms_cmd_error(interp, "movie pose: expected %d numbers, got '%s'", n, Tcl_GetString(o));
    for (int i = 0; i < n; i++) {
        double d;
        if (Tcl_GetDoubleFromObj(NULL, e[i], &d) != TCL_OK)
            return ms_cmd_error(interp, "movie pose: '%s' is not a number", Tcl_GetString(e[i]));
        out[i] = (float)d;
    }
    return TCL_OK;
}

static Tcl_Obj *pose_get(ms_app *app)
{
    Tcl_Obj *l = Tcl_NewListObj(0, NULL);
    Tcl_Obj *axes[2] = {Tcl_NewStringObj("axes", -1), floats(app->world.view->axes_rotate, 16)};
    Tcl_ListObjAppendElement(NULL, l, Tcl_NewListObj(2, axes));
    for (size_t i = 0; i < app->mols.n; i++) {
        const ms_molecule *m = app->mols.mols[i];
        Tcl_Obj *r[6] = {Tcl_NewStringObj("mol", -1), Tcl_NewIntObj(m->id), floats(m->center, 3),
                         floats(m->rotate, 16), Tcl_NewDoubleObj(m->scale), floats(m->global, 3)};
        Tcl_ListObjAppendElement(NULL, l, Tcl_NewListObj(6, r));
    }
    return l;
}

/* Set one record of a pose ({axes r16} or {mol id c3 r16 s g3}). */
static int pose_set_one(ms_app *app, Tcl_Interp *interp, Tcl_Obj *rec)
{
    Tcl_Obj **e;
    int n, id;
    float c[3], r[16], s, g[3];
    if (Tcl_ListObjGetElements(NULL, rec, &n, &e) != TCL_OK || n < 2)
        return ms_cmd_error(interp, "movie pose: bad record '%s'", Tcl_GetString(rec));
    const char *kind = Tcl_GetString(e[0]);
    if (ms_word_eq(kind, "axes") && n == 2) return get_floats(interp, e[1], 16, app->world.view->axes_rotate);
    if (!ms_word_eq(kind, "mol") || n != 6 || Tcl_GetIntFromObj(NULL, e[1], &id) != TCL_OK)
        return ms_cmd_error(interp, "movie pose: bad record '%s'", Tcl_GetString(rec));
    if (get_floats(interp, e[2], 3, c) || get_floats(interp, e[3], 16, r) ||
        get_floats(interp, e[4], 1, &s) || get_floats(interp, e[5], 3, g))
        return TCL_ERROR;
    ms_molecule *m = ms_molset_get(&app->mols, id);
    if (!m) return TCL_OK; /* deleted since: nothing to place */
    memcpy(m->center, c, sizeof c);
    memcpy(m->rotate, r, sizeof r);
    m->scale = s;
    memcpy(m->global, g, sizeof g);
    return TCL_OK;
}

static int movie_pose(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    if (objc == 1) {
        Tcl_SetObjResult(interp, pose_get(app));
        return TCL_OK;
    }
    Tcl_Obj **e;
    int n;
    if (Tcl_ListObjGetElements(NULL, objv[1], &n, &e) != TCL_OK)
        return ms_cmd_error(interp, "movie pose: bad value '%s': must be a list of records",
                            Tcl_GetString(objv[1]));
    for (int i = 0; i < n; i++)
        if (pose_set_one(app, interp, e[i]) != TCL_OK) return TCL_ERROR;
    return TCL_OK;
}

void ms_cmd_movie_register(ms_app *app)
{
    static const ms_subcmd cmds[] = {
        {"::molscope::movie::run", movie_run, 1, MS_ARGS_ANY,
         "<framecmd> -basename <B> -frames <N> -width <W> -height <H> ?-option <value> ...?"},
        {"::molscope::movie::frameok", movie_frameok, 3, 3, "<file> <width> <height>"},
        {"::molscope::movie::convert", movie_convert, 2, 2, "<from> <to>"},
        {"::molscope::movie::pose", movie_pose, 0, 1, "?<pose>?"},
        {"::molscope::movie::started", movie_started, 0, 0, ""},
        {"::molscope::movie::ffmpeg", movie_ffmpeg, 0, 0, ""}};
    Tcl_Eval(app->interp, "namespace eval ::molscope::movie {}");
    for (size_t i = 0; i < MS_COUNTOF(cmds); i++) ms_cmd_create(app, &cmds[i]);
}
