// Built-in reference motions of `idbench run`.
#pragma once

#include <memory>

#include "idbench/engine/trajectory.h"

namespace idbench {

// The paper's experiment: from rest at q = 0, hinges 1 and 2 accelerate at
// qdd [rad/s²], all other hinges locked.
std::unique_ptr<Trajectory> MakePaperMotion(int n_dof, double qdd, double duration);

// All joints moving: a two-harmonic Fourier series per joint with distinct
// amplitudes and phases, starting at q = 0 (f0 = 0.5 Hz).
std::unique_ptr<Trajectory> MakeGeneralMotion(int n_dof, double duration);

}  // namespace idbench
