/* params.h: the layout of the OpenCL tracer's parameter block, shared by the host (frame.c)
 * and the kernels (kernels.cl is compiled with this file in front of it): one float array,
 * whole numbers stored exactly as floats. It holds what rt/shade.c keeps in its rt_shader
 * and rt_camera, plus the sizes of the device buffers and whether any item has clip planes
 * (P_CLIPPED: else the kernels skip the clip test). Valid C and OpenCL C. */
#ifndef MS_OCLRT_PARAMS_H
#define MS_OCLRT_PARAMS_H

#define ORC_LIGHTS 4                /* MS_SCENE_LIGHTS */

/* an item (a placed list) in float4s: its normal matrix in three rows (w of the first: the
 * sign of the transform's determinant), then its clip planes (a point p is cut away when
 * eq . (p, 1) < 0; MS_SCENE_CLIPS of them at most, in world space), then their colours (w:
 * 1 for a solid cut, VMD's status 2) */
#define ORC_CLIPS 6                 /* MS_SCENE_CLIPS */
#define ORC_ITEM_PLANES 3
#define ORC_ITEM_COLORS (ORC_ITEM_PLANES + ORC_CLIPS)
#define ORC_ITEM (ORC_ITEM_COLORS + ORC_CLIPS)

/* primitive kinds, in the top bits of a leaf reference */
#define ORC_SPHERE 0u
#define ORC_CYLINDER 1u
#define ORC_CONE 2u
#define ORC_RING 3u
#define ORC_TRIANGLE 4u
#define ORC_KIND_SHIFT 29u
#define ORC_INDEX_MASK 0x1fffffffu

enum {
    P_WIDTH, P_HEIGHT, P_ORTHO, P_DOF, P_FOCAL, P_LENS_RADIUS, P_HALF_W, P_HALF_H,
    P_EYE, P_DIR = P_EYE + 3, P_UP = P_DIR + 3, P_RIGHT = P_UP + 3,
    P_NLIGHTS = P_RIGHT + 3, P_LDIR, P_LCOL = P_LDIR + 3 * ORC_LIGHTS,
    P_LIGHT_SCALE = P_LCOL + 3 * ORC_LIGHTS, P_FULL, P_AO_SAMPLES, P_AO_COL,
    P_BG_MODE = P_AO_COL + 3, P_BG, P_BG_TOP = P_BG + 3, P_BG_BOT = P_BG_TOP + 3,
    P_GRAD_TOP = P_BG_BOT + 3, P_GRAD_BOT, P_FOG, P_CUEMODE, P_FOG_START, P_FOG_END,
    P_FOG_DENSITY, P_EPS, P_DEPTH, P_NNODES, P_CLIPPED, P_COUNT
};

/* background modes and cue modes, as rt_bg_mode and ms_cuemode number them */
#define ORC_BG_SOLID 0
#define ORC_BG_SKY_SPHERE 1
#define ORC_BG_SKY_PLANE 2
#define ORC_CUE_LINEAR 0
#define ORC_CUE_EXP 1
#define ORC_CUE_EXP2 2

#endif
