/* rt_floor_own8.c: the own tree with 8 children a node (AVX2 and FMA). */
#define OWN_WIDTH 8
#include "rt_floor_own.inc"
