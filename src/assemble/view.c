/* view.c: display settings with VMD's text-mode defaults, the transform commands' semantics,
 * resetview, and the axes and stage geometry. */
#include "config.h"
#include "assemble/view.h"
#include "rep/rep.h"
#include "scene/graphics.h"
#include "vecmath/vecf.h"

#include <math.h>
#include <stdlib.h>
#include <string.h>
#include <strings.h>

static const char *const axes_names[MS_AXES_NLOCS] = {
    "Off", "Origin", "LowerLeft", "LowerRight", "UpperLeft", "UpperRight"};
static const char *const stage_names[MS_STAGE_NLOCS] = {
    "Off", "Origin", "Bottom", "Top", "Left", "Right", "Behind"};
static const char *const cue_names[3] = {"Linear", "Exp", "Exp2"};
static const char *const proj_names[2] = {"Perspective", "Orthographic"};

static int name_index(const char *const *names, int n, const char *s)
{
    for (int i = 0; i < n; i++)
        if (!strcasecmp(names[i], s)) return i;
    return -1;
}

const char *ms_axes_loc_name(ms_axes_loc l) { return l < MS_AXES_NLOCS ? axes_names[l] : ""; }
int ms_axes_loc_from_name(const char *s) { return name_index(axes_names, MS_AXES_NLOCS, s); }
const char *ms_stage_loc_name(ms_stage_loc l) { return l < MS_STAGE_NLOCS ? stage_names[l] : ""; }
int ms_stage_loc_from_name(const char *s) { return name_index(stage_names, MS_STAGE_NLOCS, s); }
const char *ms_cuemode_name(ms_cuemode m) { return m <= MS_CUE_EXP2 ? cue_names[m] : ""; }
int ms_cuemode_from_name(const char *s) { return name_index(cue_names, 3, s); }
const char *ms_projection_name(ms_projection p) { return p <= MS_PROJ_ORTHOGRAPHIC ? proj_names[p] : ""; }

int ms_projection_from_name(const char *s)
{
    int i = name_index(proj_names, 2, s);
    return i;
}

static const float light_pos[MS_SCENE_LIGHTS][3] = {
    {-0.1f, 0.1f, 1.0f}, {1.0f, 2.0f, 0.5f}, {-1.0f, 2.0f, -1.0f}, {-1.0f, -1.0f, 0.0f}};

const float *ms_view_default_light(int n)
{
    return light_pos[n < 0 ? 0 : n >= MS_SCENE_LIGHTS ? MS_SCENE_LIGHTS - 1 : n];
}

ms_view *ms_view_new(void)
{
    ms_view *v = calloc(1, sizeof *v);
    if (!v) return NULL;
    ms_camera *c = &v->settings.cam;
    c->projection = MS_PROJ_PERSPECTIVE;
    c->eye[2] = 2.0f;
    c->dir[2] = -1.0f;
    c->up[1] = 1.0f;
    c->height = 6.0f;
    c->distance = -2.0f;
    c->near_clip = 0.5f;
    c->far_clip = 10.0f;
    c->eyesep = 0.065f;
    c->focal_length = 2.0f;
    c->dof_fnumber = 64.0f;
    c->dof_focaldist = 0.7f;
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        v->settings.lights[i].on = i < 2;
        memcpy(v->settings.lights[i].pos, light_pos[i], sizeof light_pos[i]);
        v->settings.lights[i].color[0] = v->settings.lights[i].color[1] = v->settings.lights[i].color[2] = 1.0f;
    }
    v->settings.cuemode = MS_CUE_EXP2;
    v->settings.cue_start = 0.5f;
    v->settings.cue_end = 10.0f;
    v->settings.cue_density = 0.32f;
    v->settings.ao_ambient = 0.8f;
    v->settings.ao_direct = 0.3f;
    v->update = 1;
    strcpy(v->stereo, "Off");
    strcpy(v->rendermode, "Normal");
    strcpy(v->cachemode, "Off");
    v->axes = MS_AXES_LOWERLEFT;
    ms_mat4_identity(v->axes_rotate);
    v->stage = MS_STAGE_OFF;
    v->stage_panels = 8;
    v->stage_size = 1.0f;
    v->last_scale = 1.0f;
    return v;
}

void ms_view_free(ms_view *v)
{
    free(v);
}

/* ---------------------------------------------------------------- transforms */

void ms_view_mol_model(const ms_molecule *m, float out[16])
{
    float t[16], r[16];
    ms_mat4_translation(t, m->global[0], m->global[1], m->global[2]);
    ms_mat4_mul(t, m->rotate, r);
    ms_mat4_scaling(t, m->scale);
    ms_mat4_mul(r, t, r);
    ms_mat4_translation(t, -m->center[0], -m->center[1], -m->center[2]);
    ms_mat4_mul(r, t, out);
}

static ms_view *view_of(ms_world *w)
{
    return w->view;
}

/* Pre-multiply (by) or set (to) a rotation on the non-fixed molecules and the axes. */
static void apply_rotation(ms_world *w, const float r[16], int by)
{
    w->scene_version++;
    for (size_t i = 0; i < w->mols->n; i++) {
        ms_molecule *m = w->mols->mols[i];
        if (m->fixed) continue;
        if (by) ms_mat4_mul(r, m->rotate, m->rotate);
        else memcpy(m->rotate, r, 16 * sizeof(float));
    }
    ms_view *v = view_of(w);
    if (by) ms_mat4_mul(r, v->axes_rotate, v->axes_rotate);
    else memcpy(v->axes_rotate, r, 16 * sizeof(float));
}

void ms_view_rotate_by(ms_world *w, char axis, float deg)
{
    float r[16];
    ms_mat4_axis_rotation(r, axis, ms_deg_rad(deg));
    apply_rotation(w, r, 1);
}

void ms_view_rotate_to(ms_world *w, char axis, float deg)
{
    float r[16];
    ms_mat4_axis_rotation(r, axis, ms_deg_rad(deg));
    apply_rotation(w, r, 0);
}

void ms_view_rotmat(ms_world *w, const float r[16], int by)
{
    apply_rotation(w, r, by);
}

void ms_view_translate(ms_world *w, float x, float y, float z, int by)
{
    w->scene_version++;
    for (size_t i = 0; i < w->mols->n; i++) {
        ms_molecule *m = w->mols->mols[i];
        if (m->fixed) continue;
        float d[3] = {x, y, z};
        for (int k = 0; k < 3; k++) m->global[k] = by ? m->global[k] + d[k] : d[k];
    }
}

int ms_view_scale(ms_world *w, float s, int by)
{
    if (!(s > 0)) return -1;
    w->scene_version++;
    for (size_t i = 0; i < w->mols->n; i++) {
        ms_molecule *m = w->mols->mols[i];
        if (!m->fixed) m->scale = by ? m->scale * s : s;
    }
    return 0;
}

void ms_view_rock(ms_world *w, char axis, float step, int steps)
{
    ms_view *v = view_of(w);
    v->rock_axis = axis;
    v->rock_step = step;
    v->rock_steps = steps;
    v->rock_count = 0;
}

void ms_view_rock_step(ms_world *w)
{
    ms_view *v = view_of(w);
    if (!v->rock_axis) return;
    ms_view_rotate_by(w, v->rock_axis, v->rock_step);
    if (v->rock_steps > 0 && ++v->rock_count >= v->rock_steps) {
        v->rock_count = 0;
        v->rock_step = -v->rock_step;   /* swing back */
    }
}

/* ---------------------------------------------------------------- resetview */

/* The sums atoms_cov takes over, in ascending atom order. */
typedef struct cov_sum {
    double c[3];
    float lo[3], hi[3];
    size_t n;
} cov_sum;

static void cov_start(cov_sum *s, const float *p)
{
    memset(s->c, 0, sizeof s->c);
    memcpy(s->lo, p, sizeof s->lo);
    memcpy(s->hi, p, sizeof s->hi);
    s->n = 0;
}

/* Atoms [i0, i1) of pos into s. */
static void cov_run(cov_sum *s, const float *pos, size_t i0, size_t i1)
{
    for (size_t i = i0; i < i1; i++)
        for (int k = 0; k < 3; k++) {
            float x = pos[3 * i + k];
            s->c[k] += x;
            if (x < s->lo[k]) s->lo[k] = x;
            if (x > s->hi[k]) s->hi[k] = x;
        }
    s->n += i1 - i0;
}

/* Mean position and VMD's scale of the atoms in `in` (all n atoms when in is NULL): whole
 * words of the set as runs, the others bit by bit. */
static void atoms_cov(const float *pos, const ms_bitset *in, size_t n, float center[3],
                      float *scale)
{
    cov_sum s;
    size_t nw = in ? ms_bitset_nwords(in) : 0, w0 = 0;
    while (w0 < nw && !in->words[w0]) w0++;
    cov_start(&s, pos + 3 * (in ? 64 * w0 + (size_t)__builtin_ctzll(in->words[w0]) : 0));
    if (!in) cov_run(&s, pos, 0, n);
    for (size_t w = w0; w < nw; w++) {
        uint64_t bits = in->words[w];
        if (bits == ~(uint64_t)0) {
            cov_run(&s, pos, 64 * w, 64 * w + 64);
            continue;
        }
        for (; bits; bits &= bits - 1) {
            size_t i = 64 * w + (size_t)__builtin_ctzll(bits);
            cov_run(&s, pos, i, i + 1);
        }
    }
    for (int k = 0; k < 3; k++) center[k] = (float)(s.c[k] / (double)s.n);
    /* VMD starts from the x extent (3 when it is zero, so one atom gets 0.5), then takes the
     * larger of the y and z extents. */
    float ext = s.hi[0] - s.lo[0];
    if (ext == 0.0f) ext = 3.0f;
    ext = MS_MAX(ext, s.hi[1] - s.lo[1]);
    ext = MS_MAX(ext, s.hi[2] - s.lo[2]);
    *scale = 1.5f / ext;
}

/* A molecule of volumes alone: the centre of their boxes' union, scaled as atoms at its
 * corners would be. */
static void volumes_cov(const ms_molecule *m, float center[3], float *scale)
{
    float lo[3], hi[3], pts[6];
    for (size_t k = 0; k < m->nvolumes; k++) {
        float a[3], b[3];
        ms_volume_bounds(&m->volumes[k], a, b);
        for (int d = 0; d < 3; d++) {
            lo[d] = k == 0 || a[d] < lo[d] ? a[d] : lo[d];
            hi[d] = k == 0 || b[d] > hi[d] ? b[d] : hi[d];
        }
    }
    memcpy(pts, lo, sizeof lo);
    memcpy(pts + 3, hi, sizeof hi);
    atoms_cov(pts, NULL, 2, center, scale);
}

int ms_view_mol_cov(ms_world *w, ms_molecule *m, float center[3], float *scale)
{
    const float *pos = ms_mol_pos(m);
    ms_bitset shown;
    if (ms_rep_shown_atoms(w->reps, m, &shown)) {
        atoms_cov(pos, &shown, 0, center, scale);
        ms_bitset_free(&shown);
        return 1;
    }
    if (pos && m->atoms.n) {
        atoms_cov(pos, NULL, m->atoms.n, center, scale);
        return 1;
    }
    if (m->nvolumes) {
        volumes_cov(m, center, scale);
        return 1;
    }
    if (w->ugraphics_slot >= 0 && m->ext[w->ugraphics_slot])
        return ms_ugraphics_cov(m->ext[w->ugraphics_slot], center, scale);
    return 0;
}

void ms_view_reset(ms_world *w)
{
    w->scene_version++;
    ms_view *v = view_of(w);
    ms_molecule *top = ms_molset_top(w->mols);
    float c[3], s;
    if (top && ms_view_mol_cov(w, top, c, &s)) {
        memcpy(v->last_center, c, sizeof c);
        v->last_scale = s;
    }
    ms_mat4_identity(v->axes_rotate);
    for (size_t i = 0; i < w->mols->n; i++) {
        ms_molecule *m = w->mols->mols[i];
        ms_mat4_identity(m->rotate);
        memset(m->global, 0, sizeof m->global);
        m->scale = v->last_scale;
        memcpy(m->center, v->last_center, sizeof m->center);
    }
}

/* ---------------------------------------------------------------- axes and stage */

static ms_rgba8 item_color(const ms_colors *c, const char *cat, const char *item)
{
    int id = ms_color_item_get(c, ms_color_category_index(c, cat), item);
    return ms_rgba8_from_float(ms_color_rgb(c, id < 0 ? 0 : id), 1.0f);
}

int ms_view_axes_list(const ms_view *v, const ms_colors *c, float aspect, ms_displaylist *dl,
                      float xform[16], ms_error *err)
{
    /* VMD's axes: rods of radius 0.12 to 0.85, cones of radius 0.25 to 1, a sphere at the
     * origin, labels at 1.35 x 0.85; drawn at a quarter size in a corner of the screen. */
    static const char *const item[3] = {"X", "Y", "Z"};
    static const char *const label[3] = {"x", "y", "z"};
    const float origin[3] = {0, 0, 0};
    int rc = 0;
    for (int a = 0; a < 3; a++) {
        float rod[3] = {0, 0, 0}, tip[3] = {0, 0, 0}, txt[3] = {0, 0, 0};
        rod[a] = 0.85f;
        tip[a] = 1.0f;
        txt[a] = 1.35f * 0.85f;
        ms_rgba8 col = item_color(c, "Axes", item[a]);
        rc |= ms_dl_cylinder(dl, origin, rod, 0.12f, col, 0, 32);
        rc |= ms_dl_cone(dl, rod, tip, 0.25f, 0.0f, col, 32);
        rc |= ms_dl_text(dl, txt, label[a], 1.0f, 1.0f, item_color(c, "Axes", "Labels"));
    }
    rc |= ms_dl_sphere(dl, origin, 0.12f, item_color(c, "Axes", "Origin"), 6);
    if (rc) {
        ms_error_set(err, "out of memory building the axes");
        return -1;
    }
    float x = 0, y = 0;
    switch (v->axes) {
    case MS_AXES_LOWERLEFT: x = -0.95f * aspect; y = -0.95f; break;
    case MS_AXES_LOWERRIGHT: x = 0.95f * aspect; y = -0.95f; break;
    case MS_AXES_UPPERLEFT: x = -0.95f * aspect; y = 0.95f; break;
    case MS_AXES_UPPERRIGHT: x = 0.95f * aspect; y = 0.95f; break;
    default: break;
    }
    float t[16], s[16];
    ms_mat4_translation(t, x, y, 0);
    ms_mat4_mul(t, v->axes_rotate, t);
    ms_mat4_scaling(s, 0.25f);
    ms_mat4_mul(t, s, xform);
    return 0;
}

int ms_view_stage_list(const ms_view *v, const ms_colors *c, ms_displaylist *dl,
                       float xform[16], ms_error *err)
{
    /* A checkerboard of panels x panels squares in the xz plane, 2 * size across. */
    int np = v->stage_panels;
    float size = v->stage_size, inc = 2.0f * size / (float)np;
    ms_rgba8 odd = item_color(c, "Stage", "Odd"), even = item_color(c, "Stage", "Even");
    const float up[9] = {0, 1, 0, 0, 1, 0, 0, 1, 0};
    if (ms_dl_mesh_reserve(dl, (size_t)np * np * 4, (size_t)np * np * 2, err)) return -1;
    for (int i = 0; i < np; i++)
        for (int j = 0; j < np; j++) {
            float x0 = -size + i * inc, z0 = -size + j * inc;
            ms_rgba8 col = (i + j) % 2 == 0 ? odd : even;
            float p[9] = {x0, 0, z0, x0, 0, z0 + inc, x0 + inc, 0, z0 + inc};
            float q[9] = {x0, 0, z0, x0 + inc, 0, z0 + inc, x0 + inc, 0, z0};
            ms_rgba8 cols[3] = {col, col, col};
            ms_dl_triangle(dl, p, up, cols);
            ms_dl_triangle(dl, q, up, cols);
        }
    float t[16], r[16];
    ms_mat4_identity(r);
    ms_mat4_translation(t, 0, 0, 0);
    switch (v->stage) {
    case MS_STAGE_BOTTOM: t[7] = -1; break;
    case MS_STAGE_TOP: t[7] = 1; break;
    case MS_STAGE_LEFT: t[3] = -1; ms_mat4_axis_rotation(r, 'z', ms_deg_rad(-90)); break;
    case MS_STAGE_RIGHT: t[3] = 1; ms_mat4_axis_rotation(r, 'z', ms_deg_rad(90)); break;
    case MS_STAGE_BEHIND: t[11] = -1; ms_mat4_axis_rotation(r, 'x', ms_deg_rad(90)); break;
    default: break;
    }
    ms_mat4_mul(t, r, xform);
    return 0;
}
