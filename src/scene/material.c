/* material.c: the material list with VMD's default materials. */
#include "config.h"
#include "scene/material.h"

#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

/* Name, then ambient diffuse specular shininess(0..1) mirror opacity outline outlinewidth
 * transmode, in materials.dat's column order. Opaque and Transparent have raw exponent 40. */
static const struct {
    const char *name;
    float amb, diff, spec, shin, mirror, opac, outline, outlinew, transmode;
} defaults[] = {
    {"Opaque", 0, .65f, .5f, -40, 0, 1, 0, 0, 0},
    {"Transparent", 0, .65f, .5f, -40, 0, .3f, 0, 0, 0},
    {"BrushedMetal", .08f, .39f, .34f, .15f, 0, 1, 0, 0, 0},
    {"Diffuse", 0, .62f, 0, .53f, 0, 1, 0, 0, 0},
    {"Ghost", 0, 0, 1, .23f, 0, .1f, 0, 0, 0},
    {"Glass1", 0, .5f, .65f, .53f, 0, .15f, 0, 0, 0},
    {"Glass2", .52f, .76f, .22f, .59f, 0, .68f, 0, 0, 0},
    {"Glass3", .15f, .25f, .75f, .8f, 0, .5f, 0, 0, 0},
    {"Glossy", 0, .65f, 1, .88f, 0, 1, 0, 0, 0},
    {"HardPlastic", 0, .56f, .28f, .69f, 0, 1, 0, 0, 0},
    {"MetallicPastel", 0, .26f, .55f, .19f, 0, 1, 0, 0, 0},
    {"Steel", .25f, 0, .38f, .32f, 0, 1, 0, 0, 0},
    {"Translucent", 0, .7f, .6f, .3f, 0, .8f, 0, 0, 0},
    {"Edgy", 0, .66f, 0, .75f, 0, 1, .62f, .94f, 0},
    {"EdgyShiny", 0, .66f, .96f, .75f, 0, 1, .76f, .94f, 0},
    {"EdgyGlass", 0, .66f, .5f, .75f, 0, .62f, .62f, .94f, 0},
    {"Goodsell", .52f, 1, 0, 0, 0, 1, 4, .9f, 0},
    {"AOShiny", 0, .85f, .2f, .53f, 0, 1, 0, 0, 0},
    {"AOChalky", 0, .85f, 0, .53f, 0, 1, 0, 0, 0},
    {"AOEdgy", 0, .9f, .2f, .53f, 0, 1, .62f, .93f, 0},
    {"BlownGlass", .04f, .34f, 1, 1, 0, .1f, 0, 0, 1},
    {"GlassBubble", .25f, .34f, 1, 1, 0, .04f, 0, 0, 1},
    {"RTChrome", 0, .65f, .5f, .53f, .7f, 1, 0, 0, 0}};

static const char *const prop_names[MS_MAT_NPROPS] = {
    "ambient", "specular", "diffuse", "shininess", "mirror", "opacity", "outline",
    "outlinewidth", "transmode"};

float ms_material_shininess_from_ui(float x)
{
    return (float)pow(1000.0, x);
}

float ms_material_shininess_to_ui(float exponent)
{
    return exponent > 0 ? (float)(log(exponent) / log(1000.0)) : 0.0f;
}

static void set_default(ms_material *mat, size_t d)
{
    mat->ambient = defaults[d].amb;
    mat->diffuse = defaults[d].diff;
    mat->specular = defaults[d].spec;
    mat->shininess = defaults[d].shin < 0 ? -defaults[d].shin
                                          : ms_material_shininess_from_ui(defaults[d].shin);
    mat->mirror = defaults[d].mirror;
    mat->opacity = defaults[d].opac;
    mat->outline = defaults[d].outline;
    mat->outlinewidth = defaults[d].outlinew;
    mat->transmode = defaults[d].transmode;
}

static int find_name(const ms_materials *m, const char *name)
{
    for (size_t i = 0; i < m->n; i++)
        if (!strcasecmp(m->list[i].name, name)) return (int)i;
    return -1;
}

int ms_material_index(const ms_materials *m, const char *s)
{
    int i = find_name(m, s);
    if (i >= 0) return i;
    char *end;
    long v = strtol(s, &end, 10);
    if (*s && *end == '\0' && v >= 0 && (size_t)v < m->n) return (int)v;
    return -1;
}

const ms_material *ms_material_by_id(const ms_materials *m, int id)
{
    for (size_t i = 0; i < m->n; i++)
        if (m->list[i].id == id) return &m->list[i];
    return &m->list[0];
}

static int append(ms_materials *m, const char *name, const ms_material *from)
{
    char *n = ms_strdup(name);
    if (!n || ms_grow((void **)&m->list, &m->cap, m->n + 1, sizeof *m->list)) {
        free(n);
        return -1;
    }
    ms_material *mat = &m->list[m->n];
    *mat = *from;
    mat->name = n;
    mat->id = m->next_id++;
    m->version++;
    return (int)m->n++;
}

ms_materials *ms_materials_new(ms_error *err)
{
    ms_materials *m = calloc(1, sizeof *m);
    if (!m) goto oom;
    for (size_t d = 0; d < MS_COUNTOF(defaults); d++) {
        ms_material mat;
        memset(&mat, 0, sizeof mat);
        set_default(&mat, d);
        if (append(m, defaults[d].name, &mat) < 0) goto oom;
    }
    return m;
oom:
    ms_materials_free(m);
    ms_error_set(err, "out of memory");
    return NULL;
}

void ms_materials_free(ms_materials *m)
{
    if (!m) return;
    for (size_t i = 0; i < m->n; i++) free(m->list[i].name);
    free(m->list);
    free(m);
}

int ms_material_add(ms_materials *m, const char *name, int copy_from, ms_error *err)
{
    char buf[32];
    if (copy_from < 0 || (size_t)copy_from >= m->n) copy_from = 0;
    if (!name) {
        for (size_t k = m->n;; k++) {
            snprintf(buf, sizeof buf, "Material%zu", k);
            if (find_name(m, buf) < 0) break;
        }
        name = buf;
    } else if (!*name) {
        ms_error_set(err, "a material needs a name");
        return -1;
    } else if (find_name(m, name) >= 0) {
        ms_error_set(err, "material '%s' already exists", name);
        return -1;
    }
    ms_material from = m->list[copy_from];
    int i = append(m, name, &from);
    if (i < 0) ms_error_set(err, "out of memory");
    return i;
}

int ms_material_rename(ms_materials *m, int index, const char *name, ms_error *err)
{
    int other = find_name(m, name);
    if (!*name || (other >= 0 && other != index)) {
        ms_error_set(err, "material '%s' already exists", name);
        return -1;
    }
    char *n = ms_strdup(name);
    if (!n) {
        ms_error_set(err, "out of memory");
        return -1;
    }
    free(m->list[index].name);
    m->list[index].name = n;
    m->version++;
    return 0;
}

int ms_material_delete(ms_materials *m, int index, ms_error *err)
{
    if (index < 2) {
        ms_error_set(err, "material '%s' is built in and cannot be deleted",
                     m->list[index].name);
        return -1;
    }
    free(m->list[index].name);
    memmove(m->list + index, m->list + index + 1, (m->n - (size_t)index - 1) * sizeof *m->list);
    m->n--;
    m->version++;
    return 0;
}

int ms_material_restore_default(ms_materials *m, int index, ms_error *err)
{
    ms_material *mat = &m->list[index];
    /* Built-in materials keep ids 0..22 (the order they were created in). */
    if (mat->id < 0 || (size_t)mat->id >= MS_COUNTOF(defaults)) {
        ms_error_set(err, "material '%s' has no default values", mat->name);
        return -1;
    }
    set_default(mat, (size_t)mat->id);
    m->version++;
    return 0;
}

const char *ms_material_prop_name(ms_mat_prop p)
{
    return p < MS_MAT_NPROPS ? prop_names[p] : "";
}

int ms_material_prop_from_name(const char *name)
{
    for (int i = 0; i < MS_MAT_NPROPS; i++)
        if (!strcasecmp(name, prop_names[i])) return i;
    return -1;
}

float ms_material_get(const ms_material *mat, ms_mat_prop p)
{
    switch (p) {
    case MS_MAT_AMBIENT: return mat->ambient;
    case MS_MAT_SPECULAR: return mat->specular;
    case MS_MAT_DIFFUSE: return mat->diffuse;
    case MS_MAT_SHININESS: return ms_material_shininess_to_ui(mat->shininess);
    case MS_MAT_MIRROR: return mat->mirror;
    case MS_MAT_OPACITY: return mat->opacity;
    case MS_MAT_OUTLINE: return mat->outline;
    case MS_MAT_OUTLINEWIDTH: return mat->outlinewidth;
    case MS_MAT_TRANSMODE: return mat->transmode;
    default: return 0;
    }
}

void ms_material_set(ms_materials *m, int index, ms_mat_prop p, float v)
{
    ms_material *mat = &m->list[index];
    switch (p) {
    case MS_MAT_AMBIENT: mat->ambient = v; break;
    case MS_MAT_SPECULAR: mat->specular = v; break;
    case MS_MAT_DIFFUSE: mat->diffuse = v; break;
    case MS_MAT_SHININESS: mat->shininess = ms_material_shininess_from_ui(v); break;
    case MS_MAT_MIRROR: mat->mirror = v; break;
    case MS_MAT_OPACITY: mat->opacity = v; break;
    case MS_MAT_OUTLINE: mat->outline = v; break;
    case MS_MAT_OUTLINEWIDTH: mat->outlinewidth = v; break;
    case MS_MAT_TRANSMODE: mat->transmode = v; break;
    default: break;
    }
    m->version++;
}
