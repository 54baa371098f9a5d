// The GUI in a GLFW window with an OpenGL 3.3 core context. GL is reached
// only through glfwGetProcAddress (no libGL at link time: this binary also
// links OSMesa for the headless mode).
#include <imgui.h>
#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <backends/imgui_impl_glfw.h>

#include <cstdio>
#include <exception>
#include <string>
#include <vector>

#include "idbench/gui/gui_app.h"
#include "idbench/gui/gui_command.h"
#include "imgui_gl.h"
#include "imgui_setup.h"

namespace idbench::gui {
namespace {

void* GetProcAddress(const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); }

// The window's app, for GLFW's drop callback (a plain function; one window).
// Shift held while dropping sends a log to the held-out log.
GuiApp* g_drop_target = nullptr;
void OnDrop(GLFWwindow* window, int count, const char** paths) {
  if (!g_drop_target) return;
  const bool shift = glfwGetKey(window, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                     glfwGetKey(window, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS;
  g_drop_target->DropFiles(std::vector<std::string>(paths, paths + count), shift);
}

void OnGlfwError(int code, const char* description) { std::fprintf(stderr, "GLFW error %d: %s\n", code, description); }

}  // namespace

int RunGuiWindow(const GuiCommandOptions& options) {
  glfwSetErrorCallback(&OnGlfwError);
  if (!glfwInit()) {
    std::fprintf(stderr, "idbench gui: cannot open a window (no display?); try --headless\n");
    return 1;
  }
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 3);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 3);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  GLFWwindow* window = glfwCreateWindow(options.width, options.height, "idbench", nullptr, nullptr);
  if (!window) {
    std::fprintf(stderr, "idbench gui: cannot create an OpenGL 3.3 window\n");
    glfwTerminate();
    return 1;
  }
  glfwMakeContextCurrent(window);
  glfwSwapInterval(1);
  int code = 0;
  ImGuiContext* imgui = ImGui::CreateContext();
  try {
    internal::ConfigureImGui();
    // The recent files persist in imgui.ini (the headless GUI keeps none).
    static const std::string ini_path = internal::ImGuiIniPath();
    if (!ini_path.empty()) ImGui::GetIO().IniFilename = ini_path.c_str();
    ImGui_ImplGlfw_InitForOpenGL(window, true);
    internal::InitImGuiRenderer(&GetProcAddress);
    {
      GuiApp app({.robot = options.robot, .out_dir = options.out_dir}, &GetProcAddress);
      app.session().identify.data = options.data;  // the Log tab's logs
      app.session().identify.validate = options.validate;
      g_drop_target = &app;
      glfwSetDropCallback(window, &OnDrop);
      double last = glfwGetTime();
      for (int frame = 1; !glfwWindowShouldClose(window); ++frame) {
        // Wake up regularly while jobs run, so their progress shows.
        if (app.playing() || app.session().any_running()) glfwWaitEventsTimeout(1.0 / 30.0);
        else glfwWaitEventsTimeout(0.25);
        const double now = glfwGetTime();
        internal::NewImGuiRendererFrame();
        ImGui_ImplGlfw_NewFrame();
        ImGui::NewFrame();
        app.Frame(now - last);
        last = now;
        ImGui::Render();
        int w = 0, h = 0;
        glfwGetFramebufferSize(window, &w, &h);
        internal::RenderImGui(w, h);
        if (std::optional<std::string> path = app.TakeScreenshotRequest()) {
          try {
            internal::WriteFramebufferPng(*path, w, h);
            app.session().Info("screenshot written to " + *path);
          } catch (const std::exception& e) {
            app.session().Error(std::string("screenshot: ") + e.what());
          }
        }
        if (frame == options.frames) {
          // --frames: the last frame, then close (smoke tests).
          if (!options.screenshot.empty()) internal::WriteFramebufferPng(options.screenshot, w, h);
          break;
        }
        glfwSwapBuffers(window);
      }
      glfwSetDropCallback(window, nullptr);
      g_drop_target = nullptr;
    }
    internal::ShutdownImGuiRenderer();
    ImGui_ImplGlfw_Shutdown();
  } catch (const std::exception& e) {
    std::fprintf(stderr, "idbench gui: %s\n", e.what());
    code = 1;
  }
  ImGui::DestroyContext(imgui);
  glfwDestroyWindow(window);
  glfwTerminate();
  return code;
}

}  // namespace idbench::gui
