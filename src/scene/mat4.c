/* mat4.c: 4x4 row-major matrix helpers. */
#include "config.h"
#include "scene/mat4.h"

#include <math.h>
#include <string.h>

void ms_mat4_identity(float m[16])
{
    memset(m, 0, 16 * sizeof(float));
    m[0] = m[5] = m[10] = m[15] = 1.0f;
}

void ms_mat4_mul(const float a[16], const float b[16], float out[16])
{
    float t[16];
    for (int r = 0; r < 4; r++)
        for (int c = 0; c < 4; c++) {
            double s = 0;
            for (int k = 0; k < 4; k++) s += (double)a[4 * r + k] * b[4 * k + c];
            t[4 * r + c] = (float)s;
        }
    memcpy(out, t, sizeof t);
}

void ms_mat4_translation(float m[16], float x, float y, float z)
{
    ms_mat4_identity(m);
    m[3] = x;
    m[7] = y;
    m[11] = z;
}

void ms_mat4_scaling(float m[16], float s)
{
    ms_mat4_identity(m);
    m[0] = m[5] = m[10] = s;
}

void ms_mat4_rotation(float m[16], char axis, float deg)
{
    double a = deg * M_PI / 180.0;
    float c = (float)cos(a), s = (float)sin(a);
    ms_mat4_identity(m);
    switch (axis) {
    case 'x': case 'X':
        m[5] = c; m[6] = -s; m[9] = s; m[10] = c;
        break;
    case 'y': case 'Y':
        m[0] = c; m[2] = s; m[8] = -s; m[10] = c;
        break;
    default:
        m[0] = c; m[1] = -s; m[4] = s; m[5] = c;
        break;
    }
}

void ms_mat4_point(const float m[16], const float in[3], float out[3])
{
    float x = in[0], y = in[1], z = in[2];
    for (int r = 0; r < 3; r++)
        out[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z + m[4 * r + 3];
}

void ms_mat4_normal(const float m[16], const float in[3], float out[3])
{
    float x = in[0], y = in[1], z = in[2], v[3];
    for (int r = 0; r < 3; r++) v[r] = m[4 * r] * x + m[4 * r + 1] * y + m[4 * r + 2] * z;
    float len = sqrtf(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    float inv = len > 0 ? 1.0f / len : 0.0f;
    for (int r = 0; r < 3; r++) out[r] = v[r] * inv;
}

float ms_mat4_scale_factor(const float m[16])
{
    double det = m[0] * ((double)m[5] * m[10] - (double)m[6] * m[9]) -
                 m[1] * ((double)m[4] * m[10] - (double)m[6] * m[8]) +
                 m[2] * ((double)m[4] * m[9] - (double)m[5] * m[8]);
    return (float)cbrt(fabs(det));
}
