/* rt_floor_own.c: which width of the own tree this CPU runs (rt_floor_own.h). */
#include "rt_floor_own.h"

const own_ops *own_pick(int want)
{
    int avx2 = 0, avx512 = 0;
#if defined(__x86_64__) && defined(__GNUC__)
    __builtin_cpu_init();
    avx2 = __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    avx512 = avx2 && __builtin_cpu_supports("avx512f") && __builtin_cpu_supports("avx512vl");
#endif
    if (want == 0) want = avx512 ? 16 : 8;
    if (want == 16 && avx512 && own_ops16.build) return &own_ops16;
    if (want == 8 && avx2 && own_ops8.build) return &own_ops8;
    return NULL;
}
