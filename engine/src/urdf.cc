#include "idbench/engine/urdf.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace idbench {
namespace {

std::string Quote(const std::string& name) { return "'" + name + "'"; }

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return X;
}

bool IsMoving(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS;
}

// Mass properties of one URDF link, expressed in the frame B of the idbench
// link it is merged into.
struct PointInertia {
  double mass = 0.0;
  Eigen::Vector3d p_BoLcm_B = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_Lcm_B = Eigen::Matrix3d::Zero();
};

// Lumps rigidly attached masses into one: total mass, mass-weighted COM and
// I_Bcm = Σ R·I·Rᵀ + m·(|d|²·1 − d·dᵀ), d = p_Lcm − p_Bcm (parallel axes).
// Weights m_i/m make a single part reproduce its COM bit for bit.
LinkInertia Lump(const std::vector<PointInertia>& parts) {
  LinkInertia lumped;
  for (const PointInertia& part : parts) lumped.mass += part.mass;
  if (!(lumped.mass > 0.0)) return lumped;
  for (const PointInertia& part : parts) lumped.p_BoBcm_B += (part.mass / lumped.mass) * part.p_BoLcm_B;
  for (const PointInertia& part : parts) {
    const Eigen::Vector3d d = part.p_BoLcm_B - lumped.p_BoBcm_B;
    lumped.I_Bcm_B += part.I_Lcm_B +
                      part.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return lumped;
}

// The file a URDF <mesh filename> names:
//   package://P/rest → D/P/rest for each D in ROS_PACKAGE_PATH (':'-separated);
//     then, walking up from the URDF's directory, A/rest for an ancestor A
//     named P, or A/P/rest (a package next to or above the URDF);
//   file:///abs → /abs; an absolute path as is; a relative path against the
//   URDF's directory.
// The first existing regular file; nullopt otherwise, with every candidate in
// *looked.
std::optional<std::filesystem::path> ResolveMeshUri(const std::string& uri, const std::filesystem::path& base_directory,
                                                    std::vector<std::string>* looked) {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  const std::string package = "package://", file = "file://";
  if (uri.rfind(package, 0) == 0) {
    const std::string rest = uri.substr(package.size());
    const size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash), inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (const char* paths = std::getenv("ROS_PACKAGE_PATH")) {
      std::stringstream list(paths);
      for (std::string dir; std::getline(list, dir, ':');) {
        if (!dir.empty()) candidates.push_back(fs::path(dir) / name / inside);
      }
    }
    std::error_code error;
    for (fs::path a = fs::absolute(base_directory, error); !a.empty(); a = a.parent_path()) {
      if (a.filename() == name) candidates.push_back(a / inside);
      candidates.push_back(a / name / inside);
      if (a == a.parent_path()) break;
    }
  } else if (uri.rfind(file, 0) == 0) {
    candidates.push_back(fs::path(uri.substr(file.size())));
  } else if (fs::path(uri).is_absolute()) {
    candidates.push_back(fs::path(uri));
  } else {
    candidates.push_back(base_directory / uri);
  }
  for (const fs::path& c : candidates) {
    std::error_code error;
    if (fs::is_regular_file(c, error)) return fs::absolute(c, error).lexically_normal();
    looked->push_back(c.string());
  }
  return std::nullopt;
}

// Walks a urdfdom tree from its root along the one chain of moving joints,
// merging fixed subtrees into the link above them.
class Loader {
 public:
  Loader(const urdf::ModelInterface& urdf, std::string source, std::filesystem::path base_directory)
      : urdf_(urdf), source_(std::move(source)), base_directory_(std::move(base_directory)) {}

  UrdfLoadResult Load() {
    const urdf::LinkConstSharedPtr root = urdf_.getRoot();
    CheckJointTypes(*root);

    // The ground group (root and all fixed to it), then one group per moving
    // joint, each hanging from the previous one.
    std::vector<Link> links;
    Group group = CollectGroup(root);
    while (group.next_joint != nullptr) {
      const urdf::Joint& joint = *group.next_joint;
      const urdf::LinkConstSharedPtr child = urdf_.getLink(joint.child_link_name);
      Link link;
      link.name = child->name;
      link.joint_name = joint.name;
      link.parent = static_cast<int>(links.size()) - 1;
      link.X_PJ = group.next_joint_X_BL * ToIsometry(joint.parent_to_joint_origin_transform);
      ReadJoint(joint, &link);

      group = CollectGroup(child);
      ReadBody(*child, group, &link);
      links.push_back(std::move(link));
    }
    if (links.empty()) {
      Fail("no revolute or continuous joint below the root link " + Quote(root->name) +
           "; nothing to identify");
    }

    try {
      RobotModel model(urdf_.getName(), std::move(links));
      for (std::string& w : InertiaWarnings(model)) warnings_.push_back(source_ + ": " + w);
      return UrdfLoadResult{std::move(model), std::move(warnings_)};
    } catch (const std::invalid_argument& e) {
      Fail(e.what());
    }
  }

 private:
  // A URDF link and everything fixed to it, with their poses in the frame B
  // of the first one, and the moving joint leaving the group (if any).
  struct Group {
    std::vector<std::pair<urdf::LinkConstSharedPtr, Eigen::Isometry3d>> members;  // (L, X_BL)
    const urdf::Joint* next_joint = nullptr;
    Eigen::Isometry3d next_joint_X_BL = Eigen::Isometry3d::Identity();  // its parent L in B
  };

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + what);
  }

  void CheckJointTypes(const urdf::Link& link) const {
    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      const char* kind = nullptr;
      switch (joint->type) {
        case urdf::Joint::PRISMATIC: kind = "prismatic"; break;
        case urdf::Joint::FLOATING: kind = "floating"; break;
        case urdf::Joint::PLANAR: kind = "planar"; break;
        case urdf::Joint::UNKNOWN: kind = "unknown-type"; break;
        default: break;
      }
      if (kind != nullptr) {
        Fail("joint " + Quote(joint->name) + ": " + kind +
             " joints are not supported; idbench handles revolute chains");
      }
    }
    for (const urdf::LinkSharedPtr& child : link.child_links) CheckJointTypes(*child);
  }

  bool SubtreeHasMovingJoint(const urdf::Link& link) const {
    for (const urdf::JointSharedPtr& joint : link.child_joints) {
      if (IsMoving(*joint)) return true;
    }
    for (const urdf::LinkSharedPtr& child : link.child_links) {
      if (SubtreeHasMovingJoint(*child)) return true;
    }
    return false;
  }

  Group CollectGroup(const urdf::LinkConstSharedPtr& first) const {
    Group group;
    std::vector<std::pair<urdf::LinkConstSharedPtr, Eigen::Isometry3d>> stack{
        {first, Eigen::Isometry3d::Identity()}};
    while (!stack.empty()) {
      auto [link, X_BL] = stack.back();
      stack.pop_back();
      group.members.emplace_back(link, X_BL);
      // At most one child chain of a link may carry moving joints.
      std::string moving_chain;
      for (const urdf::JointSharedPtr& joint : link->child_joints) {
        const urdf::LinkConstSharedPtr child = urdf_.getLink(joint->child_link_name);
        if (!IsMoving(*joint) && !SubtreeHasMovingJoint(*child)) continue;
        if (!moving_chain.empty()) {
          Fail("link " + Quote(link->name) + ": the chains through joints " + Quote(moving_chain) +
               " and " + Quote(joint->name) +
               " both have moving joints; idbench handles serial chains only");
        }
        moving_chain = joint->name;
      }
      // Fixed children join the group (depth first, in urdfdom's child order);
      // the moving joint ends it.
      for (auto it = link->child_joints.rbegin(); it != link->child_joints.rend(); ++it) {
        const urdf::Joint& joint = **it;
        if (IsMoving(joint)) {
          group.next_joint = &joint;
          group.next_joint_X_BL = X_BL;
        } else {
          stack.emplace_back(urdf_.getLink(joint.child_link_name),
                             X_BL * ToIsometry(joint.parent_to_joint_origin_transform));
        }
      }
    }
    return group;
  }

  // Axis, limits and friction of a revolute or continuous joint.
  void ReadJoint(const urdf::Joint& joint, Link* link) {
    const std::string where = "joint " + Quote(joint.name) + ": ";
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || !(axis.norm() > 1e-12)) Fail(where + "joint axis must be nonzero");
    link->axis_J = axis.normalized();

    if (joint.limits != nullptr) {
      const urdf::JointLimits& limits = *joint.limits;
      if (joint.type == urdf::Joint::REVOLUTE) {
        if (!(limits.lower < limits.upper)) {
          std::ostringstream message;
          message << where << "limits need lower < upper, got lower = " << limits.lower
                  << ", upper = " << limits.upper;
          Fail(message.str());
        }
        link->limits.q_min = limits.lower;
        link->limits.q_max = limits.upper;
      }
      if (limits.velocity > 0.0) link->limits.qd_max = limits.velocity;
      if (limits.effort > 0.0) link->limits.tau_max = limits.effort;
    }
    if (joint.dynamics != nullptr) {
      if (!(joint.dynamics->damping >= 0.0 && joint.dynamics->friction >= 0.0)) {
        Fail(where + "damping and friction must be >= 0");
      }
      link->dynamics.viscous = joint.dynamics->damping;
      link->dynamics.coulomb = joint.dynamics->friction;
    }
    if (joint.mimic != nullptr) {
      warnings_.push_back(where + "<mimic> ignored; the joint is loaded as independent");
    }
  }

  // Lumped mass properties and shapes of the group hanging from `moving`.
  void ReadBody(const urdf::Link& moving, const Group& group, Link* link) {
    std::vector<PointInertia> parts;
    for (const auto& [member, X_BL] : group.members) {
      const std::string where = "link " + Quote(member->name) + ": ";
      if (member->inertial != nullptr) {
        const urdf::Inertial& inertial = *member->inertial;
        Eigen::Matrix3d I_Lcm_I;
        I_Lcm_I << inertial.ixx, inertial.ixy, inertial.ixz,  //
            inertial.ixy, inertial.iyy, inertial.iyz,         //
            inertial.ixz, inertial.iyz, inertial.izz;
        if (!(std::isfinite(inertial.mass) && inertial.mass >= 0.0)) {
          Fail(where + "mass must be >= 0, got " + std::to_string(inertial.mass));
        }
        const double min_moment = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I_Lcm_I).eigenvalues().minCoeff();
        if (!I_Lcm_I.allFinite() || min_moment < -1e-12 * I_Lcm_I.norm()) {
          Fail(where + "inertia tensor must be positive semidefinite");
        }
        // X_BI: the inertial frame I (origin at the COM) in B.
        const Eigen::Isometry3d X_BI = X_BL * ToIsometry(inertial.origin);
        PointInertia part;
        part.mass = inertial.mass;
        part.p_BoLcm_B = X_BI.translation();
        part.I_Lcm_B = X_BI.linear() * I_Lcm_I * X_BI.linear().transpose();
        parts.push_back(part);
      }
      for (const urdf::VisualSharedPtr& visual : Visuals(*member)) {
        if (visual->geometry == nullptr) continue;
        if (auto shape = ReadShape(*visual->geometry, X_BL * ToIsometry(visual->origin), where)) {
          link->shapes.push_back(std::move(*shape));
        }
      }
      for (const urdf::CollisionSharedPtr& collision : Collisions(*member)) {
        if (collision->geometry == nullptr) continue;
        if (auto shape = ReadShape(*collision->geometry, X_BL * ToIsometry(collision->origin), where)) {
          link->collision_shapes.push_back(std::move(*shape));
        }
      }
    }

    // The lumped body must be a proper rigid body.
    const std::string where = "link " + Quote(moving.name) + ": ";
    if (parts.empty()) Fail(where + "a moving link needs an <inertial> with mass > 0");
    link->inertia = Lump(parts);
    if (!(link->inertia.mass > 0.0)) {
      Fail(where + "mass must be > 0, got " + std::to_string(link->inertia.mass));
    }
    Eigen::Matrix3d& I = link->inertia.I_Bcm_B;
    I = 0.5 * (I + I.transpose()).eval();
    const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I).eigenvalues();
    if (!(moments.minCoeff() > 0.0)) Fail(where + "inertia tensor must be positive definite");
  }

  static std::vector<urdf::VisualSharedPtr> Visuals(const urdf::Link& link) {
    if (!link.visual_array.empty()) return link.visual_array;
    if (link.visual != nullptr) return {link.visual};
    return {};
  }
  static std::vector<urdf::CollisionSharedPtr> Collisions(const urdf::Link& link) {
    if (!link.collision_array.empty()) return link.collision_array;
    if (link.collision != nullptr) return {link.collision};
    return {};
  }

  // A <visual> or <collision> geometry placed at X_BG; nullopt (with a
  // warning) for a mesh that cannot be found or read.
  std::optional<Shape> ReadShape(const urdf::Geometry& geometry, const Eigen::Isometry3d& X_BG,
                                 const std::string& where) {
    Shape shape;
    shape.X_BG = X_BG;
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const urdf::Vector3& dim = static_cast<const urdf::Box&>(geometry).dim;
        shape.kind = Shape::Kind::kBox;
        shape.size = Eigen::Vector3d(dim.x, dim.y, dim.z);
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
        shape.kind = Shape::Kind::kCylinder;
        shape.size = Eigen::Vector3d(cylinder.radius, cylinder.radius, cylinder.length);
        break;
      }
      case urdf::Geometry::SPHERE: {
        const double radius = static_cast<const urdf::Sphere&>(geometry).radius;
        shape.kind = Shape::Kind::kSphere;
        shape.size = Eigen::Vector3d::Constant(radius);
        break;
      }
      case urdf::Geometry::MESH: {
        const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
        shape.kind = Shape::Kind::kMesh;
        shape.size = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        shape.mesh_uri = mesh.filename;
        shape.mesh = Mesh(mesh.filename, shape.size, where, &shape.mesh_uri);
        if (shape.mesh == nullptr) return std::nullopt;
        break;
      }
      default:
        return std::nullopt;
    }
    return shape;
  }

  // The mesh a <mesh filename> names, read once per file and scale; null with
  // a warning when it cannot be found or read (the link then lacks that shape).
  // A relative path in *uri is made absolute (so that a URDF written
  // elsewhere still finds it).
  std::shared_ptr<const TriangleMesh> Mesh(const std::string& uri, const Eigen::Vector3d& scale,
                                           const std::string& where, std::string* written_uri) {
    std::vector<std::string> looked;
    const std::optional<std::filesystem::path> path = ResolveMeshUri(uri, base_directory_, &looked);
    if (!path) {
      std::string places;
      for (const std::string& p : looked) places += (places.empty() ? "" : ", ") + p;
      warnings_.push_back(where + "mesh " + Quote(uri) + " not found (looked in " + places +
                          "; set ROS_PACKAGE_PATH for package:// names); shape skipped");
      return nullptr;
    }
    if (uri.find("://") == std::string::npos && std::filesystem::path(uri).is_relative()) *written_uri = path->string();
    const std::string key = path->string() + " " + std::to_string(scale.x()) + " " + std::to_string(scale.y()) +
                            " " + std::to_string(scale.z());
    if (const auto it = meshes_.find(key); it != meshes_.end()) return it->second;
    try {
      auto mesh = std::make_shared<const TriangleMesh>(LoadTriangleMesh(path->string(), scale));
      meshes_[key] = mesh;
      return mesh;
    } catch (const std::runtime_error& e) {
      warnings_.push_back(where + e.what() + "; shape skipped");
      return nullptr;
    }
  }

  const urdf::ModelInterface& urdf_;
  std::string source_;
  std::filesystem::path base_directory_;  // relative mesh paths start here
  std::vector<std::string> warnings_;
  std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes_;  // by path and scale
};

// ---- Writing ----

// 17 significant digits: parses back to the same double. −0 is written as 0.
std::string Number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value == 0.0 ? 0.0 : value);
  return buffer;
}

std::string Numbers(const Eigen::Vector3d& v) {
  return Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z());
}


std::string Attribute(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + EscapeXml(value) + "\"";
}

std::string Origin(const Eigen::Isometry3d& X) {
  return "<origin" + Attribute("xyz", Numbers(X.translation())) +
         Attribute("rpy", Numbers(RpyFromRotation(X.linear()))) + "/>";
}

// A name not in `taken`: `base`, else `base_1`, `base_2`, ...
std::string UniqueName(const std::string& base, const std::set<std::string>& taken) {
  if (!taken.contains(base)) return base;
  for (int k = 1;; ++k) {
    const std::string name = base + "_" + std::to_string(k);
    if (!taken.contains(name)) return name;
  }
}

// <visual> or <collision> with the shape's origin and geometry.
std::string ShapeElement(const std::string& tag, const Shape& shape) {
  std::ostringstream out;
  out << "    <" << tag << ">\n"
      << "      " << Origin(shape.X_BG) << "\n"
      << "      <geometry>";
  switch (shape.kind) {
    case Shape::Kind::kBox: out << "<box" << Attribute("size", Numbers(shape.size)) << "/>"; break;
    case Shape::Kind::kCylinder:
      out << "<cylinder" << Attribute("radius", Number(shape.size.x())) << Attribute("length", Number(shape.size.z()))
          << "/>";
      break;
    case Shape::Kind::kSphere: out << "<sphere" << Attribute("radius", Number(shape.size.x())) << "/>"; break;
    case Shape::Kind::kMesh:
      out << "<mesh" << Attribute("filename", shape.mesh_uri) << Attribute("scale", Numbers(shape.size)) << "/>";
      break;
  }
  out << "</geometry>\n"
      << "    </" << tag << ">\n";
  return out.str();
}

}  // namespace

Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R) {
  // R = Rz(y)·Ry(p)·Rx(r) has first column (cy·cp, sy·cp, −sp). Take yaw from
  // it (arbitrary, here 0, when cp = 0), then read pitch and roll from
  // M = Rz(y)ᵀ·R = Ry(p)·Rx(r) = [cp  sp·sr  sp·cr; 0  cr  −sr; −sp  cp·sr  cp·cr].
  // Near gimbal lock the yaw is poorly determined, but M's entries used here
  // have magnitude ~1 or are exact given that yaw, so Rz(y)·Ry(p)·Rx(r)
  // reproduces R to rounding for every pitch.
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const Eigen::Matrix3d M = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
  const double pitch = std::atan2(-M(2, 0), M(0, 0));
  const double roll = std::atan2(-M(1, 2), M(1, 1));
  return Eigen::Vector3d(roll, pitch, yaw);
}

UrdfLoadResult LoadUrdfString(const std::string& xml, const std::string& source_name,
                               const std::string& base_directory) {
  // urdfdom reports why a file is invalid through console_bridge: keep the
  // first error for our one message instead of letting it print.
  struct FirstError : console_bridge::OutputHandler {
    std::string text;
    void log(const std::string& message, console_bridge::LogLevel level, const char*, int) override {
      if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && text.empty()) text = message;
    }
  } first_error;
  console_bridge::useOutputHandler(&first_error);
  urdf::ModelInterfaceSharedPtr urdf;
  try {
    urdf = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    console_bridge::restorePreviousOutputHandler();
    throw std::invalid_argument(source_name + ": not a valid URDF (" + e.what() + ")");
  }
  console_bridge::restorePreviousOutputHandler();
  if (urdf == nullptr || urdf->getRoot() == nullptr) {
    throw std::invalid_argument(source_name + ": not a valid URDF" +
                                (first_error.text.empty() ? "" : " (" + first_error.text + ")"));
  }
  return Loader(*urdf, source_name, std::filesystem::path(base_directory.empty() ? "." : base_directory)).Load();
}

UrdfLoadResult LoadUrdfFile(const std::string& path) {
  std::error_code error;
  std::ifstream file(path, std::ios::binary);
  if (!file || !std::filesystem::is_regular_file(path, error)) {
    throw std::invalid_argument(path + ": cannot open the file for reading");
  }
  std::ostringstream text;
  text << file.rdbuf();
  if (file.bad()) throw std::invalid_argument(path + ": error while reading the file");
  return LoadUrdfString(text.str(), path, std::filesystem::path(path).parent_path().string());
}

std::string WriteUrdf(const RobotModel& model) {
  // Names: URDF needs unique link and joint names; the ground gets a fresh one.
  std::set<std::string> link_names;
  std::set<std::string> joint_names;
  for (const Link& link : model.links()) {
    if (!link_names.insert(link.name).second) {
      throw std::invalid_argument("WriteUrdf: link " + Quote(link.name) +
                                  ": duplicate link name; URDF needs unique names");
    }
    if (!link.joint_name.empty() && !joint_names.insert(link.joint_name).second) {
      throw std::invalid_argument("WriteUrdf: link " + Quote(link.name) + ": duplicate joint name " +
                                  Quote(link.joint_name) + "; URDF needs unique names");
    }
  }
  std::string ground = "base";
  if (link_names.contains(ground)) ground = "world";
  ground = UniqueName(ground, link_names);
  std::vector<std::string> joint_name(static_cast<size_t>(model.n_links()));
  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);
    std::string& name = joint_name[static_cast<size_t>(i)];
    name = link.joint_name.empty() ? UniqueName(link.name + "_joint", joint_names) : link.joint_name;
    joint_names.insert(name);
  }

  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<!-- Written by idbench::WriteUrdf. Not expressible in URDF and so not written:\n"
      << "     rotor inertia, acceleration limits, gravity. -->\n"
      << "<robot" << Attribute("name", model.name()) << ">\n"
      << "  <link" << Attribute("name", ground) << "/>\n";

  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);

    // The link: mass properties at the COM, then its shapes.
    const LinkInertia& inertia = link.inertia;
    const Eigen::Matrix3d& I = inertia.I_Bcm_B;
    out << "  <link" << Attribute("name", link.name) << ">\n"
        << "    <inertial>\n"
        << "      <origin" << Attribute("xyz", Numbers(inertia.p_BoBcm_B)) << " rpy=\"0 0 0\"/>\n"
        << "      <mass" << Attribute("value", Number(inertia.mass)) << "/>\n"
        << "      <inertia" << Attribute("ixx", Number(I(0, 0))) << Attribute("ixy", Number(I(0, 1)))
        << Attribute("ixz", Number(I(0, 2))) << Attribute("iyy", Number(I(1, 1)))
        << Attribute("iyz", Number(I(1, 2))) << Attribute("izz", Number(I(2, 2))) << "/>\n"
        << "    </inertial>\n";
    for (const Shape& shape : link.shapes) out << ShapeElement("visual", shape);
    for (const Shape& shape : link.collision_shapes) out << ShapeElement("collision", shape);
    out << "  </link>\n";

    // Its inboard joint. Infinite velocity/effort are written as 0, which the
    // loader (and the URDF convention) reads as "not given".
    const JointLimits& limits = link.limits;
    const bool bounded = std::isfinite(limits.q_min) && std::isfinite(limits.q_max);
    if (!bounded && (std::isfinite(limits.q_min) || std::isfinite(limits.q_max))) {
      throw std::invalid_argument("WriteUrdf: link " + Quote(link.name) +
                                  ": URDF cannot express a one-sided joint limit (q_min = " +
                                  Number(limits.q_min) + ", q_max = " + Number(limits.q_max) + ")");
    }
    const auto finite_or_zero = [](double value) { return std::isfinite(value) ? value : 0.0; };
    const std::string parent = link.parent < 0 ? ground : model.link(link.parent).name;
    out << "  <joint" << Attribute("name", joint_name[static_cast<size_t>(i)])
        << Attribute("type", bounded ? "revolute" : "continuous") << ">\n"
        << "    <parent" << Attribute("link", parent) << "/>\n"
        << "    <child" << Attribute("link", link.name) << "/>\n"
        << "    " << Origin(link.X_PJ) << "\n"
        << "    <axis" << Attribute("xyz", Numbers(link.axis_J)) << "/>\n";
    if (bounded || std::isfinite(limits.qd_max) || std::isfinite(limits.tau_max)) {
      out << "    <limit";
      if (bounded) out << Attribute("lower", Number(limits.q_min)) << Attribute("upper", Number(limits.q_max));
      out << Attribute("effort", Number(finite_or_zero(limits.tau_max)))
          << Attribute("velocity", Number(finite_or_zero(limits.qd_max))) << "/>\n";
    }
    if (link.dynamics.viscous != 0.0 || link.dynamics.coulomb != 0.0) {
      out << "    <dynamics" << Attribute("damping", Number(link.dynamics.viscous))
          << Attribute("friction", Number(link.dynamics.coulomb)) << "/>\n";
    }
    out << "  </joint>\n";
  }
  out << "</robot>\n";
  return out.str();
}

std::string EscapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace idbench
