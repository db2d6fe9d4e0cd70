/* style.c: VMD's representation style strings ("Licorice 0.2 12 12"): the first word picks
 * the method; numbers replace that method's parameters in order, "-" keeps one, missing
 * ones keep the values this style last used with the method; "Off" means Lines. The text a
 * style keeps is VMD's: the method with every parameter written out ("Licorice 0.200000
 * 12.000000 12.000000"), whatever was typed. */
#include "config.h"
#include "rep/rep_int.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

#define MAXWORDS 64

/* Split text into whitespace-separated words (pointers into buf). */
static int split(char *buf, char **w, int max)
{
    int n = 0;
    for (char *p = buf; *p;) {
        while (*p && isspace((unsigned char)*p)) p++;
        if (!*p) break;
        if (n == max) return -1;
        w[n++] = p;
        while (*p && !isspace((unsigned char)*p)) p++;
        if (*p) *p++ = '\0';
    }
    return n;
}

/* How VMD writes parameter i of method m: %f, except the whole numbers below (%d); a bond
 * cutoff is written only when it is set (VMD's strings leave it out: "Lines 1.000000"). */
enum { PARAM_FLOAT, PARAM_INT, PARAM_CUTOFF };

static int param_kind(const ms_rep_method *m, int i)
{
    const char *name = m->param[i].name;
    if (!strcmp(name, "spline")) return PARAM_INT;                  /* NewCartoon, NewRibbons */
    if (!strcmp(m->name, "Isosurface") && i > 0) return PARAM_INT;   /* volid box style step thickness */
    if (!strcmp(name, "bond cutoff")) return PARAM_CUTOFF;
    return PARAM_FLOAT;
}

/* s->text from the method and its parameters. */
static void format_text(ms_rep_style *s)
{
    const ms_rep_method *m = ms_rep_method_at((size_t)s->method);
    const float *p = s->param[s->method];
    size_t len = (size_t)snprintf(s->text, sizeof s->text, "%s", m->name);
    for (int i = 0; i < m->nparams && len < sizeof s->text; i++) {
        int kind = param_kind(m, i);
        if (kind == PARAM_CUTOFF && p[i] == 0.0f) continue;
        if (kind == PARAM_INT)
            len += (size_t)snprintf(s->text + len, sizeof s->text - len, " %d", (int)p[i]);
        else
            len += (size_t)snprintf(s->text + len, sizeof s->text - len, " %f", (double)p[i]);
    }
}

void ms_rep_style_init(ms_rep_style *s)
{
    memset(s, 0, sizeof *s);
    for (size_t k = 0; k < ms_rep_method_count(); k++) {
        const ms_rep_method *m = ms_rep_method_at(k);
        for (int i = 0; i < m->nparams; i++) s->param[k][i] = m->param[i].def;
    }
    s->method = ms_rep_method_find("Lines");
    format_text(s);
}

static int parse_number(const char *w, float *out)
{
    char *end;
    double v = strtod(w, &end);
    if (end == w || *end || !isfinite(v) || !isfinite((float)v)) return -1;
    *out = (float)v;
    return 0;
}

int ms_rep_style_parse(ms_rep_style *s, const char *text, ms_error *err)
{
    size_t len = strlen(text);
    if (len >= MS_REP_TEXTMAX) {
        ms_error_set(err, "representation string is too long (over %d characters)",
                     MS_REP_TEXTMAX - 1);
        return -1;
    }
    char buf[MS_REP_TEXTMAX], *w[MAXWORDS];
    memcpy(buf, text, len + 1);
    int n = split(buf, w, MAXWORDS);
    if (n < 0) {
        ms_error_set(err, "representation string has too many parameters");
        return -1;
    }
    if (n == 0) return 0;   /* nothing given: keep everything, as VMD */
    if (!strcasecmp(w[0], "off")) {   /* VMD's alias */
        n = 1;
        w[0] = "Lines";
    }
    int k = ms_rep_method_find(w[0]);
    if (k < 0) {
        const char *later = ms_rep_method_unavailable(w[0]);
        if (later)
            ms_error_set(err, "the %s drawing method is not available in molscope yet", later);
        else
            ms_error_set(err, "unknown drawing method '%s'", w[0]);
        return -1;
    }
    const ms_rep_method *m = ms_rep_method_at((size_t)k);
    if (n - 1 > m->nparams) {
        ms_error_set(err, "%s takes at most %d parameters, got %d", m->name, m->nparams, n - 1);
        return -1;
    }
    float v[MS_REP_MAXPARAMS];
    memcpy(v, s->param[k], sizeof v);
    for (int i = 1; i < n; i++) {
        if (!strcmp(w[i], "-")) continue;
        if (parse_number(w[i], &v[i - 1])) {
            ms_error_set(err, "%s: parameter %d (%s): expected a number or '-', got '%s'",
                         m->name, i, m->param[i - 1].name, w[i]);
            return -1;
        }
    }
    memcpy(s->param[k], v, sizeof v);
    s->method = k;
    format_text(s);
    return 0;
}
