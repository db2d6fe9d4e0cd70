/* view.h: the view and display state and VMD's semantics for changing it: the camera and
 * display settings (`display ...`) and the lights (the scene settings a built scene takes
 * whole), the axes and the stage, and the transforms that rotate / translate / scale / rock
 * / rotmat / resetview make on the world's molecules (world.h).
 *
 * VMD's rules: rotations are pre-multiplied into every non-fixed molecule's rotate matrix
 * (so they turn about the screen axes) and into the axes; translate and scale act on each
 * non-fixed molecule's global translation and scale; resetview centres every molecule on the
 * top molecule and scales so its largest extent spans 1.5 units. Defaults are VMD's text
 * mode (depth cueing off). */
#ifndef MS_VIEW_H
#define MS_VIEW_H

#include "assemble/world.h"
#include "scene/color.h"
#include "scene/displaylist.h"
#include "scene/scene.h"

typedef enum ms_axes_loc {
    MS_AXES_OFF, MS_AXES_ORIGIN, MS_AXES_LOWERLEFT, MS_AXES_LOWERRIGHT, MS_AXES_UPPERLEFT,
    MS_AXES_UPPERRIGHT, MS_AXES_NLOCS
} ms_axes_loc;

typedef enum ms_stage_loc {
    MS_STAGE_OFF, MS_STAGE_ORIGIN, MS_STAGE_BOTTOM, MS_STAGE_TOP, MS_STAGE_LEFT, MS_STAGE_RIGHT,
    MS_STAGE_BEHIND, MS_STAGE_NLOCS
} ms_stage_loc;

typedef struct ms_view {
    ms_scene_settings settings;  /* what a scene built now is drawn with */
    int light_highlight[MS_SCENE_LIGHTS];
    int antialias, culling, fps, stereoswap, update;
    char stereo[16], rendermode[16], cachemode[16];
    ms_axes_loc axes;
    float axes_rotate[16];       /* the rotations the axes received */
    ms_stage_loc stage;
    int stage_panels;
    float stage_size;
    char rock_axis;              /* '\0' when not rocking */
    float rock_step;
    int rock_steps, rock_count;
    float last_center[3], last_scale;   /* what the last resetview used */
} ms_view;

ms_view *ms_view_new(void);
void ms_view_free(ms_view *v);
/* VMD's default direction of light n (0..3). */
const float *ms_view_default_light(int n);

const char *ms_axes_loc_name(ms_axes_loc l);
int ms_axes_loc_from_name(const char *s);         /* -1 when unknown */
const char *ms_stage_loc_name(ms_stage_loc l);
int ms_stage_loc_from_name(const char *s);
const char *ms_cuemode_name(ms_cuemode m);
int ms_cuemode_from_name(const char *s);
const char *ms_projection_name(ms_projection p);
int ms_projection_from_name(const char *s);

/* A molecule's model-to-world matrix: global * rotate * scale * center. */
void ms_view_mol_model(const ms_molecule *m, float out[16]);

/* rotate x|y|z by deg: pre-multiplied into every non-fixed molecule and the axes. */
void ms_view_rotate_by(ms_world *w, char axis, float deg);
/* rotate x|y|z to deg: every non-fixed molecule's rotation becomes that one rotation. */
void ms_view_rotate_to(ms_world *w, char axis, float deg);
/* rotmat by|to with a 4x4 rotation (row-major). */
void ms_view_rotmat(ms_world *w, const float r[16], int by);
void ms_view_translate(ms_world *w, float x, float y, float z, int by);
/* scale by|to s (s > 0; returns -1 otherwise). */
int ms_view_scale(ms_world *w, float s, int by);
/* rock: start (steps < 0: forever) or stop (axis '\0'); ms_view_rock_step advances it. */
void ms_view_rock(ms_world *w, char axis, float step, int steps);
void ms_view_rock_step(ms_world *w);

/* VMD's centre of a molecule's displayed atoms (its shown reps' atoms, else all its atoms)
 * and the scale 1.5 / largest extent (single atom: 0.5), else of its volumes' boxes, else of
 * its user graphics. Returns 0 when the molecule has none of them. */
int ms_view_mol_cov(ms_world *w, ms_molecule *m, float center[3], float *scale);
/* display resetview: reset the axes and every molecule's transform, centred on the top
 * molecule (or on the last centre when it has nothing to centre on). */
void ms_view_reset(ms_world *w);

/* Geometry of the axes and the stage in world coordinates; the aspect ratio places the axes
 * in their corner. Append to dl (which the caller placed with an identity transform). */
int ms_view_axes_list(const ms_view *v, const ms_colors *c, float aspect, ms_displaylist *dl,
                      float xform[16], ms_error *err);
int ms_view_stage_list(const ms_view *v, const ms_colors *c, ms_displaylist *dl,
                       float xform[16], ms_error *err);

#endif
