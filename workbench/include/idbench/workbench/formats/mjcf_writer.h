// MJCF (MuJoCo's XML) of a robot model: what MuJoCo users load beside the URDF.
//
// One <body> per link, nested as the tree, placed at the joint frame J in its
// parent (pos, quat w x y z; at q = 0 J and B coincide), with one <joint
// type="hinge"> about axis_J at the body origin:
//   inertial     pos = p_BoBcm_B, mass, fullinertia = I_Bcm_B (about the centre of mass)
//   armature     = JointDynamics::rotor_inertia  [kg m²]
//   damping      = JointDynamics::viscous        [N m s/rad]
//   frictionloss = JointDynamics::coulomb        [N m]
//   range        = [q_min, q_max] (limited) when both are finite
// <compiler angle="radian" inertiafromgeom="false"/>, <option gravity> from
// the model. Shapes become geoms: visuals in group 1 without contacts,
// collision shapes (when the file has its own) in group 3; meshes inline as
// <mesh vertex face> (the triangles as read, scale applied), so the file
// stands alone whatever format the meshes were in.
//
// A link whose principal moments break the triangle inequality (published
// models have them; MuJoCo refuses them) gets balanceinertia="true", which
// makes MuJoCo replace its three moments by their mean; a comment names it.
//
// MuJoCo's inverse dynamics of the file (mj_inverse, constraints disabled)
// equals InverseDynamics + AddJointDynamicsTorque without Coulomb
// (tests/workbench/formats/mjcf_writer_test.cc). Not expressible and so not
// written: velocity, acceleration and effort limits.
#pragma once

#include <string>

#include "idbench/engine/robot_model.h"

namespace idbench {

// The MJCF text. Throws std::invalid_argument naming the link for a
// one-sided joint limit (MuJoCo ranges have two ends).
std::string WriteMjcf(const RobotModel& model);

// Whether the principal moments of I_Bcm_B [kg m²] break A + B ≥ C.
bool ViolatesTriangleInequality(const Eigen::Matrix3d& I_Bcm_B);

}  // namespace idbench
