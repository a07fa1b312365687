// Private GL function table: loaded from the host's getProcAddress, so sslr defines no global
// gl* symbols and never fights the host's loader (glad, epoxy, GLEW...). glcorearb.h is included
// without GL_GLEXT_PROTOTYPES: it gives the types and PFN typedefs only.
#pragma once

#include <GL/glcorearb.h>

#include <string>

#include "sslr/sslr.hpp"

namespace sslr::detail {

// X(type, name): every GL 4.5 entry point sslr calls, and nothing else.
#define SSLR_GL_FUNCTIONS(X)                                                     \
  X(PFNGLGETERRORPROC, GetError)                                                 \
  X(PFNGLFINISHPROC, Finish)                                                     \
  X(PFNGLGETINTEGERVPROC, GetIntegerv)                                           \
  X(PFNGLGETINTEGERI_VPROC, GetIntegeri_v)                                       \
  X(PFNGLGETINTEGER64I_VPROC, GetInteger64i_v)                                   \
  X(PFNGLGETBOOLEANI_VPROC, GetBooleani_v)                                       \
  X(PFNGLGETSTRINGPROC, GetString)                                               \
  X(PFNGLGETSTRINGIPROC, GetStringi)                                             \
  X(PFNGLISENABLEDPROC, IsEnabled)                                               \
  X(PFNGLISENABLEDIPROC, IsEnabledi)                                             \
  X(PFNGLENABLEPROC, Enable)                                                     \
  X(PFNGLDISABLEPROC, Disable)                                                   \
  X(PFNGLENABLEIPROC, Enablei)                                                   \
  X(PFNGLDISABLEIPROC, Disablei)                                                 \
  X(PFNGLGETBOOLEANVPROC, GetBooleanv)                                           \
  X(PFNGLCOLORMASKIPROC, ColorMaski)                                             \
  X(PFNGLDEPTHMASKPROC, DepthMask)                                               \
  X(PFNGLBLENDFUNCSEPARATEIPROC, BlendFuncSeparatei)                             \
  X(PFNGLBLENDEQUATIONSEPARATEIPROC, BlendEquationSeparatei)                     \
  X(PFNGLVIEWPORTINDEXEDFVPROC, ViewportIndexedfv)                               \
  X(PFNGLGETFLOATI_VPROC, GetFloati_v)                                           \
  X(PFNGLGETNAMEDFRAMEBUFFERATTACHMENTPARAMETERIVPROC, GetNamedFramebufferAttachmentParameteriv) \
  X(PFNGLGETNAMEDRENDERBUFFERPARAMETERIVPROC, GetNamedRenderbufferParameteriv)   \
  X(PFNGLPOLYGONMODEPROC, PolygonMode)                                           \
  X(PFNGLCLIPCONTROLPROC, ClipControl)                                           \
  X(PFNGLGETFLOATVPROC, GetFloatv)                                               \
  X(PFNGLISTEXTUREPROC, IsTexture)                                               \
  X(PFNGLISFRAMEBUFFERPROC, IsFramebuffer)                                       \
  X(PFNGLISRENDERBUFFERPROC, IsRenderbuffer)                                     \
  X(PFNGLCREATETEXTURESPROC, CreateTextures)                                     \
  X(PFNGLDELETETEXTURESPROC, DeleteTextures)                                     \
  X(PFNGLTEXTURESTORAGE2DPROC, TextureStorage2D)                                 \
  X(PFNGLTEXTURESTORAGE3DPROC, TextureStorage3D)                                 \
  X(PFNGLCREATEFRAMEBUFFERSPROC, CreateFramebuffers)                             \
  X(PFNGLDELETEFRAMEBUFFERSPROC, DeleteFramebuffers)                             \
  X(PFNGLNAMEDFRAMEBUFFERTEXTUREPROC, NamedFramebufferTexture)                   \
  X(PFNGLGETTEXTUREPARAMETERIVPROC, GetTextureParameteriv)                       \
  X(PFNGLGETTEXTURELEVELPARAMETERIVPROC, GetTextureLevelParameteriv)             \
  X(PFNGLCLEARTEXIMAGEPROC, ClearTexImage)                                       \
  X(PFNGLCLEARTEXSUBIMAGEPROC, ClearTexSubImage)                                 \
  X(PFNGLCLEARNAMEDBUFFERSUBDATAPROC, ClearNamedBufferSubData)                   \
  X(PFNGLCOPYIMAGESUBDATAPROC, CopyImageSubData)                                 \
  X(PFNGLCOPYNAMEDBUFFERSUBDATAPROC, CopyNamedBufferSubData)                     \
  X(PFNGLBINDTEXTUREUNITPROC, BindTextureUnit)                                   \
  X(PFNGLBINDTEXTUREPROC, BindTexture)                                           \
  X(PFNGLACTIVETEXTUREPROC, ActiveTexture)                                       \
  X(PFNGLBINDIMAGETEXTUREPROC, BindImageTexture)                                 \
  X(PFNGLCREATESAMPLERSPROC, CreateSamplers)                                     \
  X(PFNGLDELETESAMPLERSPROC, DeleteSamplers)                                     \
  X(PFNGLSAMPLERPARAMETERIPROC, SamplerParameteri)                               \
  X(PFNGLBINDSAMPLERPROC, BindSampler)                                           \
  X(PFNGLCREATEBUFFERSPROC, CreateBuffers)                                       \
  X(PFNGLDELETEBUFFERSPROC, DeleteBuffers)                                       \
  X(PFNGLNAMEDBUFFERSTORAGEPROC, NamedBufferStorage)                             \
  X(PFNGLNAMEDBUFFERSUBDATAPROC, NamedBufferSubData)                             \
  X(PFNGLGETNAMEDBUFFERSUBDATAPROC, GetNamedBufferSubData)                       \
  X(PFNGLFENCESYNCPROC, FenceSync)                                               \
  X(PFNGLCLIENTWAITSYNCPROC, ClientWaitSync)                                     \
  X(PFNGLDELETESYNCPROC, DeleteSync)                                             \
  X(PFNGLCREATEQUERIESPROC, CreateQueries)                                       \
  X(PFNGLDELETEQUERIESPROC, DeleteQueries)                                       \
  X(PFNGLQUERYCOUNTERPROC, QueryCounter)                                         \
  X(PFNGLGETQUERYIVPROC, GetQueryiv)                                             \
  X(PFNGLGETQUERYOBJECTUI64VPROC, GetQueryObjectui64v)                           \
  X(PFNGLBINDBUFFERPROC, BindBuffer)                                             \
  X(PFNGLBINDBUFFERRANGEPROC, BindBufferRange)                                   \
  X(PFNGLBINDBUFFERBASEPROC, BindBufferBase)                                     \
  X(PFNGLCREATEVERTEXARRAYSPROC, CreateVertexArrays)                             \
  X(PFNGLDELETEVERTEXARRAYSPROC, DeleteVertexArrays)                             \
  X(PFNGLBINDVERTEXARRAYPROC, BindVertexArray)                                   \
  X(PFNGLBINDFRAMEBUFFERPROC, BindFramebuffer)                                   \
  X(PFNGLCHECKNAMEDFRAMEBUFFERSTATUSPROC, CheckNamedFramebufferStatus)           \
  X(PFNGLCREATESHADERPROC, CreateShader)                                         \
  X(PFNGLDELETESHADERPROC, DeleteShader)                                         \
  X(PFNGLSHADERSOURCEPROC, ShaderSource)                                         \
  X(PFNGLCOMPILESHADERPROC, CompileShader)                                       \
  X(PFNGLGETSHADERIVPROC, GetShaderiv)                                           \
  X(PFNGLGETSHADERINFOLOGPROC, GetShaderInfoLog)                                 \
  X(PFNGLCREATEPROGRAMPROC, CreateProgram)                                       \
  X(PFNGLDELETEPROGRAMPROC, DeleteProgram)                                       \
  X(PFNGLATTACHSHADERPROC, AttachShader)                                         \
  X(PFNGLLINKPROGRAMPROC, LinkProgram)                                           \
  X(PFNGLGETPROGRAMIVPROC, GetProgramiv)                                         \
  X(PFNGLGETPROGRAMINFOLOGPROC, GetProgramInfoLog)                               \
  X(PFNGLUSEPROGRAMPROC, UseProgram)                                             \
  X(PFNGLPROGRAMUNIFORM1IPROC, ProgramUniform1i)                                 \
  X(PFNGLDISPATCHCOMPUTEPROC, DispatchCompute)                                   \
  X(PFNGLDISPATCHCOMPUTEINDIRECTPROC, DispatchComputeIndirect)                   \
  X(PFNGLDRAWARRAYSINDIRECTPROC, DrawArraysIndirect)                             \
  X(PFNGLMEMORYBARRIERPROC, MemoryBarrier)                                       \
  X(PFNGLOBJECTLABELPROC, ObjectLabel)                                           \
  X(PFNGLPUSHDEBUGGROUPPROC, PushDebugGroup)                                     \
  X(PFNGLPOPDEBUGGROUPPROC, PopDebugGroup)

struct Gl {
#define SSLR_GL_DECLARE(type, name) type name = nullptr;
  SSLR_GL_FUNCTIONS(SSLR_GL_DECLARE)
#undef SSLR_GL_DECLARE

  // Loads every entry point; on failure returns the names that could not be found.
  Status load(GetProcAddress getProcAddress);

  // Binds `texture` (a GL_TEXTURE_2D, or 0) to the 2D target of `unit` and nothing else:
  // glBindTextureUnit(unit, 0) would unbind every target of the unit, a host's cube map too.
  void bindTexture2D(GLuint unit, GLuint texture) const {
    if (texture != 0) {
      BindTextureUnit(unit, texture);
      return;
    }
    ActiveTexture(GL_TEXTURE0 + unit);  // the state guard restores the host's active unit
    BindTexture(GL_TEXTURE_2D, 0);
  }
};

}  // namespace sslr::detail
