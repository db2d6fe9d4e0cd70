/* plugin_util.c: line reading, field parsing, hybrid-36 and checked output for plugins. */
#include "plugin_util.h"

#include <ctype.h>
#include <errno.h>
#include <fcntl.h>
#include <limits.h>
#include <math.h>
#include <stdarg.h>
#include <stdlib.h>
#include <string.h>
#include <sys/stat.h>
#include <unistd.h>

#define LINES_BUF (1u << 20)
#define LINES_MAX_LINE (64u << 20)

/* ---------------------------------------------------------------- line reader */

int ms_lines_open(ms_lines *r, const char *path, ms_perr *err)
{
    memset(r, 0, sizeof *r);
    r->fp = fopen(path, "rb");
    if (!r->fp) return ms_perr_set(err, "%s", strerror(errno));
    r->cap = LINES_BUF;
    r->buf = malloc(r->cap + 1);
    if (!r->buf) {
        fclose(r->fp);
        r->fp = NULL;
        return ms_perr_set(err, "out of memory");
    }
    return MS_PLUGIN_OK;
}

void ms_lines_close(ms_lines *r)
{
    if (r->fp) fclose(r->fp);
    free(r->buf);
    memset(r, 0, sizeof *r);
}

void *ms_lines_create(size_t size, const char *path, ms_perr *err)
{
    ms_lines *r = calloc(1, size < sizeof *r ? sizeof *r : size);
    if (!r) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (ms_lines_open(r, path, err) != MS_PLUGIN_OK) {
        free(r);
        return NULL;
    }
    return r;
}

void ms_lines_destroy(void *reader)
{
    ms_lines_close((ms_lines *)reader);
    free(reader);
}

/* Move unread bytes to the front and read more. Returns bytes added (0 at EOF/error). */
static size_t lines_refill(ms_lines *r)
{
    if (r->eof) return 0;
    if (r->pos > 0) {
        memmove(r->buf, r->buf + r->pos, r->len - r->pos);
        r->offset += (long long)r->pos;
        r->len -= r->pos;
        r->pos = 0;
    }
    if (r->len == r->cap) {
        if (r->cap >= LINES_MAX_LINE) {
            r->error = 1;
            return 0;
        }
        char *nb = realloc(r->buf, 2 * r->cap + 1);
        if (!nb) {
            r->error = 1;
            return 0;
        }
        r->buf = nb;
        r->cap *= 2;
    }
    size_t got = fread(r->buf + r->len, 1, r->cap - r->len, r->fp);
    if (got == 0) {
        if (ferror(r->fp)) r->error = 1;
        r->eof = 1;
    }
    r->len += got;
    return got;
}

const char *ms_lines_next(ms_lines *r)
{
    for (;;) {
        char *start = r->buf + r->pos;
        char *nl = memchr(start, '\n', r->len - r->pos);
        if (nl || (r->eof && r->pos < r->len)) {
            size_t n = nl ? (size_t)(nl - start) : r->len - r->pos;
            r->pos += n + (nl ? 1 : 0);
            if (n && start[n - 1] == '\r') n--;
            start[n] = '\0';
            r->line = start;
            r->line_len = n;
            r->line_no++;
            return start;
        }
        if (r->eof || r->error) return NULL;
        if (lines_refill(r) == 0 && !r->eof) return NULL;
    }
}

long long ms_lines_tell_next(const ms_lines *r) { return r->offset + (long long)r->pos; }

int ms_lines_seek(ms_lines *r, long long offset, long line_no)
{
    if (fseeko(r->fp, (off_t)offset, SEEK_SET) != 0) return -1;
    r->offset = offset;
    r->pos = r->len = 0;
    r->eof = r->error = 0;
    r->line_no = line_no;
    return 0;
}

long long ms_lines_left(const ms_lines *r)
{
    struct stat sb;
    if (!r->fp || fstat(fileno(r->fp), &sb) != 0 || !S_ISREG(sb.st_mode)) return -1;
    long long left = (long long)sb.st_size - ms_lines_tell_next(r);
    return left > 0 ? left : 0;
}

/* ---------------------------------------------------------------- declared sizes */

int ms_check_room(ms_perr *err, double count, double min_bytes, long long left,
                  const char *unit, const char *claim, ...)
{
    if (left < 0 || count * min_bytes <= (double)left + 1) return MS_PLUGIN_OK;
    char what[384];
    va_list ap;
    va_start(ap, claim);
    vsnprintf(what, sizeof what, claim, ap);
    va_end(ap);
    return ms_perr_set(err, "%s but the file holds only %lld bytes after it (room for at most "
                       "%.0f %s)", what, left, floor(((double)left + 1) / min_bytes), unit);
}

long long ms_plugin_mem_available(void)
{
    FILE *f = fopen("/proc/meminfo", "r");
    if (!f) return -1;
    char line[256];
    long long kb = -1;
    while (fgets(line, sizeof line, f))
        if (sscanf(line, "MemAvailable: %lld kB", &kb) == 1) break;
    fclose(f);
    return kb < 0 ? -1 : kb * 1024;
}

/* ---------------------------------------------------------------- fields */

void ms_field(const char *line, size_t len, size_t c0, size_t c1, char *out)
{
    size_t b = c0, e = c1 < len ? c1 : len;
    while (b < e && (line[b] == ' ' || line[b] == '\t')) b++;
    while (e > b && (line[e - 1] == ' ' || line[e - 1] == '\t')) e--;
    size_t n = e > b ? e - b : 0;
    memcpy(out, line + b, n);
    out[n] = '\0';
}

static const double pow10_neg[] = {1e0,   1e-1,  1e-2,  1e-3,  1e-4,  1e-5,  1e-6,
                                   1e-7,  1e-8,  1e-9,  1e-10, 1e-11, 1e-12, 1e-13,
                                   1e-14, 1e-15, 1e-16, 1e-17, 1e-18};

int ms_parse_double(const char *s, size_t n, double *v)
{
    if (n == 0) return -1;
    /* Fast path: [+-]digits[.digits], the form of every fixed-format coordinate. */
    size_t i = 0;
    int neg = 0;
    if (s[i] == '-' || s[i] == '+') neg = s[i++] == '-';
    uint64_t mant = 0;
    int digits = 0, frac = 0, dot = 0;
    for (; i < n; i++) {
        char c = s[i];
        if (c >= '0' && c <= '9') {
            if (digits < 18) {
                mant = mant * 10 + (uint64_t)(c - '0');
                if (dot) frac++;
            } else if (!dot) {
                goto slow;
            }
            digits++;
        } else if (c == '.' && !dot) {
            dot = 1;
        } else {
            break;
        }
    }
    if (i == n && digits > 0 && frac <= 18) {
        double d = (double)mant * pow10_neg[frac];
        *v = neg ? -d : d;
        return 1;
    }
slow:;
    char tmp[64];
    if (n >= sizeof tmp) return -1;
    memcpy(tmp, s, n);
    tmp[n] = '\0';
    char *end;
    errno = 0;
    double d = strtod(tmp, &end);
    if (end == tmp || *end != '\0' || errno == ERANGE) return -1;
    *v = d;
    return 1;
}

int ms_parse_float(const char *s, size_t n, float *v)
{
    double d;
    if (ms_parse_double(s, n, &d) < 0) return -1;
    if (d > 3.4e38 || d < -3.4e38 || d != d) return -1;
    *v = (float)d;
    return 1;
}

int ms_whole_in(double v, double lo, double hi)
{
    return v >= lo && v <= hi && v == floor(v);
}

int ms_parse_long(const char *s, size_t n, long *v)
{
    size_t i = 0;
    int neg = 0;
    if (n == 0) return -1;
    if (s[i] == '-' || s[i] == '+') neg = s[i++] == '-';
    if (i == n) return -1;
    long val = 0;
    for (; i < n; i++) {
        if (s[i] < '0' || s[i] > '9') return -1;
        if (val > (2147483647L - (s[i] - '0')) / 10) return -1;
        val = val * 10 + (s[i] - '0');
    }
    *v = neg ? -val : val;
    return 1;
}

/* Trimmed bounds of columns [c0, c1). */
static void field_bounds(const char *line, size_t len, size_t c0, size_t c1, size_t *b,
                         size_t *e)
{
    *b = c0;
    *e = c1 < len ? c1 : len;
    while (*b < *e && (line[*b] == ' ' || line[*b] == '\t')) (*b)++;
    while (*e > *b && (line[*e - 1] == ' ' || line[*e - 1] == '\t')) (*e)--;
}

int ms_field_float(const char *line, size_t len, size_t c0, size_t c1, float *v)
{
    size_t b, e;
    if (c0 >= len) return 0;
    field_bounds(line, len, c0, c1, &b, &e);
    if (b >= e) return 0;
    return ms_parse_float(line + b, e - b, v);
}

int ms_field_int(const char *line, size_t len, size_t c0, size_t c1, int *v)
{
    size_t b, e;
    if (c0 >= len) return 0;
    field_bounds(line, len, c0, c1, &b, &e);
    if (b >= e) return 0;
    long l;
    if (ms_parse_long(line + b, e - b, &l) < 0) return -1;
    *v = (int)l;
    return 1;
}

/* ---------------------------------------------------------------- hybrid-36 */

static long ipow(long b, size_t e)
{
    long r = 1;
    while (e--) r *= b;
    return r;
}

int ms_hy36_decode(const char *s, size_t width, long *v)
{
    size_t b = 0, e = width;
    for (size_t i = 0; i < width; i++)
        if (s[i] == '\0') {
            e = i;
            break;
        }
    while (b < e && s[b] == ' ') b++;
    while (e > b && s[e - 1] == ' ') e--;
    if (b >= e) return 0;
    char c = s[b];
    if (c == '-' || (c >= '0' && c <= '9')) return ms_parse_long(s + b, e - b, v) < 0 ? -1 : 1;
    /* Hybrid-36 numbers fill the whole field. */
    if (b != 0 || e != width) return -1;
    int upper = c >= 'A' && c <= 'Z', lower = c >= 'a' && c <= 'z';
    if (!upper && !lower) return -1;
    long val = 0;
    for (size_t i = 0; i < width; i++) {
        char d = s[i];
        int dv;
        if (d >= '0' && d <= '9') dv = d - '0';
        else if (upper && d >= 'A' && d <= 'Z') dv = d - 'A' + 10;
        else if (lower && d >= 'a' && d <= 'z') dv = d - 'a' + 10;
        else return -1;
        val = val * 36 + dv;
    }
    long p = ipow(36, width - 1), t = ipow(10, (long)width);
    *v = upper ? val - 10 * p + t : val + 16 * p + t;
    return 1;
}

int ms_hy36_encode(long v, size_t width, char *out)
{
    long t = ipow(10, (long)width), p = ipow(36, width - 1);
    if (v > -ipow(10, (long)width - 1) && v < t) {
        snprintf(out, width + 1, "%*ld", (int)width, v);
        return 0;
    }
    if (v < 0) return -1;
    long val;
    const char *digits;
    if (v < t + 26 * p) {
        val = v - t + 10 * p;
        digits = "0123456789ABCDEFGHIJKLMNOPQRSTUVWXYZ";
    } else if (v < t + 52 * p) {
        val = v - t - 16 * p;
        digits = "0123456789abcdefghijklmnopqrstuvwxyz";
    } else {
        return -1;
    }
    for (size_t i = width; i-- > 0;) {
        out[i] = digits[val % 36];
        val /= 36;
    }
    out[width] = '\0';
    return 0;
}

int ms_tokens(char *line, char **tok, int max)
{
    int n = 0;
    char *p = line;
    while (n < max) {
        while (*p && isspace((unsigned char)*p)) p++;
        if (!*p) break;
        tok[n++] = p;
        while (*p && !isspace((unsigned char)*p)) p++;
        if (*p) *p++ = '\0';
    }
    return n;
}

/* ---------------------------------------------------------------- elements */

/* Element symbols by atomic number, space-separated (0 is "X"). */
static const char element_symbols[] =
    "X H He Li Be B C N O F Ne Na Mg Al Si P S Cl Ar K Ca Sc Ti V Cr Mn Fe Co Ni Cu Zn Ga "
    "Ge As Se Br Kr Rb Sr Y Zr Nb Mo Tc Ru Rh Pd Ag Cd In Sn Sb Te I Xe Cs Ba La Ce Pr Nd Pm "
    "Sm Eu Gd Tb Dy Ho Er Tm Yb Lu Hf Ta W Re Os Ir Pt Au Hg Tl Pb Bi Po At Rn Fr Ra Ac Th "
    "Pa U Np Pu Am Cm Bk Cf Es Fm Md No Lr Rf Db Sg Bh Hs Mt Ds Rg Cn Nh Fl Mc Lv Ts Og";

int ms_plugin_symbol_of(long z, char out[4])
{
    const char *p = element_symbols;
    for (long k = 0; k < z && *p; k++) p += strcspn(p, " ") + (p[strcspn(p, " ")] == ' ');
    if (z < 1 || !*p) return 0;
    size_t n = strcspn(p, " ");
    memcpy(out, p, n);
    out[n] = '\0';
    return 1;
}

int ms_plugin_element_number(const char *sym)
{
    size_t n = strlen(sym);
    if (n < 1 || n > 2) return 0;
    const char *p = element_symbols;
    for (int z = 0; *p; z++) {
        size_t len = strcspn(p, " ");
        if (z > 0 && len == n && strncmp(p, sym, n) == 0) return z;
        p += len + (p[len] == ' ');
    }
    return 0;
}

int ms_plugin_element_like(const char *s)
{
    if (!(s[0] >= 'A' && s[0] <= 'Z')) return 0;
    if (s[1] == '\0') return 1;
    return s[1] >= 'a' && s[1] <= 'z' && (s[2] == '\0' || (s[2] >= 'a' && s[2] <= 'z' && !s[3]));
}

/* ---------------------------------------------------------------- volume data */

/* Parse the numbers of one line into dst[*got..n); returns -1 with err set on a bad token. */
static int floats_of_line(const ms_lines *in, const char *p, float *dst, size_t n, size_t *got,
                          ms_perr *err)
{
    while (*got < n) {
        while (*p == ' ' || *p == '\t' || *p == '\r') p++;
        if (!*p) return 0;
        const char *e = p;
        while (*e && *e != ' ' && *e != '\t' && *e != '\r') e++;
        if (ms_parse_float(p, (size_t)(e - p), &dst[*got]) < 0)
            return ms_perr_set(err, "line %ld: bad value '%.*s'", in->line_no,
                               (int)(e - p > 32 ? 32 : e - p), p);
        (*got)++;
        p = e;
    }
    return 0;
}

int ms_read_floats(ms_lines *in, const char *first, float *dst, size_t n, ms_perr *err)
{
    size_t got = 0;
    if (first && floats_of_line(in, first, dst, n, &got, err) < 0) return MS_PLUGIN_ERROR;
    while (got < n) {
        const char *l = ms_lines_next(in);
        if (!l) {
            if (in->error) return ms_perr_set(err, "read error after line %ld", in->line_no);
            return ms_perr_set(err, "line %ld: the file ends after %zu of %zu values",
                               in->line_no, got, n);
        }
        if (floats_of_line(in, l, dst, n, &got, err) < 0) return MS_PLUGIN_ERROR;
    }
    return MS_PLUGIN_OK;
}

void ms_grid_zfast_to_xfast(const float *src, float *dst, const long n[3])
{
    size_t n0 = (size_t)n[0], n1 = (size_t)n[1], n2 = (size_t)n[2];
    for (size_t i = 0; i < n0; i++)
        for (size_t j = 0; j < n1; j++) {
            const float *s = src + (i * n1 + j) * n2;
            float *d = dst + j * n0 + i;
            for (size_t k = 0; k < n2; k++) d[k * n0 * n1] = s[k];
        }
}

void ms_grid_xfast_to_zfast(const float *src, float *dst, const long n[3])
{
    size_t n0 = (size_t)n[0], n1 = (size_t)n[1], n2 = (size_t)n[2];
    for (size_t i = 0; i < n0; i++)
        for (size_t j = 0; j < n1; j++) {
            float *d = dst + (i * n1 + j) * n2;
            const float *s = src + j * n0 + i;
            for (size_t k = 0; k < n2; k++) d[k] = s[k * n0 * n1];
        }
}

/* ---------------------------------------------------------------- output */

FILE *ms_open_sized(const char *path, long long *size, ms_perr *err)
{
    struct stat sb;
    FILE *fp = fopen(path, "rb");
    if (!fp || fstat(fileno(fp), &sb) != 0) {
        ms_perr_set(err, "%s", strerror(errno));
        if (fp) fclose(fp);
        return NULL;
    }
    *size = (long long)sb.st_size;
    return fp;
}

/* The host hands a writer "/dev/fd/N" for the output it opened (ms_plugin.h): the
 * descriptor is duplicated, so the writer writes exactly what the host opened, with its
 * offset and flags. Any other name is opened (created or truncated) as it is. */
static FILE *open_output(const char *path)
{
    const char *num = path + 8;
    if (strncmp(path, "/dev/fd/", 8) == 0 && *num >= '0' && *num <= '9') {
        char *end;
        long n = strtol(num, &end, 10);
        int fd = *end == '\0' && n <= INT_MAX ? fcntl((int)n, F_DUPFD_CLOEXEC, 0) : -1;
        FILE *fp = fd >= 0 ? fdopen(fd, "wb") : NULL;
        if (fp) return fp;
        if (fd >= 0) close(fd);
    }
    return fopen(path, "wb");
}

int ms_out_open(ms_out *o, const char *path, ms_perr *err)
{
    o->failed = 0;
    o->fp = open_output(path);
    if (!o->fp) return ms_perr_set(err, "%s", strerror(errno));
    return MS_PLUGIN_OK;
}

void *ms_out_create(size_t size, const char *path, ms_perr *err)
{
    ms_out *o = calloc(1, size < sizeof *o ? sizeof *o : size);
    if (!o) {
        ms_perr_set(err, "out of memory");
        return NULL;
    }
    if (ms_out_open(o, path, err) != MS_PLUGIN_OK) {
        free(o);
        return NULL;
    }
    return o;
}

int ms_out_destroy(void *writer, ms_perr *err)
{
    int rc = ms_out_close((ms_out *)writer, err);
    free(writer);
    return rc;
}

void ms_out_printf(ms_out *o, const char *fmt, ...)
{
    if (o->failed) return;
    va_list ap;
    va_start(ap, fmt);
    if (vfprintf(o->fp, fmt, ap) < 0) o->failed = errno ? errno : EIO;
    va_end(ap);
}

void ms_out_write(ms_out *o, const void *data, size_t n)
{
    if (o->failed || n == 0) return;
    if (fwrite(data, 1, n, o->fp) != n) o->failed = errno ? errno : EIO;
}

int ms_out_close(ms_out *o, ms_perr *err)
{
    if (!o->fp) return MS_PLUGIN_OK;
    if (fflush(o->fp) != 0 && !o->failed) o->failed = errno ? errno : EIO;
    if (fclose(o->fp) != 0 && !o->failed) o->failed = errno ? errno : EIO;
    o->fp = NULL;
    if (o->failed) return ms_perr_set(err, "write failed: %s", strerror(o->failed));
    return MS_PLUGIN_OK;
}
