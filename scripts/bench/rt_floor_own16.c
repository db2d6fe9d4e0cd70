/* rt_floor_own16.c: the own tree with 16 children a node (AVX-512). */
#define OWN_WIDTH 16
#include "rt_floor_own.inc"
