/* coloring.c: VMD's colouring methods: parsing "ColorID 3" and friends, and the colour id
 * (0..1056) of every atom. Category methods look the atom's value up in its colour category
 * (Name, Element, Resname ...); scale methods map data onto the 1024-entry colour scale
 * between a min and a max taken over all atoms when the method is (re)applied (`Volume n`:
 * volume n's value at each atom, between the volume's min and max). */
#include "config.h"
#include "rep/rep_int.h"
#include "molecule/elements.h"
#include "base/threads.h"

#include <ctype.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const names[MS_COL_NMETHODS] = {
    "Name", "Type", "Element", "ResName", "ResType", "ResID", "Chain", "SegName",
    "Conformation", "Molecule", "Structure", "ColorID", "Beta", "Occupancy", "Mass", "Charge",
    "Pos", "PosX", "PosY", "PosZ", "User", "User2", "User3", "User4", "Fragment", "Index",
    "Backbone", "Throb", "PhysicalTime", "Timestep", "Velocity", "Volume"};

const char *ms_rep_colmethod_name(ms_colmethod m)
{
    return m >= 0 && m < MS_COL_NMETHODS ? names[m] : "?";
}

void ms_rep_coloring_init(ms_rep_coloring *c)
{
    memset(c, 0, sizeof *c);
    c->method = MS_COL_NAME;
    snprintf(c->text, sizeof c->text, "Name");
}

int ms_rep_coloring_scaled(ms_colmethod m)
{
    return (m >= MS_COL_BETA && m <= MS_COL_INDEX) || m == MS_COL_VELOCITY ||
           m == MS_COL_VOLUME;
}

int ms_rep_coloring_timed(ms_colmethod m)
{
    return (m >= MS_COL_USER && m <= MS_COL_USER4) || m == MS_COL_PHYSICALTIME ||
           m == MS_COL_TIMESTEP || m == MS_COL_VELOCITY;
}

/* ---------------------------------------------------------------- parsing */

static int first_word(const char *text, char *w, size_t size, const char **rest)
{
    while (*text && isspace((unsigned char)*text)) text++;
    size_t n = 0;
    while (text[n] && !isspace((unsigned char)text[n])) n++;
    if (n >= size) n = size - 1;
    memcpy(w, text, n);
    w[n] = '\0';
    *rest = text + n;
    return (int)n;
}

static int count_words(const char *s)
{
    int n = 0;
    for (;;) {
        while (*s && isspace((unsigned char)*s)) s++;
        if (!*s) return n;
        n++;
        while (*s && !isspace((unsigned char)*s)) s++;
    }
}

int ms_rep_coloring_parse(ms_rep_coloring *c, const char *text, ms_error *err)
{
    if (strlen(text) >= MS_REP_TEXTMAX) {
        ms_error_set(err, "colouring string is too long (over %d characters)", MS_REP_TEXTMAX - 1);
        return -1;
    }
    char w[64], arg[64];
    const char *rest;
    if (!first_word(text, w, sizeof w, &rest)) return 0;   /* nothing: keep, as VMD */
    int method = -1;
    if (!strcasecmp(w, "default")) method = MS_COL_NAME;
    for (int k = 0; method < 0 && k < MS_COL_NMETHODS; k++)
        if (ms_word_eq(w, names[k])) method = k;
    if (method < 0) {
        ms_error_set(err, "unknown colouring method '%s'", w);
        return -1;
    }
    int extra = count_words(rest), index = 0;
    int takes = method == MS_COL_COLORID || method == MS_COL_VOLUME;
    /* VMD accepts (and ignores) one word more than a method uses */
    if (extra > takes + 1) {
        ms_error_set(err, "%s: too many words in '%s'", names[method], text);
        return -1;
    }
    if (takes) {
        char *end;
        first_word(rest, arg, sizeof arg, &rest);
        long v = strtol(arg, &end, 10);
        if (!*arg || *end) {
            ms_error_set(err, "%s needs a %s number, got '%s'", names[method],
                         method == MS_COL_COLORID ? "colour" : "volume", arg);
            return -1;
        }
        index = method == MS_COL_COLORID ? (int)MS_MIN(MS_MAX(v, 0), MS_COLOR_NUM - 1)
                                         : (int)MS_MIN(MS_MAX(v, 0), 1 << 20);
    }
    c->method = (ms_colmethod)method;
    c->index = index;
    snprintf(c->text, sizeof c->text, "%s", text);
    return 0;
}

/* ---------------------------------------------------------------- category methods */

typedef struct ctx {
    ms_colors *colors;
    ms_molecule *m;
    uint16_t *out;
} ctx;

static int cat_of(ms_colors *c, const char *name) { return ms_color_category_index(c, name); }

/* Every atom by an interned string field: one lookup per distinct string. */
static int by_strings(ctx *x, const char *cat, const ms_str *field, int restype)
{
    uint32_t nstr = ms_strtab_count(x->m->strings);
    int16_t *table = malloc((size_t)nstr * sizeof *table);
    if (!table) return -1;
    for (uint32_t s = 0; s < nstr; s++) table[s] = -1;
    int k = cat_of(x->colors, cat), rc = 0;
    for (size_t i = 0; i < x->m->atoms.n && rc == 0; i++) {
        ms_str s = field[i];
        if (s >= nstr) {
            x->out[i] = 0;
            continue;
        }
        if (table[s] < 0) {
            const char *v = ms_mol_str(x->m, s);
            int col;
            if (restype) {
                const char *t = ms_color_restype(x->colors, v);
                col = ms_color_item_get(x->colors, k, t ? t : "Unassigned");
            } else if ((col = ms_color_for_value(x->colors, k, v)) < 0) {
                rc = -1;
            }
            table[s] = (int16_t)(col < 0 ? 0 : col);
        }
        x->out[i] = (uint16_t)table[s];
    }
    free(table);
    return rc;
}

/* Every atom by a byte (atomic number, altloc). */
static int by_bytes(ctx *x, const char *cat, const void *field, int element)
{
    int16_t table[256];
    for (int v = 0; v < 256; v++) table[v] = -1;
    int k = cat_of(x->colors, cat);
    const uint8_t *f = field;
    for (size_t i = 0; i < x->m->atoms.n; i++) {
        uint8_t v = f[i];
        if (table[v] < 0) {
            char s[2] = {(char)v, '\0'};
            int col = ms_color_for_value(x->colors, k, element ? ms_element_symbol(v) : s);
            if (col < 0) return -1;
            table[v] = (int16_t)col;
        }
        x->out[i] = (uint16_t)table[v];
    }
    return 0;
}

static void fill(ctx *x, int col)
{
    for (size_t i = 0; i < x->m->atoms.n; i++) x->out[i] = (uint16_t)col;
}

static int item(ms_colors *c, const char *cat, const char *name)
{
    int col = ms_color_item_get(c, cat_of(c, cat), name);
    return col < 0 ? 0 : col;
}

static int by_molecule(ctx *x)
{
    char id[32];
    snprintf(id, sizeof id, "%d", x->m->id);
    int col = ms_color_item_add(x->colors, cat_of(x->colors, "Molecule"), id, -1);
    if (col < 0) return -1;
    fill(x, col);
    return 0;
}

static void by_structure(ctx *x)
{
    static const char *const items[][2] = {
        {"H", "Alpha Helix"}, {"G", "3_10_Helix"}, {"I", "Pi_Helix"}, {"E", "Extended_Beta"},
        {"B", "Bridge_Beta"}, {"T", "Turn"}};
    int table[256];
    int coil = item(x->colors, "Structure", "Coil");
    for (int v = 0; v < 256; v++) table[v] = coil;
    for (size_t k = 0; k < MS_COUNTOF(items); k++)
        table[(unsigned char)items[k][0][0]] = item(x->colors, "Structure", items[k][1]);
    for (size_t i = 0; i < x->m->atoms.n; i++)
        x->out[i] = (uint16_t)table[(unsigned char)x->m->atoms.ss[i]];
}

/* Backbone atoms count as such only when bonded to another backbone atom, as in VMD. */
static void by_backbone(ctx *x)
{
    const ms_molecule *m = x->m;
    int non = item(x->colors, "Highlight", "Nonback");
    int pro = item(x->colors, "Highlight", "Proback");
    int nuc = item(x->colors, "Highlight", "Nucback");
    for (size_t i = 0; i < m->atoms.n; i++) {
        int c = non;
        if ((m->atoms.flags[i] & (MS_AF_PROT_BB | MS_AF_NUC_BB)) && m->has_bonds) {
            for (uint32_t k = m->bonds.start[i]; k < m->bonds.start[i + 1]; k++) {
                uint16_t f = m->atoms.flags[m->bonds.to[k]];
                if (f & MS_AF_PROT_BB) { c = pro; break; }
                if (f & MS_AF_NUC_BB) { c = nuc; break; }
            }
        }
        x->out[i] = (uint16_t)c;
    }
}

/* ---------------------------------------------------------------- scale methods */

/* The data of a scale method for every atom, and its natural range. Returns 0, 1 when the
 * method needs a frame the molecule lacks, -1 when memory runs out. */
static int scale_data(const ms_molecule *m, ms_colmethod meth, long frame, float *d,
                      float *lo, float *hi)
{
    size_t n = m->atoms.n;
    const ms_frame *f = frame >= 0 && (size_t)frame < m->nframes ? &m->frames[frame] : NULL;
    if (!f || !f->pos) return 1;   /* a streamed frame not read (the builders read theirs) */
    const float *src = NULL;
    double c[3] = {0, 0, 0};
    switch (meth) {
    case MS_COL_BETA: src = m->atoms.beta; break;
    case MS_COL_OCCUPANCY: src = m->atoms.occupancy; break;
    case MS_COL_MASS: src = m->atoms.mass; break;
    case MS_COL_CHARGE: src = m->atoms.charge; break;
    case MS_COL_USER: case MS_COL_USER2: case MS_COL_USER3: case MS_COL_USER4:
        src = m->user[meth - MS_COL_USER];
        if (!src) memset(d, 0, n * sizeof *d);
        break;
    case MS_COL_POS:
        for (size_t i = 0; i < n; i++)
            for (int k = 0; k < 3; k++) c[k] += f->pos[3 * i + k];
        for (int k = 0; k < 3; k++) c[k] /= (double)(n ? n : 1);
        for (size_t i = 0; i < n; i++) {
            double dx = f->pos[3 * i] - c[0], dy = f->pos[3 * i + 1] - c[1],
                   dz = f->pos[3 * i + 2] - c[2];
            d[i] = (float)sqrt(dx * dx + dy * dy + dz * dz);
        }
        break;
    case MS_COL_POSX: case MS_COL_POSY: case MS_COL_POSZ:
        for (size_t i = 0; i < n; i++) d[i] = f->pos[3 * i + (meth - MS_COL_POSX)];
        break;
    case MS_COL_VELOCITY:
        for (size_t i = 0; i < n; i++) {
            const float *v = f->vel ? f->vel + 3 * i : NULL;
            d[i] = v ? sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]) : 0.0f;
        }
        break;
    case MS_COL_FRAGMENT:
        for (size_t i = 0; i < n; i++) d[i] = (float)m->atoms.fragment[i];
        *lo = 0;
        *hi = (float)m->nfragments - 1;
        return 0;
    default:   /* Index */
        for (size_t i = 0; i < n; i++) d[i] = (float)i;
        *lo = 0;
        *hi = (float)n - 1;
        return 0;
    }
    if (src) memcpy(d, src, n * sizeof *d);
    *lo = *hi = n ? d[0] : 0;
    for (size_t i = 1; i < n; i++) {
        if (d[i] < *lo) *lo = d[i];
        if (d[i] > *hi) *hi = d[i];
    }
    return 0;
}

/* VMD's mapping: index = int((v - min) * 1023 / (max - min)) clamped, 512 when min == max. */
static void map_scale(const float *d, size_t n, float lo, float hi, uint16_t *out)
{
    if (lo == hi) {
        for (size_t i = 0; i < n; i++) out[i] = MS_COLOR_SCALE_BEGIN + MS_COLOR_SCALE_SIZE / 2;
        return;
    }
    float f = (float)(MS_COLOR_SCALE_SIZE - 1) / (hi - lo);
    for (size_t i = 0; i < n; i++) {
        float x = f * (d[i] - lo);
        int k = !(x > 0) ? 0 : x >= MS_COLOR_SCALE_SIZE - 1 ? MS_COLOR_SCALE_SIZE - 1 : (int)x;
        out[i] = (uint16_t)(MS_COLOR_SCALE_BEGIN + k);
    }
}

static int by_scale(ctx *x, ms_colmethod meth, long frame, int recompute, float *min, float *max)
{
    float *d = ms_alloc_array(x->m->atoms.n ? x->m->atoms.n : 1, sizeof *d);
    if (!d) return -1;
    float lo = 0, hi = 0;
    int rc = scale_data(x->m, meth, frame, d, &lo, &hi);
    if (rc == 1) {   /* no frame: VMD colours by molecule */
        free(d);
        return by_molecule(x);
    }
    if (recompute) {
        *min = lo;
        *max = hi;
    }
    map_scale(d, x->m->atoms.n, *min, *max, x->out);
    free(d);
    return 0;
}

typedef struct vol_job {
    ms_volume_sampler s;
    const float *pos;
    float *d;
} vol_job;

static void sample_atoms(void *ctx, size_t begin, size_t end, int thread)
{
    vol_job *j = ctx;
    (void)thread;
    for (size_t i = begin; i < end; i++) j->d[i] = ms_volume_sample(&j->s, j->pos + 3 * i);
}

/* Volume n: volume n's value at every atom (at the nearest point of its grid for atoms
 * outside it, as VMD's clamped 3-D texture), on the scale between the volume's min and max.
 * White without the volume or a frame. */
static int by_volume(ctx *x, int k, long frame, int recompute, float *min, float *max)
{
    const ms_molecule *m = x->m;
    const ms_volume *v = k >= 0 && (size_t)k < m->nvolumes ? &m->volumes[k] : NULL;
    if (recompute) {
        *min = v ? v->min : 0.0f;
        *max = v ? v->max : 0.0f;
    }
    if (!v || frame < 0 || (size_t)frame >= m->nframes || !m->frames[frame].pos) {
        fill(x, 8);
        return 0;
    }
    vol_job j = {.pos = m->frames[frame].pos};
    if (!(j.d = ms_alloc_array(m->atoms.n ? m->atoms.n : 1, sizeof *j.d))) return -1;
    ms_volume_sampler_init(&j.s, v);
    ms_parallel_for(m->atoms.n, 4096, sample_atoms, &j);
    map_scale(j.d, m->atoms.n, *min, *max, x->out);
    free(j.d);
    return 0;
}

/* Timestep, PhysicalTime, Throb: one scale colour for every atom. */
static void by_time(ctx *x, ms_colmethod meth, long frame, int recompute, float *min, float *max)
{
    const ms_molecule *m = x->m;
    int k = MS_COLOR_SCALE_SIZE / 2;
    if (recompute) *min = *max = 0;
    if (meth == MS_COL_TIMESTEP) {
        k = 0;
        if (m->nframes > 1 && frame > 0)
            k = (int)(0.5f + (float)frame * (float)(MS_COLOR_SCALE_SIZE - 1) /
                                 (float)(m->nframes - 1));
    } else if (meth == MS_COL_PHYSICALTIME) {
        if (frame >= 0 && (size_t)frame < m->nframes && *max > *min) {
            float f = (float)(MS_COLOR_SCALE_SIZE - 1) / (*max - *min);
            k = (int)(f * ((float)m->frames[frame].time - *min));
        }
    } else {   /* Throb: a pulse with a two-second period */
        double t = fmod(ms_now() / 2.0, 1.0) * 254.0;
        k = (int)(0.5 + t * (MS_COLOR_SCALE_SIZE - 1) / 255.0);
    }
    k = MS_MIN(MS_MAX(k, 0), MS_COLOR_SCALE_SIZE - 1);
    fill(x, MS_COLOR_SCALE_BEGIN + k);
}

int ms_rep_color_ids(ms_colors *colors, ms_molecule *m, const ms_rep_coloring *c, long frame,
                     int recompute_range, float *min, float *max, uint16_t *out,
                     ms_error *err)
{
    ctx x = {colors, m, out};
    const ms_atoms *a = &m->atoms;
    int rc = 0;
    switch (c->method) {
    case MS_COL_NAME: rc = by_strings(&x, "Name", a->name, 0); break;
    case MS_COL_TYPE: rc = by_strings(&x, "Type", a->type, 0); break;
    case MS_COL_RESNAME: rc = by_strings(&x, "Resname", a->resname, 0); break;
    case MS_COL_RESTYPE: rc = by_strings(&x, "Restype", a->resname, 1); break;
    case MS_COL_CHAIN: rc = by_strings(&x, "Chain", a->chain, 0); break;
    case MS_COL_SEGNAME: rc = by_strings(&x, "Segname", a->segname, 0); break;
    case MS_COL_ELEMENT: rc = by_bytes(&x, "Element", a->atomicnumber, 1); break;
    case MS_COL_CONFORMATION: rc = by_bytes(&x, "Conformation", a->altloc, 0); break;
    case MS_COL_MOLECULE: rc = by_molecule(&x); break;
    case MS_COL_STRUCTURE: by_structure(&x); break;
    case MS_COL_BACKBONE: by_backbone(&x); break;
    case MS_COL_COLORID: fill(&x, c->index); break;
    case MS_COL_VOLUME: rc = by_volume(&x, c->index, frame, recompute_range, min, max); break;
    case MS_COL_RESID:
        for (size_t i = 0; i < a->n; i++) {
            int r = a->resid[i] % MS_COLOR_AUTO_CYCLE;
            out[i] = (uint16_t)(r < 0 ? r + MS_COLOR_AUTO_CYCLE : r);
        }
        break;
    case MS_COL_TIMESTEP: case MS_COL_PHYSICALTIME: case MS_COL_THROB:
        by_time(&x, c->method, frame, recompute_range, min, max);
        break;
    default:
        rc = by_scale(&x, c->method, frame, recompute_range, min, max);
        break;
    }
    if (rc) ms_error_set(err, "out of memory computing colours");
    return rc;
}
