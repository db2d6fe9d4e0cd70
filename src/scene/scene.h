/* scene.h: the Scene, the one input of every device: the visible display lists with their
 * model-to-world transforms and resolved materials, VMD's camera, the lights, depth cueing,
 * the background (and gradient), shadow / ambient-occlusion / depth-of-field settings and
 * the image size. Devices never read a Molecule.
 *
 * VMD's camera: the eye at (0, 0, 2) looks down -z with +y up; the screen plane is at
 * z = distance (-2) and is `height` (6) tall. Perspective: a point projects through the eye
 * onto the screen plane. Orthographic: the visible height is height / 2 at every depth.
 *
 * A scene is assembled from the molecules, their reps and user graphics, the axes and the
 * stage by ms_world_build_scene (assemble/world.h); a device only reads it. */
#ifndef MS_SCENE_H
#define MS_SCENE_H

#include "scene/displaylist.h"
#include "scene/material.h"

#define MS_SCENE_LIGHTS 4

typedef enum ms_projection { MS_PROJ_PERSPECTIVE, MS_PROJ_ORTHOGRAPHIC } ms_projection;
typedef enum ms_cuemode { MS_CUE_LINEAR, MS_CUE_EXP, MS_CUE_EXP2 } ms_cuemode;

typedef struct ms_camera {
    ms_projection projection;
    float eye[3], dir[3], up[3];     /* (0,0,2), (0,0,-1), (0,1,0) */
    float height;                    /* screen height (display height) */
    float distance;                  /* z of the screen plane (display distance) */
    float near_clip, far_clip;
    float eyesep, focal_length;
    int dof;
    float dof_fnumber, dof_focaldist;
} ms_camera;

typedef struct ms_light {
    int on;
    float pos[3];                    /* direction towards the light (VMD's light position) */
    float color[3];
} ms_light;

/* How a scene is drawn: the camera and lights, background gradient, depth cueing, shadows and
 * ambient occlusion (VMD's `display` and `light` settings). The view (assemble/view.h) keeps
 * one and a built scene takes it whole. */
typedef struct ms_scene_settings {
    ms_camera cam;
    ms_light lights[MS_SCENE_LIGHTS];
    int bg_gradient;
    int depthcue;
    ms_cuemode cuemode;
    float cue_start, cue_end, cue_density;
    int shadows, ao;
    float ao_ambient, ao_direct;
} ms_scene_settings;

/* VMD's clip planes: each rep has six; a plane that is on cuts away the part of the rep on
 * the side its normal points to. */
#define MS_SCENE_CLIPS 6
enum { MS_CLIP_OFF = 0, MS_CLIP_ON = 1, MS_CLIP_SOLID = 2 };

typedef struct ms_clip {
    float center[3], normal[3];      /* in the coordinates the rep is drawn in */
    float color[3];                  /* of the cut, for MS_CLIP_SOLID */
    int mode;                        /* MS_CLIP_* */
} ms_clip;

/* A clip plane in world coordinates: a point p is kept when eq . (p, 1) >= 0. */
typedef struct ms_clip_plane {
    float eq[4];
    float color[3];
    int solid;                       /* the cut shows the plane's colour (MS_CLIP_SOLID) */
} ms_clip_plane;

/* One display list placed in the world. */
typedef struct ms_scene_item {
    const ms_displaylist *dl;
    float xform[16];                 /* model to world, row-major */
    ms_material mat;                 /* resolved (name not owned) */
    int nclip;                       /* the planes that are on */
    ms_clip_plane clip[MS_SCENE_CLIPS];
} ms_scene_item;

typedef struct ms_scene {
    int width, height;
    ms_scene_settings settings;
    float background[3];
    float bg_top[3], bg_bottom[3];
    int aa_samples, ao_samples;      /* filled in by the renderer that draws it */
    ms_scene_item *items;
    size_t nitems, capitems;
    ms_displaylist **owned;          /* lists made while building (axes, stage) */
    size_t nowned, capowned;
} ms_scene;

void ms_scene_init(ms_scene *s);
void ms_scene_free(ms_scene *s);

/* Place a display list (not copied: it must outlive the scene) with a transform. */
int ms_scene_add(ms_scene *s, const ms_displaylist *dl, const float xform[16],
                 const ms_materials *mats, ms_error *err);
/* Clip the item placed last by the planes of clips that are on (n of them, given in the
 * coordinates that model takes to the world). */
void ms_scene_clip_last(ms_scene *s, const ms_clip *clips, int n, const float model[16]);
/* Is a world point cut away by one of the item's planes? */
static inline int ms_scene_clipped(const ms_scene_item *it, const float p[3])
{
    for (int i = 0; i < it->nclip; i++) {
        const float *e = it->clip[i].eq;
        if (e[0] * p[0] + e[1] * p[1] + e[2] * p[2] + e[3] < 0.0f) return 1;
    }
    return 0;
}
/* A plane eq (a x + b y + c z + d = 0) carried by the transform m to the space m maps onto
 * (out = eq m^-1). Returns -1 (out the plane unchanged) when m is singular. */
int ms_plane_map(const float eq[4], const float m[16], float out[4]);

/* A new empty display list the scene owns (freed with it); NULL when memory runs out. Fill
 * it, then place it with ms_scene_add. */
ms_displaylist *ms_scene_new_list(ms_scene *s, ms_error *err);

/* Screen position of a world point: pixel x from the left, y from the top (pixel centres at
 * +0.5), and the depth along the view direction. Returns 0, or -1 when the point is at or
 * behind the eye (perspective). */
int ms_scene_project(const ms_scene *s, const float world[3], float *px, float *py, float *depth);
/* World-space size of one pixel at a given depth (distance along the view direction). */
float ms_scene_pixel_size(const ms_scene *s, float depth);

#endif
