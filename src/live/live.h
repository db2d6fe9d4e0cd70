/* live.h: the live view of a running session in a browser (doc/live.md). `display live on`
 * starts a small web server inside molscope (libmicrohttpd, driven from Tcl's event loop, so
 * everything runs on the interpreter's thread) that serves one page, the current image and
 * a view-change endpoint, every request checked against a random token.
 *
 * The frames: whenever the picture may have changed (the world's scene_version, scene builds
 * by others, colours, materials, display size), the scene is rebuilt and drawn at once with the
 * GL display device when one runs, then TachyonInternal passes refine it at idle time, one
 * pass per idle turn, each pass's average replacing the image until the pass count of
 * `render aasamples TachyonInternal` is reached. A text session (no GL) shows the ray-traced
 * passes only. Every new image gets the next serial number; the page polls for it.
 *
 * View changes from the page (rotation angles about the screen axes, a scale factor, a
 * translation) are numbers checked against bounds and applied through assemble/view.h, as the
 * rotate / scale / translate commands do, so molinfo's matrices follow them. */
#ifndef MS_LIVE_H
#define MS_LIVE_H

#include <stddef.h>

#include <tcl.h>

#include "app/app.h"
#include "base/base.h"
#include "rt/rt.h"
#include "scene/lod.h"
#include "scene/scene.h"

/* ---------------------------------------------------------------- frames (frames.c) */

#define MS_LIVE_LOD_TRIS 150000   /* mesh triangles a drag's coarse image draws at most */

typedef struct ms_live_frames {
    ms_app *app;
    int valid;                    /* the counters below describe the scene held */
    unsigned long version, builds, colors_version, materials_version;
    int width, height;
    ms_scene scene;               /* what the ray tracer traces (its lists must not change) */
    int have_scene;
    ms_rt_session *rt;
    int rt_pending;               /* the ray tracer starts at the next step */
    int max_passes;               /* TachyonInternal's aasamples + 1 */
    unsigned char *png;           /* the current image, PNG (malloc'd) */
    size_t png_len;
    unsigned long serial;         /* bumped at every new image */
    int passes;                   /* ray-traced passes in the current image (0: raster) */
    char error[256];              /* why the last image could not be made ("" when fine) */
    int idle_queued;
    void *timer;                  /* Tcl_TimerToken of the change check */
    int raster_only;              /* no ray-traced passes while a GL display draws */
    double timing[4];             /* the last raster image's seconds: scene, upload, draw, PNG */
    double interact_until;        /* view changes from the page: coarse images until then */
    int coarse;                   /* the image is a coarse one (redrawn whole after the drag) */
    ms_scene_lod lod;             /* the decimated meshes coarse images draw (kept for a drag) */
    size_t triangles;             /* mesh triangles the last raster image drew */
    void (*on_image)(void *ud);   /* called after each new image (may be NULL) */
    void *ud;
} ms_live_frames;

/* Start following app (the first image is made at the next idle turn); stop and free. */
void ms_live_frames_start(ms_live_frames *f, ms_app *app);
void ms_live_frames_stop(ms_live_frames *f);
/* Render at the next idle turn, not at the next change check (after a view change). */
void ms_live_frames_kick(ms_live_frames *f);
/* A view change from the page: while they come (0.3 s apart at most) the raster images are
 * drawn at half the size each way, from meshes decimated to MS_LIVE_LOD_TRIS triangles in
 * all (scene/lod.h, made once per drag and list), and not ray traced; then the whole image
 * follows. */
void ms_live_frames_interact(ms_live_frames *f);
/* Show the raster image only (1) or refine it with ray-traced passes (0); the next image
 * follows the choice. */
void ms_live_frames_set_raster(ms_live_frames *f, int raster_only);
/* Whether the picture may have changed since the image was made. */
int ms_live_frames_stale(const ms_live_frames *f);
/* One unit of work: a new scene and its first image when stale, else one more pass.
 * Returns 1 when more work remains. */
int ms_live_frames_step(ms_live_frames *f);

/* ---------------------------------------------------------------- view changes */

/* A view change from the page: degrees about the screen x, y, z axes, a scale factor and a
 * translation in VMD's world units, as `rotate x by`, `scale by`, `translate by`. */
typedef struct ms_live_view {
    float rot[3], scale, trans[3];
} ms_live_view;

#define MS_LIVE_MAX_DEG 180.0
#define MS_LIVE_MIN_SCALE 0.1
#define MS_LIVE_MAX_SCALE 10.0
#define MS_LIVE_MAX_TRANS 10.0

void ms_live_view_init(ms_live_view *v);
/* Set one field from a form pair (rx ry rz scale tx ty tz): 0, or -1 with err set for an
 * unknown key or a value that is not a plain finite number within the bounds above. */
int ms_live_view_set(ms_live_view *v, const char *key, const char *value, ms_error *err);
/* Apply through assemble/view.h (rotations x, y, z in turn, then scale, then translation). */
void ms_live_view_apply(ms_app *app, const ms_live_view *v);

/* ---------------------------------------------------------------- the server */

typedef struct ms_live_status {
    int on;
    char url[300];
    int port;
    unsigned long images;         /* serial of the current image */
    int passes;
    char error[256];
    double timing[4];             /* ms_live_frames.timing */
    size_t triangles;             /* ms_live_frames.triangles */
    int coarse;                   /* the current image is a drag's coarse one */
} ms_live_status;

/* Whether this build has the server; when not, why is written in why. */
int ms_live_available(char *why, size_t size);
/* Start serving app's session on port (0: a free one) at bind_addr (NULL: 127.0.0.1; an
 * IPv4 address). Returns 0 and fills st (the URL with its token), or -1 with err set
 * (already on, bad address, port taken, no page). The server stops with the interpreter. */
int ms_live_start(ms_app *app, int port, const char *bind_addr, ms_live_status *st,
                  ms_error *err);
/* Stop serving: 0, or -1 when it was not on. */
int ms_live_stop(ms_app *app);
void ms_live_get_status(ms_app *app, ms_live_status *st);
/* `display live mode`: 0 and the mode in *raster_only (1 raster, 0 progressive); with set,
 * change it first. -1 when the server is not on. */
int ms_live_mode(ms_app *app, int set, int *raster_only);

/* ---------------------------------------------------------------- the console (console.c) */

/* s (n bytes) as a JSON string, control characters escaped. */
void ms_live_json_str(Tcl_DString *out, const char *s, size_t n);
/* Run cmd at the global level as the prompt would: a script, or (as_words) one command of
 * the list's words. Appends {"ok":true,"result":R,"output":O} or {"ok":false,"error":E,
 * "output":O} to json (O: what it wrote to stdout and stderr, which still get it); 0, or -1
 * when the command failed. */
int ms_live_run(ms_app *app, Tcl_Obj *cmd, int as_words, Tcl_DString *json);
/* The session's state for the page's panels (tcl/live/live.tcl) with the scene version,
 * the display mode and the catalog of rep methods, as JSON; -1 with err set. */
int ms_live_session_json(ms_app *app, int raster_only, Tcl_DString *json, ms_error *err);

#endif
