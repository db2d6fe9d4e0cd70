/* mat4.h: 4x4 row-major matrices for the view and model transforms (VMD's molinfo matrices
 * are written in the same row-major order). Points are column vectors: p' = M p. */
#ifndef MS_MAT4_H
#define MS_MAT4_H

void ms_mat4_identity(float m[16]);
/* out = a * b (out may alias a or b). */
void ms_mat4_mul(const float a[16], const float b[16], float out[16]);
void ms_mat4_translation(float m[16], float x, float y, float z);
void ms_mat4_scaling(float m[16], float s);
/* A right-handed rotation by deg degrees about the x, y or z axis ('x', 'y', 'z'). */
void ms_mat4_rotation(float m[16], char axis, float deg);
/* Transform a point (w = 1) and a direction (w = 0, then normalised). */
void ms_mat4_point(const float m[16], const float in[3], float out[3]);
void ms_mat4_normal(const float m[16], const float in[3], float out[3]);
/* The factor by which m scales lengths (cube root of the 3x3 determinant's magnitude). */
float ms_mat4_scale_factor(const float m[16]);

#endif
