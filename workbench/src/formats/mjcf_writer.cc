// WriteMjcf (mjcf_writer.h).
#include "idbench/workbench/formats/mjcf_writer.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>

#include "idbench/engine/urdf.h"

namespace idbench {
namespace {

// 17 significant digits: MuJoCo parses back the same double. −0 is written as 0.
std::string Number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%.17g", value == 0.0 ? 0.0 : value);
  return buffer;
}

std::string Numbers(std::initializer_list<double> values) {
  std::string out;
  for (double v : values) out += (out.empty() ? "" : " ") + Number(v);
  return out;
}

std::string Attribute(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + EscapeXml(value) + "\"";
}

// pos and quat (w x y z) of a frame.
std::string Placement(const Eigen::Isometry3d& X) {
  const Eigen::Vector3d p = X.translation();
  Eigen::Quaterniond r(X.linear());
  r.normalize();
  return Attribute("pos", Numbers({p.x(), p.y(), p.z()})) + Attribute("quat", Numbers({r.w(), r.x(), r.y(), r.z()}));
}

// The mesh assets, one per distinct triangle set.
class MeshAssets {
 public:
  const std::string& NameOf(const Shape& shape, const std::string& link_name) {
    auto it = names_.find(shape.mesh.get());
    if (it != names_.end()) return it->second;
    const std::string name = link_name + "_mesh" + std::to_string(names_.size());
    std::ostringstream asset;
    asset << "    <mesh" << Attribute("name", name) << " vertex=\"";
    char buffer[64];
    for (const Eigen::Vector3d& v : shape.mesh->vertices) {
      std::snprintf(buffer, sizeof buffer, "%.9g %.9g %.9g ", v.x(), v.y(), v.z());
      asset << buffer;
    }
    asset << "\" face=\"";
    for (const Eigen::Vector3i& t : shape.mesh->triangles) asset << t.x() << ' ' << t.y() << ' ' << t.z() << ' ';
    asset << "\"/>\n";
    assets_ += asset.str();
    return names_.emplace(shape.mesh.get(), name).first->second;
  }
  const std::string& text() const { return assets_; }

 private:
  std::map<const TriangleMesh*, std::string> names_;
  std::string assets_;
};

// A geom of a shape; visual: group 1 and no contacts, else group 3.
std::string Geom(const Shape& shape, const std::string& link_name, bool visual, MeshAssets* meshes) {
  std::string out = "<geom";
  switch (shape.kind) {
    case Shape::Kind::kBox:
      out += Attribute("type", "box") + Attribute("size", Numbers({shape.size.x() / 2, shape.size.y() / 2, shape.size.z() / 2}));
      break;
    case Shape::Kind::kCylinder:
      out += Attribute("type", "cylinder") + Attribute("size", Numbers({shape.size.x(), shape.size.z() / 2}));
      break;
    case Shape::Kind::kSphere: out += Attribute("type", "sphere") + Attribute("size", Number(shape.size.x())); break;
    case Shape::Kind::kMesh:
      if (!shape.mesh || shape.mesh->triangles.empty()) return "";
      out += Attribute("type", "mesh") + Attribute("mesh", meshes->NameOf(shape, link_name));
      break;
  }
  out += Placement(shape.X_BG);
  out += visual ? " group=\"1\" contype=\"0\" conaffinity=\"0\"" : " group=\"3\"";
  return out + "/>";
}

}  // namespace

bool ViolatesTriangleInequality(const Eigen::Matrix3d& I_Bcm_B) {
  const Eigen::Vector3d d = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I_Bcm_B, Eigen::EigenvaluesOnly).eigenvalues();
  return d[0] + d[1] < d[2] || d[0] + d[2] < d[1] || d[1] + d[2] < d[0];
}

std::string WriteMjcf(const RobotModel& model) {
  MeshAssets meshes;
  // The bodies, written depth first so children nest in their parents.
  std::ostringstream bodies;
  // A link's visual then collision shapes, one geom per line.
  auto write_geoms = [&](const std::vector<Shape>& visual, const std::vector<Shape>& collision,
                         const std::string& name, const std::string& indent) {
    for (const Shape& shape : visual)
      if (const std::string geom = Geom(shape, name, true, &meshes); !geom.empty()) bodies << indent << geom << "\n";
    for (const Shape& shape : collision)
      if (const std::string geom = Geom(shape, name, false, &meshes); !geom.empty()) bodies << indent << geom << "\n";
  };
  auto write_body = [&](auto&& self, int i, int depth) -> void {
    const Link& link = model.link(i);
    const std::string indent(static_cast<size_t>(2 * depth), ' ');
    bodies << indent << "<body" << Attribute("name", link.name) << Placement(link.X_PJ) << ">\n";
    // Mass properties at the centre of mass, in B.
    const LinkInertia& inertia = link.inertia;
    const Eigen::Matrix3d& I = inertia.I_Bcm_B;
    const Eigen::Vector3d& c = inertia.p_BoBcm_B;
    bodies << indent << "  <inertial" << Attribute("pos", Numbers({c.x(), c.y(), c.z()}))
           << Attribute("mass", Number(inertia.mass))
           << Attribute("fullinertia", Numbers({I(0, 0), I(1, 1), I(2, 2), I(0, 1), I(0, 2), I(1, 2)})) << "/>\n";
    // The hinge with its drive and friction.
    const JointLimits& limits = link.limits;
    const bool bounded = std::isfinite(limits.q_min) && std::isfinite(limits.q_max);
    if (!bounded && (std::isfinite(limits.q_min) || std::isfinite(limits.q_max))) {
      throw std::invalid_argument("WriteMjcf: link '" + link.name + "': a one-sided joint limit (q_min = " +
                                  Number(limits.q_min) + ", q_max = " + Number(limits.q_max) +
                                  ") has no MJCF range");
    }
    const Eigen::Vector3d& a = link.axis_J;
    bodies << indent << "  <joint" << Attribute("name", link.joint_name.empty() ? link.name + "_joint" : link.joint_name)
           << " type=\"hinge\" pos=\"0 0 0\"" << Attribute("axis", Numbers({a.x(), a.y(), a.z()}));
    if (bounded) bodies << " limited=\"true\"" << Attribute("range", Numbers({limits.q_min, limits.q_max}));
    else bodies << " limited=\"false\"";
    bodies << Attribute("armature", Number(link.dynamics.rotor_inertia))
           << Attribute("damping", Number(link.dynamics.viscous))
           << Attribute("frictionloss", Number(link.dynamics.coulomb)) << "/>\n";
    // Shapes, then the children.
    write_geoms(link.shapes, link.collision_shapes, link.name, indent + "  ");
    for (int child : model.children(i)) self(self, child, depth + 1);
    bodies << indent << "</body>\n";
  };
  // The ground links (a table, a pedestal: RobotModel::ground): bodies
  // without a joint, welded to the world, their shapes where the base frame
  // (MJCF's world) has them.
  for (const GroundLink& link : model.ground()) {
    bodies << "    <body" << Attribute("name", link.name) << ">\n";
    write_geoms(link.shapes, link.collision_shapes, link.name, "      ");
    bodies << "    </body>\n";
  }
  for (int root : model.children(-1)) write_body(write_body, root, 2);

  // MuJoCo refuses principal moments that break the triangle inequality
  // unless balanceinertia replaces them by their mean: say which links.
  std::string unbalanced;
  for (const Link& link : model.links())
    if (ViolatesTriangleInequality(link.inertia.I_Bcm_B)) unbalanced += (unbalanced.empty() ? "" : ", ") + link.name;

  const Eigen::Vector3d& g = model.gravity_W();
  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<!-- Written by idbench::WriteMjcf: inertials at the centre of mass, armature = rotor inertia,\n"
      << "     damping = viscous, frictionloss = Coulomb friction. Not expressible and so not written:\n"
      << "     torque offsets, velocity, acceleration and effort limits. -->\n"
      << "<mujoco" << Attribute("model", model.name()) << ">\n";
  if (!unbalanced.empty()) {
    out << "  <!-- The principal moments of inertia of " << EscapeXml(unbalanced)
        << " break the triangle inequality (no real body has them):\n"
        << "       balanceinertia makes MuJoCo replace them by their mean. -->\n";
  }
  out << "  <compiler angle=\"radian\" inertiafromgeom=\"false\"" << (unbalanced.empty() ? "" : " balanceinertia=\"true\"")
      << "/>\n"
      << "  <option" << Attribute("gravity", Numbers({g.x(), g.y(), g.z()})) << "/>\n";
  if (!meshes.text().empty()) out << "  <asset>\n" << meshes.text() << "  </asset>\n";
  out << "  <worldbody>\n" << bodies.str() << "  </worldbody>\n</mujoco>\n";
  return out.str();
}

}  // namespace idbench
