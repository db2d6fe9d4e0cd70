/* user.c: what the user geometries (cylinder.c, cone.c, ring.c) share: reading ray i of the
 * N-ray packets Embree hands their callbacks (N is 1 for the single rays molscope traces,
 * but any N works), and reporting a hit or an occlusion back (passing crossings that a clip
 * plane cut away, as Tachyon's clip groups do for shadow rays). The layout is Embree's
 * RTCRayHitN: twelve ray fields of N lanes each, then the hit fields. */
#include "config.h"
#include "rt/rt_internal.h"

#include <math.h>

enum { R_OX, R_OY, R_OZ, R_TNEAR, R_DX, R_DY, R_DZ, R_TIME, R_TFAR, R_MASK, R_ID, R_FLAGS,
       H_NGX, H_NGY, H_NGZ, H_U, H_V, H_PRIM, H_GEOM, H_INST };

void rt_user_hit(const struct RTCIntersectFunctionNArguments *args, unsigned i, float t)
{
    rt_user_hit_part(args, i, t, 0.0f);
}

void rt_user_hit_part(const struct RTCIntersectFunctionNArguments *args, unsigned i, float t,
                      float part)
{
    unsigned N = args->N;
    float *f = (float *)args->rayhit;
    unsigned *u = (unsigned *)args->rayhit;
    f[R_TFAR * N + i] = t;
    f[H_NGX * N + i] = 0.0f;      /* the shading code finds the normal from the hit point */
    f[H_NGY * N + i] = 0.0f;
    f[H_NGZ * N + i] = 1.0f;
    f[H_U * N + i] = part;
    f[H_V * N + i] = 0.0f;
    u[H_PRIM * N + i] = args->primID;
    u[H_GEOM * N + i] = args->geomID;
    u[H_INST * N + i] = args->context->instID[0];
}

void rt_user_block(const struct RTCOccludedFunctionNArguments *args, unsigned i, int nhits,
                   const float *t, const rt_uray *r)
{
    const rt_geom *g = args->geometryUserPtr;
    int kept = 0;
    for (int k = 0; k < nhits; k++) kept += !rt_geom_clipped(g, r->o, r->d, t[k]);
    if (!kept) return;
    if (g->transparent) {
        float op = rt_geom_opacity(g, args->primID, 0.0f, 0.0f);
        if (op < 1.0f) {
            float *f = &((rt_ctx *)args->context)->filter[r->id];
            for (int k = 0; k < kept; k++) *f *= 1.0f - op;
            return;
        }
    }
    ((float *)args->ray)[R_TFAR * args->N + i] = -INFINITY;
}

float rt_geom_opacity(const rt_geom *g, unsigned prim, float u, float v)
{
    float a;
    if (!g->alpha) return g->mat.opacity;
    if (g->kind == RT_MESH) {
        const uint32_t *t = g->tri + 3 * (size_t)prim;
        a = (1.0f - u - v) * g->color[t[0]].a + u * g->color[t[1]].a + v * g->color[t[2]].a;
    } else {
        a = g->color[prim].a;
    }
    return g->mat.opacity * a * (1.0f / 255.0f);
}

int rt_geom_clipped(const rt_geom *g, const float o[3], const float d[3], float t)
{
    if (!g->item || !g->item->nclip) return 0;
    float p[3] = {o[0] + t * d[0], o[1] + t * d[1], o[2] + t * d[2]}, w[3];
    if (!g->xf) return ms_scene_clipped(g->item, p);
    ms_mat4_point(g->xf, p, w);           /* a mesh: the ray in its instance's coordinates */
    return ms_scene_clipped(g->item, w);
}

/* Embree calls the filter with the ray in the geometry's coordinates (world space, or a
 * mesh's list under its instance) and its tfar at the crossing. */
void rt_occlusion_filter(const struct RTCFilterFunctionNArguments *args)
{
    const rt_geom *g = args->geometryUserPtr;
    const float *hit = (const float *)args->hit, *ray = (const float *)args->ray;
    unsigned N = args->N;
    for (unsigned i = 0; i < N; i++) {
        if (!args->valid[i]) continue;
        rt_uray r;
        rt_user_ray(ray, N, i, &r);
        if (rt_geom_clipped(g, r.o, r.d, r.tfar)) {
            args->valid[i] = 0;                       /* cut away: the traversal goes on */
            continue;
        }
        if (!g->transparent) continue;                /* an opaque geometry: it blocks */
        unsigned prim = ((const unsigned *)hit)[(H_PRIM - H_NGX) * N + i];
        float op = rt_geom_opacity(g, prim, hit[(H_U - H_NGX) * N + i], hit[(H_V - H_NGX) * N + i]);
        if (op >= 1.0f) continue;                     /* an opaque primitive: it blocks */
        ((rt_ctx *)args->context)->filter[r.id] *= 1.0f - op;
        args->valid[i] = 0;                           /* passed: the traversal goes on */
    }
}

/* Solve a t^2 + 2 b t + c = 0 (a > 0) as the stable formula does; 0 when there is no root. */
int rt_quadratic(float a, float b, float c, float *t0, float *t1)
{
    float disc = b * b - a * c;
    if (!(disc >= 0.0f)) return 0;
    float q = -(b + copysignf(sqrtf(disc), b));
    float r0 = c / q, r1 = q / a;
    if (q == 0.0f) r0 = r1;
    *t0 = fminf(r0, r1);
    *t1 = fmaxf(r0, r1);
    return 1;
}

void rt_bounds_empty(struct RTCBounds *b)
{
    b->lower_x = b->lower_y = b->lower_z = INFINITY;
    b->upper_x = b->upper_y = b->upper_z = -INFINITY;
}

RTCGeometry rt_user_geometry(rt_world *w, const rt_geom *g, RTCBoundsFunction bounds,
                             RTCIntersectFunctionN isect, RTCOccludedFunctionN occluded,
                             ms_error *err)
{
    RTCGeometry geom = rtcNewGeometry(w->dev, RTC_GEOMETRY_TYPE_USER);
    if (!geom) {
        if (!rt_device_check(w->dev, rt_prims[g->kind]->name, err))
            ms_error_set(err, "%s: out of memory", rt_prims[g->kind]->name);
        return NULL;
    }
    rtcSetGeometryUserPrimitiveCount(geom, (unsigned)g->n);
    rtcSetGeometryUserData(geom, (void *)g);
    rtcSetGeometryBoundsFunction(geom, bounds, (void *)g);
    rtcSetGeometryIntersectFunction(geom, isect);
    rtcSetGeometryOccludedFunction(geom, occluded);
    return geom;
}
