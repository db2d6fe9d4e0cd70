/* cmd_state.c: `save_state <file>`: the session as a VMD state script, laid out as VMD's
 * save_state writes it, so that VMD or molscope (`molscope -e file`, `play`, `source`)
 * rebuilds it: the materials, the display settings and lights, every molecule with its
 * files, its reps (every setting, the six clip planes of each included), its user graphics
 * (`graphics top ...`, as `graphics info` describes each item), its name and view matrices,
 * the top molecule, the colours and colour scale (the three colours of every blended
 * method included), the display size, and the labels. */
#include "config.h"
#include "assemble/view.h"
#include "base/safewrite.h"
#include "commands/scenecmds.h"
#include "vecmath/vecf.h"

#include <stdio.h>
#include <string.h>

/* A word as a Tcl list element (braced or escaped when it needs to be). */
static void word(FILE *f, const char *s)
{
    Tcl_Obj *e = Tcl_NewStringObj(s, -1), *l = Tcl_NewListObj(1, &e);
    Tcl_IncrRefCount(l);
    fputs(*s ? Tcl_GetString(l) : "{}", f);
    Tcl_DecrRefCount(l);
}

static void vec3(FILE *f, const float v[3])
{
    fprintf(f, "{%.9g %.9g %.9g}", v[0], v[1], v[2]);
}

static void materials(FILE *f, const ms_materials *mats)
{
    fputs("proc vmdrestoremymaterials {} {\n  set mlist { ", f);
    for (size_t i = 0; i < mats->n; i++) fprintf(f, "%s ", mats->list[i].name);
    fputs("}\n  set mymlist [material list]\n  foreach mat $mlist {\n"
          "    if { [lsearch $mymlist $mat] == -1 } {\n      material add $mat\n    }\n  }\n", f);
    for (size_t i = 0; i < mats->n; i++) {
        const ms_material *m = &mats->list[i];
        const struct { const char *name; float v; } p[] = {
            {"ambient", m->ambient}, {"diffuse", m->diffuse}, {"specular", m->specular},
            {"shininess", ms_material_shininess_to_ui(m->shininess)}, {"mirror", m->mirror}, {"opacity", m->opacity},
            {"outline", m->outline}, {"outlinewidth", m->outlinewidth},
            {"transmode", m->transmode}};
        for (size_t k = 0; k < MS_COUNTOF(p); k++)
            fprintf(f, "  material change %s %s %f\n", p[k].name, m->name, p[k].v);
    }
    fputs("}\nvmdrestoremymaterials\n", f);
}

static const char *onoff(int v)
{
    return v ? "on" : "off";
}

static void display(FILE *f, const ms_world *w)
{
    const ms_view *v = w->view;
    const ms_scene_settings *s = &v->settings;
    fputs("# Display settings\n", f);
    fprintf(f, "display resize %d %d\n", w->width, w->height);
    fprintf(f, "display eyesep       %f\ndisplay focallength  %f\n", s->cam.eyesep, s->cam.focal_length);
    fprintf(f, "display height       %f\ndisplay distance     %f\n", s->cam.height, s->cam.distance);
    fprintf(f, "display projection   %s\n", ms_projection_name(s->cam.projection));
    fprintf(f, "display nearclip set %f\ndisplay farclip  set %f\n", s->cam.near_clip, s->cam.far_clip);
    fprintf(f, "display depthcue   %s\ndisplay cuestart   %f\ndisplay cueend     %f\n",
            onoff(s->depthcue), s->cue_start, s->cue_end);
    fprintf(f, "display cuedensity %f\ndisplay cuemode    %s\n", s->cue_density,
            ms_cuemode_name(s->cuemode));
    fprintf(f, "display shadows %s\ndisplay ambientocclusion %s\n", onoff(s->shadows), onoff(s->ao));
    fprintf(f, "display aoambient %f\ndisplay aodirect %f\n", s->ao_ambient, s->ao_direct);
    fprintf(f, "display dof %s\ndisplay dof_fnumber %f\ndisplay dof_focaldist %f\n", onoff(s->cam.dof),
            s->cam.dof_fnumber, s->cam.dof_focaldist);
    fprintf(f, "display backgroundgradient %s\n", onoff(s->bg_gradient));
    fprintf(f, "display rendermode %s\n", v->rendermode);
    fprintf(f, "display antialias %s\ndisplay culling %s\n", onoff(v->antialias), onoff(v->culling));
    fprintf(f, "axes location %s\nstage location %s\nstage panels %d\nstage size %f\n",
            ms_axes_loc_name(v->axes), ms_stage_loc_name(v->stage), v->stage_panels, v->stage_size);
    for (int i = 0; i < MS_SCENE_LIGHTS; i++) {
        fprintf(f, "light %d %s\nlight %d pos ", i, onoff(s->lights[i].on), i);
        vec3(f, s->lights[i].pos);
        fputc('\n', f);
    }
}

static void clip_planes(FILE *f, const ms_rep *r, size_t i)
{
    for (int k = 0; k < MS_SCENE_CLIPS; k++) {
        const ms_clip *c = &r->clip[k];
        fprintf(f, "mol clipplane center %d %zu top ", k, i);
        vec3(f, c->center);
        fprintf(f, "\nmol clipplane color  %d %zu top ", k, i);
        vec3(f, c->color);
        fprintf(f, "\nmol clipplane normal %d %zu top ", k, i);
        vec3(f, c->normal);
        fprintf(f, "\nmol clipplane status %d %zu top {%d}\n", k, i, c->mode);
    }
}

static void rep(FILE *f, ms_rep_state *reps, const ms_rep *r, size_t i)
{
    char periodic[8];
    fprintf(f, "mol representation %s\nmol color %s\nmol selection ",
            ms_rep_text(reps, r, MS_REP_STYLE), ms_rep_text(reps, r, MS_REP_COLOR));
    fputc('{', f);
    fputs(ms_rep_text(reps, r, MS_REP_SELECTION), f);
    fprintf(f, "}\nmol material %s\nmol addrep top\n", ms_rep_text(reps, r, MS_REP_MATERIAL));
    fprintf(f, "mol selupdate %zu top %d\nmol colupdate %zu top %d\n", i, r->selupdate, i, r->colupdate);
    if (r->range_auto) fprintf(f, "mol scaleminmax top %zu auto\n", i);
    else fprintf(f, "mol scaleminmax top %zu %f %f\n", i, r->cmin, r->cmax);
    fprintf(f, "mol smoothrep top %zu %d\nmol drawframes top %zu ", i, r->smooth, i);
    word(f, r->frames);
    ms_rep_periodic_text(r, periodic);
    fprintf(f, "\nmol showperiodic top %zu %s\nmol numperiodic top %zu %d\n", i, periodic, i, r->npbc);
    clip_planes(f, r, i);
    if (!r->shown) fprintf(f, "mol showrep top %zu 0\n", i);
}

/* The molecule's user graphics as `graphics top` commands, in order (places kept for
 * `replace` are left out). */
static void graphics(FILE *f, ms_world *w, const ms_molecule *m)
{
    const ms_ugraphics *g = w->ugraphics_slot >= 0 ? m->ext[w->ugraphics_slot] : NULL;
    char buf[1024];
    for (size_t i = 0; g && i < g->n; i++) {
        const ms_ug_item *it = &g->items[i];
        if (it->kind == MS_UG_NONE) continue;
        if (it->kind == MS_UG_TEXT) {   /* the text as one Tcl word, whatever it holds */
            fputs("graphics top text ", f);
            vec3(f, it->data);
            fputc(' ', f);
            word(f, it->text ? it->text : "");
            fprintf(f, " size %f thickness %f\n", it->size, it->thickness);
            continue;
        }
        if (it->kind == MS_UG_MATERIAL) {   /* by name, as VMD's command takes it */
            fputs("graphics top material ", f);
            word(f, ms_material_by_id(w->materials, it->iv[0])->name);
            fputc('\n', f);
            continue;
        }
        ms_ugraphics_info(g, (long)i, w->materials, buf, sizeof buf);
        fprintf(f, "graphics top %s\n", buf);
    }
}

static void matrix(FILE *f, const float m[16])
{
    fputc('{', f);
    for (int r = 0; r < 4; r++)
        fprintf(f, "%s{%.9g %.9g %.9g %.9g}", r ? " " : "", m[4 * r], m[4 * r + 1], m[4 * r + 2], m[4 * r + 3]);
    fputc('}', f);
}

static void molecule(FILE *f, ms_app *app, const ms_molecule *m)
{
    ms_rep_state *reps = app->world.reps;
    fprintf(f, "# molecule %d\n", m->id);
    for (size_t i = 0; i < m->nfiles; i++) {
        fputs(i ? "mol addfile " : "mol new ", f);
        word(f, m->files[i].path);
        fprintf(f, " type %s first 0 last -1 step 1 waitfor all%s\n", m->files[i].type, i ? " top" : "");
    }
    if (!m->nfiles) fputs("mol new\n", f);
    fputs("mol delrep 0 top\n", f);
    for (size_t i = 0; i < ms_rep_count(reps, m); i++) rep(f, reps, ms_rep_get(reps, m, (long)i), i);
    graphics(f, &app->world, m);
    fputs("mol rename top ", f);
    word(f, m->name ? m->name : "");
    float c[16], s[16], g[16];
    ms_mat4_translation(c, -m->center[0], -m->center[1], -m->center[2]);
    ms_mat4_scaling(s, m->scale);
    ms_mat4_translation(g, m->global[0], m->global[1], m->global[2]);
    fputs("\nset viewpoints([molinfo top]) {", f);
    matrix(f, c), fputc(' ', f), matrix(f, m->rotate), fputc(' ', f), matrix(f, s), fputc(' ', f);
    matrix(f, g);
    fprintf(f, "}\nlappend viewplist [molinfo top]\nset molid_of(%d) [molinfo top]\n", m->id);
    if (m->fixed) fputs("lappend fixedlist [molinfo top]\n", f);
    if (!m->active) fputs("mol inactive top\n", f);
    if (!m->displayed) fputs("mol off top\n", f);
    fprintf(f, "# done with molecule %d\n", m->id);
}

static void colors(FILE *f, const ms_colors *c)
{
    fputs("proc vmdrestoremycolors {} {\n", f);
    for (int k = 0; k < MS_COLOR_SCALE_METHODS; k++) {
        if (c->methods[k].map) continue;   /* a perceptual table: not three colours */
        fprintf(f, "  color scale colors %s", c->methods[k].name);
        for (int i = 0; i < 3; i++) fputc(' ', f), vec3(f, c->methods[k].rgb[i]);
        fputc('\n', f);
    }
    fprintf(f, "  color scale method %s\n  color scale midpoint %f\n  color scale min %f\n"
               "  color scale max %f\n", c->methods[c->method].name, c->scale_mid,
            c->scale_min, c->scale_max);
    for (int i = 0; i < 33; i++)
        fprintf(f, "  color change rgb %d %f %f %f\n", i, c->rgb[i][0], c->rgb[i][1], c->rgb[i][2]);
    for (size_t k = 0; k < c->ncats; k++)
        for (size_t i = 0; i < c->cats[k].n; i++) {
            const char *name = ms_color_name(c->cats[k].items[i].color);
            if (!c->cats[k].items[i].name[0]) continue;   /* no command can name it */
            /* in a catch: items of molecules deleted before the save are not there */
            fputs("  catch {color ", f);
            word(f, c->cats[k].name);
            fputc(' ', f);
            word(f, c->cats[k].items[i].name);
            if (name) fprintf(f, " %s}\n", name);
            else fprintf(f, " %d}\n", c->cats[k].items[i].color);
        }
    fputs("}\nvmdrestoremycolors\n", f);
}

static void labels(FILE *f, const ms_labels *L)
{
    fprintf(f, "label textsize %f\nlabel textthickness %f\n", L->size, L->thickness);
    for (int c = 0; c < MS_LABEL_NCATS; c++)
        for (size_t i = 0; i < L->n[c]; i++) {
            const ms_label *l = &L->v[c][i];
            fprintf(f, "label add %s", ms_label_cat_name(c));
            for (int k = 0; k < l->n; k++) fprintf(f, " $molid_of(%d)/%u", l->mol[k], l->atom[k]);
            fputc('\n', f);
        }
}

static void state(FILE *f, ms_app *app)
{
    ms_world *w = &app->world;
    fprintf(f, "#!/usr/local/bin/vmd\n# VMD script written by save_state (molscope %s)\n"
               "set viewplist {}\nset fixedlist {}\narray set molid_of {}\n", PACKAGE_VERSION);
    materials(f, w->materials);
    display(f, w);
    const ms_molecule *top = ms_molset_top(w->mols);
    for (size_t i = 0; i < w->mols->n; i++) {
        molecule(f, app, w->mols->mols[i]);
        if (w->mols->mols[i] == top) fputs("set topmol [molinfo top]\n", f);
    }
    fputs("foreach v $viewplist {\n  molinfo $v set {center_matrix rotate_matrix scale_matrix "
          "global_matrix} $viewpoints($v)\n}\nforeach v $fixedlist {\n  mol fix $v\n}\n"
          "unset viewplist\nunset fixedlist\n", f);
    if (top) fputs("mol top $topmol\nunset topmol\n", f);
    colors(f, w->colors);
    labels(f, &w->labels);
    fputs("array unset molid_of\n", f);
}

static int save_state(ms_app *app, Tcl_Interp *interp, int objc, Tcl_Obj *const objv[])
{
    ms_error err = {{0}};
    ms_ofile *out;
    FILE *f = ms_ofile_open_stream(Tcl_GetString(objv[1]), &out, &err);
    if (!f) return ms_cmd_error(interp, "save_state: %s", err.msg);
    state(f, app);
    if (ms_ofile_commit(out, &err)) return ms_cmd_error(interp, "save_state: %s", err.msg);
    return TCL_OK;
}

void ms_cmd_state_register(ms_app *app)
{
    static const ms_subcmd spec = {"save_state", save_state, 1, 1, "<file>"};
    ms_cmd_create(app, &spec);
}
