/* color.c: the colour table, VMD's default colours and category assignments, the colour
 * scale formula, and residue types. */
#include "config.h"
#include "scene/color.h"
#include "scene/colormaps.h"
#include "molecule/elements.h"

#include <ctype.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const color_names[MS_COLOR_NUM] = {
    "blue", "red", "gray", "orange", "yellow", "tan", "silver", "green", "white", "pink",
    "cyan", "purple", "lime", "mauve", "ochre", "iceblue", "black", "yellow2", "yellow3",
    "green2", "green3", "cyan2", "cyan3", "blue2", "blue3", "violet", "violet2", "magenta",
    "magenta2", "red2", "red3", "orange2", "orange3"};

static const float color_defaults[MS_COLOR_NUM][3] = {
    {0, 0, 1}, {1, 0, 0}, {.35f, .35f, .35f}, {1, .5f, 0}, {1, 1, 0}, {.5f, .5f, .2f},
    {.6f, .6f, .6f}, {0, 1, 0}, {1, 1, 1}, {1, .6f, .6f}, {.25f, .75f, .75f},
    {.65f, 0, .65f}, {.5f, .9f, .4f}, {.9f, .4f, .7f}, {.5f, .3f, 0}, {.5f, .5f, .75f},
    {0, 0, 0}, {.88f, .97f, .02f}, {.55f, .90f, .02f}, {0, .90f, .04f}, {0, .90f, .50f},
    {0, .88f, 1}, {0, .76f, 1}, {.02f, .38f, .67f}, {.01f, .04f, .93f}, {.27f, 0, .98f},
    {.45f, 0, .90f}, {.90f, 0, .90f}, {1, 0, .66f}, {.98f, 0, .23f}, {.81f, 0, 0},
    {.89f, .35f, 0}, {.96f, .72f, 0}};

static const ms_color_scale_method scale_defaults[MS_COLOR_SCALE_METHODS] = {
    {"RWB", {{1, 0, 0}, {1, 1, 1}, {0, 0, 1}}, NULL},
    {"BWR", {{0, 0, 1}, {1, 1, 1}, {1, 0, 0}}, NULL},
    {"RGryB", {{1, 0, 0}, {.5f, .5f, .5f}, {0, 0, 1}}, NULL},
    {"BGryR", {{0, 0, 1}, {.5f, .5f, .5f}, {1, 0, 0}}, NULL},
    {"RGB", {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}, NULL},
    {"BGR", {{0, 0, 1}, {0, 1, 0}, {1, 0, 0}}, NULL},
    {"RWG", {{1, 0, 0}, {1, 1, 1}, {0, 1, 0}}, NULL},
    {"GWR", {{0, 1, 0}, {1, 1, 1}, {1, 0, 0}}, NULL},
    {"GWB", {{0, 1, 0}, {1, 1, 1}, {0, 0, 1}}, NULL},
    {"BWG", {{0, 0, 1}, {1, 1, 1}, {0, 1, 0}}, NULL},
    {"BlkW", {{0, 0, 0}, {.5f, .5f, .5f}, {1, 1, 1}}, NULL},
    {"WBlk", {{1, 1, 1}, {.5f, .5f, .5f}, {0, 0, 0}}, NULL},
    {"viridis", {{0}}, ms_colormap_viridis},
    {"magma", {{0}}, ms_colormap_magma},
    {"inferno", {{0}}, ms_colormap_inferno},
    {"plasma", {{0}}, ms_colormap_plasma},
    {"cividis", {{0}}, ms_colormap_cividis},
    {"turbo", {{0}}, ms_colormap_turbo}};

/* Categories in VMD's order of creation. */
static const char *const category_names[] = {
    "Display", "Axes", "Stage", "Labels", "Name", "Type", "Element", "Resname", "Restype",
    "Chain", "Segname", "Conformation", "Molecule", "Highlight", "Structure", "Surface"};

/* Default assignments: category, item, colour (VMD's colordefs and built-in items). */
static const struct {
    const char *cat, *item, *color;
} item_defaults[] = {
    {"Display", "Background", "black"}, {"Display", "BackgroundTop", "black"},
    {"Display", "BackgroundBot", "blue2"}, {"Display", "Foreground", "white"},
    {"Display", "FPS", "white"},
    {"Axes", "X", "red"}, {"Axes", "Y", "green"}, {"Axes", "Z", "blue"},
    {"Axes", "Origin", "cyan"}, {"Axes", "Labels", "white"},
    {"Stage", "Even", "gray"}, {"Stage", "Odd", "silver"},
    {"Labels", "Atoms", "green"}, {"Labels", "Bonds", "white"}, {"Labels", "Angles", "yellow"},
    {"Labels", "Dihedrals", "cyan"}, {"Labels", "Springs", "orange"},
    {"Name", "H", "white"}, {"Name", "O", "red"}, {"Name", "N", "blue"}, {"Name", "C", "cyan"},
    {"Name", "S", "yellow"}, {"Name", "P", "tan"}, {"Name", "Z", "silver"},
    {"Name", "LPA", "green"}, {"Name", "LPB", "green"},
    {"Type", "H", "white"}, {"Type", "O", "red"}, {"Type", "N", "blue"}, {"Type", "C", "cyan"},
    {"Type", "S", "yellow"}, {"Type", "P", "tan"}, {"Type", "Z", "silver"},
    {"Type", "LP", "green"}, {"Type", "DRUD", "pink"},
    {"Element", "X", "purple"},
    {"Resname", "ALA", "blue"}, {"Resname", "ARG", "white"}, {"Resname", "ASN", "tan"},
    {"Resname", "ASP", "red"}, {"Resname", "CYS", "yellow"}, {"Resname", "GLY", "white"},
    {"Resname", "GLU", "pink"}, {"Resname", "GLN", "orange"}, {"Resname", "HIS", "cyan"},
    {"Resname", "ILE", "green"}, {"Resname", "LEU", "pink"}, {"Resname", "LYS", "cyan"},
    {"Resname", "MET", "yellow"}, {"Resname", "PHE", "purple"}, {"Resname", "PRO", "ochre"},
    {"Resname", "SER", "yellow"}, {"Resname", "THR", "mauve"}, {"Resname", "TRP", "silver"},
    {"Resname", "TYR", "green"}, {"Resname", "VAL", "tan"}, {"Resname", "ADE", "blue"},
    {"Resname", "CYT", "orange"}, {"Resname", "GUA", "yellow"}, {"Resname", "THY", "purple"},
    {"Resname", "URA", "green"}, {"Resname", "TIP", "cyan"}, {"Resname", "TIP3", "cyan"},
    {"Resname", "WAT", "cyan"}, {"Resname", "SOL", "cyan"}, {"Resname", "H2O", "cyan"},
    {"Resname", "LYR", "purple"}, {"Resname", "ZN", "silver"}, {"Resname", "NA", "yellow"},
    {"Resname", "CL", "green"}, {"Resname", "HSE", "cyan"}, {"Resname", "HSD", "cyan"},
    {"Resname", "HSP", "cyan"}, {"Resname", "CYX", "yellow"},
    {"Restype", "Unassigned", "cyan"}, {"Restype", "Solvent", "yellow"},
    {"Restype", "Nucleic_Acid", "purple"}, {"Restype", "Basic", "blue"},
    {"Restype", "Acidic", "red"}, {"Restype", "Polar", "green"},
    {"Restype", "Nonpolar", "white"}, {"Restype", "Ion", "tan"},
    {"Highlight", "Proback", "green"}, {"Highlight", "Nucback", "yellow"},
    {"Highlight", "Nonback", "blue"},
    {"Structure", "Alpha Helix", "purple"}, {"Structure", "3_10_Helix", "blue"},
    {"Structure", "Pi_Helix", "red"}, {"Structure", "Extended_Beta", "yellow"},
    {"Structure", "Bridge_Beta", "tan"}, {"Structure", "Turn", "cyan"},
    {"Structure", "Coil", "white"},
    {"Surface", "Grasp", "gray"}};

/* Elements VMD's colordefs names (all ochre except C cyan, H white, N blue, O red, P tan,
 * S yellow, Zn silver), in its order. */
static const char element_list[] =
    "Ac Ag Al Am Ar As At Au B Ba Be Bh Bi Bk Br C Ca Cd Ce Cf Cl Cm Co Cr Cs Cu Db Ds Dy Er "
    "Es Eu F Fe Fm Fr Ga Gd Ge H He Hf Hg Ho Hs I In Ir K Kr La Li Lr Lu Md Mg Mn Mo Mt N Na "
    "Nb Nd Ne Ni No Np O Os P Pa Pb Pd Pm Po Pr Pt Pu Ra Rb Re Rf Rg Rh Rn Ru S Sb Sc Se Sg Si "
    "Sm Sn Sr Ta Tb Tc Te Th Ti Tl Tm U V W Xe Y Yb Zn Zr";

static const char *const restype_defaults[][2] = {
    {"ALA", "Nonpolar"}, {"ARG", "Basic"}, {"ASN", "Polar"}, {"ASP", "Acidic"},
    {"CYS", "Nonpolar"}, {"GLY", "Polar"}, {"GLU", "Acidic"}, {"GLN", "Polar"},
    {"HIS", "Basic"}, {"ILE", "Nonpolar"}, {"LEU", "Nonpolar"}, {"LYS", "Basic"},
    {"MET", "Nonpolar"}, {"PHE", "Nonpolar"}, {"PRO", "Nonpolar"}, {"SER", "Polar"},
    {"THR", "Polar"}, {"TRP", "Nonpolar"}, {"TYR", "Polar"}, {"VAL", "Nonpolar"},
    {"ADE", "Nucleic_Acid"}, {"CYT", "Nucleic_Acid"}, {"GUA", "Nucleic_Acid"},
    {"THY", "Nucleic_Acid"}, {"URA", "Nucleic_Acid"}, {"TIP", "Solvent"}, {"TIP3", "Solvent"},
    {"WAT", "Solvent"}, {"SOL", "Solvent"}, {"H2O", "Solvent"}, {"LYR", "Nonpolar"},
    {"ZN", "Ion"}, {"NA", "Ion"}, {"CL", "Ion"}, {"HSD", "Polar"}, {"HSE", "Polar"},
    {"HSP", "Basic"}, {"TP3M", "Solvent"}, {"CAL", "Ion"}, {"CES", "Ion"}, {"CLA", "Ion"},
    {"MG", "Ion"}, {"POT", "Ion"}, {"SOD", "Ion"}, {"ZN2", "Ion"}, {"CYX", "Nonpolar"}};

/* ---------------------------------------------------------------- colours */

const char *ms_color_name(int id)
{
    return id >= 0 && id < MS_COLOR_NUM ? color_names[id] : NULL;
}

int ms_color_index(const ms_colors *c, const char *s)
{
    (void)c;
    for (int i = 0; i < MS_COLOR_NUM; i++)
        if (!strcasecmp(s, color_names[i])) return i;
    char *end;
    long v = strtol(s, &end, 10);
    if (*s && *end == '\0' && v >= 0 && v < MS_COLOR_MAX) return (int)v;
    return -1;
}

void ms_color_scale_eval(const float rgb[3][3], float mid, float offset, float x, float out[3])
{
    float wlo = x > mid ? 0.0f : mid == 0 ? 1.0f : 1.0f - x / mid;
    float whi = x < mid ? 0.0f : mid == 1 ? 1.0f : 1.0f - (1.0f - x) / (1.0f - mid);
    float wmid = x < mid ? x / mid : x > mid ? (1.0f - x) / (1.0f - mid) : 1.0f;
    float sum = wlo + wmid + whi;
    for (int k = 0; k < 3; k++) {
        float v = (rgb[0][k] * wlo + rgb[1][k] * wmid + rgb[2][k] * whi) / sum + offset;
        out[k] = v < 0 ? 0 : v > 1 ? 1 : v;
    }
}

/* A perceptual map at x in [0, 1], interpolated linearly between its 256 entries. */
static void map_eval(const float (*map)[3], float x, float out[3])
{
    float f = x * 255.0f;
    int i = f <= 0 ? 0 : f >= 255 ? 254 : (int)f;
    float t = f - (float)i;
    t = t < 0 ? 0 : t > 1 ? 1 : t;
    for (int k = 0; k < 3; k++) out[k] = map[i][k] + t * (map[i + 1][k] - map[i][k]);
}

/* The three colours a perceptual map answers for (color scale colors): its ends and middle. */
static void map_colors(ms_color_scale_method *m)
{
    for (int j = 0; j < 3; j++) map_eval(m->map, 0.5f * (float)j, m->rgb[j]);
}

static void rebuild_scale(ms_colors *c)
{
    const ms_color_scale_method *m = &c->methods[c->method];
    for (int i = 0; i < MS_COLOR_SCALE_SIZE; i++) {
        float x = (float)i / (float)(MS_COLOR_SCALE_SIZE - 1);
        /* a perceptual map is its published colours: no midpoint, no offset */
        if (m->map) map_eval(m->map, x, c->rgb[MS_COLOR_SCALE_BEGIN + i]);
        else ms_color_scale_eval(m->rgb, c->scale_mid, c->scale_min, x,
                                 c->rgb[MS_COLOR_SCALE_BEGIN + i]);
    }
    c->version++;
}

int ms_color_scale_index(float v, float min, float max)
{
    if (!(max != min)) return MS_COLOR_SCALE_BEGIN + MS_COLOR_SCALE_SIZE / 2;
    float f = (v - min) * (float)(MS_COLOR_SCALE_SIZE - 1) / (max - min);
    int i = f != f ? 0 : f < 0 ? 0 : f > MS_COLOR_SCALE_SIZE - 1 ? MS_COLOR_SCALE_SIZE - 1 : (int)f;
    return MS_COLOR_SCALE_BEGIN + i;
}

int ms_color_default_rgb(int id, float rgb[3])
{
    if (id < 0 || id >= MS_COLOR_MAX) return -1;
    if (id < MS_COLOR_NUM) {
        memcpy(rgb, color_defaults[id], 3 * sizeof(float));
        return 0;
    }
    ms_color_scale_eval(scale_defaults[0].rgb, 0.5f, 0.1f,
                        (float)(id - MS_COLOR_SCALE_BEGIN) / (float)(MS_COLOR_SCALE_SIZE - 1), rgb);
    return 0;
}

int ms_color_set_rgb(ms_colors *c, int id, const float rgb[3])
{
    if (id < 0 || id >= MS_COLOR_MAX) return -1;
    for (int k = 0; k < 3; k++)
        c->rgb[id][k] = rgb[k] < 0 ? 0 : rgb[k] > 1 ? 1 : rgb[k];
    c->version++;
    return 0;
}

int ms_color_scale_method_index(const ms_colors *c, const char *name)
{
    for (int i = 0; i < MS_COLOR_SCALE_METHODS; i++)
        if (!strcasecmp(name, c->methods[i].name)) return i;
    return -1;
}

void ms_color_scale_set_method(ms_colors *c, int method)
{
    if (method < 0 || method >= MS_COLOR_SCALE_METHODS) return;
    c->method = method;
    rebuild_scale(c);
}

void ms_color_scale_set_values(ms_colors *c, float mid, float min, float max)
{
    c->scale_mid = mid;
    c->scale_min = min;
    c->scale_max = max;
    rebuild_scale(c);
}

void ms_color_scale_set_colors(ms_colors *c, int method, const float rgb[3][3])
{
    if (method < 0 || method >= MS_COLOR_SCALE_METHODS) return;
    memcpy(c->methods[method].rgb, rgb, sizeof c->methods[method].rgb);
    c->methods[method].map = NULL;   /* three colours of the user's: blended from now on */
    rebuild_scale(c);
}

/* ---------------------------------------------------------------- categories */

int ms_color_category_index(const ms_colors *c, const char *name)
{
    for (size_t i = 0; i < c->ncats; i++)
        if (!strcasecmp(c->cats[i].name, name)) return (int)i;
    return -1;
}

int ms_color_category_add(ms_colors *c, const char *name)
{
    int i = ms_color_category_index(c, name);
    if (i >= 0) return i;
    if (ms_grow((void **)&c->cats, &c->capcats, c->ncats + 1, sizeof *c->cats)) return -1;
    ms_color_category *cat = &c->cats[c->ncats];
    memset(cat, 0, sizeof *cat);
    if (!(cat->name = ms_strdup(name))) return -1;
    return (int)c->ncats++;
}

int ms_color_item_index(const ms_colors *c, int cat, const char *item)
{
    if (cat < 0 || (size_t)cat >= c->ncats) return -1;
    const ms_color_category *k = &c->cats[cat];
    for (size_t i = 0; i < k->n; i++)
        if (!strcmp(k->items[i].name, item)) return (int)i;
    return -1;
}

int ms_color_item_get(const ms_colors *c, int cat, const char *item)
{
    int i = ms_color_item_index(c, cat, item);
    return i < 0 ? -1 : c->cats[cat].items[i].color;
}

int ms_color_item_set(ms_colors *c, int cat, const char *item, int color)
{
    int i = ms_color_item_index(c, cat, item);
    if (i < 0 || color < 0 || color >= MS_COLOR_MAX) return -1;
    c->cats[cat].items[i].color = color;
    c->version++;
    return 0;
}

int ms_color_item_add(ms_colors *c, int cat, const char *item, int color)
{
    if (cat < 0 || (size_t)cat >= c->ncats) return -1;
    int i = ms_color_item_index(c, cat, item);
    if (i >= 0) return c->cats[cat].items[i].color;
    ms_color_category *k = &c->cats[cat];
    if (color < 0 || color >= MS_COLOR_MAX) color = (int)(k->n % MS_COLOR_AUTO_CYCLE);
    if (ms_grow((void **)&k->items, &k->cap, k->n + 1, sizeof *k->items)) return -1;
    if (!(k->items[k->n].name = ms_strdup(item))) return -1;
    k->items[k->n++].color = color;
    c->version++;
    return color;
}

int ms_color_for_value(ms_colors *c, int cat, const char *value)
{
    if (cat < 0 || (size_t)cat >= c->ncats) return -1;
    const char *cname = c->cats[cat].name;
    char key[2];
    if (!strcmp(cname, "Name") || !strcmp(cname, "Type")) {
        const char *p = value;
        while (*p && isdigit((unsigned char)*p)) p++;
        if (!*p) p = value;
        key[0] = (char)toupper((unsigned char)*p);
        key[1] = '\0';
        value = key;
    } else if (!strcmp(cname, "Conformation") && !*value) {
        value = "all";
    }
    return ms_color_item_add(c, cat, value, -1);
}

/* ---------------------------------------------------------------- residue types */

const char *ms_color_restype(const ms_colors *c, const char *resname)
{
    for (size_t i = 0; i < c->nrestypes; i++)
        if (!strcmp(c->restypes[i].resname, resname)) return c->restypes[i].type;
    return NULL;
}

static int restype_put(ms_colors *c, const char *resname, const char *type)
{
    char *t = ms_strdup(type);
    if (!t) return -1;
    for (size_t i = 0; i < c->nrestypes; i++)
        if (!strcmp(c->restypes[i].resname, resname)) {
            free(c->restypes[i].type);
            c->restypes[i].type = t;
            return 0;
        }
    char *r = ms_strdup(resname);
    if (!r || ms_grow((void **)&c->restypes, &c->caprestypes, c->nrestypes + 1,
                      sizeof *c->restypes)) {
        free(r);
        free(t);
        return -1;
    }
    c->restypes[c->nrestypes].resname = r;
    c->restypes[c->nrestypes++].type = t;
    return 0;
}

int ms_color_set_restype(ms_colors *c, const char *resname, const char *type)
{
    int cat = ms_color_category_index(c, "Restype");
    if (ms_color_item_index(c, cat, type) < 0) return -1;
    if (restype_put(c, resname, type)) return -1;
    c->version++;
    return 0;
}

/* ---------------------------------------------------------------- molecules */

/* Add every distinct string of one per-atom field, in order of first appearance. */
static int add_field(ms_colors *c, int cat, const ms_molecule *m, const ms_str *field,
                     uint8_t *seen, int restypes)
{
    uint32_t nstr = ms_strtab_count(m->strings);
    memset(seen, 0, nstr);
    ms_str prev = MS_STR_NONE;
    for (size_t i = 0; i < m->atoms.n; i++) {
        ms_str s = field[i];
        if (s == prev) continue;  /* runs of one value: residues, chains, segments */
        prev = s;
        if (s >= nstr || seen[s]) continue;
        seen[s] = 1;
        const char *v = ms_mol_str(m, s);
        if (ms_color_for_value(c, cat, v) < 0) return -1;
        if (restypes && !ms_color_restype(c, v) && restype_put(c, v, "Unassigned")) return -1;
    }
    return 0;
}

static int add_chars(ms_colors *c, int cat, const ms_molecule *m, const char *field)
{
    uint8_t seen[256] = {0};
    for (size_t i = 0; i < m->atoms.n; i++) {
        unsigned char ch = (unsigned char)field[i];
        if ((i && field[i - 1] == field[i]) || seen[ch]) continue;
        seen[ch] = 1;
        char v[2] = {(char)ch, '\0'};
        if (ms_color_for_value(c, cat, v) < 0) return -1;
    }
    return 0;
}

int ms_colors_add_molecule(ms_colors *c, const ms_molecule *m, ms_error *err)
{
    uint8_t *seen = malloc(ms_strtab_count(m->strings) + 1);
    int rc = seen ? 0 : -1;
    const struct {
        const char *cat;
        const ms_str *field;
    } fields[] = {{"Name", m->atoms.name}, {"Type", m->atoms.type},
                  {"Resname", m->atoms.resname}, {"Chain", m->atoms.chain},
                  {"Segname", m->atoms.segname}};
    for (size_t f = 0; rc == 0 && f < MS_COUNTOF(fields); f++)
        rc = add_field(c, ms_color_category_index(c, fields[f].cat), m, fields[f].field, seen,
                       f == 2);
    free(seen);
    if (rc == 0 && m->atoms.n)
        rc = add_chars(c, ms_color_category_index(c, "Conformation"), m, m->atoms.altloc);
    int ecat = ms_color_category_index(c, "Element");
    uint8_t zseen[256] = {0};
    for (size_t i = 0; rc == 0 && i < m->atoms.n; i++) {
        int z = m->atoms.atomicnumber[i];
        if (zseen[z]) continue;
        zseen[z] = 1;
        rc = ms_color_for_value(c, ecat, ms_element_symbol(z)) < 0 ? -1 : 0;
    }
    char id[32];
    snprintf(id, sizeof id, "%d", m->id);
    if (rc == 0 && ms_color_item_add(c, ms_color_category_index(c, "Molecule"), id, -1) < 0)
        rc = -1;
    if (rc) ms_error_set(err, "out of memory adding colour names");
    return rc;
}

/* ---------------------------------------------------------------- creation */

static int add_defaults(ms_colors *c)
{
    for (size_t i = 0; i < MS_COUNTOF(category_names); i++)
        if (ms_color_category_add(c, category_names[i]) < 0) return -1;
    for (size_t i = 0; i < MS_COUNTOF(item_defaults); i++) {
        int cat = ms_color_category_index(c, item_defaults[i].cat);
        int col = ms_color_index(c, item_defaults[i].color);
        if (ms_color_item_add(c, cat, item_defaults[i].item, col) < 0) return -1;
        if (!strcmp(item_defaults[i].cat, "Element")) {
            /* Element X: keep the list in colordefs' order after it */
            const char *p = element_list;
            while (*p) {
                char sym[4];
                size_t n = strcspn(p, " ");
                snprintf(sym, sizeof sym, "%.*s", (int)n, p);
                const char *colname = !strcmp(sym, "C") ? "cyan" : !strcmp(sym, "H") ? "white"
                                      : !strcmp(sym, "N") ? "blue" : !strcmp(sym, "O") ? "red"
                                      : !strcmp(sym, "P") ? "tan" : !strcmp(sym, "S") ? "yellow"
                                      : !strcmp(sym, "Zn") ? "silver" : "ochre";
                if (ms_color_item_add(c, cat, sym, ms_color_index(c, colname)) < 0) return -1;
                p += n;
                while (*p == ' ') p++;
            }
        }
    }
    for (size_t i = 0; i < MS_COUNTOF(restype_defaults); i++)
        if (restype_put(c, restype_defaults[i][0], restype_defaults[i][1])) return -1;
    return 0;
}

ms_colors *ms_colors_new(ms_error *err)
{
    ms_colors *c = calloc(1, sizeof *c);
    if (!c) {
        ms_error_set(err, "out of memory");
        return NULL;
    }
    memcpy(c->rgb, color_defaults, sizeof color_defaults);
    memcpy(c->methods, scale_defaults, sizeof scale_defaults);
    for (int i = 0; i < MS_COLOR_SCALE_METHODS; i++)
        if (c->methods[i].map) map_colors(&c->methods[i]);
    c->scale_mid = 0.5f;
    c->scale_min = 0.1f;
    c->scale_max = 1.0f;
    rebuild_scale(c);
    if (add_defaults(c)) {
        ms_colors_free(c);
        ms_error_set(err, "out of memory");
        return NULL;
    }
    c->version = 1;
    return c;
}

void ms_colors_free(ms_colors *c)
{
    if (!c) return;
    for (size_t i = 0; i < c->ncats; i++) {
        for (size_t j = 0; j < c->cats[i].n; j++) free(c->cats[i].items[j].name);
        free(c->cats[i].items);
        free(c->cats[i].name);
    }
    free(c->cats);
    for (size_t i = 0; i < c->nrestypes; i++) {
        free(c->restypes[i].resname);
        free(c->restypes[i].type);
    }
    free(c->restypes);
    free(c);
}
