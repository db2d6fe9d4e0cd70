/* displaylist.h: what a representation builder produces and a device draws. A display list
 * holds typed primitive arrays in structure-of-arrays form (float32 geometry, RGBA8 colours
 * resolved at build time): spheres, cylinders (a bond is one two-coloured cylinder), cones,
 * one indexed triangle mesh (signed-byte normals quantized as the OpenGL 1.2.1 spec, table
 * 2.6, says), lines, points and text; plus one material and one 4x4 model matrix for the
 * whole list.
 *
 * Appending is amortized O(1) and never allocates per primitive: reserve up front with
 * ms_dl_reserve, or claim a block with ms_dl_extend and fill it (from several threads if you
 * like: the block's slots are disjoint). */
#ifndef MS_DISPLAYLIST_H
#define MS_DISPLAYLIST_H

#include <stddef.h>
#include <stdint.h>

#include "base/base.h"

typedef struct ms_rgba8 {
    uint8_t r, g, b, a;
} ms_rgba8;

/* A cylinder's flags: the ends that are closed, and its role. A bond (MS_CYL_BOND) is one
 * tube from base to apex in two colours, color up to the joint and color2 beyond it; VMD
 * draws it as two half cylinders meeting at the joint, which is what the exporters write
 * (ms_dl_pieces): base to joint and joint to apex, or with MS_CYL_INWARD both halves from
 * their end to the joint (VMD's atom-centred halves, Licorice and CPK). */
enum { MS_CAP_BASE = 1, MS_CAP_APEX = 2, MS_CAP_MASK = 3 };
enum { MS_CYL_BOND = 4, MS_CYL_INWARD = 8 };
enum { MS_LINE_SOLID = 0, MS_LINE_DASHED = 1 };

typedef enum ms_dl_kind {
    MS_DL_SPHERES, MS_DL_CYLINDERS, MS_DL_CONES, MS_DL_LINES, MS_DL_POINTS, MS_DL_TEXTS,
    MS_DL_NKINDS
} ms_dl_kind;

typedef struct ms_dl_spheres {
    size_t n, cap;
    float *xyz;          /* 3n centres */
    float *radius;
    ms_rgba8 *color;
    uint16_t *res;       /* tessellation resolution, for devices that tessellate */
} ms_dl_spheres;

typedef struct ms_dl_cylinders {
    size_t n, cap;
    float *base, *apex;  /* 3n each: the end centres */
    float *joint;        /* 3n: where a bond's colour changes (on the axis); else the middle */
    float *radius;
    ms_rgba8 *color;
    ms_rgba8 *color2;    /* a bond's colour beyond the joint; else color */
    uint8_t *flags;      /* MS_CAP_* | MS_CYL_* */
    uint16_t *res;
    /* The order VMD writes the pieces in (ms_dl_pieces), when it is not the list's: norder
     * entries 2 * cylinder + half (0 the base's, 1 the apex's; a plain cylinder is its
     * half 0). Set by ms_dl_cylinder_order after the cylinders are in; appending a cylinder
     * drops it. */
    uint32_t *order;
    size_t norder, ordercap;
} ms_dl_cylinders;

typedef struct ms_dl_cones {
    size_t n, cap;
    float *base, *apex;  /* 3n each */
    float *rbase, *rapex;/* radius at the base and at the apex (0: a pointed cone) */
    ms_rgba8 *color;
    uint16_t *res;
} ms_dl_cones;

typedef struct ms_dl_lines {
    size_t n, cap;
    float *a, *b;        /* 3n each */
    float *width;        /* VMD's line width (pixels, 1..255) */
    ms_rgba8 *color;
    uint8_t *style;      /* MS_LINE_* */
} ms_dl_lines;

typedef struct ms_dl_points {
    size_t n, cap;
    float *xyz;
    float *size;         /* VMD's point size (pixels) */
    ms_rgba8 *color;
} ms_dl_points;

typedef struct ms_dl_texts {
    size_t n, cap;
    float *xyz;          /* anchor: the lower left of the first character */
    float *size, *thickness;
    ms_rgba8 *color;
    uint32_t *start;     /* offset of each NUL-terminated string in chars */
    char *chars;
    size_t nchars, ccap;
} ms_dl_texts;

/* One triangle mesh per list; several meshes append into it with offset indices. The vertex
 * arrays always hold at least one vertex more than nverts (vcap > nverts), so that xyz can be
 * handed to Embree as it is (it reads 16 bytes per vertex). */
typedef struct ms_dl_mesh {
    size_t nverts, vcap;
    float *xyz;          /* 3 nverts */
    int8_t *normal;      /* 3 nverts, quantized (ms_normal_quantize) */
    ms_rgba8 *color;
    size_t ntris, tcap;
    uint32_t *tri;       /* 3 ntris vertex indices */
} ms_dl_mesh;

typedef struct ms_displaylist {
    int material;        /* material id (scene/material.h), 0 = Opaque */
    int lit;             /* 1: shaded with the material; 0: flat colour (VMD's materials off) */
    float model[16];     /* row-major; applied before the owner's view transform */
    ms_dl_spheres spheres;
    ms_dl_cylinders cylinders;
    ms_dl_cones cones;
    ms_dl_lines lines;
    ms_dl_points points;
    ms_dl_texts texts;
    ms_dl_mesh mesh;
    unsigned long gen;   /* a number no other list state had: new at init, clear, free and
                          * adopt (a rebuild); appends change only the counts */
} ms_displaylist;

/* An empty list: material 0, lit, identity model matrix. */
void ms_dl_init(ms_displaylist *dl);
/* Free every array (the list is empty and usable afterwards). */
void ms_dl_free(ms_displaylist *dl);
/* Empty the list but keep its memory, for a rebuild. */
void ms_dl_clear(ms_displaylist *dl);

/* Room for n more primitives of one kind (text characters grow as strings arrive).
 * Returns 0, or -1 with err set. */
int ms_dl_reserve(ms_displaylist *dl, ms_dl_kind kind, size_t n, ms_error *err);
int ms_dl_mesh_reserve(ms_displaylist *dl, size_t nverts, size_t ntris, ms_error *err);
/* Claim count uninitialised primitives of one kind (not texts); returns the index of the
 * first, or -1 with err set. The caller fills every array of the claimed block. */
long ms_dl_extend(ms_displaylist *dl, ms_dl_kind kind, size_t count, ms_error *err);
/* Claim vertices and triangles of the mesh; *v0 and *t0 receive the first of each. */
int ms_dl_mesh_extend(ms_displaylist *dl, size_t nverts, size_t ntris, size_t *v0, size_t *t0,
                      ms_error *err);

/* Make the list's mesh these malloc'd arrays (a surface engine's output, taken without a
 * copy): nverts vertices in arrays of vcap >= nverts (vcap > nverts spares the tracer a
 * padded copy of xyz); whatever mesh the list held is freed. */
void ms_dl_mesh_adopt(ms_displaylist *dl, float *xyz, int8_t *normal, ms_rgba8 *color,
                      size_t nverts, size_t vcap, uint32_t *tri, size_t ntris);

/* Append one primitive. Each returns 0, or -1 when memory runs out (the list is unchanged). */
int ms_dl_sphere(ms_displaylist *dl, const float c[3], float r, ms_rgba8 col, int res);
int ms_dl_cylinder(ms_displaylist *dl, const float a[3], const float b[3], float r, ms_rgba8 col,
                   int caps, int res);
/* A bond: one tube from a to b of radius r, coloured c1 up to the joint j and c2 beyond; flags
 * MS_CYL_INWARD and MS_CAP_* (MS_CYL_BOND is implied). */
int ms_dl_bond(ms_displaylist *dl, const float a[3], const float j[3], const float b[3], float r,
               ms_rgba8 c1, ms_rgba8 c2, int flags, int res);
/* Room for the pieces' order (n entries, see ms_dl_cylinders.order) for the caller to fill;
 * NULL with err set when memory runs out. */
uint32_t *ms_dl_cylinder_order(ms_displaylist *dl, size_t n, ms_error *err);
int ms_dl_cone(ms_displaylist *dl, const float base[3], const float apex[3], float rbase,
               float rapex, ms_rgba8 col, int res);
int ms_dl_line(ms_displaylist *dl, const float a[3], const float b[3], float width, ms_rgba8 col,
               int style);
int ms_dl_point(ms_displaylist *dl, const float p[3], float size, ms_rgba8 col);
int ms_dl_text(ms_displaylist *dl, const float p[3], const char *s, float size, float thickness,
               ms_rgba8 col);
/* A mesh vertex (normal as floats, quantized here); returns its index or -1. */
long ms_dl_vertex(ms_displaylist *dl, const float p[3], const float n[3], ms_rgba8 col);
int ms_dl_tri(ms_displaylist *dl, uint32_t i, uint32_t j, uint32_t k);
/* Three new vertices and the triangle between them. */
int ms_dl_triangle(ms_displaylist *dl, const float p[9], const float n[9], const ms_rgba8 c[3]);

/* The pieces of a list's cylinders as VMD has them and the exporters write them: a plain
 * cylinder is one piece, a bond its two halves (its flags' caps on its own ends, the joint
 * open), in the list's order or the one ms_dl_cylinder_order set. Walk them with
 *     ms_dl_pieces it = ms_dl_pieces_of(cy); ms_dl_piece p;
 *     while (ms_dl_pieces_next(&it, &p)) ...  */
typedef struct ms_dl_piece {
    const float *a, *b;  /* the ends */
    float radius;
    ms_rgba8 color;
    int caps;            /* MS_CAP_* of this piece's ends */
    int res;
    size_t cylinder;     /* the cylinder it is part of */
} ms_dl_piece;
typedef struct ms_dl_pieces {
    const ms_dl_cylinders *cy;
    size_t next;         /* the next order entry, or 2 * cylinder + half */
} ms_dl_pieces;
static inline ms_dl_pieces ms_dl_pieces_of(const ms_dl_cylinders *cy)
{
    ms_dl_pieces it = {cy, 0};
    return it;
}
/* The next piece into *p; 0 when there are no more. */
int ms_dl_pieces_next(ms_dl_pieces *it, ms_dl_piece *p);
/* How many pieces the cylinders make. */
size_t ms_dl_piece_count(const ms_dl_cylinders *cy);

/* Number of primitives of every kind (mesh triangles included), and memory held. */
size_t ms_dl_count(const ms_displaylist *dl);
size_t ms_dl_bytes(const ms_displaylist *dl);
/* Bounding box of the primitives' defining points (centres, ends, vertices, anchors), in the
 * list's own coordinates. Returns 0 when the list is empty. */
int ms_dl_bounds(const ms_displaylist *dl, float lo[3], float hi[3]);

/* Normals as signed bytes, OpenGL 1.2.1 table 2.6: f = (2c + 1) / 255. */
static inline int8_t ms_normal_quantize(float f)
{
    float c = (f * 255.0f - 1.0f) * 0.5f;
    c = c < -128.0f ? -128.0f : c > 127.0f ? 127.0f : c;
    return (int8_t)(c < 0 ? c - 0.5f : c + 0.5f);
}
static inline float ms_normal_dequantize(int8_t c)
{
    return (2.0f * (float)c + 1.0f) * (1.0f / 255.0f);
}

/* RGBA8 from floats in [0, 1] (clamped). */
ms_rgba8 ms_rgba8_from_float(const float rgb[3], float alpha);
static inline void ms_rgba8_to_float(ms_rgba8 c, float rgb[3])
{
    rgb[0] = c.r * (1.0f / 255.0f);
    rgb[1] = c.g * (1.0f / 255.0f);
    rgb[2] = c.b * (1.0f / 255.0f);
}

#endif
