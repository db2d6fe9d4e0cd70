/* clip.c: cutting geometry by a scene item's clip planes, for file formats that have no clip
 * planes of their own (Wavefront): a triangle becomes the polygon left on the kept side of
 * every plane, fanned into triangles (normals interpolated along the cut edges); a segment is
 * shortened to its kept part. */
#include "config.h"
#include "render/export.h"

#include <string.h>

#define MAXV (3 + MS_SCENE_CLIPS)

static float side(const float eq[4], const float p[3])
{
    return eq[0] * p[0] + eq[1] * p[1] + eq[2] * p[2] + eq[3];
}

/* One Sutherland-Hodgman step: the polygon (p, n: nv vertices) on the kept side of eq. */
static int clip_poly(const float eq[4], float p[][3], float n[][3], int nv, float op[][3],
                     float on[][3])
{
    int m = 0;
    for (int i = 0; i < nv; i++) {
        int j = (i + 1) % nv;
        float di = side(eq, p[i]), dj = side(eq, p[j]);
        if (di >= 0.0f) {
            memcpy(op[m], p[i], sizeof op[m]);
            memcpy(on[m++], n[i], sizeof on[m]);
        }
        if ((di >= 0.0f) != (dj >= 0.0f)) {
            float t = di / (di - dj);
            for (int k = 0; k < 3; k++) {
                op[m][k] = p[i][k] + t * (p[j][k] - p[i][k]);
                on[m][k] = n[i][k] + t * (n[j][k] - n[i][k]);
            }
            m++;
        }
    }
    return m;
}

void ms_export_clip_tri(const ms_scene_item *it, const float p[9], const float n[9],
                        ms_tri_cb cb, void *ud)
{
    if (!it->nclip) {
        cb(ud, p, n);
        return;
    }
    float pa[MAXV][3], na[MAXV][3], pb[MAXV][3], nb[MAXV][3];
    memcpy(pa, p, 9 * sizeof(float));
    memcpy(na, n, 9 * sizeof(float));
    int nv = 3;
    for (int i = 0; i < it->nclip && nv >= 3; i++) {
        nv = clip_poly(it->clip[i].eq, pa, na, nv, pb, nb);
        memcpy(pa, pb, sizeof pa);
        memcpy(na, nb, sizeof na);
    }
    for (int i = 1; i + 1 < nv; i++) {
        float tp[9], tn[9];
        const int v[3] = {0, i, i + 1};
        for (int k = 0; k < 3; k++) {
            memcpy(tp + 3 * k, pa[v[k]], 3 * sizeof(float));
            memcpy(tn + 3 * k, na[v[k]], 3 * sizeof(float));
        }
        cb(ud, tp, tn);
    }
}

int ms_export_clip_seg(const ms_scene_item *it, float a[3], float b[3])
{
    for (int i = 0; i < it->nclip; i++) {
        float da = side(it->clip[i].eq, a), db = side(it->clip[i].eq, b);
        if (da < 0.0f && db < 0.0f) return 0;
        if (da >= 0.0f && db >= 0.0f) continue;
        float t = da / (da - db), q[3];
        for (int k = 0; k < 3; k++) q[k] = a[k] + t * (b[k] - a[k]);
        memcpy(da < 0.0f ? a : b, q, sizeof q);
    }
    return 1;
}
