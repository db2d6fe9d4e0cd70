/* device.c: the Embree device the ray tracer shares for the whole process (as many threads
 * as molscope's own pool: MOLSCOPE_THREADS), its error reports, a memory budget enforced through Embree's
 * memory monitor (so a scene too large for memory fails its build instead of the process),
 * and the floating-point mode of rendering threads. */
#include "config.h"
#include "rt/rt_internal.h"
#include "base/threads.h"

#include <pthread.h>
#include <stdatomic.h>
#include <stdio.h>
#include <string.h>
#include <xmmintrin.h>

static pthread_once_t once = PTHREAD_ONCE_INIT;
static RTCDevice device;
static char start_error[256];

static atomic_llong held;            /* bytes Embree holds */
static atomic_llong peak;            /* the most it held since the last reset */
static atomic_llong budget;          /* 0: no limit */
static atomic_int denied;            /* an allocation was refused */
static __thread char last_error[256];

static void on_error(void *user, enum RTCError code, const char *str)
{
    snprintf(last_error, sizeof last_error, "%s", str ? str : "unknown Embree error");
}

/* Embree's memory monitor: refuse an allocation that would pass the budget. */
static bool on_memory(void *user, ssize_t bytes, bool post)
{
    long long now = atomic_fetch_add(&held, (long long)bytes) + bytes;
    long long limit = atomic_load(&budget);
    if (bytes > 0 && !post && limit > 0 && now > limit) {
        atomic_fetch_sub(&held, (long long)bytes);
        atomic_store(&denied, 1);
        return false;
    }
    for (long long p = atomic_load(&peak); now > p && !atomic_compare_exchange_weak(&peak, &p, now);)
        ;
    return true;
}

/* As many threads as molscope's pool. When that is every hardware thread, Embree is left to
 * its default (which is that): naming the count explicitly made builds on 2 cores 30-40%
 * slower, as if one more thread joined them. */
static void make_device(void)
{
    char config[64];
    int n = ms_threads_count();
    snprintf(config, sizeof config, "threads=%d", n == ms_cpu_count() ? 0 : n);
    device = rtcNewDevice(config);
    if (!device) {
        snprintf(start_error, sizeof start_error, "Embree could not start (error %d)",
                 (int)rtcGetDeviceError(NULL));
        return;
    }
    rtcSetDeviceErrorFunction(device, on_error, NULL);
    rtcSetDeviceMemoryMonitorFunction(device, on_memory, NULL);
}

RTCDevice rt_device(ms_error *err)
{
    pthread_once(&once, make_device);
    if (!device) ms_error_set(err, "%s", start_error);
    return device;
}

void rt_device_set_budget(size_t bytes)
{
    long long now = atomic_load(&held);
    atomic_store(&budget, bytes ? now + (long long)MS_MIN(bytes, (size_t)1 << 60) : 0);
    atomic_store(&denied, 0);
}

size_t rt_device_room(void)
{
    long long limit = atomic_load(&budget), h = atomic_load(&held);
    if (limit <= 0) return 0;
    return limit > h ? (size_t)(limit - h) : 1;
}

size_t rt_device_held(void)
{
    long long h = atomic_load(&held);
    return h > 0 ? (size_t)h : 0;
}

size_t rt_device_peak(void)
{
    long long p = atomic_load(&peak);
    return p > 0 ? (size_t)p : 0;
}

void rt_device_peak_reset(void)
{
    atomic_store(&peak, atomic_load(&held));
}

int rt_device_check(RTCDevice dev, const char *what, ms_error *err)
{
    enum RTCError code = rtcGetDeviceError(dev);
    if (code == RTC_ERROR_NONE && !atomic_load(&denied)) return 0;
    if (code == RTC_ERROR_OUT_OF_MEMORY || atomic_load(&denied))
        ms_error_set(err, "%s: the scene is too large for the memory available (%.2f GB "
                     "allowed): a coarser QuickSurf grid spacing, fewer atoms drawn or a smaller "
                     "image would fit", what, (double)MS_MAX(atomic_load(&budget), 0) / 1e9);
    else
        ms_error_set(err, "%s: %s", what, last_error[0] ? last_error : "Embree failed");
    atomic_store(&denied, 0);
    last_error[0] = '\0';
    return -1;
}

unsigned rt_fpu_fast(void)
{
    unsigned old = _mm_getcsr();
    _mm_setcsr(old | 0x8040);         /* FTZ (bit 15) and DAZ (bit 6) */
    return old;
}

void rt_fpu_restore(unsigned state)
{
    _mm_setcsr(state);
}
