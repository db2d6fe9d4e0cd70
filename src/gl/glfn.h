/* glfn.h: the OpenGL functions the renderer calls, as a table of pointers loaded from the
 * context's own library (OSMesaGetProcAddress or eglGetProcAddress). molscope never calls a
 * gl* symbol by name, so OSMesa's GL and the EGL vendor's GL can live in one program without
 * their entry points colliding, and each context uses the functions of its own library.
 * Internal to src/gl. */
#ifndef MS_GLFN_H
#define MS_GLFN_H

#include <GL/glcorearb.h>

#include "base/base.h"

/* X(type, name): the function gl<name> of type PFNGL<NAME>PROC. */
#define MS_GLFN_LIST(X)                                                                    \
    X(PFNGLGETERRORPROC, GetError) X(PFNGLGETSTRINGPROC, GetString)                        \
    X(PFNGLGETINTEGERVPROC, GetIntegerv) X(PFNGLGETFLOATVPROC, GetFloatv)                  \
    X(PFNGLENABLEPROC, Enable) X(PFNGLDISABLEPROC, Disable)                                \
    X(PFNGLVIEWPORTPROC, Viewport) X(PFNGLCLEARPROC, Clear)                                \
    X(PFNGLCLEARCOLORPROC, ClearColor) X(PFNGLCLEARDEPTHPROC, ClearDepth)                  \
    X(PFNGLCLEARBUFFERFVPROC, ClearBufferfv) X(PFNGLDEPTHFUNCPROC, DepthFunc)              \
    X(PFNGLDEPTHMASKPROC, DepthMask) X(PFNGLBLENDFUNCPROC, BlendFunc)                      \
    X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate) X(PFNGLFINISHPROC, Finish)            \
    X(PFNGLPIXELSTOREIPROC, PixelStorei) X(PFNGLREADPIXELSPROC, ReadPixels)                \
    X(PFNGLREADBUFFERPROC, ReadBuffer) X(PFNGLDRAWBUFFERSPROC, DrawBuffers)                \
    X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                           \
    X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                     \
    X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                           \
    X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                           \
    X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                                 \
    X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                             \
    X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                         \
    X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                                   \
    X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                         \
    X(PFNGLRENDERBUFFERSTORAGEPROC, RenderbufferStorage)                                   \
    X(PFNGLGENTEXTURESPROC, GenTextures) X(PFNGLDELETETEXTURESPROC, DeleteTextures)        \
    X(PFNGLBINDTEXTUREPROC, BindTexture) X(PFNGLTEXIMAGE2DPROC, TexImage2D)                \
    X(PFNGLTEXPARAMETERIPROC, TexParameteri) X(PFNGLACTIVETEXTUREPROC, ActiveTexture)      \
    X(PFNGLCREATESHADERPROC, CreateShader) X(PFNGLSHADERSOURCEPROC, ShaderSource)          \
    X(PFNGLCOMPILESHADERPROC, CompileShader) X(PFNGLGETSHADERIVPROC, GetShaderiv)          \
    X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog) X(PFNGLDELETESHADERPROC, DeleteShader)  \
    X(PFNGLCREATEPROGRAMPROC, CreateProgram) X(PFNGLATTACHSHADERPROC, AttachShader)        \
    X(PFNGLLINKPROGRAMPROC, LinkProgram) X(PFNGLGETPROGRAMIVPROC, GetProgramiv)            \
    X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                       \
    X(PFNGLDELETEPROGRAMPROC, DeleteProgram) X(PFNGLUSEPROGRAMPROC, UseProgram)            \
    X(PFNGLBINDATTRIBLOCATIONPROC, BindAttribLocation)                                     \
    X(PFNGLBINDFRAGDATALOCATIONPROC, BindFragDataLocation)                                 \
    X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation) X(PFNGLUNIFORM1IPROC, Uniform1i)    \
    X(PFNGLUNIFORM1FPROC, Uniform1f) X(PFNGLUNIFORM2FPROC, Uniform2f)                      \
    X(PFNGLUNIFORM3FVPROC, Uniform3fv) X(PFNGLUNIFORM4FVPROC, Uniform4fv)                  \
    X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv) X(PFNGLVERTEXATTRIB1FPROC, VertexAttrib1f) \
    X(PFNGLVERTEXATTRIB3FPROC, VertexAttrib3f)                                             \
    X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                           \
    X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                     \
    X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray) X(PFNGLGENBUFFERSPROC, GenBuffers)        \
    X(PFNGLDELETEBUFFERSPROC, DeleteBuffers) X(PFNGLBINDBUFFERPROC, BindBuffer)            \
    X(PFNGLBUFFERDATAPROC, BufferData)                                                     \
    X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                   \
    X(PFNGLVERTEXATTRIBIPOINTERPROC, VertexAttribIPointer)                                 \
    X(PFNGLVERTEXATTRIBDIVISORPROC, VertexAttribDivisor)                                   \
    X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                           \
    X(PFNGLDISABLEVERTEXATTRIBARRAYPROC, DisableVertexAttribArray)                         \
    X(PFNGLDRAWARRAYSPROC, DrawArrays) X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced) \
    X(PFNGLDRAWELEMENTSPROC, DrawElements)

typedef struct ms_glfn {
#define MS_GLFN_FIELD(type, name) type name;
    MS_GLFN_LIST(MS_GLFN_FIELD)
#undef MS_GLFN_FIELD
} ms_glfn;

typedef void (*ms_glproc)(void);

/* Fill the table with getproc("gl<name>") for every function; -1 with err naming the first
 * function the library does not have. */
int ms_glfn_load(ms_glfn *f, ms_glproc (*getproc)(const char *name), ms_error *err);

#endif
