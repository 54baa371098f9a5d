// Headless GUI frame time at 1280×720 (OSMesa llvmpipe): ImGui's panels plus
// the 3D viewport, drawn into the offscreen window and finished (glFinish).
// Results in BENCHMARKS.md.
#include <benchmark/benchmark.h>

#include <stdexcept>
#include <string>

#include "idbench/gui/headless_gui.h"

namespace {

using idbench::gui::HeadlessGui;

const idbench::gui::HeadlessGuiOptions kOptions{
    .width = 1280, .height = 720, .session = {.robot = "paper6r", .out_dir = "/tmp/idbench_gui_benchmark"}};

void Click(HeadlessGui& gui, const std::string& widget) {
  std::string why;
  if (!gui.Click(widget, &why)) throw std::runtime_error(why);
}

// The robot moving (the paper motion playing): the viewport is redrawn every frame.
void BM_GuiFramePlaying(benchmark::State& state) {
  HeadlessGui gui(kOptions);
  Click(gui, "timeline.play");
  for (auto _ : state) {
    gui.RenderFrame();
    gui.Finish();
  }
}
BENCHMARK(BM_GuiFramePlaying)->Unit(benchmark::kMillisecond)->UseRealTime();

// Nothing moving: the viewport's texture is reused, ImGui redraws the panels.
void BM_GuiFrameStill(benchmark::State& state) {
  HeadlessGui gui(kOptions);
  for (auto _ : state) {
    gui.RenderFrame();
    gui.Finish();
  }
}
BENCHMARK(BM_GuiFrameStill)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
