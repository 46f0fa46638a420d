// The OpenGL 4.5 core functions the viewer uses, loaded at run time through
// the platform's get-proc-address (the build has no network, so the loader
// lives here instead of coming from glad/GLEW). Call as gl::CreateShader(...).
// Every function is checked at load time; a context without one of them is
// rejected with the list of missing names.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#define GLOBE_GL_FUNCTIONS(X)                                          \
  X(PFNGLGETSTRINGPROC, GetString)                                     \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                 \
  X(PFNGLGETERRORPROC, GetError)                                       \
  X(PFNGLVIEWPORTPROC, Viewport)                                       \
  X(PFNGLCLEARCOLORPROC, ClearColor)                                   \
  X(PFNGLCLEARPROC, Clear)                                             \
  X(PFNGLENABLEPROC, Enable)                                           \
  X(PFNGLDISABLEPROC, Disable)                                         \
  X(PFNGLDEPTHFUNCPROC, DepthFunc)                                     \
  X(PFNGLFINISHPROC, Finish)                                           \
  X(PFNGLPIXELSTOREIPROC, PixelStorei)                                 \
  X(PFNGLREADPIXELSPROC, ReadPixels)                                   \
  X(PFNGLCREATESHADERPROC, CreateShader)                               \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                               \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                             \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                 \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                       \
  X(PFNGLDELETESHADERPROC, DeleteShader)                               \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                             \
  X(PFNGLATTACHSHADERPROC, AttachShader)                               \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                 \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                               \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                     \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                             \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                   \
  X(PFNGLGETUNIFORMLOCATIONPROC, GetUniformLocation)                   \
  X(PFNGLUNIFORM1IPROC, Uniform1i)                                     \
  X(PFNGLUNIFORM1FPROC, Uniform1f)                                     \
  X(PFNGLUNIFORM1FVPROC, Uniform1fv)                                   \
  X(PFNGLUNIFORM2FPROC, Uniform2f)                                     \
  X(PFNGLUNIFORM3FPROC, Uniform3f)                                     \
  X(PFNGLUNIFORM4FPROC, Uniform4f)                                     \
  X(PFNGLUNIFORMMATRIX4FVPROC, UniformMatrix4fv)                       \
  X(PFNGLTRANSFORMFEEDBACKVARYINGSPROC, TransformFeedbackVaryings)     \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                   \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                         \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                   \
  X(PFNGLVERTEXARRAYELEMENTBUFFERPROC, VertexArrayElementBuffer)       \
  X(PFNGLVERTEXARRAYVERTEXBUFFERPROC, VertexArrayVertexBuffer)         \
  X(PFNGLVERTEXARRAYATTRIBIFORMATPROC, VertexArrayAttribIFormat)       \
  X(PFNGLVERTEXARRAYATTRIBBINDINGPROC, VertexArrayAttribBinding)       \
  X(PFNGLENABLEVERTEXARRAYATTRIBPROC, EnableVertexArrayAttrib)         \
  X(PFNGLVERTEXARRAYBINDINGDIVISORPROC, VertexArrayBindingDivisor)     \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                             \
  X(PFNGLNAMEDBUFFERDATAPROC, NamedBufferData)                         \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                   \
  X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)             \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                           \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                             \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                           \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                       \
  X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                       \
  X(PFNGLTEXTURESUBIMAGE2DPROC, TextureSubImage2D)                     \
  X(PFNGLTEXTURESUBIMAGE3DPROC, TextureSubImage3D)                     \
  X(PFNGLTEXTUREPARAMETERIPROC, TextureParameteri)                     \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                         \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                           \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                   \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)         \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus) \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                         \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                   \
  X(PFNGLBLITNAMEDFRAMEBUFFERPROC, BlitNamedFramebuffer)               \
  X(PFNGLDRAWELEMENTSINSTANCEDPROC, DrawElementsInstanced)             \
  X(PFNGLBEGINTRANSFORMFEEDBACKPROC, BeginTransformFeedback)           \
  X(PFNGLENDTRANSFORMFEEDBACKPROC, EndTransformFeedback)               \
  X(PFNGLCREATEQUERIESPROC, CreateQueries)                             \
  X(PFNGLBEGINQUERYPROC, BeginQuery)                                   \
  X(PFNGLENDQUERYPROC, EndQuery)                                       \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                 \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                             \
  X(PFNGLNAMEDFRAMEBUFFERDRAWBUFFERSPROC, NamedFramebufferDrawBuffers) \
  X(PFNGLCLEARNAMEDFRAMEBUFFERFVPROC, ClearNamedFramebufferfv)         \
  X(PFNGLDRAWARRAYSPROC, DrawArrays)                                   \
  X(PFNGLDRAWARRAYSINSTANCEDPROC, DrawArraysInstanced)                 \
  X(PFNGLPOLYGONOFFSETPROC, PolygonOffset)                             \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                     \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                             \
  X(PFNGLUNIFORM1UIPROC, Uniform1ui)                                   \
  X(PFNGLUNIFORM2IPROC, Uniform2i)                                     \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                   \
  X(PFNGLNAMEDFRAMEBUFFERREADBUFFERPROC, NamedFramebufferReadBuffer)   \
  X(PFNGLBLENDFUNCSEPARATEPROC, BlendFuncSeparate)                     \
  X(PFNGLVERTEXARRAYATTRIBFORMATPROC, VertexArrayAttribFormat)         \
  X(PFNGLCLEARNAMEDFRAMEBUFFERUIVPROC, ClearNamedFramebufferuiv)       \
  X(PFNGLUNIFORM4FVPROC, Uniform4fv)                                   \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)

namespace gl {

#define GLOBE_GL_DECLARE(type, name) inline type name = nullptr;
GLOBE_GL_FUNCTIONS(GLOBE_GL_DECLARE)
#undef GLOBE_GL_DECLARE

using GetProc = void* (*)(const char* name);

// Loads every function of the list; throws std::runtime_error naming the
// missing ones, or if the context is older than OpenGL 4.5.
void load(GetProc get_proc);

// "OpenGL 4.5 (Core Profile) Mesa 22.3.6 / llvmpipe (LLVM 15.0.6, 256 bits)".
std::string describe_context();

// Throws std::runtime_error("<what>: GL error 0x...") if an error is pending.
void check(const char* what);

}  // namespace gl
