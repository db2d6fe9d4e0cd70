/* glrender.c: the renderer's GL objects: compiling and linking the programs of shaders.c,
 * the framebuffer of the image's size (RGBA8 colour, 24-bit depth) and the translucency
 * targets that share its depth (RGBA16F weighted sums, R16F weights), and the pool of
 * buffers a frame fills with display-list arrays. */
#include "config.h"
#include "gl/glrender.h"

#include <stdio.h>
#include <stdlib.h>
#include <string.h>

static const char *const uniform_names[MS_U_COUNT] = {
    [MS_U_PROJ] = "u_proj", [MS_U_VIEWPORT] = "u_viewport", [MS_U_RAY] = "u_ray",
    [MS_U_NEARFAR] = "u_nearfar", [MS_U_NLIGHTS] = "u_nlights", [MS_U_LIGHT_DIR] = "u_light_dir",
    [MS_U_LIGHT_COL] = "u_light_col", [MS_U_MAT] = "u_mat", [MS_U_MAT2] = "u_mat2",
    [MS_U_LIT] = "u_lit", [MS_U_FOG] = "u_fog", [MS_U_FOGP] = "u_fogp", [MS_U_BG_TOP] = "u_bg_top",
    [MS_U_BG_BOT] = "u_bg_bot", [MS_U_PASS] = "u_pass", [MS_U_MV] = "u_mv",
    [MS_U_RSCALE] = "u_rscale", [MS_U_SQUARE] = "u_square", [MS_U_ACCUM] = "u_accum",
    [MS_U_WSUM] = "u_wsum", [MS_U_NCLIP] = "u_nclip", [MS_U_CLIP] = "u_clip",
    [MS_U_CLIPCOL] = "u_clipcol"};

static GLuint compile(ms_gl *g, GLenum type, const char *const src[2], const char *name,
                      ms_error *err)
{
    const ms_glfn *f = &g->f;
    GLuint sh = f->CreateShader(type);
    GLint ok = 0;
    f->ShaderSource(sh, 2, src, NULL);
    f->CompileShader(sh);
    f->GetShaderiv(sh, GL_COMPILE_STATUS, &ok);
    if (ok) return sh;
    char log[600] = "";
    f->GetShaderInfoLog(sh, sizeof log, NULL, log);
    ms_error_set(err, "%s: the %s %s shader does not compile: %s", ms_gl_kind_name(g->kind), name,
                 type == GL_VERTEX_SHADER ? "vertex" : "fragment", log);
    f->DeleteShader(sh);
    return 0;
}

static int build(ms_gl *g, int which, ms_error *err)
{
    const ms_glfn *f = &g->f;
    const ms_glr_source *src = &ms_glr_sources[which];
    ms_glr_prog *p = &g->r.prog[which];
    GLuint vs = compile(g, GL_VERTEX_SHADER, src->vs, src->name, err);
    GLuint fs = vs ? compile(g, GL_FRAGMENT_SHADER, src->fs, src->name, err) : 0;
    if (!fs) {
        if (vs) f->DeleteShader(vs);
        return -1;
    }
    p->id = f->CreateProgram();
    f->AttachShader(p->id, vs);
    f->AttachShader(p->id, fs);
    f->LinkProgram(p->id);
    f->DeleteShader(vs);
    f->DeleteShader(fs);
    GLint ok = 0;
    f->GetProgramiv(p->id, GL_LINK_STATUS, &ok);
    if (!ok) {
        char log[600] = "";
        f->GetProgramInfoLog(p->id, sizeof log, NULL, log);
        ms_error_set(err, "%s: the %s program does not link: %s", ms_gl_kind_name(g->kind),
                     src->name, log);
        return -1;
    }
    for (int u = 0; u < MS_U_COUNT; u++) p->u[u] = f->GetUniformLocation(p->id, uniform_names[u]);
    return 0;
}

int ms_glr_init(ms_gl *g, ms_error *err)
{
    for (int i = 0; i < MS_GLR_NPROGS; i++)
        if (build(g, i, err)) return -1;
    g->f.GenVertexArrays(1, &g->r.vao);
    g->f.BindVertexArray(g->r.vao);
    return 0;
}

static void free_targets(ms_gl *g)
{
    const ms_glfn *f = &g->f;
    ms_glr *r = &g->r;
    f->DeleteFramebuffers(1, &r->fbo);
    f->DeleteFramebuffers(1, &r->oit_fbo);
    f->DeleteRenderbuffers(1, &r->color_rb);
    f->DeleteRenderbuffers(1, &r->depth_rb);
    f->DeleteTextures(1, &r->accum_tex);
    f->DeleteTextures(1, &r->wsum_tex);
    r->fbo = r->oit_fbo = r->color_rb = r->depth_rb = r->accum_tex = r->wsum_tex = 0;
    r->width = r->height = r->oit_ready = 0;
}

void ms_glr_free(ms_gl *g)
{
    const ms_glfn *f = &g->f;
    ms_glr *r = &g->r;
    free_targets(g);
    for (int i = 0; i < MS_GLR_NPROGS; i++)
        if (r->prog[i].id) f->DeleteProgram(r->prog[i].id);
    if (r->vao) f->DeleteVertexArrays(1, &r->vao);
    if (r->nbuffers) f->DeleteBuffers((GLsizei)r->nbuffers, r->buffers);
    free(r->buffers);
    memset(r, 0, sizeof *r);
}

/* Complete, and no GL error on the way (GL_OUT_OF_MEMORY for a size the device cannot
 * hold). */
static int check_fbo(ms_gl *g, const char *what, ms_error *err)
{
    GLenum e = g->f.GetError(), st = g->f.CheckFramebufferStatus(GL_FRAMEBUFFER);
    if (e == GL_NO_ERROR && st == GL_FRAMEBUFFER_COMPLETE) return 0;
    ms_error_set(err, "%s: cannot make the %s framebuffer of %dx%d pixels (%s)",
                 ms_gl_kind_name(g->kind), what, g->r.width, g->r.height,
                 e == GL_OUT_OF_MEMORY ? "out of memory" : "incomplete");
    free_targets(g);
    return -1;
}

int ms_glr_framebuffer(ms_gl *g, int width, int height, ms_error *err)
{
    const ms_glfn *f = &g->f;
    ms_glr *r = &g->r;
    if (r->fbo && r->width == width && r->height == height) return 0;
    free_targets(g);
    while (f->GetError() != GL_NO_ERROR) {}
    r->width = width;
    r->height = height;
    f->GenRenderbuffers(1, &r->color_rb);
    f->BindRenderbuffer(GL_RENDERBUFFER, r->color_rb);
    f->RenderbufferStorage(GL_RENDERBUFFER, GL_RGBA8, width, height);
    f->GenRenderbuffers(1, &r->depth_rb);
    f->BindRenderbuffer(GL_RENDERBUFFER, r->depth_rb);
    f->RenderbufferStorage(GL_RENDERBUFFER, GL_DEPTH_COMPONENT24, width, height);
    f->GenFramebuffers(1, &r->fbo);
    f->BindFramebuffer(GL_FRAMEBUFFER, r->fbo);
    f->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, r->color_rb);
    f->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->depth_rb);
    return check_fbo(g, "image", err);
}

static GLuint float_texture(ms_gl *g, GLint internal, GLenum format, int w, int h)
{
    const ms_glfn *f = &g->f;
    GLuint t;
    f->GenTextures(1, &t);
    f->BindTexture(GL_TEXTURE_2D, t);
    f->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    f->TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    f->TexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, GL_FLOAT, NULL);
    return t;
}

int ms_glr_oit_targets(ms_gl *g, ms_error *err)
{
    const ms_glfn *f = &g->f;
    ms_glr *r = &g->r;
    if (r->oit_ready) return 0;
    r->accum_tex = float_texture(g, GL_RGBA16F, GL_RGBA, r->width, r->height);
    r->wsum_tex = float_texture(g, GL_R16F, GL_RED, r->width, r->height);
    f->GenFramebuffers(1, &r->oit_fbo);
    f->BindFramebuffer(GL_FRAMEBUFFER, r->oit_fbo);
    f->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, r->accum_tex, 0);
    f->FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT1, GL_TEXTURE_2D, r->wsum_tex, 0);
    f->FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, r->depth_rb);
    static const GLenum bufs[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    f->DrawBuffers(2, bufs);
    if (check_fbo(g, "translucency", err)) return -1;
    r->oit_ready = 1;
    return 0;
}

GLuint ms_glr_upload(ms_gl *g, GLenum target, const void *data, size_t n, ms_error *err)
{
    ms_glr *r = &g->r;
    if (r->used == r->nbuffers) {
        if (ms_grow((void **)&r->buffers, &r->capbuffers, r->nbuffers + 16, sizeof *r->buffers)) {
            ms_error_set(err, "out of memory");
            return 0;
        }
        g->f.GenBuffers(16, r->buffers + r->nbuffers);
        r->nbuffers += 16;
    }
    GLuint b = r->buffers[r->used++];
    g->f.BindBuffer(target, b);
    g->f.BufferData(target, (GLsizeiptr)n, data, GL_STREAM_DRAW);
    if (g->f.GetError() == GL_OUT_OF_MEMORY) {
        ms_error_set(err, "%s: out of memory for %zu bytes of geometry", ms_gl_kind_name(g->kind),
                     n);
        return 0;
    }
    return b;
}
