/* nolive.c: the live view in a build without libmicrohttpd: `display live on` says why it
 * is unavailable (the frames and view changes of frames.c are still built). */
#include "config.h"
#include "live/live.h"

#include <stdio.h>
#include <string.h>

#define WHY "molscope was built without libmicrohttpd (Debian: libmicrohttpd-dev), so it " \
            "cannot serve the live view; reconfigure after installing it"

int ms_live_available(char *why, size_t size)
{
    if (size) snprintf(why, size, "%s", WHY);
    return 0;
}

int ms_live_start(ms_app *app, int port, const char *bind_addr, ms_live_status *st,
                  ms_error *err)
{
    memset(st, 0, sizeof *st);
    ms_error_set(err, "%s", WHY);
    return -1;
}

int ms_live_stop(ms_app *app)
{
    return -1;
}

void ms_live_get_status(ms_app *app, ms_live_status *st)
{
    memset(st, 0, sizeof *st);
}

int ms_live_mode(ms_app *app, int set, int *raster_only)
{
    return -1;
}
