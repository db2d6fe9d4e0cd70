/* camera.c: VMD's camera as the ray tracer sees it, matching ms_scene_project exactly. The
 * eye looks along dir with up; perspective rays leave the eye through a screen `distance`
 * away (eye z minus the display's distance) and `height` tall; orthographic rays run
 * parallel to dir from the eye plane, through a view height / 2 tall. Depth of field (VMD's
 * dof_focaldist and dof_fnumber, perspective only) jitters the origin over a lens and aims
 * at the point focal-distance along the pinhole ray, as Tachyon does; the lens radius is
 * Tachyon's for the aperture the exporter writes (focal distance / (2 f-number), sampled over
 * a disc of half that radius).
 * src/oclrt/kernels.cl mirrors this file function by function for the OpenCL tracer: change
 * both together. */
#include "config.h"
#include "rt/rt_common.h"

#include <math.h>

void rt_camera_init(rt_camera *c, const ms_scene *s)
{
    const ms_camera *m = &s->settings.cam;
    c->ortho = m->projection == MS_PROJ_ORTHOGRAPHIC;
    c->width = s->width;
    c->height = s->height;
    for (int k = 0; k < 3; k++) {
        c->eye[k] = m->eye[k];
        c->dir[k] = m->dir[k];
        c->up[k] = m->up[k];
    }
    ms_v3f_normalize_rcp(c->dir);
    ms_v3f_cross(c->dir, c->up, c->right);
    ms_v3f_normalize_rcp(c->right);
    ms_v3f_cross(c->right, c->dir, c->up);
    float aspect = (float)s->width / (float)s->height;
    float screen = m->eye[2] - m->distance;
    c->half_h = c->ortho ? m->height / 4.0f : (m->height / 2.0f) / screen;
    c->half_w = c->half_h * aspect;
    c->dof = !c->ortho && m->dof && m->dof_fnumber > 0 && m->dof_focaldist > 0;
    c->focal = m->dof_focaldist;
    c->lens_radius = c->dof ? 0.5f * m->dof_focaldist / (2.0f * m->dof_fnumber) : 0.0f;
}

void rt_camera_ray(const rt_camera *c, float px, float py, const float lens[2], float org[3],
                   float dir[3])
{
    float sx = (2.0f * px / (float)c->width - 1.0f) * c->half_w;
    float sy = (1.0f - 2.0f * py / (float)c->height) * c->half_h;
    if (c->ortho) {
        for (int k = 0; k < 3; k++) {
            org[k] = c->eye[k] + sx * c->right[k] + sy * c->up[k];
            dir[k] = c->dir[k];
        }
        return;
    }
    for (int k = 0; k < 3; k++) {
        org[k] = c->eye[k];
        dir[k] = c->dir[k] + sx * c->right[k] + sy * c->up[k];
    }
    ms_v3f_normalize_rcp(dir);
    if (!lens || !c->dof) return;
    float focus[3];
    for (int k = 0; k < 3; k++) {
        focus[k] = org[k] + c->focal * dir[k];
        org[k] += c->lens_radius * (lens[0] * c->right[k] + lens[1] * c->up[k]);
        dir[k] = focus[k] - org[k];
    }
    ms_v3f_normalize_rcp(dir);
}
