// WriteUrdf and EscapeXml (declared in urdf.h).
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "idbench/engine/urdf.h"
#include "urdf_messages.h"

namespace idbench {
namespace {

using internal::Quote;

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
  for (const GroundLink& link : model.ground()) {
    if (!link_names.insert(link.name).second) {
      throw std::invalid_argument("WriteUrdf: ground link " + Quote(link.name) +
                                  ": duplicate link name; URDF needs unique names");
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
  // The ground links (a table, a pedestal), held to the root where they are:
  // their shapes are placed in the root's frame.
  for (const GroundLink& link : model.ground()) {
    out << "  <link" << Attribute("name", link.name) << ">\n";
    for (const Shape& shape : link.shapes) out << ShapeElement("visual", shape);
    for (const Shape& shape : link.collision_shapes) out << ShapeElement("collision", shape);
    const std::string joint = UniqueName(ground + "_" + link.name, joint_names);
    joint_names.insert(joint);
    out << "  </link>\n"
        << "  <joint" << Attribute("name", joint) << " type=\"fixed\">\n"
        << "    <parent" << Attribute("link", ground) << "/>\n"
        << "    <child" << Attribute("link", link.name) << "/>\n"
        << "  </joint>\n";
  }

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
