// Reading and writing RobotModels as URDF (http://wiki.ros.org/urdf/XML),
// parsed with urdfdom.
//
// Frames match without conversion: a URDF child link frame is its joint
// frame, and so is an idbench link frame B at q = 0 (robot_model.h). A joint
// <origin> is X_PJ, its <axis> is axis_J, an <inertial> origin is the centre
// of mass with the inertia's principal-or-not axes, a <visual> origin is X_BG.
// URDF rpy angles are fixed-axis roll about x, then pitch about y, then yaw
// about z: R = Rz(yaw)·Ry(pitch)·Rx(roll).
//
// Not expressed in URDF, so neither read nor written: JointDynamics::
// rotor_inertia, JointLimits::qdd_max, and gravity (a loaded model gets the
// RobotModel default). Collision geometry and materials are ignored.
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"

namespace idbench {

struct UrdfLoadResult {
  RobotModel model;
  // What was accepted but not fully kept, one line each naming the link or
  // joint: mesh visuals that could not be found or read, ignored <mimic>, inertias that break the
  // triangle inequality (not physically realisable, still loaded).
  std::vector<std::string> warnings;
};

// Loads a serial revolute chain from URDF.
//
// The URDF root link, and every link fixed to it, is the ground: their
// inertials and visuals are dropped. Each revolute or continuous joint becomes
// one idbench Link, named after the URDF child link, with joint_name the URDF
// joint name. Links hanging from a moving link by fixed joints are merged into
// it: their masses are lumped (COM and inertia about the lumped COM by the
// parallel-axis theorem), their visuals become its shapes, and moving joints
// below them get X_PJ composed with the fixed offsets.
//
// Joint axes are normalised. Limits: revolute lower/upper → q_min/q_max
// (continuous: none); velocity → qd_max and effort → tau_max, where a value
// ≤ 0 (urdfdom's default when absent) means not given = ∞; qdd_max = ∞.
// <dynamics damping friction> → JointDynamics viscous, coulomb.
// Visuals: box, cylinder (size (r, r, length), axis along z of G), sphere, and
// mesh (read with assimp: STL, COLLADA, OBJ, …; scale applied; the file found
// as ResolveMeshUri in urdf.cc says: package:// names through
// ROS_PACKAGE_PATH or a directory of that name above the URDF, relative paths
// against `base_directory`, the current directory when empty). <collision>
// geometry, the same kinds, goes to Link::collision_shapes (what clearance
// checks). A mesh that cannot be found or read is skipped
// with a warning naming the link and the file.
//
// Throws std::invalid_argument with one message that starts with the source
// name and names the link or joint at fault, for: text urdfdom rejects ("not a
// valid URDF"); floating, planar or prismatic joints; a link where two chains
// with moving joints diverge; a moving link whose lumped mass is not > 0
// (including no <inertial>) or whose lumped inertia is not positive definite;
// a negative mass or an inertia that is not positive semidefinite on any
// merged link; a zero joint axis; revolute limits with lower ≥ upper;
// negative damping or friction; no moving joint at all.
UrdfLoadResult LoadUrdfString(const std::string& xml, const std::string& source_name = "<string>",
                               const std::string& base_directory = "");

// As LoadUrdfString, with source_name = path and meshes looked up from the
// file's directory. Also throws
// std::invalid_argument naming the path when the file cannot be read.
UrdfLoadResult LoadUrdfFile(const std::string& path);

// URDF text of a model: a root link for the ground (named "base", or another
// name no link uses), then per idbench link a <link> with <inertial> (origin
// at the COM, rpy 0, the full inertia tensor), one <visual> per shape and one
// <collision> per collision shape, and
// a <joint> with origin X_PJ, axis, <limit> and <dynamics> (when friction is
// nonzero). Joints with infinite q limits are written as continuous; an
// infinite velocity or effort is written as 0 (= not given). An empty
// joint_name is replaced by "<link name>_joint" (made unique).
// Every number is written with 17 significant digits, so that
// LoadUrdfString(WriteUrdf(m)) reproduces m to rounding (~1e-15 relative),
// except for what URDF cannot express (see the top of this file).
// Throws std::invalid_argument naming the link for one-sided q limits (one
// finite, one infinite) and for duplicate link or joint names, which URDF
// cannot represent.
std::string WriteUrdf(const RobotModel& model);

// URDF roll-pitch-yaw of a rotation matrix: R = Rz(y)·Ry(p)·Rx(r), returned as
// (r, p, y) with p ∈ [−π/2, π/2]. At and near gimbal lock (|p| → π/2) the
// angles are not unique, but RotationFromRpy of the result reproduces R to
// rounding. R must be a rotation (not checked).
Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R);

// R = Rz(rpy.z)·Ry(rpy.y)·Rx(rpy.x), the rotation URDF means by rpy.
Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy);

// Text with &, <, >, " and ' as XML entities (URDF attributes, HTML).
std::string EscapeXml(const std::string& text);

}  // namespace idbench
