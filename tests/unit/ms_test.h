/* ms_test.h: the C unit tests' reporting: each check prints "PASS: name" or
 * "FAIL: name: detail", the lines tests/run-tests counts. */
#ifndef MS_TEST_H
#define MS_TEST_H

#include <stdarg.h>
#include <stdio.h>
#include <stdlib.h>

static int t_failures;
static const char *t_suite = "unit";

/* Report a check named by fmt; returns cond. */
static int t_ok(int cond, const char *fmt, ...) __attribute__((format(printf, 2, 3), unused));
static int t_ok(int cond, const char *fmt, ...)
{
    va_list ap;
    printf("%s: %s: ", cond ? "PASS" : "FAIL", t_suite);
    va_start(ap, fmt);
    vprintf(fmt, ap);
    va_end(ap);
    printf("\n");
    fflush(stdout);
    if (!cond) t_failures++;
    return cond;
}

static void t_skip(const char *name, const char *why) __attribute__((unused));
static void t_skip(const char *name, const char *why)
{
    printf("SKIP: %s: %s: %s\n", t_suite, name, why);
}

/* The test data folder (tests/data), from the environment the runner sets. */
static const char *t_data(void) __attribute__((unused));
static const char *t_data(void)
{
    const char *d = getenv("MS_TEST_DATA");
    return d ? d : "tests/data";
}

static int t_done(void) __attribute__((unused));
static int t_done(void) { return t_failures ? 1 : 0; }

#endif
