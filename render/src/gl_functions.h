// The OpenGL 3.3 core entry points the renderer uses, loaded at run time
// through a GlProcLoader (OSMesaGetProcAddress headless, glfwGetProcAddress
// in a window). Nothing links against libGL, so the same code runs under any
// context; internal to the render module.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "idbench/render/gl_proc_loader.h"

namespace idbench::render_internal {

#define IDBENCH_GL_FUNCTIONS(X)                                                                           \
  X(PFNGLGETSTRINGPROC, GetString)                                                                        \
  X(PFNGLGETERRORPROC, GetError)                                                                          \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                                                    \
  X(PFNGLVIEWPORTPROC, Viewport)                                                                          \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                                                      \
  X(PFNGLCLEARPROC, Clear)                                                                                \
  X(PFNGLENABLEPROC, Enable)                                                                              \
  X(PFNGLDISABLEPROC, Disable)                                                                            \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                                                        \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                                                        \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                                                                \
  X(PFNGLBLENDFUNCPROC, BlendFunc)                                                                        \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                                                    \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                                                      \
  X(PFNGLFINISHPROC, Finish)                                                                              \
  X(PFNGLGENFRAMEBUFFERSPROC, GenFramebuffers)                                                            \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                                                      \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                                            \
  X(PFNGLFRAMEBUFFERRENDERBUFFERPROC, FramebufferRenderbuffer)                                            \
  X(PFNGLFRAMEBUFFERTEXTURE2DPROC, FramebufferTexture2D)                                                  \
  X(PFNGLCHECKFRAMEBUFFERSTATUSPROC, CheckFramebufferStatus)                                              \
  X(PFNGLBLITFRAMEBUFFERPROC, BlitFramebuffer)                                                            \
  X(PFNGLGENRENDERBUFFERSPROC, GenRenderbuffers)                                                          \
  X(PFNGLDELETERENDERBUFFERSPROC, DeleteRenderbuffers)                                                    \
  X(PFNGLBINDRENDERBUFFERPROC, BindRenderbuffer)                                                          \
  X(PFNGLRENDERBUFFERSTORAGEMULTISAMPLEPROC, RenderbufferStorageMultisample)                              \
  X(PFNGLGENTEXTURESPROC, GenTextures)                                                                    \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                                              \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                                                    \
  X(PFNGLTEXIMAGE2DPROC, TexImage2D)                                                                      \
  X(PFNGLTEXPARAMETERIPROC, TexParameteri)                                                                \
  X(PFNGLCREATESHADERPROC, CreateShader)                                                                  \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                                                  \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                                                \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                                                    \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                                          \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                                                  \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                                                \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                                                  \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                                                    \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                                                  \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                                                        \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                                                \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                                                      \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                                                      \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                                                          \
  X(PFNGLUNIFORMMATRIX3FVPROC, UniformMatrix3fv)                                                          \
  X(PFNGLUNIFORM3FVPROC, Uniform3fv)                                                                      \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                                                        \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                                                        \
  X(PFNGLGENVERTEXARRAYSPROC, GenVertexArrays)                                                            \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                                                      \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                                            \
  X(PFNGLGENBUFFERSPROC, GenBuffers)                                                                      \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                                                \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                                                      \
  X(PFNGLBUFFERDATAPROC, BufferData)                                                                      \
  X(PFNGLVERTEXATTRIBPOINTERPROC, VertexAttribPointer)                                                    \
  X(PFNGLENABLEVERTEXATTRIBARRAYPROC, EnableVertexAttribArray)                                            \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)

// One pointer per entry point, named without the gl prefix: gl.Clear(...).
struct GlFunctions {
#define IDBENCH_GL_MEMBER(type, name) type name = nullptr;
  IDBENCH_GL_FUNCTIONS(IDBENCH_GL_MEMBER)
#undef IDBENCH_GL_MEMBER
};

// Loads every entry point. Throws std::runtime_error naming the first one the
// loader does not provide.
GlFunctions LoadGlFunctions(GlProcLoader loader);

}  // namespace idbench::render_internal
