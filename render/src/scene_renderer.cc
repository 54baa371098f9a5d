#include "idbench/render/scene_renderer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>

#include "gl_functions.h"

namespace idbench {
namespace {

using render_internal::GlFunctions;

// Look of the stage: neutral greys, so that only the robot is coloured.
const Eigen::Vector3f kBackground(0.965f, 0.965f, 0.975f);
const Eigen::Vector3f kFloorLight(0.86f, 0.86f, 0.87f), kFloorDark(0.80f, 0.80f, 0.815f);
const Eigen::Vector3f kShadow(0.58f, 0.58f, 0.60f);
// Direction towards the key light (W): above, from the camera's left.
const Eigen::Vector3d kToLight_W = Eigen::Vector3d(-0.25, -0.75, 1.3).normalized();

constexpr const char* kVertexShader = R"(#version 330 core
layout(location = 0) in vec3 a_position_G;
layout(location = 1) in vec3 a_normal_G;
uniform mat4 u_model;      // G -> W, scaled
uniform mat3 u_normal;     // normals G -> W (inverse transpose of u_model)
uniform mat4 u_view_proj;  // W -> clip
out vec3 v_position_W;
out vec3 v_normal_W;
void main() {
  vec4 p_W = u_model * vec4(a_position_G, 1.0);
  v_position_W = p_W.xyz;
  v_normal_W = u_normal * a_normal_G;
  gl_Position = u_view_proj * p_W;
}
)";

constexpr const char* kFragmentShader = R"(#version 330 core
in vec3 v_position_W;
in vec3 v_normal_W;
uniform int u_mode;          // 0 lit primitive, 1 floor, 2 shadow, 3 ghost below the floor
uniform vec3 u_color;
uniform vec3 u_eye_W;
uniform vec3 u_to_light_W;
uniform vec3 u_background;
uniform vec3 u_floor_light;
uniform vec3 u_floor_dark;
uniform vec3 u_floor_center; // (x, y, radius)
uniform float u_tile;        // checker size [m]
uniform float u_floor_z;     // [m]
out vec4 frag_color;
float FloorFade() {
  float d = length(v_position_W.xy - u_floor_center.xy) / u_floor_center.z;
  return smoothstep(0.55, 1.0, d);
}
void main() {
  if (u_mode == 1) {
    vec2 cell = floor(v_position_W.xy / u_tile);
    vec3 c = mod(cell.x + cell.y, 2.0) < 0.5 ? u_floor_light : u_floor_dark;
    frag_color = vec4(mix(c, u_background, FloorFade()), 1.0);
    return;
  }
  if (u_mode == 2) {
    frag_color = vec4(mix(u_color, u_background, FloorFade()), 1.0);
    return;
  }
  if (u_mode == 3 && v_position_W.z > u_floor_z) discard;
  vec3 n = normalize(v_normal_W);
  vec3 v = normalize(u_eye_W - v_position_W);
  if (dot(n, v) < 0.0) n = -n;
  vec3 l = normalize(u_to_light_W);
  float key = max(dot(n, l), 0.0);
  float fill = 0.25 * max(dot(n, normalize(vec3(v.xy, 0.2))), 0.0);
  float sky = 0.12 * (0.5 + 0.5 * n.z);
  float spec = 0.28 * pow(max(dot(n, normalize(l + v)), 0.0), 40.0);
  vec3 c = u_color * (0.30 + sky + 0.55 * key + fill) + vec3(spec);
  frag_color = vec4(min(c, vec3(1.0)), u_mode == 3 ? 0.5 : 1.0);
}
)";

// Unit meshes, triangles of (position, normal): a cylinder of radius 1 and
// length 1 along z centred at the origin, a unit cube, a unit sphere.
struct MeshRange {
  int first = 0, count = 0;  // vertices
};

void AddVertex(std::vector<float>* v, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  for (int k = 0; k < 3; ++k) v->push_back(static_cast<float>(p[k]));
  for (int k = 0; k < 3; ++k) v->push_back(static_cast<float>(n[k]));
}

void AddCylinder(std::vector<float>* v, int segments) {
  const auto rim = [&](int k) {
    const double a = 2.0 * std::numbers::pi * k / segments;
    return Eigen::Vector3d(std::cos(a), std::sin(a), 0.0);
  };
  const Eigen::Vector3d top(0, 0, 0.5), bottom(0, 0, -0.5);
  for (int k = 0; k < segments; ++k) {
    const Eigen::Vector3d a = rim(k), b = rim(k + 1);
    // Side: two triangles with smooth normals.
    AddVertex(v, a + bottom, a), AddVertex(v, b + bottom, b), AddVertex(v, b + top, b);
    AddVertex(v, a + bottom, a), AddVertex(v, b + top, b), AddVertex(v, a + top, a);
    // Caps.
    AddVertex(v, top, Eigen::Vector3d::UnitZ()), AddVertex(v, a + top, Eigen::Vector3d::UnitZ()),
        AddVertex(v, b + top, Eigen::Vector3d::UnitZ());
    AddVertex(v, bottom, -Eigen::Vector3d::UnitZ()), AddVertex(v, b + bottom, -Eigen::Vector3d::UnitZ()),
        AddVertex(v, a + bottom, -Eigen::Vector3d::UnitZ());
  }
}

void AddBox(std::vector<float>* v) {
  for (int axis = 0; axis < 3; ++axis) {
    for (double sign : {-1.0, 1.0}) {
      Eigen::Vector3d n = Eigen::Vector3d::Zero();
      n[axis] = sign;
      const Eigen::Vector3d u = Eigen::Vector3d::Unit((axis + 1) % 3), w = Eigen::Vector3d::Unit((axis + 2) % 3);
      const Eigen::Vector3d c = 0.5 * n;
      const Eigen::Vector3d p[4] = {c - 0.5 * u - 0.5 * w, c + 0.5 * u - 0.5 * w, c + 0.5 * u + 0.5 * w,
                                    c - 0.5 * u + 0.5 * w};
      for (int i : {0, 1, 2, 0, 2, 3}) AddVertex(v, p[i], n);
    }
  }
}

void AddSphere(std::vector<float>* v, int slices, int stacks) {
  const auto point = [&](int i, int j) {
    const double theta = std::numbers::pi * j / stacks, phi = 2.0 * std::numbers::pi * i / slices;
    return Eigen::Vector3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  };
  for (int j = 0; j < stacks; ++j) {
    for (int i = 0; i < slices; ++i) {
      const Eigen::Vector3d a = point(i, j), b = point(i + 1, j), c = point(i + 1, j + 1), d = point(i, j + 1);
      AddVertex(v, a, a), AddVertex(v, d, d), AddVertex(v, c, c);
      AddVertex(v, a, a), AddVertex(v, c, c), AddVertex(v, b, b);
    }
  }
}

Eigen::Matrix4f ToFloat(const Eigen::Matrix4d& m) { return m.cast<float>(); }

// G scaled to the unit mesh: cylinder (r, r, length), box edges, sphere radius.
Eigen::Matrix4d ModelMatrix(const ScenePrimitive& p) {
  Eigen::Matrix4d scale = Eigen::Matrix4d::Identity();
  scale.diagonal().head<3>() = p.size;
  return p.X_WG.matrix() * scale;
}

}  // namespace

Floor FitFloor(const std::vector<Eigen::Vector3d>& points) {
  Eigen::Vector3d lo = Eigen::Vector3d::Constant(INFINITY), hi = Eigen::Vector3d::Constant(-INFINITY);
  for (const Eigen::Vector3d& p : points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  Floor floor;
  floor.z = 0.0;  // where the robot stands; what reaches below shows through it
  floor.center_W = 0.5 * (lo.head<2>() + hi.head<2>());
  // Wide enough for the farthest point and its shadow.
  const double height = hi.z() - floor.z;
  floor.radius = 1.6 * (0.5 * (hi.head<2>() - lo.head<2>()).norm() + height);
  return floor;
}

// A triangle mesh on the GPU, in its own buffer: flat-shaded triangles of
// (position, normal).
struct GpuMesh {
  GLuint vao = 0, vbo = 0;
  int count = 0;  // vertices
};

std::vector<float> FlatTriangles(const TriangleMesh& mesh) {
  std::vector<float> v;
  v.reserve(18 * mesh.triangles.size());
  for (const Eigen::Vector3i& t : mesh.triangles) {
    const Eigen::Vector3d &a = mesh.vertices[t[0]], &b = mesh.vertices[t[1]], &c = mesh.vertices[t[2]];
    const Eigen::Vector3d n = (b - a).cross(c - a);
    if (!(n.norm() > 0.0)) continue;  // degenerate
    const Eigen::Vector3d unit = n.normalized();
    AddVertex(&v, a, unit), AddVertex(&v, b, unit), AddVertex(&v, c, unit);
  }
  return v;
}

struct SceneRenderer::Impl {
  GlFunctions gl;
  int samples = 4;
  GLuint program = 0, vao = 0, vbo = 0;
  MeshRange cylinder, box, sphere, quad;
  // Meshes uploaded on first use, kept while the renderer lives (the shared
  // pointer keeps the key's address from being reused).
  std::map<std::shared_ptr<const TriangleMesh>, GpuMesh> meshes;
  // Multisampled target and its resolved copy (a texture).
  GLuint msaa_fbo = 0, msaa_color = 0, msaa_depth = 0, resolve_fbo = 0, resolve_texture = 0;
  int width = 0, height = 0;
  // Uniform locations.
  GLint u_model = -1, u_normal = -1, u_view_proj = -1, u_mode = -1, u_color = -1, u_eye = -1, u_to_light = -1,
        u_background = -1, u_floor_light = -1, u_floor_dark = -1, u_floor_center = -1, u_tile = -1,
        u_floor_z = -1;

  // Throws with the info log unless `status` of the shader or program is set.
  static void Check(GLuint object, GLenum status, PFNGLGETSHADERIVPROC get_iv, PFNGLGETSHADERINFOLOGPROC get_log,
                    const char* what) {
    GLint ok = 0;
    get_iv(object, status, &ok);
    if (ok) return;
    char log[1024] = {};
    get_log(object, sizeof(log), nullptr, log);
    throw std::runtime_error(std::string("OpenGL: ") + what + ": " + log);
  }

  GLuint Compile(GLenum type, const char* source) {
    const GLuint shader = gl.CreateShader(type);
    gl.ShaderSource(shader, 1, &source, nullptr);
    gl.CompileShader(shader);
    Check(shader, GL_COMPILE_STATUS, gl.GetShaderiv, gl.GetShaderInfoLog, "shader does not compile");
    return shader;
  }

  void BuildProgram() {
    const GLuint vs = Compile(GL_VERTEX_SHADER, kVertexShader), fs = Compile(GL_FRAGMENT_SHADER, kFragmentShader);
    program = gl.CreateProgram();
    gl.AttachShader(program, vs);
    gl.AttachShader(program, fs);
    gl.LinkProgram(program);
    gl.DeleteShader(vs);
    gl.DeleteShader(fs);
    Check(program, GL_LINK_STATUS, gl.GetProgramiv, gl.GetProgramInfoLog, "shaders do not link");
    const auto at = [&](const char* name) { return gl.GetUniformLocation(program, name); };
    u_model = at("u_model"), u_normal = at("u_normal"), u_view_proj = at("u_view_proj"), u_mode = at("u_mode");
    u_color = at("u_color"), u_eye = at("u_eye_W"), u_to_light = at("u_to_light_W"), u_background = at("u_background");
    u_floor_light = at("u_floor_light"), u_floor_dark = at("u_floor_dark"), u_floor_center = at("u_floor_center");
    u_tile = at("u_tile"), u_floor_z = at("u_floor_z");
  }

  // Binds the vertex array of a primitive's mesh (the shared one for the unit
  // primitives); returns the vertex range to draw.
  MeshRange BindMeshOf(const ScenePrimitive& p) {
    if (p.kind != Shape::Kind::kMesh || p.mesh == nullptr) {
      gl.BindVertexArray(vao);
      return MeshOf(p.kind);
    }
    auto it = meshes.find(p.mesh);
    if (it == meshes.end()) {
      const std::vector<float> v = FlatTriangles(*p.mesh);
      GpuMesh g;
      g.count = static_cast<int>(v.size() / 6);
      gl.GenVertexArrays(1, &g.vao);
      gl.BindVertexArray(g.vao);
      gl.GenBuffers(1, &g.vbo);
      gl.BindBuffer(GL_ARRAY_BUFFER, g.vbo);
      gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
      SetVertexLayout();
      it = meshes.emplace(p.mesh, g).first;
    }
    gl.BindVertexArray(it->second.vao);
    return MeshRange{0, it->second.count};
  }

  // Position at location 0 and normal at 1, interleaved, for the bound buffer.
  void SetVertexLayout() {
    gl.VertexAttribPointer(0, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), nullptr);
    gl.EnableVertexAttribArray(0);
    gl.VertexAttribPointer(1, 3, GL_FLOAT, GL_FALSE, 6 * sizeof(float), reinterpret_cast<void*>(3 * sizeof(float)));
    gl.EnableVertexAttribArray(1);
  }

  void BuildMeshes() {
    std::vector<float> v;
    const auto range = [&](auto add) {
      MeshRange r;
      r.first = static_cast<int>(v.size() / 6);
      add();
      r.count = static_cast<int>(v.size() / 6) - r.first;
      return r;
    };
    cylinder = range([&] { AddCylinder(&v, 48); });
    box = range([&] { AddBox(&v); });
    sphere = range([&] { AddSphere(&v, 32, 16); });
    // The floor: the cube's +z face, scaled flat.
    quad = MeshRange{box.first + 5 * 6, 6};
    gl.GenVertexArrays(1, &vao);
    gl.BindVertexArray(vao);
    gl.GenBuffers(1, &vbo);
    gl.BindBuffer(GL_ARRAY_BUFFER, vbo);
    gl.BufferData(GL_ARRAY_BUFFER, static_cast<GLsizeiptr>(v.size() * sizeof(float)), v.data(), GL_STATIC_DRAW);
    SetVertexLayout();
    gl.BindVertexArray(0);
  }

  void DeleteTargets() {
    if (msaa_fbo) gl.DeleteFramebuffers(1, &msaa_fbo), gl.DeleteFramebuffers(1, &resolve_fbo);
    if (msaa_color) gl.DeleteRenderbuffers(1, &msaa_color), gl.DeleteRenderbuffers(1, &msaa_depth);
    if (resolve_texture) gl.DeleteTextures(1, &resolve_texture);
    msaa_fbo = resolve_fbo = msaa_color = msaa_depth = resolve_texture = 0;
  }

  // (Re)creates the framebuffers at w × h.
  void Resize(int w, int h) {
    if (w == width && h == height && msaa_fbo) return;
    DeleteTargets();
    gl.GenRenderbuffers(1, &msaa_color);
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaa_color);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_RGBA8, w, h);
    gl.GenRenderbuffers(1, &msaa_depth);
    gl.BindRenderbuffer(GL_RENDERBUFFER, msaa_depth);
    gl.RenderbufferStorageMultisample(GL_RENDERBUFFER, samples, GL_DEPTH_COMPONENT24, w, h);
    gl.GenFramebuffers(1, &msaa_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, msaa_fbo);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_RENDERBUFFER, msaa_color);
    gl.FramebufferRenderbuffer(GL_FRAMEBUFFER, GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, msaa_depth);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error("OpenGL: cannot create a " + std::to_string(w) + "x" + std::to_string(h) + " MSAA" +
                               std::to_string(samples) + " framebuffer");
    }
    gl.GenTextures(1, &resolve_texture);
    gl.BindTexture(GL_TEXTURE_2D, resolve_texture);
    gl.TexImage2D(GL_TEXTURE_2D, 0, GL_RGBA8, w, h, 0, GL_RGBA, GL_UNSIGNED_BYTE, nullptr);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.TexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.GenFramebuffers(1, &resolve_fbo);
    gl.BindFramebuffer(GL_FRAMEBUFFER, resolve_fbo);
    gl.FramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, resolve_texture, 0);
    if (gl.CheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
      throw std::runtime_error("OpenGL: cannot create the resolve framebuffer");
    }
    width = w, height = h;
  }

  void DrawMesh(const MeshRange& mesh, const Eigen::Matrix4d& model) {
    const Eigen::Matrix4f m = ToFloat(model);
    const Eigen::Matrix3f n = m.topLeftCorner<3, 3>().inverse().transpose();
    gl.UniformMatrix4fv(u_model, 1, GL_FALSE, m.data());
    gl.UniformMatrix3fv(u_normal, 1, GL_FALSE, n.data());
    gl.DrawArrays(GL_TRIANGLES, mesh.first, mesh.count);
  }

  const MeshRange& MeshOf(Shape::Kind kind) const {
    return kind == Shape::Kind::kBox ? box : kind == Shape::Kind::kSphere ? sphere : cylinder;
  }
};

SceneRenderer::SceneRenderer(GlProcLoader loader, int msaa_samples) : impl_(std::make_unique<Impl>()) {
  impl_->gl = render_internal::LoadGlFunctions(loader);
  impl_->samples = msaa_samples;
  impl_->BuildProgram();
  impl_->BuildMeshes();
}

SceneRenderer::~SceneRenderer() {
  Impl& r = *impl_;
  r.DeleteTargets();
  for (auto& [mesh, g] : r.meshes) r.gl.DeleteBuffers(1, &g.vbo), r.gl.DeleteVertexArrays(1, &g.vao);
  r.gl.DeleteBuffers(1, &r.vbo);
  r.gl.DeleteVertexArrays(1, &r.vao);
  r.gl.DeleteProgram(r.program);
}

void SceneRenderer::Draw(const Scene& scene, const Floor& floor, const Camera& camera, int width, int height) {
  if (width < 1 || height < 1 || width > kMaxSize || height > kMaxSize) {
    throw std::invalid_argument("image size: expected 1..." + std::to_string(kMaxSize) + " px per side, got " +
                                std::to_string(width) + "x" + std::to_string(height));
  }
  Impl& r = *impl_;
  const GlFunctions& gl = r.gl;
  // Keep the caller's framebuffer and viewport (a GUI draws around us).
  GLint previous_fbo = 0, previous_viewport[4] = {};
  gl.GetIntegerv(GL_FRAMEBUFFER_BINDING, &previous_fbo);
  gl.GetIntegerv(GL_VIEWPORT, previous_viewport);
  r.Resize(width, height);

  // Clear and set the frame-wide uniforms.
  gl.BindFramebuffer(GL_FRAMEBUFFER, r.msaa_fbo);
  gl.Viewport(0, 0, width, height);
  gl.ClearColor(kBackground.x(), kBackground.y(), kBackground.z(), 1.0f);
  gl.Clear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
  gl.Enable(GL_DEPTH_TEST);
  gl.DepthFunc(GL_LEQUAL);
  gl.Enable(GL_MULTISAMPLE);
  gl.UseProgram(r.program);
  gl.BindVertexArray(r.vao);
  const Eigen::Matrix4f view_proj = ToFloat(camera.Projection(double(width) / height) * camera.View());
  gl.UniformMatrix4fv(r.u_view_proj, 1, GL_FALSE, view_proj.data());
  const Eigen::Vector3f eye = camera.p_WEye_W.cast<float>(), to_light = kToLight_W.cast<float>();
  gl.Uniform3fv(r.u_eye, 1, eye.data());
  gl.Uniform3fv(r.u_to_light, 1, to_light.data());
  gl.Uniform3fv(r.u_background, 1, kBackground.data());
  gl.Uniform3fv(r.u_floor_light, 1, kFloorLight.data());
  gl.Uniform3fv(r.u_floor_dark, 1, kFloorDark.data());
  const Eigen::Vector3f floor_center(float(floor.center_W.x()), float(floor.center_W.y()), float(floor.radius));
  gl.Uniform3fv(r.u_floor_center, 1, floor_center.data());
  // Tiles: a power of two metres, about 8 across the floor's radius.
  gl.Uniform1f(r.u_tile, float(std::exp2(std::round(std::log2(floor.radius / 8.0)))));

  // The floor.
  gl.Uniform1i(r.u_mode, 1);
  Eigen::Matrix4d floor_model = Eigen::Matrix4d::Identity();
  floor_model.diagonal().head<2>().setConstant(2.0 * floor.radius);
  floor_model.block<3, 1>(0, 3) = Eigen::Vector3d(floor.center_W.x(), floor.center_W.y(), floor.z - 0.5);
  r.DrawMesh(r.quad, floor_model);

  // Shadows: every primitive flattened onto the floor along the light,
  // p' = p − ((p_z − z_f)/l_z) l, drawn opaque just above it.
  gl.Uniform1i(r.u_mode, 2);
  gl.Uniform3fv(r.u_color, 1, kShadow.data());
  Eigen::Matrix4d shadow = Eigen::Matrix4d::Identity();
  const Eigen::Vector3d l = kToLight_W;
  shadow.block<3, 1>(0, 2) -= l / l.z();
  shadow.block<3, 1>(0, 2).z() = 0.0;
  shadow.block<3, 1>(0, 3) = (floor.z / l.z()) * l;
  shadow(2, 3) = floor.z;
  gl.Enable(GL_POLYGON_OFFSET_FILL);
  gl.PolygonOffset(-1.0f, -4.0f);
  for (const ScenePrimitive& p : scene.primitives) r.DrawMesh(r.BindMeshOf(p), shadow * ModelMatrix(p));
  gl.Disable(GL_POLYGON_OFFSET_FILL);

  // The lit primitives.
  gl.Uniform1i(r.u_mode, 0);
  for (const ScenePrimitive& p : scene.primitives) {
    gl.Uniform3fv(r.u_color, 1, p.color.data());
    r.DrawMesh(r.BindMeshOf(p), ModelMatrix(p));
  }

  // What lies below the floor and is hidden by it, see-through: the parts of
  // the primitives under z_f drawn again where something is in front of
  // them, at half opacity (a link through the floor stays visible).
  gl.Uniform1i(r.u_mode, 3);
  gl.Uniform1f(r.u_floor_z, float(floor.z));
  gl.DepthFunc(GL_GREATER);
  gl.DepthMask(GL_FALSE);
  gl.Enable(GL_BLEND);
  gl.BlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  for (const ScenePrimitive& p : scene.primitives) {
    gl.Uniform3fv(r.u_color, 1, p.color.data());
    r.DrawMesh(r.BindMeshOf(p), ModelMatrix(p));
  }
  gl.Disable(GL_BLEND);
  gl.DepthMask(GL_TRUE);
  gl.DepthFunc(GL_LEQUAL);

  // Resolve the samples into the texture; restore the caller's state.
  gl.BindVertexArray(0);
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r.msaa_fbo);
  gl.BindFramebuffer(GL_DRAW_FRAMEBUFFER, r.resolve_fbo);
  gl.BlitFramebuffer(0, 0, width, height, 0, 0, width, height, GL_COLOR_BUFFER_BIT, GL_NEAREST);
  gl.BindFramebuffer(GL_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
  gl.Viewport(previous_viewport[0], previous_viewport[1], previous_viewport[2], previous_viewport[3]);
}

unsigned SceneRenderer::color_texture() const { return impl_->resolve_texture; }

Image SceneRenderer::ReadImage() const {
  const Impl& r = *impl_;
  const GlFunctions& gl = r.gl;
  GLint previous_fbo = 0;
  gl.GetIntegerv(GL_READ_FRAMEBUFFER_BINDING, &previous_fbo);
  std::vector<std::uint8_t> rgba(4 * static_cast<size_t>(r.width) * static_cast<size_t>(r.height));
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, r.resolve_fbo);
  gl.PixelStorei(GL_PACK_ALIGNMENT, 1);
  gl.ReadPixels(0, 0, r.width, r.height, GL_RGBA, GL_UNSIGNED_BYTE, rgba.data());
  gl.BindFramebuffer(GL_READ_FRAMEBUFFER, static_cast<GLuint>(previous_fbo));
  if (const GLenum error = gl.GetError(); error != GL_NO_ERROR) {
    throw std::runtime_error("OpenGL: error " + std::to_string(error) + " while rendering");
  }
  // GL rows run bottom to top.
  Image image(r.width, r.height);
  for (int y = 0; y < r.height; ++y) {
    const std::uint8_t* src = rgba.data() + 4 * static_cast<size_t>(r.height - 1 - y) * static_cast<size_t>(r.width);
    std::uint8_t* dst = image.at(0, y);
    for (int x = 0; x < r.width; ++x) dst[3 * x] = src[4 * x], dst[3 * x + 1] = src[4 * x + 1], dst[3 * x + 2] = src[4 * x + 2];
  }
  return image;
}

Image SceneRenderer::Render(const Scene& scene, const Floor& floor, const Camera& camera, int width, int height) {
  Draw(scene, floor, camera, width, height);
  return ReadImage();
}

}  // namespace idbench
