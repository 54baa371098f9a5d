// Draws a Scene with OpenGL 3.3 core into the renderer's own multisampled
// framebuffer object: lit primitives, a checkered floor fading into the
// background, the primitives' shadow cast on the floor by a directional
// light (planar projection), and the parts below the floor that it hides
// seen through it at half opacity. GL is reached only through the loader, so the
// renderer works under OSMesa (headless, see osmesa_context.h) and in a GUI
// window alike; a GL context must be current on the calling thread for the
// renderer's whole life.
#pragma once

#include <Eigen/Core>
#include <memory>
#include <vector>

#include "idbench/render/camera.h"
#include "idbench/render/gl_proc_loader.h"
#include "idbench/render/image.h"
#include "idbench/render/robot_scene.h"

namespace idbench {

// The ground the scene stands on: a square of half-size `radius` at height z.
struct Floor {
  double z = 0.0;                                       // [m]
  Eigen::Vector2d center_W = Eigen::Vector2d::Zero();   // [m]
  double radius = 5.0;                                  // [m]; fades out towards it
};

// The floor the robot stands on: at z = 0 (also when points reach below it:
// Draw shows what lies under the floor through it), centred under the
// points, wide enough to catch their shadows. Points must not be empty.
Floor FitFloor(const std::vector<Eigen::Vector3d>& points);

class SceneRenderer {
 public:
  static constexpr int kMaxSize = 8192;  // [px] per side

  // Loads the GL entry points and builds shaders and meshes. Throws
  // std::runtime_error naming what the context lacks.
  explicit SceneRenderer(GlProcLoader loader, int msaa_samples = 4);
  ~SceneRenderer();
  SceneRenderer(const SceneRenderer&) = delete;
  SceneRenderer& operator=(const SceneRenderer&) = delete;

  // Draws into the renderer's framebuffer, (re)sized to width × height; the
  // caller's framebuffer binding and viewport are restored. Throws
  // std::invalid_argument if a size is outside [1, kMaxSize].
  void Draw(const Scene& scene, const Floor& floor, const Camera& camera, int width, int height);

  // The resolved colour texture of the last Draw (a GL texture name), for a
  // GUI to show without a read-back.
  unsigned color_texture() const;

  // The last Draw, read back.
  Image ReadImage() const;

  // Draw, then ReadImage.
  Image Render(const Scene& scene, const Floor& floor, const Camera& camera, int width, int height);

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace idbench
