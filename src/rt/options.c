/* options.c: the ray tracer's options (defaults, and the pass limit and time budget read from
 * the environment) and its statistics; built with or without Embree. */
#include "config.h"
#include "rt/rt.h"

#include <errno.h>
#include <stdlib.h>
#include <string.h>
#include <unistd.h>

void ms_rt_options_default(ms_rt_options *o)
{
    memset(o, 0, sizeof *o);
    o->aasamples = 12;
    o->aosamples = 12;
}

/* One of names (NULL-terminated) from the environment, as its index into *out (unset or
 * empty: *out is left); an error naming the choices (expected) otherwise. */
static int env_choice(const char *name, const char *const *names, const char *expected, int *out,
                      ms_error *err)
{
    const char *v = getenv(name);
    if (!v || !*v) return 0;
    for (int k = 0; names[k]; k++)
        if (!strcmp(v, names[k])) {
            *out = k;
            return 0;
        }
    ms_error_set(err, "%s='%s': expected %s", name, v, expected);
    return -1;
}

/* A positive number from the environment (unset or empty: 0). */
static int env_number(const char *name, double max, double *out, ms_error *err)
{
    const char *v = getenv(name);
    *out = 0;
    if (!v || !*v) return 0;
    char *end;
    errno = 0;
    double d = strtod(v, &end);
    while (*end == ' ') end++;
    if (errno || *end || !(d > 0) || d > max) {
        ms_error_set(err, "%s='%s': expected a positive number up to %g", name, v, max);
        return -1;
    }
    *out = d;
    return 0;
}

int ms_rt_options_from_env(ms_rt_options *o, ms_error *err)
{
    double passes, seconds, depth;
    if (env_number("MOLSCOPE_RT_PASSES", MS_RT_MAX_AASAMPLES + 1, &passes, err) ||
        env_number("MOLSCOPE_RT_TIME", 1e7, &seconds, err) ||
        env_number("MOLSCOPE_RT_DEPTH", MS_RT_MAX_DEPTH, &depth, err))
        return -1;
    const char *whole = passes != (double)(int)passes ? "MOLSCOPE_RT_PASSES" :
                        depth != (double)(int)depth ? "MOLSCOPE_RT_DEPTH" : NULL;
    if (whole) {
        ms_error_set(err, "%s='%s': expected a whole number", whole, getenv(whole));
        return -1;
    }
    o->max_passes = (int)passes;
    o->max_depth = (int)depth;
    o->time_budget = seconds;
    o->raydump = getenv("MOLSCOPE_RT_RAYDUMP");
    static const char *const leaves[] = {"auto", "compact", "fast", NULL};
    static const char *const order[] = {"pixels", "passes", NULL};
    if (env_choice("MOLSCOPE_RT_LEAVES", leaves, "auto, compact or fast", &o->leaves, err) ||
        env_choice("MOLSCOPE_RT_ORDER", order, "pixels or passes", &o->order, err))
        return -1;
    o->progress = isatty(2);
    return 0;
}

int ms_rt_options_for_scene(const ms_scene *s, ms_rt_options *o, ms_error *err)
{
    ms_rt_options_default(o);
    o->aasamples = s->aa_samples;
    o->aosamples = s->ao_samples;
    return ms_rt_options_from_env(o, err);
}

uint64_t ms_rt_stats_rays(const ms_rt_stats *st)
{
    uint64_t n = 0;
    for (int k = 0; k < MS_RT_NRAYKINDS; k++) n += st->rays[k];
    return n;
}

int ms_rt_available(void)
{
#ifdef MS_HAVE_EMBREE
    return 1;
#else
    return 0;
#endif
}
