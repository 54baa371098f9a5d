#include "idbench/gui/headless_gui.h"

#include <imgui.h>

#include <cfloat>
#include <chrono>
#include <stdexcept>
#include <thread>

#include "idbench/render/osmesa_context.h"
#include "imgui_gl.h"
#include "imgui_setup.h"

namespace idbench::gui {

struct HeadlessGui::Impl {
  explicit Impl(const HeadlessGuiOptions& o) : options(o) {
    imgui = ImGui::CreateContext();
    ImGui::SetCurrentContext(imgui);
    ImGuiIO& io = ImGui::GetIO();
    io.DisplaySize = ImVec2(static_cast<float>(o.width), static_cast<float>(o.height));
    io.MousePos = ImVec2(-FLT_MAX, -FLT_MAX);
    internal::ConfigureImGui();
    internal::InitImGuiRenderer(OsMesaContext::loader());
    target = std::make_unique<internal::OffscreenTarget>(o.width, o.height);
    app = std::make_unique<GuiApp>(o.session, OsMesaContext::loader());
  }
  ~Impl() {
    ImGui::SetCurrentContext(imgui);
    app.reset();  // stops the jobs while GL and ImGui still exist
    target.reset();
    internal::ShutdownImGuiRenderer();
    ImGui::DestroyContext(imgui);
  }

  HeadlessGuiOptions options;
  OsMesaContext context;  // first: everything below needs it current
  ImGuiContext* imgui = nullptr;
  std::unique_ptr<internal::OffscreenTarget> target;
  std::unique_ptr<GuiApp> app;
};

HeadlessGui::HeadlessGui(const HeadlessGuiOptions& options) {
  if (options.width < 64 || options.height < 64 || options.width > 8192 || options.height > 8192)
    throw std::invalid_argument("headless GUI: expected a size within [64, 8192] px, got " +
                                std::to_string(options.width) + "x" + std::to_string(options.height));
  impl_ = std::make_unique<Impl>(options);
  // ImGui hides a window in its first frame: the second one is what a user sees.
  RenderFrame();
  RenderFrame();
}

HeadlessGui::~HeadlessGui() = default;

void HeadlessGui::RenderFrame() {
  ImGui::SetCurrentContext(impl_->imgui);
  impl_->app->WaitForLogPlot();  // scripted frames see the plot once its log is read
  ImGuiIO& io = ImGui::GetIO();
  io.DeltaTime = static_cast<float>(impl_->options.frame_seconds);
  internal::NewImGuiRendererFrame();
  ImGui::NewFrame();
  impl_->app->Frame(impl_->options.frame_seconds);
  ImGui::Render();
  impl_->target->Bind();
  internal::RenderImGui(impl_->options.width, impl_->options.height);
  if (std::optional<std::string> path = impl_->app->TakeScreenshotRequest()) {
    try {
      WriteScreenshot(*path);
      impl_->app->session().Info("screenshot written to " + *path);
    } catch (const std::exception& e) {
      impl_->app->session().Error(std::string("screenshot: ") + e.what());
    }
  }
}

void HeadlessGui::Finish() { internal::FinishGl(); }

Image HeadlessGui::Screenshot() {
  impl_->target->Bind();
  return internal::ReadFramebuffer(impl_->options.width, impl_->options.height);
}

void HeadlessGui::WriteScreenshot(const std::string& path) {
  impl_->target->Bind();
  internal::WriteFramebufferPng(path, impl_->options.width, impl_->options.height);
}

namespace {

// The widget of the last frame the mouse can reach, or null with *why.
const WidgetEntry* Reachable(const WidgetRegistry& widgets, const std::string& widget, std::string* why) {
  const WidgetEntry* entry = widgets.Find(widget);
  if (!entry) {
    *why = "no widget '" + widget + "' on screen (a tab may need clicking first)";
    return nullptr;
  }
  if (!entry->visible) {
    *why = "widget '" + widget + "' is scrolled out of view";
    return nullptr;
  }
  return entry;
}

}  // namespace

bool HeadlessGui::Click(const std::string& widget, std::string* why) {
  const WidgetEntry* entry = Reachable(widgets(), widget, why);
  if (!entry) return false;
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  io.MousePos = ImVec2(entry->rect.center_x(), entry->rect.center_y());
  RenderFrame();  // hover
  io.MouseDown[0] = true;
  RenderFrame();  // press
  io.MouseDown[0] = false;
  RenderFrame();  // release: the click
  RenderFrame();  // what the click changed (e.g. a robot loaded at the end of the last frame) is drawn
  return true;
}

void HeadlessGui::Drop(const std::vector<std::string>& paths, bool held_out) {
  ImGui::SetCurrentContext(impl_->imgui);
  app().DropFiles(paths, held_out);
  RenderFrame();  // a dropped robot loads at the end of this frame
  RenderFrame();
}

bool HeadlessGui::Drag(const std::string& widget, double from, double to, std::string* why) {
  if (!(from >= 0.0 && from < 1.0) || !(to >= 0.0 && to <= 1.0)) {
    *why = "drag " + widget + ": expected fractions 0 <= from < 1 and 0 <= to <= 1, got " + std::to_string(from) +
           " and " + std::to_string(to);
    return false;
  }
  const WidgetEntry* entry = Reachable(widgets(), widget, why);
  if (!entry) return false;
  const WidgetRect rect = entry->rect;  // the registry changes with the frames below
  ImGui::SetCurrentContext(impl_->imgui);
  ImGuiIO& io = ImGui::GetIO();
  auto at = [&](double fraction) {
    return ImVec2(static_cast<float>(rect.x0 + fraction * rect.width()), rect.center_y());
  };
  io.MousePos = at(from);
  RenderFrame();  // hover
  io.MouseDown[0] = true;
  RenderFrame();  // press
  io.MousePos = at(to);
  RenderFrame();  // move
  io.MouseDown[0] = false;
  RenderFrame();  // release
  RenderFrame();  // what the drag changed is drawn
  return true;
}

bool HeadlessGui::Set(const std::string& widget, const std::string& value, std::string* why) {
  const WidgetEntry* entry = widgets().Find(widget);
  if (!entry) {
    *why = "no widget '" + widget + "' on screen (a tab may need clicking first)";
    return false;
  }
  if (!entry->setter) {
    *why = "widget '" + widget + "' has no value to set";
    return false;
  }
  std::string problem;
  if (!entry->setter(value, &problem)) {
    *why = widget + ": " + problem;
    return false;
  }
  RenderFrame();
  return true;
}

bool HeadlessGui::WaitForJob(JobKind kind, double timeout_seconds, std::string* why) {
  const auto start = std::chrono::steady_clock::now();
  while (session().running(kind)) {
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > timeout_seconds) {
      *why = std::string("job '") + JobName(kind) + "' still running after " + std::to_string(timeout_seconds) + " s";
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
    RenderFrame();
  }
  RenderFrame();
  return true;
}

GuiApp& HeadlessGui::app() { return *impl_->app; }
int HeadlessGui::width() const { return impl_->options.width; }
int HeadlessGui::height() const { return impl_->options.height; }

}  // namespace idbench::gui
