// Built-in reference motions, by name for the commands' --trajectory.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "idbench/engine/trajectory.h"

namespace idbench {

// The paper's experiment: from rest at q = 0, hinges 1 and 2 accelerate at
// qdd [rad/s²], all other hinges locked.
std::unique_ptr<Trajectory> MakePaperMotion(int n_dof, double qdd, double duration);

// All joints moving: a two-harmonic Fourier series per joint with distinct
// amplitudes and phases, starting at q = 0 (f0 = 0.5 Hz).
std::unique_ptr<Trajectory> MakeGeneralMotion(int n_dof, double duration);

// A motion played backwards: q(t) = q_f(T − t), qd(t) = −qd_f(T − t),
// qdd(t) = qdd_f(T − t). Every velocity changes sign, which makes it a good
// held-out motion for models with friction.
class ReversedTrajectory final : public Trajectory {
 public:
  explicit ReversedTrajectory(std::unique_ptr<Trajectory> forward) : forward_(std::move(forward)) {}
  int n_dof() const override { return forward_->n_dof(); }
  double duration() const override { return forward_->duration(); }
  void Evaluate(double t, JointState* state) const override;

 private:
  std::unique_ptr<Trajectory> forward_;
};

// "paper", "general", "general-reversed".
std::vector<std::string> BuiltinMotionNames();

// What a built-in motion needs besides its name and the robot's n_dof.
struct BuiltinMotionOptions {
  double duration = 10.0;  // [s]
  double paper_qdd = 0.5;  // acceleration of the "paper" motion [rad/s²]
};

// A built-in motion by name; paper_qdd is the paper motion's acceleration
// [rad/s²]. Throws std::invalid_argument naming the unknown motion.
std::unique_ptr<Trajectory> MakeBuiltinMotion(const std::string& name, int n_dof, double duration,
                                              double paper_qdd);
inline std::unique_ptr<Trajectory> MakeBuiltinMotion(const std::string& name, int n_dof,
                                                     const BuiltinMotionOptions& options) {
  return MakeBuiltinMotion(name, n_dof, options.duration, options.paper_qdd);
}

}  // namespace idbench
