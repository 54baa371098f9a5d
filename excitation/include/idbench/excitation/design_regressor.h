// The identification regressor an excitation design shapes, one sample at a
// time: W stacks Rows(x_t) over the sample times t, x = (q, qd, qdd).
//
//   joint torque  Rows = Y_base(q, qd, qdd): n rows, one column per base
//                 parameter (inertial and friction; base_parameters.h).
//   per body      per body b, 6 rows: its Newton rows (a_WBcm − g, the mass
//                 column) and its Euler rows S(ω_B, ω̇_B) (per_body_regressor.h)
//                 in the columns of its structurally identifiable principal
//                 moments (those the paper's method can identify from some
//                 motion: a moment whose column is zero or dependent at every
//                 state, like J11, J22 of a body turning about a fixed axis, is
//                 left out).
//
// StateGradient differentiates ⟨G, Rows(x)⟩ exactly with respect to x by
// reverse-mode automatic differentiation (adjoint.h): the function is recorded
// once on a tape and one backward sweep gives all 3n derivatives, for the
// design's gradient (joint torque: through ContractJointTorqueRegressorT,
// without forming Y).
#pragma once

#include <Eigen/Core>
#include <string>
#include <vector>

#include "idbench/engine/adjoint.h"
#include "idbench/engine/enum_names.h"
#include "idbench/engine/kinematics.h"
#include "idbench/engine/robot_model.h"
#include "idbench/engine/trajectory.h"
#include "idbench/ident/base_parameters.h"
#include "idbench/ident/joint_torque_regressor.h"

namespace idbench {

// The identification model: joint torques (base parameters, friction) or
// per body (every link's inertial parameters, from the wrench through each
// hinge). Option fields `model` name it "torque" | "per-body".
enum class IdentificationModel { kJointTorque, kPerBody };
inline constexpr EnumNames<IdentificationModel, 2> kIdentificationModelNames{"model", {"torque", "per-body"}, true};

class DesignRegressor {
 public:
  // Mutable per-thread scratch space.
  struct Workspace {
    explicit Workspace(const RobotModel& model);
    KinematicsData<double> kinematics;
    KinematicsData<Adjoint> adjoint_kinematics;
    Eigen::MatrixXd Y, G_standard;
    AdjointTape tape;
    Eigen::Matrix<Adjoint, Eigen::Dynamic, Eigen::Dynamic> adjoint_Y;
    Eigen::Matrix<Adjoint, Eigen::Dynamic, 1> q, qd, qdd;
  };

  static DesignRegressor JointTorque(const RobotModel& model, const FrictionModel& friction,
                                     const BaseParameterOptions& base_options = {});
  static DesignRegressor PerBody(const RobotModel& model);

  IdentificationModel kind() const { return kind_; }
  const RobotModel& model() const { return *model_; }
  int rows_per_sample() const { return rows_per_sample_; }
  int n_parameters() const { return static_cast<int>(names_.size()); }
  const std::vector<std::string>& parameter_names() const { return names_; }
  // Joint torque model only: the base parameters and the friction terms.
  const BaseParameters& base() const { return base_; }
  const FrictionModel& friction() const { return friction_; }
  // The true values of the parameters (for predicted relative σ).
  const Eigen::VectorXd& true_parameters() const { return true_parameters_; }

  // rows (rows_per_sample × n_parameters) at the state x.
  void Rows(const JointState& x, Workspace* ws, Eigen::Ref<Eigen::MatrixXd> rows) const;

  // g = ∂⟨G, Rows(x)⟩/∂(q, qd, qdd), length 3n in that order.
  void StateGradient(const JointState& x, const Eigen::Ref<const Eigen::MatrixXd>& G, Workspace* ws,
                     Eigen::Ref<Eigen::VectorXd> g) const;

  // W for the states of a trajectory at the given times.
  Eigen::MatrixXd Stack(const Trajectory& trajectory, const std::vector<double>& times) const;

 private:
  DesignRegressor(const RobotModel& model, IdentificationModel kind) : model_(&model), kind_(kind) {}
  // Per-body rows on any scalar; column indices from col_m_ / col_J_.
  template <typename Scalar>
  void PerBodyRows(const KinematicsData<Scalar>& k,
                   Eigen::Matrix<Scalar, Eigen::Dynamic, Eigen::Dynamic>* rows) const;

  const RobotModel* model_;  // not owned; outlives the regressor
  IdentificationModel kind_;
  int rows_per_sample_ = 0;
  std::vector<std::string> names_;
  Eigen::VectorXd true_parameters_;
  FrictionModel friction_;
  BaseParameters base_;
  std::vector<int> col_m_;                // per body: column of its mass
  std::vector<std::vector<int>> col_J_;   // per body, per principal moment: column or −1
};

}  // namespace idbench
