#include "idbench/workbench/formats/scene_file.h"

#include <cmath>
#include <filesystem>
#include <memory>
#include <nlohmann/json.hpp>
#include <set>
#include <stdexcept>

#include "idbench/engine/input_file.h"
#include "idbench/engine/json_input.h"
#include "idbench/engine/printable_text.h"
#include "idbench/engine/triangle_mesh.h"
#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

using nlohmann::json;

// Reads one obstacle's fields; `where` is "source: .obstacles[i]".
class ObstacleReader {
 public:
  ObstacleReader(const json& object, std::string where) : object_(object), where_(std::move(where)) {}

  [[noreturn]] void Fail(const std::string& field, const std::string& what) const {
    throw std::invalid_argument(where_ + (field.empty() ? "" : "." + field) + ": " + what);
  }

  // Refuses keys outside `allowed` (those of the obstacle's type).
  void OnlyKeys(const std::set<std::string>& allowed) const {
    for (const auto& [key, value] : object_.items()) {
      if (!allowed.count(key)) {
        std::string list;
        for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
        Fail(PrintableText(key, 80), "unknown key for this type (" + list + ")");
      }
    }
  }

  const json* Find(const std::string& key) const {
    auto it = object_.find(key);
    return it == object_.end() ? nullptr : &*it;
  }

  double Positive(const std::string& key) const {
    const json* v = Find(key);
    if (!v) Fail(key, "missing");
    if (!v->is_number() || !std::isfinite(v->get<double>()) || !(v->get<double>() > 0.0)) {
      Fail(key, "expected a number > 0 [m], got " + PrintableText(v->dump(), 80));
    }
    return v->get<double>();
  }

  // n finite numbers; positive when asked.
  std::vector<double> Numbers(const std::string& key, size_t n, bool positive) const {
    const json* v = Find(key);
    if (!v) Fail(key, "missing");
    if (!v->is_array() || v->size() != n) {
      Fail(key, "expected " + std::to_string(n) + " numbers, got " + PrintableText(v->dump(), 80));
    }
    std::vector<double> out;
    for (size_t i = 0; i < n; ++i) {
      const json& x = (*v)[i];
      if (!x.is_number() || !std::isfinite(x.get<double>()) || (positive && !(x.get<double>() > 0.0))) {
        Fail(key + "[" + std::to_string(i) + "]",
             std::string("expected a finite number") + (positive ? " > 0" : "") + ", got " + PrintableText(x.dump(), 80));
      }
      out.push_back(x.get<double>());
    }
    return out;
  }

  const std::string& where() const { return where_; }

 private:
  const json& object_;
  std::string where_;
};

Obstacle ReadObstacle(const json& item, const std::string& where, const std::string& base_dir) {
  if (!item.is_object()) throw std::invalid_argument(where + ": expected an object");
  const ObstacleReader r(item, where);
  const json* type = r.Find("type");
  if (!type || !type->is_string()) r.Fail("type", "expected \"box\", \"cylinder\", \"sphere\" or \"mesh\"");
  const std::string kind = type->get<std::string>();
  Obstacle o;
  if (const json* name = r.Find("name")) {
    if (!name->is_string() || name->get<std::string>().empty() || name->get<std::string>().size() > 64) {
      r.Fail("name", "expected a string of 1 to 64 characters");
    }
    o.name = PrintableText(name->get<std::string>(), 64);
  }
  if (kind == "box") {
    r.OnlyKeys({"type", "name", "pose", "size"});
    const std::vector<double> s = r.Numbers("size", 3, true);
    o.shape.kind = Shape::Kind::kBox;
    o.shape.size = Eigen::Vector3d(s[0], s[1], s[2]);
  } else if (kind == "cylinder") {
    r.OnlyKeys({"type", "name", "pose", "radius", "length"});
    const double radius = r.Positive("radius");
    o.shape.kind = Shape::Kind::kCylinder;
    o.shape.size = Eigen::Vector3d(radius, radius, r.Positive("length"));
  } else if (kind == "sphere") {
    r.OnlyKeys({"type", "name", "pose", "radius"});
    o.shape.kind = Shape::Kind::kSphere;
    o.shape.size = Eigen::Vector3d::Constant(r.Positive("radius"));
  } else if (kind == "mesh") {
    r.OnlyKeys({"type", "name", "pose", "path", "scale"});
    const json* path = r.Find("path");
    if (!path || !path->is_string() || path->get<std::string>().empty()) r.Fail("path", "expected a file path");
    std::filesystem::path file(path->get<std::string>());
    if (file.is_relative()) file = std::filesystem::path(base_dir) / file;
    const std::vector<double> s = r.Find("scale") ? r.Numbers("scale", 3, true) : std::vector<double>{1, 1, 1};
    o.shape.kind = Shape::Kind::kMesh;
    o.shape.size = Eigen::Vector3d(s[0], s[1], s[2]);
    try {
      o.shape.mesh = std::make_shared<const TriangleMesh>(LoadTriangleMesh(file.string(), o.shape.size));
    } catch (const std::exception& e) {
      r.Fail("path", PrintableText(e.what(), 300));
    }
    o.shape.mesh_uri = path->get<std::string>();
    if (o.shape.mesh->vertices.empty()) r.Fail("path", "the mesh '" + file.string() + "' has no vertices");
  } else {
    r.Fail("type", "expected \"box\", \"cylinder\", \"sphere\" or \"mesh\", got " + PrintableText(type->dump(), 80));
  }
  const std::vector<double> pose = r.Numbers("pose", 6, false);
  o.X_WO.linear() = RotationFromRpy(Eigen::Vector3d(pose[3], pose[4], pose[5]));
  o.X_WO.translation() = Eigen::Vector3d(pose[0], pose[1], pose[2]);
  return o;
}

}  // namespace

Cell ParseSceneJson(const std::string& text, const std::string& source, const std::string& base_dir) {
  const json doc = ParseJsonInput(text, source);
  if (!doc.is_object()) throw std::invalid_argument(source + ": expected an object {\"floor\", \"obstacles\"}");
  Cell scene;
  for (const auto& [key, value] : doc.items()) {
    if (key == "floor") {
      if (!value.is_boolean()) throw std::invalid_argument(source + ": .floor: expected true or false");
      scene.floor = value.get<bool>();
    } else if (key == "obstacles") {
      if (!value.is_array()) throw std::invalid_argument(source + ": .obstacles: expected an array");
      if (value.size() > static_cast<size_t>(Cell::kMaxObstacles)) {
        throw std::invalid_argument(source + ": .obstacles: at most " + std::to_string(Cell::kMaxObstacles) +
                                    " obstacles, got " + std::to_string(value.size()));
      }
      for (size_t i = 0; i < value.size(); ++i) {
        scene.obstacles.push_back(
            ReadObstacle(value[i], source + ": .obstacles[" + std::to_string(i) + "]", base_dir));
      }
    } else {
      throw std::invalid_argument(source + ": ." + PrintableText(key, 80) + ": unknown key (floor, obstacles)");
    }
  }
  if (std::string why; !scene.IsValid(&why)) throw std::invalid_argument(source + ": ." + why);
  return scene;
}

Cell ReadSceneFile(const std::string& path) {
  return ParseSceneJson(ReadInputFile(path), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace idbench
