/* numfmt.c: fast number text for the exporters. Scene files hold millions of numbers and
 * printf's %g dominates writing them; these give the same text (6 significant digits, no
 * trailing zeros; or 3 fixed decimals) for the usual range and defer to printf elsewhere. */
#include "config.h"
#include "render/export.h"

#include <math.h>
#include <stdio.h>

static const double pow10d[10] = {1, 1e1, 1e2, 1e3, 1e4, 1e5, 1e6, 1e7, 1e8, 1e9};
static const long long pow10i[10] = {1, 10, 100, 1000, 10000, 100000, 1000000, 10000000,
                                     100000000, 1000000000};

/* Digits of a non-negative integer; returns the count. */
static int put_uint(char *out, long long v)
{
    char tmp[24];
    int n = 0;
    do {
        tmp[n++] = (char)('0' + v % 10);
        v /= 10;
    } while (v);
    for (int i = 0; i < n; i++) out[i] = tmp[n - 1 - i];
    return n;
}

/* Rounding is to nearest, ties to even, as printf rounds. */

/* sign, integer part, and d fraction digits of s / 10^d, trailing zeros dropped if trim */
static int put_fixed(char *out, int neg, long long s, int d, int trim)
{
    char *p = out;
    if (neg && s) *p++ = '-';
    p += put_uint(p, s / pow10i[d]);
    long long frac = s % pow10i[d];
    if (d > 0 && (frac || !trim)) {
        *p++ = '.';
        for (int k = d - 1; k >= 0; k--) p[k] = (char)('0' + frac % 10), frac /= 10;
        p += d;
        if (trim) while (p[-1] == '0') p--;
    }
    *p = '\0';
    return (int)(p - out);
}

int ms_fmt_g(char *out, float fv)
{
    double v = fv, a = fabs(v);
    if (v == 0) {
        out[0] = '0';
        out[1] = '\0';
        return 1;
    }
    if (!(a >= 1e-4 && a < 1e6)) return snprintf(out, 32, "%g", v);
    int e = (int)floor(log10(a));
    int d = 5 - e;                 /* fraction digits for 6 significant ones */
    if (d < 0 || d > 9) return snprintf(out, 32, "%g", v);
    long long s = (long long)nearbyint(a * pow10d[d]);
    if (s >= 1000000) {            /* rounded up to the next power of ten */
        if (d == 0) return snprintf(out, 32, "%g", v);
        s = (long long)nearbyint(a * pow10d[--d]);
    }
    return put_fixed(out, v < 0, s, d, 1);
}

int ms_fmt_f3(char *out, float fv)
{
    double v = fv, a = fabs(v);
    if (!(a < 1e12)) return snprintf(out, 32, "%.3f", v);
    long long s = (long long)nearbyint(a * 1000.0);
    return put_fixed(out, v < 0 && s, s, 3, 0);
}
