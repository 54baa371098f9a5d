// Headless rendering speed (OSMesa llvmpipe): the default pose figure, one
// large frame, and the fixed cost of a context and renderer. Results in
// BENCHMARKS.md; the whole `idbench render` command is timed with hyperfine.
#include <benchmark/benchmark.h>

#include <numbers>

#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"
#include "idbench/render/osmesa_context.h"
#include "idbench/render/png_codec.h"
#include "idbench/render/pose_figure.h"

namespace {

using namespace idbench;

constexpr double kPaperQdd = 30.0 * std::numbers::pi / 180.0;  // [rad/s²]

// The paper's Figure 2: 8 panels of 480×360, MSAA 4, encoded as PNG.
void BM_PoseFigureDefault(benchmark::State& state) {
  OsMesaContext context;
  SceneRenderer renderer(OsMesaContext::loader(), 4);
  const RobotModel model = MakePaper6r();
  const auto motion = MakePaperMotion(6, kPaperQdd, 2.0);
  const PoseFigureOptions options;
  for (auto _ : state) benchmark::DoNotOptimize(EncodePng(RenderPoseFigure(renderer, model, *motion, options)));
}
BENCHMARK(BM_PoseFigureDefault)->Unit(benchmark::kMillisecond)->UseRealTime();

// One 1600×1200 MSAA 4 frame of paper6r, read back (no PNG).
void BM_Frame1600x1200(benchmark::State& state) {
  OsMesaContext context;
  SceneRenderer renderer(OsMesaContext::loader(), 4);
  const RobotModel model = MakePaper6r();
  RobotData data(model);
  const Eigen::VectorXd q = Eigen::VectorXd::Constant(6, 0.3), zero = Eigen::VectorXd::Zero(6);
  ComputeKinematics(model, q, zero, zero, &data);
  const Scene scene = BuildRobotScene(model, data);
  const std::vector<Eigen::Vector3d> points = scene.BoundingPoints();
  const Camera camera = FitCamera(points, 1600.0 / 1200.0);
  const Floor floor = FitFloor(points);
  for (auto _ : state) benchmark::DoNotOptimize(renderer.Render(scene, floor, camera, 1600, 1200));
}
BENCHMARK(BM_Frame1600x1200)->Unit(benchmark::kMillisecond)->UseRealTime();

// PNG encoding of the default figure (1920×720 RGB).
void BM_EncodeFigurePng(benchmark::State& state) {
  OsMesaContext context;
  SceneRenderer renderer(OsMesaContext::loader(), 4);
  const RobotModel model = MakePaper6r();
  const auto motion = MakePaperMotion(6, kPaperQdd, 2.0);
  const Image figure = RenderPoseFigure(renderer, model, *motion, PoseFigureOptions{});
  for (auto _ : state) benchmark::DoNotOptimize(EncodePng(figure));
}
BENCHMARK(BM_EncodeFigurePng)->Unit(benchmark::kMillisecond)->UseRealTime();

// Creating the OSMesa context and the renderer (shaders, meshes).
void BM_ContextAndRenderer(benchmark::State& state) {
  for (auto _ : state) {
    OsMesaContext context;
    SceneRenderer renderer(OsMesaContext::loader(), 4);
    benchmark::DoNotOptimize(renderer.color_texture());
  }
}
BENCHMARK(BM_ContextAndRenderer)->Unit(benchmark::kMillisecond)->UseRealTime();

}  // namespace

BENCHMARK_MAIN();
