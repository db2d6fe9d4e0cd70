/* test_live.c: unit tests of the live view's checks on what a page sends (live.h): the
 * fields and bounds accepted, and everything else refused with the view change untouched:
 * Tcl code, words (nan, inf), hexadecimal, spaces, empty values, numbers out of range. */
#include "config.h"
#include "ms_test.h"
#include "live/live.h"

#include <string.h>

static int accepts(const char *key, const char *value, float *got)
{
    ms_live_view v;
    ms_error err = {{0}};
    ms_live_view_init(&v);
    if (ms_live_view_set(&v, key, value, &err)) return 0;
    const char *keys[] = {"rx", "ry", "rz", "scale", "tx", "ty", "tz"};
    float *slot[] = {&v.rot[0], &v.rot[1], &v.rot[2], &v.scale, &v.trans[0], &v.trans[1], &v.trans[2]};
    for (int i = 0; i < 7; i++)
        if (!strcmp(key, keys[i])) *got = *slot[i];
    return 1;
}

static void refused(const char *key, const char *value)
{
    ms_live_view v, before;
    ms_error err = {{0}};
    ms_live_view_init(&v);
    before = v;
    int rc = ms_live_view_set(&v, key, value, &err);
    t_ok(rc == -1 && !memcmp(&v, &before, sizeof v) && err.msg[0],
         "refused: %s=%s (%s)", key, value, err.msg);
}

int main(void)
{
    t_suite = "live view changes";
    ms_live_view v;
    ms_live_view_init(&v);
    t_ok(v.scale == 1.0f && v.rot[0] == 0 && v.trans[2] == 0, "starts as no change (scale 1)");
    float got = 0;
    t_ok(accepts("rx", "12.5", &got) && got == 12.5f, "rx=12.5");
    t_ok(accepts("ry", "-180", &got) && got == -180.0f, "ry=-180 (the bound)");
    t_ok(accepts("rz", "180", &got) && got == 180.0f, "rz=180 (the bound)");
    t_ok(accepts("scale", "1.1", &got) && got == 1.1f, "scale=1.1");
    t_ok(accepts("scale", "0.1", &got) && got == 0.1f, "scale=0.1 (the bound)");
    t_ok(accepts("tx", "-10", &got) && got == -10.0f, "tx=-10 (the bound)");
    t_ok(accepts("ty", "2.5e-1", &got) && got == 0.25f, "ty=2.5e-1");
    refused("rx", "180.001");
    refused("ry", "1e9");
    refused("scale", "0");
    refused("scale", "-1");
    refused("scale", "10.5");
    refused("tz", "11");
    refused("rx", "nan");
    refused("rx", "inf");
    refused("rx", "0x10");
    refused("rx", "");
    refused("rx", " 1");
    refused("rx", "1 ");
    refused("rx", "[exit]");
    refused("rx", "1;exit");
    refused("rx", "$x");
    refused("cmd", "1");
    refused("RX", "1");
    refused("rx", "1.000000000000000000000000000000001");
    return t_done();
}
