// The one file of gui/ that calls GL: ImGui's OpenGL 3 backend, compiled from
// its source with the gl3w loader header's declarations (gl* are macros over
// a table of pointers) filled by our loader instead of by dlopen("libGL").
#include "imgui_gl.h"

#include <filesystem>
#include <stdexcept>
#include <string>

#include "idbench/workbench/formats/atomic_file.h"
#include "idbench/render/png_codec.h"

#define IMGL3W_IMPL
#include <backends/imgui_impl_opengl3_loader.h>
#define IMGUI_IMPL_OPENGL_LOADER_CUSTOM
// The backend source from libimgui-dev (its directory is on the include path).
#include "imgui_impl_opengl3.cpp"

namespace idbench::gui::internal {
namespace {

// Framebuffer objects are not in the backend's table: load them alongside.
// Types from the Khronos headers (glcorearb.h), repeated because the gl3w
// header above declares a subset of them.
using GenFn = void (*)(GLsizei, GLuint*);
using DeleteFn = void (*)(GLsizei, const GLuint*);
using BindFn = void (*)(GLenum, GLuint);
using StorageFn = void (*)(GLenum, GLenum, GLsizei, GLsizei);
using AttachFn = void (*)(GLenum, GLenum, GLenum, GLuint);
using StatusFn = GLenum (*)(GLenum);
constexpr GLenum kFramebuffer = 0x8D40, kRenderbuffer = 0x8D41, kColorAttachment0 = 0x8CE0,
                 kDepthAttachment = 0x8D00, kFramebufferComplete = 0x8CD5, kRgba8 = 0x8058,
                 kDepthComponent24 = 0x81A6;

struct FramebufferFunctions {
  GenFn GenFramebuffers = nullptr, GenRenderbuffers = nullptr;
  DeleteFn DeleteFramebuffers = nullptr, DeleteRenderbuffers = nullptr;
  BindFn BindFramebuffer = nullptr, BindRenderbuffer = nullptr;
  StorageFn RenderbufferStorage = nullptr;
  AttachFn FramebufferRenderbuffer = nullptr;
  StatusFn CheckFramebufferStatus = nullptr;
  void (*Finish)() = nullptr;
};
FramebufferFunctions fb;
GlProcLoader current_loader = nullptr;

GL3WglProc LoadThroughLoader(const char* name) { return reinterpret_cast<GL3WglProc>(current_loader(name)); }

template <typename F>
void Load(F* f, const char* name) {
  *f = reinterpret_cast<F>(current_loader(name));
  if (*f == nullptr) throw std::runtime_error(std::string("OpenGL: the context lacks ") + name);
}

}  // namespace

void InitImGuiRenderer(GlProcLoader loader) {
  current_loader = loader;
  if (imgl3wInit2(&LoadThroughLoader) != GL3W_OK)
    throw std::runtime_error("OpenGL: the GUI needs an OpenGL 3.3 context");
  Load(&fb.GenFramebuffers, "glGenFramebuffers");
  Load(&fb.GenRenderbuffers, "glGenRenderbuffers");
  Load(&fb.DeleteFramebuffers, "glDeleteFramebuffers");
  Load(&fb.DeleteRenderbuffers, "glDeleteRenderbuffers");
  Load(&fb.BindFramebuffer, "glBindFramebuffer");
  Load(&fb.BindRenderbuffer, "glBindRenderbuffer");
  Load(&fb.RenderbufferStorage, "glRenderbufferStorage");
  Load(&fb.FramebufferRenderbuffer, "glFramebufferRenderbuffer");
  Load(&fb.CheckFramebufferStatus, "glCheckFramebufferStatus");
  Load(&fb.Finish, "glFinish");
  if (!ImGui_ImplOpenGL3_Init("#version 330 core"))
    throw std::runtime_error("OpenGL: Dear ImGui's renderer did not initialise");
}

void ShutdownImGuiRenderer() { ImGui_ImplOpenGL3_Shutdown(); }

void NewImGuiRendererFrame() { ImGui_ImplOpenGL3_NewFrame(); }

void RenderImGui(int width, int height) {
  glViewport(0, 0, width, height);
  const ImVec4 bg = ImGui::GetStyle().Colors[ImGuiCol_WindowBg];
  glClearColor(bg.x, bg.y, bg.z, 1.0f);
  glClear(GL_COLOR_BUFFER_BIT);
  ImGui_ImplOpenGL3_RenderDrawData(ImGui::GetDrawData());
}

void FinishGl() { fb.Finish(); }

Image ReadFramebuffer(int width, int height) {
  Image image(width, height);
  std::vector<unsigned char> rgba(static_cast<size_t>(4) * static_cast<size_t>(width) * static_cast<size_t>(height));
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  // GL rows run bottom to top.
  for (int y = 0; y < height; ++y) {
    const unsigned char* src = rgba.data() + 4 * static_cast<size_t>(height - 1 - y) * static_cast<size_t>(width);
    for (int x = 0; x < width; ++x) {
      std::uint8_t* dst = image.at(x, y);
      dst[0] = src[4 * x], dst[1] = src[4 * x + 1], dst[2] = src[4 * x + 2];
    }
  }
  return image;
}

void WriteFramebufferPng(const std::string& path, int width, int height) {
  const std::filesystem::path p(path);
  if (p.has_parent_path()) EnsureOutputDirectory(p.parent_path());
  WriteFileAtomically(p, EncodePng(ReadFramebuffer(width, height)));
}

OffscreenTarget::OffscreenTarget(int width, int height) {
  fb.GenFramebuffers(1, &framebuffer_);
  fb.GenRenderbuffers(1, &color_);
  fb.GenRenderbuffers(1, &depth_);
  fb.BindRenderbuffer(kRenderbuffer, color_);
  fb.RenderbufferStorage(kRenderbuffer, kRgba8, width, height);
  fb.BindRenderbuffer(kRenderbuffer, depth_);
  fb.RenderbufferStorage(kRenderbuffer, kDepthComponent24, width, height);
  fb.BindFramebuffer(kFramebuffer, framebuffer_);
  fb.FramebufferRenderbuffer(kFramebuffer, kColorAttachment0, kRenderbuffer, color_);
  fb.FramebufferRenderbuffer(kFramebuffer, kDepthAttachment, kRenderbuffer, depth_);
  if (fb.CheckFramebufferStatus(kFramebuffer) != kFramebufferComplete)
    throw std::runtime_error("OpenGL: cannot create a " + std::to_string(width) + "x" + std::to_string(height) +
                             " offscreen framebuffer");
}

OffscreenTarget::~OffscreenTarget() {
  fb.BindFramebuffer(kFramebuffer, 0);
  fb.DeleteFramebuffers(1, &framebuffer_);
  fb.DeleteRenderbuffers(1, &color_);
  fb.DeleteRenderbuffers(1, &depth_);
}

void OffscreenTarget::Bind() const { fb.BindFramebuffer(kFramebuffer, framebuffer_); }

}  // namespace idbench::gui::internal
