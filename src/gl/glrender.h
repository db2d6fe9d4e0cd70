/* glrender.h: inside src/gl: the context every back-end fills, the renderer's programs and
 * its per-frame state. Not part of the public API (gl.h is). */
#ifndef MS_GLRENDER_H
#define MS_GLRENDER_H

#include "gl/gl.h"
#include "gl/glfn.h"

/* The programs (shaders.c). */
enum {
    MS_GLR_SPHERE, MS_GLR_CONE, MS_GLR_MESH, MS_GLR_LINE, MS_GLR_GRADIENT, MS_GLR_COMPOSITE,
    MS_GLR_NPROGS
};

typedef struct ms_glr_source {
    const char *name;
    const char *vs[2], *fs[2];     /* each stage is its two strings joined */
} ms_glr_source;
extern const ms_glr_source ms_glr_sources[MS_GLR_NPROGS];

/* Uniforms by name; a program lacks those it does not use (location -1, ignored by GL). */
enum {
    MS_U_PROJ, MS_U_VIEWPORT, MS_U_RAY, MS_U_NEARFAR, MS_U_NLIGHTS, MS_U_LIGHT_DIR,
    MS_U_LIGHT_COL, MS_U_MAT, MS_U_MAT2, MS_U_LIT, MS_U_FOG, MS_U_FOGP, MS_U_BG_TOP,
    MS_U_BG_BOT, MS_U_PASS, MS_U_MV, MS_U_RSCALE, MS_U_SQUARE, MS_U_ACCUM, MS_U_WSUM,
    MS_U_NCLIP, MS_U_CLIP, MS_U_CLIPCOL, MS_U_COUNT
};

typedef struct ms_glr_prog {
    GLuint id;
    GLint u[MS_U_COUNT];
} ms_glr_prog;

/* The renderer's GL objects. */
typedef struct ms_glr {
    ms_glr_prog prog[MS_GLR_NPROGS];
    GLuint vao;
    GLuint *buffers;               /* pool, handed out in order during a frame */
    size_t nbuffers, capbuffers, used;
    GLuint fbo, color_rb, depth_rb;    /* the image */
    GLuint oit_fbo, accum_tex, wsum_tex;
    int width, height, oit_ready;
} ms_glr;

struct ms_gl {
    ms_gl_kind kind;
    ms_glfn f;
    char info[512];
    int hardware, max_side;
    int loaded;                    /* the function table is complete */
    ms_glr r;
    /* the back-end */
    void *impl;
    int (*make_current)(ms_gl *g, ms_error *err);
    void (*release)(ms_gl *g);     /* no context current in this thread */
    void (*destroy)(ms_gl *g);
};

/* Back-ends: create a context with a GL 3.3 core (or later) profile, make it current, load
 * the function table, and set impl, make_current, release, destroy and the start of info.
 * On failure the caller still calls destroy when it was set. */
int ms_gl_osmesa_init(ms_gl *g, ms_error *err);
int ms_gl_egl_init(ms_gl *g, ms_error *err);

/* Make g the current context of this thread, releasing another back-end's context first
 * (OSMesa and EGL track the current context separately; context.c). */
int ms_gl_use(ms_gl *g, ms_error *err);

/* The renderer (glrender.c): programs and objects, made once per context. */
int ms_glr_init(ms_gl *g, ms_error *err);
void ms_glr_free(ms_gl *g);
/* The framebuffer at a size (re-made when the size changes). */
int ms_glr_framebuffer(ms_gl *g, int width, int height, ms_error *err);
/* The translucency targets of the current size, made on first need. */
int ms_glr_oit_targets(ms_gl *g, ms_error *err);
/* A buffer of the pool filled with n bytes (GL_ARRAY_BUFFER or GL_ELEMENT_ARRAY_BUFFER). */
GLuint ms_glr_upload(ms_gl *g, GLenum target, const void *data, size_t n, ms_error *err);

/* The camera of a frame in eye space (the eye at the origin looking down -z). */
typedef struct ms_glcam {
    int width, height, ortho;
    float hx, hy;                  /* tangents of the half angles, or half sizes */
    float near, far;
} ms_glcam;

/* Occlusion culling of impostors (cull.c): an occlusion buffer filled from the opaque
 * spheres and cylinders of every list, then a test per primitive. */
typedef struct ms_glcull ms_glcull;
typedef struct ms_glcull_sel {
    size_t n, kept;
    uint8_t *keep;                 /* per primitive: may be seen */
    size_t *offset;                /* per block of primitives: first kept index */
} ms_glcull_sel;
ms_glcull *ms_glcull_new(const ms_glcam *cam, ms_error *err);
void ms_glcull_free(ms_glcull *c);
/* Add the opaque spheres and cylinders of a list placed with mv (model to eye). */
void ms_glcull_occluders(ms_glcull *c, const ms_displaylist *dl, const float mv[16], float rscale);
/* Which primitives of one kind (MS_DL_SPHERES, _CYLINDERS, _CONES) may be seen. */
int ms_glcull_test(const ms_glcull *c, const ms_displaylist *dl, int kind, const float mv[16],
                   float rscale, ms_glcull_sel *sel, ms_error *err);
void ms_glcull_sel_free(ms_glcull_sel *sel);
/* The kept elements of an array of elsize-byte elements, packed (malloc'd; NULL on no
 * memory). */
void *ms_glcull_gather(const ms_glcull_sel *sel, const void *src, size_t elsize);

/* The frame (glframe.c): draw a scene into the framebuffer. */
int ms_glr_draw_scene(ms_gl *g, const ms_scene *s, ms_gl_times *t, ms_error *err);

#endif
