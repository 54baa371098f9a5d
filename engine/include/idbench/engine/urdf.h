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
// RobotModel default). Materials are ignored.
#pragma once

#include <Eigen/Core>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/transmission.h"

namespace idbench {

// Beyond any robot link: the largest <inertial> mass [kg], inertia entry
// [kg m²] and centre-of-mass offset from the link frame [m] a robot file may
// give. The URDF reader refuses larger values; so does `export` in an
// identified.json (the same bounds for a model read and one written).
inline constexpr double kMaxLinkMass = 1e6;
inline constexpr double kMaxLinkInertia = 1e8;
inline constexpr double kMaxLinkComOffset = 1e3;

struct UrdfLoadResult {
  RobotModel model;
  // What was accepted but not fully kept, one line each naming the link or
  // joint: mesh visuals that could not be found or read, ignored <mimic> on a
  // chain joint, the joints locked off the chain (one line for all of them),
  // inertias that are not positive definite (replaced, see LoadUrdfString) or
  // break the triangle inequality (not physically realisable, still loaded).
  std::vector<std::string> warnings;
  // The ros_control <transmission> elements of the chain's joints
  // (SimpleTransmission, <mechanicalReduction>) as a diagonal A; nullopt when
  // the file has none (urdf_transmissions.cc).
  std::optional<Transmission> transmission;
};

// How a URDF becomes a chain: which link ends it, which joints are held still.
struct UrdfLoadOptions {
  // Joints fixed at a value: [rad] for revolute and continuous joints, [m]
  // for prismatic ones; floating and planar joints only at 0 (their <origin>).
  // A locked joint acts as a fixed joint. Any joint may be locked, also one on
  // the chain (which then has one degree of freedom less).
  std::map<std::string, double> locked_joints;
  // The last link of the arm's chain; empty: chosen automatically (see
  // LoadUrdfString).
  std::string tip_link;

  bool empty() const { return locked_joints.empty() && tip_link.empty(); }
  // Names are not empty and values finite; *why says what is wrong.
  bool IsValid(std::string* why) const;
};

// "JOINT=VALUE" (as the CLI's --lock takes it) into *options->locked_joints. False with
// *why (quoting the text) when there is no '=', no name, a value that is not
// one finite number, or a joint given twice.
bool AddJointLock(const std::string& text, UrdfLoadOptions* options, std::string* why);

// Loads the revolute chain of a URDF robot.
//
// The chain. Every joint is one of: a degree of freedom (revolute or
// continuous, not locked), rigid (fixed, or locked by options.locked_joints),
// or other (prismatic, floating, planar, not locked). With options.tip_link,
// the chain is the path from the root link to that link: its degrees of
// freedom become the model's joints; an "other" joint on it is refused. Without
// a tip, the chain ends at the one revolute joint that can be reached from the
// root through degree-of-freedom and rigid joints and has none of them below
// it. Refused (naming the links and joints, saying to pass --tip LINK or
// --lock JOINT=VALUE): two or more such ends (a branch: two arms, revolute
// gripper fingers), and an "other" joint reachable that way with a revolute
// joint below it (a linear axis carrying the arm: it is not clear whether it
// belongs to the arm). So prismatic gripper fingers (Panda), any joint hanging
// from the last link, and fixed side branches need no option.
//
// Every joint off the chain (any type, also one with <mimic>) is locked: at
// options.locked_joints' value, else a <mimic> joint at multiplier·value +
// offset of the joint it follows (a chain joint counts as 0), else at 0. The
// links below it are merged into the chain link it hangs from, as links on
// fixed joints are (below); one warning lists every locked joint, its value
// and that link. A locked joint's value is checked against its <limit>.
//
// The URDF root link, and every link rigidly attached to it, is the ground:
// their inertials are dropped, their shapes kept as the model's ground links
// (RobotModel::ground(), one per link with shapes: a table or pedestal the
// arm stands on is an obstacle to the links above it). Each degree of freedom becomes
// one idbench Link, named after the URDF child link, with joint_name the URDF
// joint name. Links hanging from a moving link by rigid joints are merged into
// it: their masses are lumped (COM and inertia about the lumped COM by the
// parallel-axis theorem), their visuals become its shapes, and moving joints
// below them get X_PJ composed with the rigid offsets.
//
// Geometry against inertia. A link whose own centre of mass lies outside the
// box around its shapes by more than the tolerance of
// CheckCenterOfMassInGeometry (link_bounding_box.h) loads with a warning
// naming it and the distance: its shapes are likely not placed in the frame
// of its inertial, and identification drops that box as the link's
// centre-of-mass bound (MakePlausibleFitOptions).
//
// Inertia. A chain link whose lumped inertia is not positive definite (all
// zero: a point mass; semidefinite; smallest principal moment ≤ 10⁻¹² of the
// largest) loads with a warning naming it: the file's values are a prior that
// identification replaces. Its principal moments below m·(2/5)·(1 cm)², those
// of a uniform sphere of 1 cm radius and the link's mass, are raised to that
// value (the principal axes are kept), so the model is a valid rigid body
// (Bullet, inverse dynamics). Moments that break the triangle inequality load
// as they are, with a warning.
//
// Joint axes are normalised. Limits: revolute lower/upper → q_min/q_max
// (continuous: none); velocity → qd_max and effort → tau_max, where a value
// ≤ 0 (urdfdom's default when absent) means not given = ∞; qdd_max = ∞.
// <dynamics damping friction> → JointDynamics viscous, coulomb.
// Visuals: box, cylinder (size (r, r, length), axis along z of G), sphere, and
// mesh (read with assimp: STL, COLLADA, OBJ, …; scale applied; the file found
// as ResolveMeshUri in mesh_uri.h says: package:// names through
// ROS_PACKAGE_PATH or a directory of that name above the URDF, relative paths
// against `base_directory`, the current directory when empty). <collision>
// geometry, the same kinds, goes to Link::collision_shapes (what clearance
// checks). A mesh that cannot be found or read is skipped
// with a warning naming the link and the file.
//
// Throws std::invalid_argument with one message that starts with the source
// name, names the link or joint at fault and the element, and says what to
// change, for: text urdfdom rejects ("not a valid URDF"); options that do not
// fit the file (an unknown joint or link, a locked value outside the joint's
// limits, a fixed joint locked); a chain that cannot be chosen (above); a
// moving link whose lumped mass is not > 0 (including no <inertial>); a
// negative or non-finite mass, or an inertia with a negative principal
// moment (beyond rounding) or non-finite entries, on any merged link; values
// beyond any robot link (a mass above 10⁶ kg, an inertia entry above
// 10⁸ kg m², a centre of mass more than 10³ m from the link frame); a zero
// joint axis; revolute limits with lower ≥ upper; negative damping or
// friction; no moving joint at all.
UrdfLoadResult LoadUrdfString(const std::string& xml, const std::string& source_name = "<string>",
                               const std::string& base_directory = "", const UrdfLoadOptions& options = {});

// As LoadUrdfString, with source_name = path and meshes looked up from the
// file's directory. Also throws
// std::invalid_argument naming the path when the file cannot be read.
UrdfLoadResult LoadUrdfFile(const std::string& path, const UrdfLoadOptions& options = {});

// URDF text of a model: a root link for the ground (named "base", or another
// name no link uses), then per idbench link a <link> with <inertial> (origin
// at the COM, rpy 0, the full inertia tensor), one <visual> per shape and one
// <collision> per collision shape, and
// a <joint> with origin X_PJ, axis, <limit> and <dynamics> (when friction is
// nonzero). Joints with infinite q limits are written as continuous; an
// infinite velocity or effort is written as 0 (= not given). An empty
// joint_name is replaced by "<link name>_joint" (made unique). The ground
// links (RobotModel::ground) hang from the fresh root by fixed joints.
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
