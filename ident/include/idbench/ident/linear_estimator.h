// Least-squares estimators of the base parameters from stacked torques
// τ = W β + e, with parameter standard deviations (Gautier & Khalil):
//   OLS: β̂ = argmin ‖W β − τ‖, σ² = ‖r‖²/(N − p), cov = σ² (WᵀW)⁻¹;
//   WLS: rows of joint j weighted by 1/σ_j, σ_j² from joint j's OLS residuals.
// Rows are ordered sample by sample, joints within a sample (row = s·n_dof + j).
// Solved by QR; normal equations are never formed.
#pragma once

#include <Eigen/Core>

namespace idbench {

struct LinearFit {
  Eigen::VectorXd beta;            // estimate (p)
  Eigen::MatrixXd covariance;      // (p × p)
  Eigen::VectorXd sigma;           // standard deviations (p)
  Eigen::VectorXd rel_sigma_percent;  // 100 σ/|β| (p)
  Eigen::VectorXd joint_rms;       // residual RMS per joint [N m] (n_dof), unweighted
  Eigen::VectorXd joint_sigma;     // per-joint noise estimates (WLS weights are 1/σ_j)
  double cond = 0.0;               // cond(W) (weighted for WLS)
};

// RMS per joint of stacked residuals r (rows interleaved by joint) (n_dof).
Eigen::VectorXd JointRms(const Eigen::VectorXd& r, int n_dof);

// Throws std::invalid_argument on size mismatch or fewer rows than p + 1.
LinearFit SolveOls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof);
LinearFit SolveWls(const Eigen::MatrixXd& W, const Eigen::VectorXd& tau, int n_dof);

}  // namespace idbench
