// The tests' independent solver for the physically consistent estimate: a
// semidefinite program handed to DSDP (Benson & Ye, Debian libdsdp-dev), a
// dual-scaling interior-point method unrelated to ident's own barrier method
// (ident/src/quadratic_sdp.h). The only file that includes DSDP's headers.
//
// DSDP solves the dual form
//   maximise bᵀy  over y ∈ ℝᵐ
//   subject to  C_j − Σ_i y_i A_ij ⪰ 0   for every block j (symmetric),
//               c_k − a_kᵀ y ≥ 0         for every linear row k,
// together with its primal (P), and stops when the relative duality gap
// (p − d) / (1 + |p| + |d|) is below gap_tolerance, p ≥ d the primal and dual
// objectives.
#pragma once

#include <Eigen/Core>
#include <string>
#include <utility>
#include <vector>

#include "quadratic_sdp.h"

namespace idbench::test {

struct SdpSolverOptions {
  double gap_tolerance = 1e-10;  // relative duality gap at which DSDP stops
  int max_iterations = 500;
  // A known upper bound on max bᵀy (DSDP's z̄; its default 1e10 costs
  // iterations), and a start y₀ (empty: y = 0).
  double objective_upper_bound = 1e10;
  Eigen::VectorXd y0;
};

struct SdpSolution {
  Eigen::VectorXd y;              // the dual variables (the unknowns)
  double primal_objective = 0.0;  // p, an upper bound on max bᵀy
  double dual_objective = 0.0;    // d = bᵀy
  int iterations = 0;
  bool feasible = false;          // DSDP classed (P) and (D) feasible and bounded
  bool stopped_on_gap = false;    // DSDP stopped on gap_tolerance (else on a numerical limit)
  std::string status;             // DSDP's stop reason and solution type, e.g. "converged, feasible"
};

class SdpProblem {
 public:
  // Throws std::invalid_argument unless n_variables ≥ 1.
  explicit SdpProblem(int n_variables);

  int n_variables() const { return n_variables_; }

  // b (n_variables).
  void SetObjective(const Eigen::VectorXd& b);

  // Adds a block with constant matrix C (symmetric, its lower triangle is
  // read) and no A's yet; returns its index.
  int AddBlock(const Eigen::MatrixXd& C);
  // A_ij(row, col) += value and its mirror; row ≥ col (0-based).
  void AddBlockEntry(int block, int variable, int row, int col, double value);

  // Adds the row c − Σ a_i y_i ≥ 0, a given as (variable, coefficient).
  void AddLinearRow(double c, const std::vector<std::pair<int, double>>& a);

  // Solves with DSDP. Throws std::runtime_error if DSDP reports an error in
  // its setup (a bug, not a property of the data).
  SdpSolution Solve(const SdpSolverOptions& options = {}) const;

 private:
  struct Entry {
    int variable, row, col;
    double value;
  };
  struct Block {
    Eigen::MatrixXd C;
    std::vector<Entry> entries;
  };
  struct Row {
    double c;
    std::vector<std::pair<int, double>> a;
  };
  int n_variables_;
  Eigen::VectorXd b_;
  std::vector<Block> blocks_;
  std::vector<Row> rows_;
};

// min ‖R u − z‖² of a QuadraticSdp by DSDP through its epigraph
// [[t, (Ru − z)ᵀ], [Ru − z, 𝟙]] ⪰ 0; writes u and returns the solution (the
// minimum is −dual_objective).
SdpSolution SolveWithDsdp(const internal::QuadraticSdp& problem, Eigen::VectorXd* u,
                          const SdpSolverOptions& options = {});

}  // namespace idbench::test
