// Robot model: rigid links in a tree of revolute joints, fixed base.
//
// Frames (Drake-style names): W world, P parent link frame, J joint frame,
// B link (body) frame, Bcm the link's centre of mass. Every link B has one
// inboard revolute joint whose frame J is fixed in the parent P; at q = 0
// the frames J and B coincide, and B rotates by +q about the joint axis:
//   X_PB(q) = X_PJ · Rot(axis_J, q).
// The hinge point of a link is the origin of J (= origin of B).
//
// The model is immutable once built; algorithms take `const RobotModel&` and
// write into a RobotData (see kinematics.h).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/triangle_mesh.h"

namespace idbench {

// Mass properties of one link, expressed in its link frame B.
struct LinkInertia {
  double mass = 0.0;                                    // [kg]
  Eigen::Vector3d p_BoBcm_B = Eigen::Vector3d::Zero();  // centre of mass [m]
  Eigen::Matrix3d I_Bcm_B = Eigen::Matrix3d::Zero();    // inertia about Bcm [kg m²]
};

struct JointLimits {
  static constexpr double kInf = std::numeric_limits<double>::infinity();
  double q_min = -kInf;   // [rad]
  double q_max = kInf;    // [rad]
  double qd_max = kInf;   // [rad/s]
  double qdd_max = kInf;  // [rad/s²]
  double tau_max = kInf;  // [N m]
};

// Joint-side drive and friction, the true values of the joint-torque model's
// friction terms: τ_joint = τ_rigid + viscous·qd + coulomb·sign(qd) + rotor_inertia·qdd.
struct JointDynamics {
  double viscous = 0.0;        // Fv [N m s/rad]
  double coulomb = 0.0;        // Fc [N m]
  double rotor_inertia = 0.0;  // Ia, reflected to the joint [kg m²]
};

// A visual/collision shape attached to a link: a primitive or a mesh.
struct Shape {
  enum class Kind { kCylinder, kBox, kSphere, kMesh };
  Kind kind = Kind::kCylinder;
  // Cylinder: (radius, radius, length) with the axis along z of G;
  // box: full edge lengths; sphere: (radius, radius, radius); mesh: the
  // scale its file was read with (already applied to `mesh`).
  Eigen::Vector3d size = Eigen::Vector3d::Zero();
  Eigen::Isometry3d X_BG = Eigen::Isometry3d::Identity();  // shape frame G in B
  std::shared_ptr<const TriangleMesh> mesh;  // kMesh: the triangles, in G
  std::string mesh_uri;                      // kMesh: as the robot file names it (package://…, a path)
};

struct Link {
  std::string name;
  int parent = -1;  // parent link index; -1 is the ground (world frame)
  std::string joint_name;
  Eigen::Isometry3d X_PJ = Eigen::Isometry3d::Identity();  // joint frame in parent
  Eigen::Vector3d axis_J = Eigen::Vector3d::UnitZ();       // unit hinge axis in J (and B)
  JointLimits limits;
  JointDynamics dynamics;
  LinkInertia inertia;
  std::vector<Shape> shapes;            // what is drawn (URDF <visual>)
  std::vector<Shape> collision_shapes;  // what clearance checks (URDF <collision>); empty: `shapes`

  const std::vector<Shape>& CollisionShapes() const { return collision_shapes.empty() ? shapes : collision_shapes; }
};

// A part of the ground: a link of the robot file that no joint moves (its
// root, a table or pedestal the arm stands on, and every link held to the
// root by fixed joints). Not a degree of freedom and without inertia; its
// shapes are placed in the base frame (X_BG is the shape in the frame of the
// root, which is the base frame R). Link clearance (link_clearance.h) keeps
// every moving link but those hinged to the ground away from them.
struct GroundLink {
  std::string name;                     // the robot file's link name
  std::vector<Shape> shapes;            // what is drawn (URDF <visual>)
  std::vector<Shape> collision_shapes;  // what clearance checks (URDF <collision>); empty: `shapes`

  const std::vector<Shape>& CollisionShapes() const { return collision_shapes.empty() ? shapes : collision_shapes; }
};

class RobotModel {
 public:
  // Validates and builds the model. Throws std::invalid_argument naming the
  // offending link when: no links, a parent index not smaller than the link's
  // own index, an axis that is not unit length, mass <= 0, an inertia that is
  // not symmetric positive definite, or limits with lo >= hi.
  // `ground`: the fixed links of the robot file with shapes (none for a
  // model without them).
  RobotModel(std::string name, std::vector<Link> links, Eigen::Vector3d g_W = StandardGravity_W(),
             std::vector<GroundLink> ground = {});
  // [m/s²] standard gravity along −z of W.
  static Eigen::Vector3d StandardGravity_W() { return Eigen::Vector3d(0.0, 0.0, -9.80665); }

  const std::string& name() const { return name_; }
  int n_links() const { return static_cast<int>(links_.size()); }
  int n_dof() const { return n_links(); }  // one revolute joint per link
  const Link& link(int i) const { return links_.at(static_cast<size_t>(i)); }
  const std::vector<Link>& links() const { return links_; }
  const Eigen::Vector3d& gravity_W() const { return g_W_; }
  // The links no joint moves (GroundLink), in the robot file's order.
  const std::vector<GroundLink>& ground() const { return ground_; }
  // Indices of the links whose parent is link i (i = -1: the ground).
  const std::vector<int>& children(int i) const {
    return children_.at(static_cast<size_t>(i + 1));
  }

 private:
  std::string name_;
  std::vector<Link> links_;
  Eigen::Vector3d g_W_;
  std::vector<GroundLink> ground_;
  std::vector<std::vector<int>> children_;  // indexed by parent + 1
};

// One message per link whose principal moments of inertia violate the
// triangle inequality (no real body has them, but published models do).
std::vector<std::string> InertiaWarnings(const RobotModel& model);

}  // namespace idbench
