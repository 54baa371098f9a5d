// The Unimation PUMA 560, the classic identification benchmark, from the
// standard published parameters (Armstrong, Khatib & Burdick 1986, as used in
// Corke's Robotics Toolbox `mdl_puma560`): standard DH geometry, link masses,
// centres of mass, principal inertias, joint limits, and the motor inertias,
// gear ratios and friction reflected to the joints.
//
// Joint angles have the same zero and sign as Corke's model. Link frames follow
// idbench's convention (robot_model.h): link i's frame is DH frame i−1 rotated
// by q_i about its z axis, i.e. it sits on joint i's axis, as in a URDF; the
// DH frame i is that frame moved by Tz(d_i)·Tx(a_i)·Rx(α_i). The published
// centres of mass and inertias (given in DH frame i) are transformed into it,
// so every joint torque equals the DH model's, but the 10 standard parameters
// of a link are about a different origin than the DH ones.
//
// The published model leaves link 1's mass and its inertias about the two axes
// normal to joint 1 at zero. Here link 1 has 10 kg with its centre of mass on
// the joint-1 axis at the shoulder and Ixx = Izz = 0.2 kg m² (DH frame 1),
// which changes no joint torque. Link 3's published inertia violates the
// triangle inequality (0.066 + 0.0125 < 0.086); it is kept as published.
// The shoulder (DH frame 0) is 0.672 m above the ground.
#pragma once

#include "idbench/engine/robot_model.h"

namespace idbench {

RobotModel MakePuma560();

}  // namespace idbench
