// Dear ImGui's OpenGL 3 renderer (the backend source Debian ships in
// libimgui-dev, compiled here) with its GL entry points loaded through our
// GlProcLoader, so it draws under OSMesa as under GLFW. Internal to gui/.
#pragma once

#include <string>

#include "idbench/render/gl_proc_loader.h"
#include "idbench/render/image.h"

namespace idbench::gui::internal {

// Loads GL for the backend and initialises it (GLSL 330 core) for the current
// ImGui context. Throws std::runtime_error when the context lacks GL 3.3.
void InitImGuiRenderer(GlProcLoader loader);
void ShutdownImGuiRenderer();
void NewImGuiRendererFrame();
// Clears the bound framebuffer (width × height) to the windows' background
// colour (ImGuiCol_WindowBg, drawn transparent) and draws ImGui's draw data.
void RenderImGui(int width, int height);

// Waits until GL has executed every command (timing a frame).
void FinishGl();

// The bound framebuffer's width × height pixels, top row first.
Image ReadFramebuffer(int width, int height);
// ReadFramebuffer as a PNG file, written atomically (directories created).
// Throws std::runtime_error naming the path.
void WriteFramebufferPng(const std::string& path, int width, int height);

// A framebuffer object with colour and depth renderbuffers: the "window" of
// the headless GUI (OSMesa's own buffer is 1 × 1).
class OffscreenTarget {
 public:
  OffscreenTarget(int width, int height);  // after InitImGuiRenderer; throws std::runtime_error
  ~OffscreenTarget();
  OffscreenTarget(const OffscreenTarget&) = delete;
  OffscreenTarget& operator=(const OffscreenTarget&) = delete;
  void Bind() const;

 private:
  unsigned framebuffer_ = 0, color_ = 0, depth_ = 0;
};

}  // namespace idbench::gui::internal
