/* regex.c: regular expressions as selections use them. VMD's are Perl-style; molscope uses
 * POSIX extended expressions (glibc also knows \w \s \b) and translates \d and \D, the Perl
 * classes scripts most often use. Keyword values in "double quotes" are anchored ^(...)$. */
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

int ms_sel_regcomp(regex_t *re, const char *pattern, int anchored, int nosub, ms_error *err)
{
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
