/* test_map.c: the source map (src/molscope.h) compiles with every module's header, the tables
 * it points to hold what they should (the render devices in `render list` order, the command
 * sets, the drawing methods), the world is made and freed without Tcl, and the application
 * is made by ms_app_new and freed by ms_app_free with its commands in place. */
#include "config.h"
#include "ms_test.h"
#include "molscope.h"

#include <string.h>

static void test_devices(void)
{
    t_suite = "map devices";
    static const char *const names[] = {"snapshot", "Tachyon", "TachyonInternal",
                                        "TachyonLOpenCLInternal", "TachyonLOptiXInternal",
                                        "POV3", "Wavefront", "Raster3D", "RenderMan", "STL",
                                        "VRML-2", "X3D"};
    int ok = ms_render_count() == MS_COUNTOF(names);
    for (size_t i = 0; ok && i < MS_COUNTOF(names); i++)
        ok = !strcmp(ms_render_device_at(i)->name, names[i]) && ms_render_device_at(i)->write;
    t_ok(ok, "the table lists %zu devices in VMD's render list order", ms_render_count());
    t_ok(ms_render_device_at(ms_render_count()) == NULL, "past the table: none");
    t_ok(ms_render_find("tachyoninternal") == &ms_render_tachyon_internal &&
             ms_render_find("SNAPSHOT") == &ms_gl_snapshot && !ms_render_find("nosuch"),
         "found by name, case-insensitively");
}

static void test_tables(void)
{
    t_suite = "map tables";
    size_t n = 0;
    while (ms_command_sets[n]) n++;
    t_ok(n >= 10, "the command sets end with NULL (%zu of them)", n);
    int ok = ms_rep_method_count() > 0;
    for (size_t i = 0; ok && i < ms_rep_method_count(); i++)
        ok = ms_rep_method_find(ms_rep_method_at(i)->name) == (int)i;
    t_ok(ok, "every drawing method is found by its name (%zu)", ms_rep_method_count());
}

static void test_world(void)
{
    t_suite = "map world";
    ms_molset mols;
    ms_world w;
    ms_error err = {{0}};
    ms_molset_init(&mols);
    if (!t_ok(ms_world_init(&w, &mols, &err) == 0, "made without Tcl%s%s", *err.msg ? ": " : "",
              err.msg))
        return;
    t_ok(w.colors && w.materials && w.view && w.renderers && w.reps && w.ugraphics_slot >= 0,
         "it holds the colours, materials, view, device settings, reps and graphics slot");
    t_ok(w.width == 512 && w.height == 512, "VMD's text-mode display size");
    ms_scene s;
    int rc = ms_world_build_scene(&w, &s, &err);
    t_ok(rc == 0 && s.width == 512 && s.nitems == 1 && w.scene_builds == 1 &&
             !memcmp(&s.settings, &w.view->settings, sizeof s.settings),
         "an empty world's scene: the axes alone, drawn with the view's settings");
    if (rc == 0) ms_scene_free(&s);
    ms_molset_free(&mols);
    ms_world_free(&w);
    t_ok(!w.colors && !w.view && !w.reps, "freed");
}

static void test_app(void)
{
    t_suite = "map application";
    ms_app *app = ms_app_new("test_map", ms_command_sets);
    if (!t_ok(app != NULL, "made by ms_app_new")) return;
    int rc = Tcl_Eval(app->interp, "list [molinfo num] [llength [render list]] [display get size]");
    t_ok(rc == TCL_OK && !strcmp(Tcl_GetStringResult(app->interp), "0 12 {512 512}"),
         "its commands answer from its world: %s", Tcl_GetStringResult(app->interp));
    rc = Tcl_Eval(app->interp, "display resize 64 48; display get size");
    t_ok(rc == TCL_OK && app->world.width == 64 && app->world.height == 48,
         "display resize changes the world's size");
    ms_app_free(app);
    app = ms_app_new("test_map", NULL);
    t_ok(app && Tcl_Eval(app->interp, "mol list") == TCL_ERROR && app->world.view,
         "with no command sets: the state without the commands");
    ms_app_free(app);
}

int main(void)
{
    test_devices();
    test_tables();
    test_world();
    test_app();
    return t_done();
}
