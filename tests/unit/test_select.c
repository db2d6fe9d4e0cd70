/* test_select.c: unit tests of the selection language. Counts on 1tii.pdb were checked
 * independently (awk over the file's columns, MDAnalysis, or a Python sequence scan; see
 * the comments); distance terms are compared with brute-force searches written here;
 * precedence and operators on a small molecule built in the test, where each alternative
 * reading of a selection gives a different count. */
#include "config.h"
#include "ms_test.h"
#include "fileio/load.h"
#include "molecule/analysis.h"
#include "select/selint.h"

#include <math.h>
#include <string.h>

#include "ms_testload.h"

static void expect(ms_molecule *m, const char *text, long want)
{
    long got = count(m, text);
    t_ok(got == want, "'%s' selects %ld (got %ld)", text, want, got);
}

static void expect_error(const char *text, const char *want)
{
    ms_error err = {{0}};
    ms_selexpr *e = ms_sel_compile(text, &err);
    t_ok(!e && strstr(err.msg, want), "'%s' fails with '%s' (got '%s')", text, want,
         e ? "no error" : err.msg);
    ms_sel_free(e);
}

/* ---------------------------------------------------------------- the lexer */

static void test_lexer(void)
{
    t_suite = "select/lexer";
    static const struct {
        const char *text;
        ms_tok_kind kinds[8];
    } cases[] = {
        {"C5' 1A 3'A", {TK_WORD, TK_WORD, TK_WORD, TK_END}},
        {"5. .5 5 1e5", {TK_FLOAT, TK_FLOAT, TK_INT, TK_WORD, TK_END}},
        {"and andrew && ||", {TK_AND, TK_WORD, TK_AND, TK_OR, TK_END}},
        {"<= < == = =~ ** ^", {TK_NLE, TK_NLT, TK_NEQ, TK_NEQ, TK_MATCH, TK_POW, TK_POW, TK_END}},
        {"{a} \"b\" 'c'", {TK_LPAREN, TK_WORD, TK_RPAREN, TK_DQ, TK_SQ, TK_END}},
        {"1 to 5 ... lt", {TK_INT, TK_THROUGH, TK_INT, TK_THROUGH, TK_SLT, TK_END}},
    };
    for (size_t c = 0; c < MS_COUNTOF(cases); c++) {
        ms_tok *t;
        ms_error err = {{0}};
        long n = ms_sel_lex(cases[c].text, &t, &err);
        int ok = n > 0;
        for (long i = 0; ok && i < n; i++) ok = t[i].kind == cases[c].kinds[i];
        ok = ok && cases[c].kinds[n - 1] == TK_END;
        t_ok(ok, "tokens of '%s'", cases[c].text);
        if (n > 0) ms_sel_free_tokens(t, (size_t)n);
    }
    ms_tok *t;
    ms_error err = {{0}};
    long n = ms_sel_lex("name 'C5\\''", &t, &err);
    t_ok(n == 3 && !strcmp(t[1].str, "C5'"), "escaped quote in a single-quoted string");
    if (n > 0) ms_sel_free_tokens(t, (size_t)n);
}

/* ---------------------------------------------------------------- a molecule on a line */

/* Eight atoms at x = 0..7: CA CB N O of ALA 1, then CA CB N O of GLY 2. */
static ms_molecule *line_molecule(void)
{
    ms_error err = {{0}};
    ms_molecule *m = ms_mol_new(&err);
    const char *names[4] = {"CA", "CB", "N", "O"};
    for (int i = 0; i < 8; i++) {
        ms_mol_add_blank_atom(m, &err);
        m->atoms.name[i] = ms_strtab_intern_cstr(m->strings, names[i % 4]);
        m->atoms.resname[i] = ms_strtab_intern_cstr(m->strings, i < 4 ? "ALA" : "GLY");
        m->atoms.resid[i] = i < 4 ? 1 : 2;
        m->atoms.beta[i] = (float)i * 0.5f;
    }
    ms_frame *f = ms_mol_add_frame(m, 0, &err);
    for (int i = 0; i < 8; i++) {
        f->pos[3 * i] = (float)i;
        f->pos[3 * i + 1] = f->pos[3 * i + 2] = 0;
    }
    m->frame = 0;
    ms_bonds_build(m, NULL, 0, NULL, &err);
    ms_analysis_classify(m, &err);
    return m;
}

static void test_precedence(void)
{
    t_suite = "select/precedence";
    ms_molecule *m = line_molecule();
    ms_error err = {{0}};
    /* each comment gives the count of the reading that must not win */
    expect(m, "not name CA and resname ALA", 3);           /* not (CA and ALA): 7 */
    expect(m, "name CA or name CB and resname GLY", 3);    /* (CA or CB) and GLY: 2 */
    expect(m, "within 1.5 of name CA and resname GLY", 3); /* (within ..CA) and GLY: 2 */
    expect(m, "same resid as name CA and resname GLY", 4); /* (same ..CA) and GLY: 4, so: */
    expect(m, "same resid as name CA and resname ALA", 4); /* (same .. CA) and ALA: 4 */
    expect(m, "resname GLY and same resid as name CA", 4);
    t_ok(ms_sel_macro_define("t_gly", "resname GLY", &err) == 0, "define macro t_gly");
    expect(m, "t_gly name CA or name CB", 2);              /* (gly and CA) or CB: 3 */
    expect(m, "x == 2^3^2 / 16", 1);                       /* 2^(3^2)/16 = 32: 0 */
    expect(m, "-x^2 == 4", 1);                             /* -(x^2) = 4: 0 */
    expect(m, "x + 1 * 2 == 4", 1);                        /* (x+1)*2 = 4: x=1 */
    expect(m, "(x + 1) * 2 == 4", 1);
    expect(m, "x % 3 == 1", 3);
    expect(m, "x - -1 > 7", 1);
    expect(m, "sqr(x) > 10 and sqrt(x) < 2.5", 3);         /* x = 4, 5, 6 */
    expect(m, "abs(x - 3.5) <= 1 and floor(x / 2) == 1", 1);
    expect(m, "((name CA))", 2);
    expect(m, "{name CA} or (x < 1)", 2);
    ms_mol_free(m);
}

static void test_values(void)
{
    t_suite = "select/values";
    ms_molecule *m = line_molecule();
    expect(m, "name CA CB", 4);
    expect(m, "name \"C\"", 0);                 /* regexes are anchored */
    expect(m, "name \"C.\"", 4);
    expect(m, "name 'C.*'", 0);                 /* single quotes are exact */
    expect(m, "name =~ \"C\"", 4);              /* =~ is not anchored */
    expect(m, "name =~ \"^C$\"", 0);
    expect(m, "name CA to CB", 4);              /* string ranges are lexical */
    expect(m, "name lt CB", 2);
    expect(m, "name ge N", 4);
    expect(m, "CB gt name", 2);                 /* constant on the left */
    expect(m, "resid 1 to 1", 4);
    expect(m, "resid 2 to 1", 0);
    expect(m, "resid \"2\"", 4);                /* numbers in quotes are numbers */
    expect(m, "index 1 3 5 to 6", 4);
    expect(m, "serial 1", 1);
    expect(m, "x 2.001", 1);                    /* floats match within 0.1% */
    expect(m, "x 2.01", 0);
    expect(m, "beta 0.5 to 1.5", 3);
    expect(m, "x 1 to 2 6", 3);
    expect(m, "name eq resname", 0);
    expect(m, "x == index", 8);
    expect(m, "resid eq 2", 4);                 /* integers compare as strings with %d */
    /* or-chains of one keyword are merged into one list: the meaning must not change */
    expect(m, "name CA or name CB", 4);
    expect(m, "name CA or x < 1 or name CB or name \"O\"", 6);
    expect(m, "name CA or name CB and resname GLY or name N", 5);
    expect(m, "x 1 or x 2 to 3 or resid 2 or x 7", 7);
    expect(m, "not (name CA or name CB) and resname ALA", 2);
    expect(m, "index 2 to 4 or serial 8", 4);
    expect(m, "index 6 to 100 or index 0 or index '-5' to '-1'", 3); /* VMD lexes -5 as minus 5 */
    expect(m, "serial 0 to 1", 1);
    expect(m, "all", 8);
    expect(m, "none", 0);
    expect(m, "not all", 0);
    ms_mol_free(m);
}

static void test_errors(void)
{
    t_suite = "select/errors";
    expect_error("protein and of water", "syntax error near 'of' at position 12");
    expect_error("nmae CA", "unknown keyword or macro 'nmae' at position 0");
    expect_error("name \"[A-\"", "bad regular expression \"[A-\"");
    expect_error("name =~ \"(\"", "bad regular expression");
    expect_error("name CA and", "unexpected end of selection at position 11");
    expect_error("within 5 protein", "syntax error near 'protein' at position 9");
    expect_error("x < 5 < 6", "syntax error near '<' at position 6");
    expect_error("name CA #", "bad character '#' at position 8");
    expect_error("name \"CA", "unterminated double-quoted string at position 5");
    expect_error("", "empty selection");
    expect_error("   ", "empty selection");
    expect_error("same foo as all", "'foo' at position 5 is not a keyword");
    expect_error("x + protein > 1", "'protein' at position 4 cannot be used in an expression");
    expect_error("(name CA", "unexpected end of selection");
    expect_error("name CA)", "syntax error near ')' at position 7");
    char deep[3000];
    memset(deep, '(', 1500);
    strcpy(deep + 1500, "all");
    memset(deep + 1503, ')', 1496);
    deep[2999] = '\0';
    expect_error(deep, "nested too deeply");
}

static void test_macros(void)
{
    t_suite = "select/macros";
    ms_molecule *m = line_molecule();
    ms_error err = {{0}};
    t_ok(ms_sel_macro_define("t_ends", "index 0 7", &err) == 0, "define t_ends");
    expect(m, "t_ends", 2);
    expect(m, "not t_ends and x < 3", 2);
    t_ok(ms_sel_macro_define("t_ends", "index 0", &err) == 0, "redefine t_ends");
    expect(m, "t_ends", 1);
    t_ok(ms_sel_macro_define("t_outer", "t_ends or index 1", &err) == 0, "macro using a macro");
    expect(m, "t_outer", 2);
    t_ok(ms_sel_macro_define("t_ends", "t_outer", &err) == -1 &&
             strstr(err.msg, "refers to itself"), "indirect recursion refused (%s)", err.msg);
    t_ok(ms_sel_macro_define("name", "all", &err) == -1 && strstr(err.msg, "built-in"),
         "a keyword cannot be a macro (%s)", err.msg);
    t_ok(ms_sel_macro_define("and", "all", &err) == -1, "a reserved word cannot be a macro");
    t_ok(ms_sel_macro_define("two words", "all", &err) == -1, "a macro name is one word");
    t_ok(ms_sel_macro_define("t_bad", "name CA and", &err) == -1, "a macro must compile");
    t_ok(ms_sel_macro_delete("t_outer", &err) == 0, "delete t_outer");
    expect_error("t_outer", "unknown keyword or macro 't_outer'");
    t_ok(ms_sel_macro_delete("t_outer", &err) == -1, "deleting twice fails");
    char buf[64];
    t_ok(ms_sel_macro_get("acidic", buf, sizeof buf) > 0 && !strcmp(buf, "resname ASP GLU"),
         "default macro acidic");
    ms_mol_free(m);
}

/* ---------------------------------------------------------------- 1tii: hand-checked */

static void test_1tii_counts(ms_molecule *m)
{
    t_suite = "select/1tii";
    /* awk over 1tii.pdb: ATOM records 5469, HETATM (all HOH) 215, ATOM names N/CA/C/O 2848,
     * chain A 1479, names O* 1278, N* 956, S* 45, CA|CB 1372. */
    expect(m, "all", 5684);
    expect(m, "protein", 5469);
    expect(m, "water", 215);
    expect(m, "waters", 215);
    expect(m, "resname HOH", 215);
    expect(m, "backbone", 2848);
    expect(m, "protein and not backbone", 2621);
    expect(m, "chain A", 1479);
    expect(m, "chain A C", 1769);
    expect(m, "oxygen", 1278);
    expect(m, "nitrogen", 956);
    expect(m, "sulfur", 45);
    expect(m, "name \"C[AB]\"", 1372);
    expect(m, "name CA", 712);                              /* also MDAnalysis */
    expect(m, "alpha", 712);
    expect(m, "resid 10 to 20", 483);                        /* MDAnalysis resid 10:20 */
    /* awk: (x-40)^2+(y-20)^2+(z-30)^2 < 400: 689; x+y > 60: 2885; z/2-5 >= 10: 531 */
    expect(m, "sqr(x-40) + sqr(y-20) + sqr(z-30) < 400", 689);
    expect(m, "x + y > 60", 2885);
    expect(m, "z / 2 - 5 >= 10", 531);
    /* MDAnalysis: (around 5 resname HOH) or resname HOH: 2870;
     * byres ((around 3 resname HOH) or resname HOH): 1660; around 4 (resid 10 and chainID A): 32 */
    expect(m, "within 5 of resname HOH", 2870);
    expect(m, "exwithin 5 of resname HOH", 2655);
    expect(m, "same residue as (within 3 of resname HOH)", 1660);
    expect(m, "exwithin 4 of (resid 10 and chain A)", 32);
    /* a Python scan of the sequences of the backbone-linked chains (re.finditer) */
    expect(m, "sequence GQ", 26);
    expect(m, "sequence \"A.D\"", 110);
    expect(m, "sequence C", 72);
    expect(m, "sequence \"W.*Y\"", 719);
    /* helix and sheet from HELIX/SHEET records; every residue has a structure code */
    expect(m, "helix or sheet or turn or coil", 5684);
    expect(m, "structure H G I", count(m, "helix"));
    expect(m, "hydrogen", 0);
    expect(m, "noh", 5684);
    expect(m, "acidic", count(m, "resname ASP GLU"));
    expect(m, "element C N O S", 5684);
    expect(m, "residuetype 'protein'", 5469);
    expect(m, "backbonetype proteinback", 2848);
}

/* phi/psi against the known geometry of helices and strands. */
static void test_phipsi(ms_molecule *m)
{
    t_suite = "select/phipsi";
    long helix = count(m, "name CA and alpha_helix and phi < -40 and phi > -90 and "
                          "psi < -10 and psi > -70");
    long all_helix = count(m, "name CA and alpha_helix");
    t_ok(helix >= all_helix * 8 / 10, "helix CAs: phi and psi near -60/-45 (%ld of %ld)", helix,
         all_helix);
    long strand = count(m, "name CA and extended_beta and phi < -60 and psi > 90");
    long all_strand = count(m, "name CA and extended_beta");
    t_ok(strand >= all_strand * 7 / 10, "strand CAs: phi < -60, psi > 90 (%ld of %ld)", strand,
         all_strand);
}

/* ---------------------------------------------------------------- brute force references */

static ms_bitset select_bits(ms_molecule *m, const char *text)
{
    ms_bitset b;
    ms_error err = {{0}};
    if (ms_sel_select(m, -1, text, &b, &err)) ms_bitset_init(&b, m->atoms.n);
    return b;
}

static double dist2(const float *a, const float *b, const double *shift)
{
    double d = 0;
    for (int k = 0; k < 3; k++) {
        double e = (double)a[k] - ((double)b[k] + (shift ? shift[k] : 0));
        d += e * e;
    }
    return d;
}

/* within d of S, through the 27 periodic images when cell vectors are given. */
static long brute_within(ms_molecule *m, const ms_bitset *s, double d, double v[3][3])
{
    const float *p = ms_mol_pos(m);
    long n = 0;
    for (size_t i = 0; i < m->atoms.n; i++) {
        int hit = 0;
        for (size_t j = 0; j < m->atoms.n && !hit; j++) {
            if (!ms_bitset_get(s, j)) continue;
            for (int a = v ? -1 : 0; a <= (v ? 1 : 0) && !hit; a++)
                for (int b = v ? -1 : 0; b <= (v ? 1 : 0) && !hit; b++)
                    for (int c = v ? -1 : 0; c <= (v ? 1 : 0) && !hit; c++) {
                        double sh[3] = {0, 0, 0};
                        for (int k = 0; v && k < 3; k++)
                            sh[k] = a * v[0][k] + b * v[1][k] + c * v[2][k];
                        hit = dist2(p + 3 * i, p + 3 * j, sh) <= d * d;
                    }
        }
        n += hit;
    }
    return n;
}

static void test_within(ms_molecule *m)
{
    t_suite = "select/within";
    static const struct {
        const char *sub;
        double d;
    } cases[] = {{"resname HOH", 3.5}, {"name SG", 6}, {"index 17", 0.5}, {"resid 50", 10},
                 {"chain C and name CA", 2.2}, {"none", 5}};
    for (size_t c = 0; c < MS_COUNTOF(cases); c++) {
        ms_bitset s = select_bits(m, cases[c].sub);
        char text[256];
        snprintf(text, sizeof text, "within %g of %s", cases[c].d, cases[c].sub);
        expect(m, text, brute_within(m, &s, cases[c].d, NULL));
        ms_bitset_free(&s);
    }
    expect(m, "within 0 of name SG", count(m, "name SG"));
    expect(m, "exwithin 3 of name SG", count(m, "within 3 of name SG") - count(m, "name SG"));
    /* pbwithin through a hexagonal cell small enough for images to matter (1tii's own cell
     * is large: its images come nowhere near) */
    float saved[6];
    memcpy(saved, m->frames[0].cell, sizeof saved);
    const float cell[6] = {40, 40, 50, 90, 90, 120};
    memcpy(m->frames[0].cell, cell, sizeof cell);
    double v[3][3] = {{40, 0, 0}, {40 * cos(2 * M_PI / 3), 40 * sin(2 * M_PI / 3), 0},
                      {0, 0, 50}};
    ms_bitset s = select_bits(m, "resname HOH");
    long pb = brute_within(m, &s, 6, v), plain = count(m, "within 6 of resname HOH");
    expect(m, "pbwithin 6 of resname HOH", pb);
    t_ok(pb > plain, "periodic images add atoms (%ld > %ld)", pb, plain);
    ms_bitset_free(&s);
    memcpy(m->frames[0].cell, saved, sizeof saved);
    expect(m, "pbwithin 6 of resname HOH", plain);
}

/* pbwithin on the line molecule in an 8 A cubic cell: x = 0 and x = 7 are 1 A apart. */
static void test_pbwithin_line(void)
{
    t_suite = "select/within";
    ms_molecule *m = line_molecule();
    const float cell[6] = {8, 8, 8, 90, 90, 90};
    memcpy(m->frames[0].cell, cell, sizeof cell);
    expect(m, "pbwithin 1.5 of index 0", 3);
    expect(m, "within 1.5 of index 0", 2);
    expect(m, "pbwithin 0 of index 0", 1);
    ms_mol_free(m);
}

static void test_same_and_bonds(ms_molecule *m)
{
    t_suite = "select/same";
    /* same residue as S, brute force: every atom whose residue has an atom of S */
    ms_bitset s = select_bits(m, "within 4 of name SG");
    long n = 0;
    for (size_t i = 0; i < m->atoms.n; i++) {
        int hit = 0;
        for (size_t j = 0; j < m->atoms.n && !hit; j++)
            hit = ms_bitset_get(&s, j) && m->atoms.residue[j] == m->atoms.residue[i];
        n += hit;
    }
    ms_bitset_free(&s);
    expect(m, "same residue as (within 4 of name SG)", n);
    expect(m, "same resname as resid 1", count(m, "resname GLY ASN HOH")); /* awk: resid 1 */
    expect(m, "same chain as index 0", count(m, "chain D"));
    expect(m, "same beta as index 0", 2);     /* awk: two atoms have B = 43.86 exactly */
    expect(m, "beta 43.86", 7);               /* within 0.1%: 43.82 to 43.90 */
    expect(m, "same name as name CA", 712);
    expect(m, "same x as index 5", 1);
    /* withinbonds 1 of name CA: each CA with its N, C and CB (glycines have no CB) */
    long gly = count(m, "resname GLY and name CA");
    expect(m, "withinbonds 1 of name CA", 712 * 4 - gly);
    expect(m, "withinbonds 0 of name CA", 712);
    expect(m, "withinbonds 1000000 of index 0", count(m, "same fragment as index 0"));
    expect(m, "bonded", count(m, "numbonds > 0"));
    expect(m, "sidechain", count(m, "protein and not backbone"));
}

/* ---------------------------------------------------------------- get and set */

static void test_access(ms_molecule *m)
{
    t_suite = "select/access";
    ms_error err = {{0}};
    const ms_selkw *name = ms_sel_keyword("name"), *x = ms_sel_keyword("x"),
                   *ss = ms_sel_keyword("structure"), *idx = ms_sel_keyword("index");
    uint32_t atoms[2] = {0, 1};
    const char *vals[2] = {"QQ1", "QQ2"}, *got[2];
    t_ok(ms_sel_set_strings(name, m, -1, atoms, 2, vals, &err) == 0, "set name");
    t_ok(ms_sel_get_strings(name, m, -1, atoms, 2, got, &err) == 0 && !strcmp(got[0], "QQ1") &&
             !strcmp(got[1], "QQ2"), "get the new names");
    expect(m, "name QQ1 QQ2", 2);
    double xs[2] = {1000, 1001}, gx[2];
    t_ok(ms_sel_set_numbers(x, m, -1, atoms, 2, xs, &err) == 0, "set x");
    t_ok(ms_sel_get_numbers(x, m, -1, atoms, 2, gx, &err) == 0 && gx[0] == 1000 && gx[1] == 1001,
         "get x");
    expect(m, "x > 999", 2);
    const char *helix[1] = {"alpha_helix"};
    uint32_t one = 2;  /* an atom of residue 0 */
    long before = count(m, "residue 0");
    t_ok(ms_sel_set_strings(ss, m, -1, &one, 1, helix, &err) == 0, "set structure");
    expect(m, "residue 0 and structure H", before);  /* the whole residue changed */
    t_ok(ms_sel_set_numbers(idx, m, -1, atoms, 1, xs, &err) == -1, "index cannot be set");
    uint32_t bad = 99999999;
    t_ok(ms_sel_get_numbers(x, m, -1, &bad, 1, gx, &err) == -1, "index out of range refused");
}

int main(void)
{
    ms_registry_init(&reg);
    ms_registry_add(&reg, ms_plugin_entry_pdb(), NULL, NULL);
    test_lexer();
    test_precedence();
    test_values();
    test_errors();
    test_macros();
    test_pbwithin_line();
    ms_molecule *m = load("1tii.pdb");
    if (m) {
        test_1tii_counts(m);
        test_phipsi(m);
        test_within(m);
        test_same_and_bonds(m);
        test_access(m);
        ms_mol_free(m);
    }
    ms_registry_free(&reg);
    return t_done();
}
