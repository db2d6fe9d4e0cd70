/* stub.c: the ray tracer in a build without Embree: every render says so. */
#include "config.h"
#include "rt/rt.h"

#include <string.h>

static int unavailable(ms_error *err)
{
    ms_error_set(err, "molscope was built without Embree (Debian: libembree-dev), so it cannot "
                      "ray trace; render Tachyon writes a scene for the tachyon program instead");
    return -1;
}

int ms_rt_render(const ms_scene *s, const ms_rt_options *o, ms_image *img, ms_rt_stats *st,
                 ms_error *err)
{
    memset(img, 0, sizeof *img);
    if (st) memset(st, 0, sizeof *st);
    return unavailable(err);
}

int ms_rt_write(const ms_scene *s, const ms_rt_options *o, const char *path, ms_rt_stats *st,
                ms_error *err)
{
    if (st) memset(st, 0, sizeof *st);
    return unavailable(err);
}

ms_rt_session *ms_rt_session_begin(const ms_scene *s, const ms_rt_options *o, ms_error *err)
{
    unavailable(err);
    return NULL;
}

int ms_rt_session_pass(ms_rt_session *ss) { return 0; }
int ms_rt_session_passes(const ms_rt_session *ss) { return 0; }

int ms_rt_session_image(const ms_rt_session *ss, ms_image *img, ms_error *err)
{
    memset(img, 0, sizeof *img);
    return unavailable(err);
}

void ms_rt_session_end(ms_rt_session *ss) {}

void ms_rt_last_memory(ms_rt_memory *out) { memset(out, 0, sizeof *out); }
