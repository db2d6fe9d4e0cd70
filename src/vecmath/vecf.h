/* vecf.h: 3-vectors and 4x4 matrices in single precision for the view, model and scene
 * transforms and the ray tracers: ms_v3f_* and ms_mat4_*, the float instance of
 * vec_tmpl.h (vecmath.h is the double one, ms_v3_* and ms_mat4d_*). */
#ifndef MS_VECF_H
#define MS_VECF_H

#define MS_T float
#define MS_T_SQRT sqrtf
#define MS_VEC(name) ms_v3f_##name
#define MS_MAT(name) ms_mat4_##name
#include "vecmath/vec_tmpl.h"

/* Degrees (as a float, the view's unit) to radians for ms_mat4_axis_rotation. */
static inline double ms_deg_rad(float deg) { return deg * M_PI / 180.0; }

#endif
