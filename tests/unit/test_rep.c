/* test_rep.c: unit tests of the rep module's parts that are clearest in C: VMD's style string
 * rules (the defaults of doc/vmd-behaviour.md's table, omitted parameters, '-', too many
 * numbers, Off), colouring strings, drawframes specs, smoothing (window averages worked out by
 * hand, periodic unwrapping), the spline bases, and the colour data mapping (VMD's formula
 * index = int((v - min) * 1023 / (max - min))). */
#include "config.h"
#include "ms_test.h"
#include "rep/rep.h"
#include "scene/color.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>

/* Declared in rep_int.h, which only src/rep includes; the tests reach the spline directly. */
void ms_rep_spline_basis(float basis[4][4], int bspline);
void ms_rep_spline_eval(const float basis[4][4], const float *p0, const float *p1,
                        const float *p2, const float *p3, float t, float out[3]);
int ms_rep_ribbon_divs(float res);

static int near(float a, float b, float tol) { return fabsf(a - b) <= tol; }

static const float *params(const ms_rep_style *s, const char *method)
{
    return s->param[ms_rep_method_find(method)];
}

static void test_style(void)
{
    t_suite = "rep style";
    ms_rep_style s;
    ms_rep_style_init(&s);
    ms_error err = {{0}};
    t_ok(!strcmp(ms_rep_method_at((size_t)s.method)->name, "Lines") && !strcmp(s.text, "Lines 1.000000"),
         "a new style is Lines (VMD's text: \"Lines 1.000000\")");
    /* doc/vmd-behaviour.md section 5 */
    const float *p = params(&s, "CPK");
    t_ok(p[0] == 1.0f && p[1] == 0.3f && p[2] == 12 && p[3] == 12 && p[4] == 0, "CPK defaults");
    p = params(&s, "NewCartoon");
    t_ok(p[0] == 0.3f && p[1] == 12 && p[2] == 4.5f && p[3] == 0, "NewCartoon defaults");
    p = params(&s, "HBonds");
    t_ok(p[0] == 3.0f && p[1] == 20 && p[2] == 1, "HBonds defaults");
    p = params(&s, "DynamicBonds");
    t_ok(p[0] == 3.0f && p[1] == 0.3f && p[2] == 12, "DynamicBonds defaults");
    p = params(&s, "NewRibbons");
    t_ok(p[0] == 0.3f && p[1] == 12 && p[2] == 3 && p[3] == 0, "NewRibbons defaults");
    p = params(&s, "Licorice");
    t_ok(p[0] == 0.3f && p[1] == 12 && p[2] == 12 && p[3] == 0, "Licorice defaults");

    t_ok(ms_rep_style_parse(&s, "licorice 0.1 20", &err) == 0 &&
         !strcmp(ms_rep_method_at((size_t)s.method)->name, "Licorice") &&
         ms_rep_style_params(&s)[0] == 0.1f && ms_rep_style_params(&s)[1] == 20 &&
         ms_rep_style_params(&s)[2] == 12, "names match case-insensitively; given values replace");
    t_ok(ms_rep_style_parse(&s, "VDW", &err) == 0 && ms_rep_style_parse(&s, "Licorice", &err) == 0 &&
         ms_rep_style_params(&s)[0] == 0.1f && ms_rep_style_params(&s)[1] == 20,
         "a method keeps the values this style last used with it");
    t_ok(ms_rep_style_parse(&s, "Licorice - - 7", &err) == 0 && ms_rep_style_params(&s)[0] == 0.1f &&
         ms_rep_style_params(&s)[2] == 7, "'-' keeps a value");
    ms_rep_style before = s;
    t_ok(ms_rep_style_parse(&s, "Licorice 1 2 3 4 5", &err) == -1 &&
         strstr(err.msg, "at most 4") && !memcmp(&s, &before, sizeof s),
         "too many numbers is an error and changes nothing (%s)", err.msg);
    t_ok(ms_rep_style_parse(&s, "Licorice 0.2x", &err) == -1 && strstr(err.msg, "0.2x") &&
         !memcmp(&s, &before, sizeof s), "a bad number is an error (%s)", err.msg);
    t_ok(ms_rep_style_parse(&s, "VDW 1e40", &err) == -1, "a number too large for a float is refused");
    t_ok(ms_rep_style_parse(&s, "Sticks", &err) == -1 && strstr(err.msg, "Sticks"),
         "unknown method named (%s)", err.msg);
    t_ok(ms_rep_style_parse(&s, "MSMS 1.5", &err) == -1 && strstr(err.msg, "MSMS") &&
             strstr(err.msg, "not available"),
         "a VMD method molscope does not draw is known and named (%s)", err.msg);
    t_ok(ms_rep_style_parse(&s, "   ", &err) == 0 && !memcmp(&s, &before, sizeof s),
         "an empty style changes nothing");
    t_ok(ms_rep_style_parse(&s, "Off", &err) == 0 && !strcmp(s.text, "Lines 1.000000") &&
         !strcmp(ms_rep_method_at((size_t)s.method)->name, "Lines"), "Off is Lines");
    /* VMD's own strings (its state files): %f, the spline style %d, no zero bond cutoff */
    t_ok(ms_rep_style_parse(&s, "newcartoon 0.3 10 4.1 0", &err) == 0 &&
         !strcmp(s.text, "NewCartoon 0.300000 10.000000 4.100000 0"), "NewCartoon text (%s)", s.text);
    t_ok(ms_rep_style_parse(&s, "CPK", &err) == 0 &&
         !strcmp(s.text, "CPK 1.000000 0.300000 12.000000 12.000000"), "CPK text (%s)", s.text);
    t_ok(ms_rep_style_parse(&s, "Isosurface 0.5 0 0 0 1 1", &err) == 0 &&
         !strcmp(s.text, "Isosurface 0.500000 0 0 0 1 1"), "Isosurface text (%s)", s.text);
    t_ok(ms_rep_style_parse(&s, "Lines 1 2.5", &err) == 0 && !strcmp(s.text, "Lines 1.000000 2.500000"),
         "a bond cutoff that is set is written (%s)", s.text);
    char longtext[600];
    memset(longtext, 'x', sizeof longtext - 1);
    longtext[sizeof longtext - 1] = '\0';
    t_ok(ms_rep_style_parse(&s, longtext, &err) == -1 && strstr(err.msg, "too long"),
         "an over-long string is refused");
}

static void test_coloring(void)
{
    t_suite = "rep coloring";
    ms_rep_coloring c;
    ms_error err = {{0}};
    ms_rep_coloring_init(&c);
    t_ok(c.method == MS_COL_NAME && !strcmp(c.text, "Name"), "Name by default");
    t_ok(ms_rep_coloring_parse(&c, "colorid 7", &err) == 0 && c.method == MS_COL_COLORID &&
         c.index == 7, "ColorID 7");
    t_ok(ms_rep_coloring_parse(&c, "ColorID 99", &err) == 0 && c.index == 32, "ColorID clamps to 32");
    t_ok(ms_rep_coloring_parse(&c, "ColorID -4", &err) == 0 && c.index == 0, "and to 0");
    t_ok(ms_rep_coloring_parse(&c, "PosX", &err) == 0 && c.method == MS_COL_POSX, "PosX is not Pos");
    t_ok(ms_rep_coloring_parse(&c, "default", &err) == 0 && c.method == MS_COL_NAME, "default is Name");
    ms_rep_coloring before = c;
    t_ok(ms_rep_coloring_parse(&c, "ColorID", &err) == -1 && !memcmp(&c, &before, sizeof c),
         "ColorID needs a number (%s)", err.msg);
    t_ok(ms_rep_coloring_parse(&c, "Rainbow", &err) == -1 && strstr(err.msg, "Rainbow"),
         "unknown method named (%s)", err.msg);
    t_ok(ms_rep_coloring_parse(&c, "Beta a b c", &err) == -1, "too many words");
    t_ok(ms_rep_coloring_scaled(MS_COL_BETA) && !ms_rep_coloring_scaled(MS_COL_CHAIN) &&
         ms_rep_coloring_timed(MS_COL_USER) && !ms_rep_coloring_timed(MS_COL_BETA),
         "scale and time-dependent methods");
}

static int frames_are(const char *spec, long nframes, long now, const long *want, size_t n)
{
    long *f;
    size_t k;
    ms_error err = {{0}};
    if (ms_rep_frames_list(spec, nframes, now, &f, &k, &err)) return 0;
    int ok = k == n && (n == 0 || !memcmp(f, want, n * sizeof *f));
    free(f);
    return ok;
}

static void test_frames(void)
{
    t_suite = "rep drawframes";
    ms_error err = {{0}};
    t_ok(frames_are("now", 10, 4, (long[]){4}, 1), "now: the current frame");
    t_ok(frames_are("0:3", 10, 4, (long[]){0, 1, 2, 3}, 4), "a:b inclusive");
    t_ok(frames_are("1:3:9", 10, 4, (long[]){1, 4, 7}, 3), "a:step:b with the step in the middle");
    t_ok(frames_are("7:", 10, 4, (long[]){7, 8, 9}, 3), "empty upper bound: the last frame");
    t_ok(frames_are("2 0:1 now", 10, 4, (long[]){2, 0, 1, 4}, 4), "items in order");
    t_ok(frames_are("3,5,12", 10, 4, (long[]){3, 5}, 2), "comma lists; frames past the end left out");
    t_ok(frames_are("-5:2:3", 10, 4, (long[]){1, 3}, 2), "a range from before frame 0");
    t_ok(frames_are("8:2000000000000", 10, 4, (long[]){8, 9}, 2), "a huge bound stops at the last frame");
    t_ok(ms_rep_frames_check("0:0:5", &err) == -1 && strstr(err.msg, "0:0:5"), "step 0 refused (%s)", err.msg);
    t_ok(ms_rep_frames_check("1:x", &err) == -1, "bad number refused");
    t_ok(ms_rep_frames_check(":3", &err) == -1, "missing first frame refused");
    t_ok(ms_rep_frames_check("", &err) == -1, "empty spec refused");
}

/* A molecule of two atoms and frames with given x coordinates (y = z = 0) and cells. */
static ms_molecule *xmol(const float *x0, const float *x1, size_t nframes, const float *cell)
{
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    ms_mol_add_blank_atom(m, &err);
    ms_mol_add_blank_atom(m, &err);
    for (size_t f = 0; f < nframes; f++) {
        ms_frame *fr = ms_mol_add_frame(m, 0, &err);
        memset(fr->pos, 0, 6 * sizeof(float));
        fr->pos[0] = x0[f];
        fr->pos[3] = x1[f];
        if (cell) memcpy(fr->cell, cell, 6 * sizeof(float));
    }
    m->frame = 0;
    return m;
}

static void test_smooth(void)
{
    t_suite = "rep smoothrep";
    float a[] = {0, 3, 6, 12}, b[] = {1, 1, 1, 5}, out[6];
    ms_molecule *m = xmol(a, b, 4, NULL);
    ms_rep_smooth(m, 1, 1, out);
    t_ok(near(out[0], 3, 1e-6f) && near(out[3], 1, 1e-6f), "frame 1, window 3: (0+3+6)/3 = 3");
    ms_rep_smooth(m, 0, 1, out);
    t_ok(near(out[0], 1, 1e-6f), "clamped at the start: (0+0+3)/3 = 1 (%g)", out[0]);
    ms_rep_smooth(m, 3, 2, out);
    t_ok(near(out[0], (3 + 6 + 12 * 3) / 5.0f, 1e-5f), "clamped at the end: (3+6+12+12+12)/5 (%g)", out[0]);
    ms_rep_smooth(m, 2, 0, out);
    t_ok(out[0] == 6 && out[3] == 1, "window 0: the frame itself");
    ms_mol_free(m);

    /* an orthogonal box of 10: x = 9.5 next to 0.5 is a jump back to -0.5 */
    float c[] = {0.5f, 9.5f, 0.5f}, d[] = {5, 5, 5}, box[6] = {10, 10, 10, 90, 90, 90};
    m = xmol(c, d, 3, box);
    ms_rep_smooth(m, 0, 1, out);
    t_ok(near(out[0], (0.5f + 0.5f - 0.5f) / 3, 1e-5f), "periodic jumps undone against the frame (%g)", out[0]);
    ms_mol_free(m);
    float tri[6] = {10, 10, 10, 90, 90, 100};
    m = xmol(c, d, 3, tri);
    ms_rep_smooth(m, 0, 1, out);
    t_ok(near(out[0], (0.5f + 0.5f + 9.5f) / 3, 1e-5f), "not for a triclinic cell, as VMD (%g)", out[0]);
    ms_mol_free(m);
}

static void test_spline(void)
{
    t_suite = "rep spline";
    float cr[4][4], bs[4][4], out[3];
    float p0[3] = {0, 0, 0}, p1[3] = {1, 2, 0}, p2[3] = {3, 2, 1}, p3[3] = {4, 0, 1};
    ms_rep_spline_basis(cr, 0);
    ms_rep_spline_basis(bs, 1);
    ms_rep_spline_eval(cr, p0, p1, p2, p3, 0, out);
    int ok = near(out[0], 1, 1e-6f) && near(out[1], 2, 1e-6f) && near(out[2], 0, 1e-6f);
    ms_rep_spline_eval(cr, p0, p1, p2, p3, 1, out);
    ok &= near(out[0], 3, 1e-5f) && near(out[1], 2, 1e-5f) && near(out[2], 1, 1e-5f);
    t_ok(ok, "the Catmull-Rom spline passes through its control points");
    /* cardinal tangent at p1: s (p2 - p0) with s = 1/1.25: midpoint by Hermite form */
    ms_rep_spline_eval(cr, p0, p1, p2, p3, 0.5f, out);
    float s = 0.8f, m1 = s * (p2[0] - p0[0]), m2 = s * (p3[0] - p1[0]);
    float hx = 0.5f * p1[0] + 0.5f * p2[0] + 0.125f * m1 - 0.125f * m2;
    t_ok(near(out[0], hx, 1e-5f), "VMD's slope 1.25: tangents (p2 - p0) / 1.25 (%g, %g)", out[0], hx);
    ms_rep_spline_eval(bs, p0, p1, p2, p3, 0, out);
    t_ok(near(out[0], (0 + 4 * 1 + 3) / 6.0f, 1e-6f) && near(out[1], (0 + 8 + 2) / 6.0f, 1e-6f),
         "the B-spline starts at (p0 + 4 p1 + p2) / 6");
    t_ok(ms_rep_ribbon_divs(12) == 4 && ms_rep_ribbon_divs(24) == 8 && ms_rep_ribbon_divs(6) == 2 &&
         ms_rep_ribbon_divs(0) == 2, "sections per residue from the resolution");
}

static void test_color_data(void)
{
    t_suite = "rep colour data";
    ms_error err = {{0}};
    ms_colors *colors = ms_colors_new(&err);
    /* five atoms, one frame */
    ms_molecule *m = ms_mol_new(&err);
    for (int i = 0; i < 5; i++) ms_mol_add_blank_atom(m, &err);
    ms_frame *fr = ms_mol_add_frame(m, 0, &err);
    memset(fr->pos, 0, 15 * sizeof(float));
    m->frame = 0;
    int32_t resid[5] = {1, 33, -1, 64, 40};
    float beta[5] = {10, 20, 30, 40, 50};
    for (int i = 0; i < 5; i++) {
        m->atoms.resid[i] = resid[i];
        m->atoms.beta[i] = beta[i];
    }
    uint16_t col[5];
    float lo = 0, hi = 0;
    ms_rep_coloring c;
    ms_rep_coloring_init(&c);
    ms_rep_coloring_parse(&c, "Index", &err);
    ms_rep_color_ids(colors, m, &c, 0, 1, &lo, &hi, col, &err);
    t_ok(lo == 0 && hi == 4 && col[0] == 33 && col[2] == 33 + 511 && col[4] == 33 + 1023,
         "Index: 33 + int(i 1023 / 4) (%d %d %d)", col[0], col[2], col[4]);
    ms_rep_coloring_parse(&c, "Beta", &err);
    ms_rep_color_ids(colors, m, &c, 0, 1, &lo, &hi, col, &err);
    t_ok(lo == 10 && hi == 50 && col[1] == 33 + 255 && col[3] == 33 + 767,
         "Beta over its range: int(10 x 1023 / 40) = 255 (%d %d)", col[1], col[3]);
    lo = 30;
    hi = 30;
    ms_rep_color_ids(colors, m, &c, 0, 0, &lo, &hi, col, &err);
    t_ok(col[0] == 33 + 512 && col[4] == 33 + 512, "min == max: the middle of the scale");
    lo = 20;
    hi = 30;
    ms_rep_color_ids(colors, m, &c, 0, 0, &lo, &hi, col, &err);
    t_ok(col[0] == 33 && col[4] == 1056 && col[2] == 1056, "a given range clamps");
    ms_rep_coloring_parse(&c, "ResID", &err);
    ms_rep_color_ids(colors, m, &c, 0, 1, &lo, &hi, col, &err);
    t_ok(col[0] == 1 && col[1] == 1 && col[2] == 31 && col[3] == 0 && col[4] == 8, "ResID mod 32");
    ms_rep_coloring_parse(&c, "Timestep", &err);
    ms_rep_color_ids(colors, m, &c, 0, 1, &lo, &hi, col, &err);
    t_ok(col[0] == 33, "Timestep of a single frame: the scale's start");
    ms_rep_coloring_parse(&c, "Beta", &err);
    ms_rep_color_ids(colors, m, &c, -1, 1, &lo, &hi, col, &err);
    int mol = ms_color_item_get(colors, ms_color_category_index(colors, "Molecule"), "0");
    t_ok(col[0] == mol, "no frame: VMD colours by molecule (%d %d)", col[0], mol);
    ms_mol_free(m);
    ms_colors_free(colors);
}

int main(void)
{
    test_style();
    test_coloring();
    test_frames();
    test_smooth();
    test_spline();
    test_color_data();
    return t_done();
}
