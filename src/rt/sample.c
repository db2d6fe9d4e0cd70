/* sample.c: where the samples go. Pixels: pass 0 at the centre, pass k at point k of the R2
 * low-discrepancy sequence (in 32-bit fixed point, exact for any pass count), rotated per
 * pixel so neighbours differ. Lenses: uniform on the disc. Ambient occlusion: n directions
 * of the hemisphere, uniform as Tachyon's (its uniform sphere directions flipped onto the
 * normal's side), but stratified: cos theta in n equal slices, azimuth spread by the golden
 * ratio (the azimuth turned by the golden angle from one direction to the next: four
 * multiplications instead of a sine and a cosine), the whole set rotated at random per
 * shaded point. Random numbers come from the pixel's own state (rt_rand), kept from pass to
 * pass.
 * src/oclrt/kernels.cl mirrors this file function by function for the OpenCL tracer: change
 * both together. */
#include "config.h"
#include "rt/rt_internal.h"

#include <math.h>

void rt_sample_pixel(uint32_t idx, int k, float *x, float *y)
{
    if (k == 0) {
        *x = *y = 0.5f;
        return;
    }
    uint32_t h1 = rt_hash2(idx, 0x51f15eu), h2 = rt_hash2(idx, 0x2545f491u);
    uint32_t u = h1 + (uint32_t)k * 3242174889u, v = h2 + (uint32_t)k * 2447445414u;
    *x = (float)(u >> 8) * (1.0f / 16777216.0f);
    *y = (float)(v >> 8) * (1.0f / 16777216.0f);
}

void rt_sample_disc(uint32_t *rng, float p[2])
{
    float r = sqrtf(rt_randf(rng)), a = 6.2831853f * rt_randf(rng);
    p[0] = r * cosf(a);
    p[1] = r * sinf(a);
}

/* The golden angle's rotation: azimuth i + 1 is azimuth i turned by 2 pi 0.618034. */
#define GOLDEN_COS (-0.73736883f)
#define GOLDEN_SIN (-0.67549035f)

void rt_hemisphere_init(rt_hemisphere *h, const float n[3], int count, uint32_t *rng)
{
    float a[3] = {1.0f, 0.0f, 0.0f};
    if (fabsf(n[0]) > 0.5f) a[0] = 0.0f, a[1] = 1.0f;
    for (int k = 0; k < 3; k++) h->n[k] = n[k];
    ms_v3f_cross(n, a, h->t);
    ms_v3f_normalize_rcp(h->t);
    ms_v3f_cross(n, h->t, h->b);
    h->count = count;
    h->i = 0;
    h->r1 = rt_randf(rng);
    float r2 = rt_randf(rng);
    h->cs = cosf(6.2831853f * r2);
    h->sn = sinf(6.2831853f * r2);
}

float rt_hemisphere_next(rt_hemisphere *h, float d[3])
{
    float u = ((float)h->i + h->r1) / (float)h->count;
    float r2 = 1.0f - u * u;    /* (not fmaxf: a libm call here) */
    float r = sqrtf(r2 > 0.0f ? r2 : 0.0f), cs = h->cs, sn = h->sn;
    for (int k = 0; k < 3; k++) d[k] = r * (cs * h->t[k] + sn * h->b[k]) + u * h->n[k];
    h->cs = cs * GOLDEN_COS - sn * GOLDEN_SIN;
    h->sn = sn * GOLDEN_COS + cs * GOLDEN_SIN;
    h->i++;
    return u;
}
