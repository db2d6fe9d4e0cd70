/* regex.c: regular expressions as selections use them. VMD's are Perl-style; molscope uses
 * POSIX extended expressions (glibc also knows \w \s \b) and translates \d and \D, the Perl
 * classes scripts most often use. Keyword values in "double quotes" are anchored ^(...)$.
 * glibc's compiler copies a repeated subexpression once per repetition, so stacked or nested
 * repetitions grow exponentially: patterns whose expanded size would pass a limit are
 * refused before they reach it. */
#include "config.h"
#include "select/selint.h"

#include <stdlib.h>
#include <string.h>

/* Copy pattern to out, turning \d into [0-9] and \D into [^0-9] (0-9 inside brackets). */
static void translate(const char *p, char *out)
{
    int in_bracket = 0;
    size_t o = 0;
    for (size_t i = 0; p[i]; i++) {
        char ch = p[i];
        if (in_bracket) {
            if (ch == ']' && !(i > 0 && (p[i - 1] == '[' || (p[i - 1] == '^' && i > 1 &&
                                                              p[i - 2] == '['))))
                in_bracket = 0;
            if (ch == '\\' && p[i + 1] == 'd') {
                memcpy(out + o, "0-9", 3);
                o += 3;
                i++;
                continue;
            }
            out[o++] = ch;
            continue;
        }
        if (ch == '\\' && (p[i + 1] == 'd' || p[i + 1] == 'D')) {
            const char *rep = p[i + 1] == 'd' ? "[0-9]" : "[^0-9]";
            memcpy(out + o, rep, strlen(rep));
            o += strlen(rep);
            i++;
            continue;
        }
        if (ch == '\\' && p[i + 1]) {
            out[o++] = ch;
            out[o++] = p[++i];
            continue;
        }
        if (ch == '[') in_bracket = 1;
        out[o++] = ch;
    }
    out[o] = '\0';
}

#define EXPANDED_LIMIT 20000.0

/* The bound of a {n}, {n,} or {n,m} at p (just after '{'), or -1 when it is not one. */
static double brace_bound(const char *p)
{
    char *end;
    double lo = strtod(p, &end), hi = lo;
    if (end == p) return -1;
    if (*end == ',') {
        const char *q = end + 1;
        hi = *q == '}' ? 1 : strtod(q, &end);
        if (*q != '}' && end == q) return -1;
        if (*q == '}') end = (char *)q;
    }
    return *end == '}' ? MS_MAX(MS_MAX(lo, hi), 1) : -1;
}

/* Estimate the size glibc expands a pattern to; NULL when acceptable, else why not. */
static const char *too_costly(const char *p)
{
    double stack[64], cur = 0, last = 0;
    int depth = 0, after_quant = 0;
    for (size_t i = 0; p[i]; i++) {
        char ch = p[i];
        int quant = ch == '*' || ch == '+' || ch == '?' || (ch == '{' && brace_bound(p + i + 1) >= 0);
        if (quant) {
            if (after_quant) return "repeated repetition operators";
            double times = ch == '{' ? brace_bound(p + i + 1) : ch == '+' ? 2 : 1;
            cur += last * (times - 1);
            last *= times;
            if (ch == '{') while (p[i] && p[i] != '}') i++;
        } else if (ch == '(') {
            if (depth == 64) return "parentheses nested too deeply";
            stack[depth++] = cur;
            cur = 0;
        } else if (ch == ')' && depth > 0) {
            last = cur + 1;
            cur = stack[--depth] + last;
        } else {
            if (ch == '\\' && p[i + 1]) i++;
            else if (ch == '[')   /* a bracket expression is one atom */
                for (i += (p[i + 1] == '^') + 1 + (p[i + 1 + (p[i + 1] == '^')] == ']');
                     p[i] && p[i] != ']'; i++) {}
            if (!p[i]) break;
            last = 1;
            cur += 1;
        }
        after_quant = quant;
        if (cur > EXPANDED_LIMIT || last > EXPANDED_LIMIT) return "too large once expanded";
    }
    return NULL;
}

int ms_sel_regcomp(regex_t *re, const char *pattern, int anchored, int nosub, ms_error *err)
{
    const char *why = too_costly(pattern);
    if (why) {
        ms_error_set(err, "bad regular expression \"%.200s\": %s", pattern, why);
        return -1;
    }
    size_t len = strlen(pattern);
    char *body = ms_alloc_array(len * 3 + 8, 1), *full = ms_alloc_array(len * 3 + 16, 1);
    if (!body || !full) {
        free(body);
        free(full);
        ms_error_set(err, "out of memory compiling a regular expression");
        return -1;
    }
    translate(pattern, body);
    if (anchored) {
        strcpy(full, "^(");
        strcat(full, body);
        strcat(full, ")$");
    } else {
        strcpy(full, body);
    }
    int rc = regcomp(re, full, REG_EXTENDED | (nosub ? REG_NOSUB : 0));
    free(body);
    free(full);
    if (rc) {
        char msg[256];
        regerror(rc, re, msg, sizeof msg);
        ms_error_set(err, "bad regular expression \"%.200s\": %s", pattern, msg);
        return -1;
    }
    return 0;
}
