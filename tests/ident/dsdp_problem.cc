#include "ident/dsdp_problem.h"

#include <algorithm>
#include <mutex>
#include <stdexcept>

extern "C" {
#include <dsdp/dsdp5.h>
}

namespace idbench::test {
namespace {

// DSDP's packed symmetric storage ('P'): entry (row ≥ col) of an n × n block.
int PackedIndex(int row, int col) { return row * (row + 1) / 2 + col; }

void Check(int info, const char* call) {
  if (info != 0) throw std::runtime_error(std::string("DSDP: ") + call + " failed (" + std::to_string(info) + ")");
}

const char* StopReasonText(DSDPTerminationReason reason) {
  switch (reason) {
    case DSDP_CONVERGED: return "converged";
    case DSDP_INFEASIBLE_START: return "infeasible start";
    case DSDP_SMALL_STEPS: return "short steps (numerical difficulties)";
    case DSDP_INDEFINITE_SCHUR_MATRIX: return "indefinite Schur matrix";
    case DSDP_MAX_IT: return "iteration limit reached";
    case DSDP_NUMERICAL_ERROR: return "numerical error";
    case DSDP_UPPERBOUND: return "objective bound reached";
    case DSDP_USER_TERMINATION: return "stopped";
    default: return "not finished";
  }
}

const char* SolutionTypeText(DSDPSolutionType type) {
  switch (type) {
    case DSDP_PDFEASIBLE: return "feasible";
    case DSDP_UNBOUNDED: return "unbounded";
    case DSDP_INFEASIBLE: return "infeasible: no parameters satisfy every constraint";
    default: return "feasibility unknown";
  }
}

// DSDP keeps global event logs; one solve at a time.
std::mutex g_dsdp_mutex;

}  // namespace

SdpProblem::SdpProblem(int n_variables) : n_variables_(n_variables), b_(Eigen::VectorXd::Zero(std::max(n_variables, 0))) {
  if (n_variables < 1) throw std::invalid_argument("SdpProblem: expected at least 1 variable, got " + std::to_string(n_variables));
}

void SdpProblem::SetObjective(const Eigen::VectorXd& b) {
  if (b.size() != n_variables_) throw std::invalid_argument("SdpProblem::SetObjective: size mismatch");
  b_ = b;
}

int SdpProblem::AddBlock(const Eigen::MatrixXd& C) {
  if (C.rows() != C.cols() || C.rows() < 1) throw std::invalid_argument("SdpProblem::AddBlock: expected a square matrix");
  blocks_.push_back(Block{C, {}});
  return static_cast<int>(blocks_.size()) - 1;
}

void SdpProblem::AddBlockEntry(int block, int variable, int row, int col, double value) {
  const int n = static_cast<int>(blocks_.at(static_cast<size_t>(block)).C.rows());
  if (variable < 0 || variable >= n_variables_ || col < 0 || row < col || row >= n)
    throw std::invalid_argument("SdpProblem::AddBlockEntry: index out of range");
  blocks_[static_cast<size_t>(block)].entries.push_back(Entry{variable, row, col, value});
}

void SdpProblem::AddLinearRow(double c, const std::vector<std::pair<int, double>>& a) {
  for (const auto& [variable, coefficient] : a)
    if (variable < 0 || variable >= n_variables_) throw std::invalid_argument("SdpProblem::AddLinearRow: variable out of range");
  rows_.push_back(Row{c, a});
}

SdpSolution SdpProblem::Solve(const SdpSolverOptions& options) const {
  const int m = n_variables_;
  // DSDP reads the data arrays during the solve without copying them: they
  // live here until DSDPDestroy. Per block, per matrix (0 = C, i + 1 = A_i):
  // packed indices and values, sorted by index.
  struct PackedMatrix {
    std::vector<int> index;
    std::vector<double> value;
  };
  std::vector<std::vector<PackedMatrix>> packed(blocks_.size());
  for (size_t j = 0; j < blocks_.size(); ++j) {
    const Block& block = blocks_[j];
    const int n = static_cast<int>(block.C.rows());
    std::vector<Eigen::VectorXd> dense(static_cast<size_t>(m) + 1);  // summed entries per matrix
    std::vector<bool> used(static_cast<size_t>(m) + 1, false);
    dense[0] = Eigen::VectorXd::Zero(n * (n + 1) / 2);
    for (int r = 0; r < n; ++r)
      for (int c = 0; c <= r; ++c) dense[0][PackedIndex(r, c)] = block.C(r, c);
    used[0] = true;
    for (const Entry& e : block.entries) {
      auto& d = dense[static_cast<size_t>(e.variable) + 1];
      if (d.size() == 0) d = Eigen::VectorXd::Zero(n * (n + 1) / 2);
      d[PackedIndex(e.row, e.col)] += e.value;
      used[static_cast<size_t>(e.variable) + 1] = true;
    }
    packed[j].resize(static_cast<size_t>(m) + 1);
    for (size_t i = 0; i <= static_cast<size_t>(m); ++i) {
      if (!used[i]) continue;
      for (Eigen::Index k = 0; k < dense[i].size(); ++k) {
        if (dense[i][k] == 0.0) continue;
        packed[j][i].index.push_back(static_cast<int>(k));
        packed[j][i].value.push_back(dense[i][k]);
      }
    }
  }
  // Linear rows, column-compressed: column 0 is c, column i + 1 holds a_i.
  std::vector<int> lp_start(static_cast<size_t>(m) + 2, 0), lp_row;
  std::vector<double> lp_value;
  {
    std::vector<std::vector<std::pair<int, double>>> columns(static_cast<size_t>(m) + 1);
    for (size_t k = 0; k < rows_.size(); ++k) {
      if (rows_[k].c != 0.0) columns[0].emplace_back(static_cast<int>(k), rows_[k].c);
      std::vector<double> a(static_cast<size_t>(m), 0.0);
      for (const auto& [variable, coefficient] : rows_[k].a) a[static_cast<size_t>(variable)] += coefficient;
      for (int i = 0; i < m; ++i)
        if (a[static_cast<size_t>(i)] != 0.0) columns[static_cast<size_t>(i) + 1].emplace_back(static_cast<int>(k), a[static_cast<size_t>(i)]);
    }
    for (size_t i = 0; i <= static_cast<size_t>(m); ++i) {
      for (const auto& [row, value] : columns[i]) {
        lp_row.push_back(row);
        lp_value.push_back(value);
      }
      lp_start[i + 1] = static_cast<int>(lp_row.size());
    }
  }

  const std::lock_guard<std::mutex> lock(g_dsdp_mutex);
  DSDP dsdp = nullptr;
  Check(DSDPCreate(m, &dsdp), "DSDPCreate");
  SdpSolution solution;
  try {
    for (int i = 0; i < m; ++i) Check(DSDPSetDualObjective(dsdp, i + 1, b_[i]), "DSDPSetDualObjective");
    if (!blocks_.empty()) {
      SDPCone sdpcone = nullptr;
      Check(DSDPCreateSDPCone(dsdp, static_cast<int>(blocks_.size()), &sdpcone), "DSDPCreateSDPCone");
      for (size_t j = 0; j < blocks_.size(); ++j) {
        const int block = static_cast<int>(j);
        const int n = static_cast<int>(blocks_[j].C.rows());
        Check(SDPConeSetBlockSize(sdpcone, block, n), "SDPConeSetBlockSize");
        for (size_t i = 0; i <= static_cast<size_t>(m); ++i) {
          const PackedMatrix& p = packed[j][i];
          if (p.index.empty()) continue;
          Check(SDPConeSetASparseVecMat(sdpcone, block, static_cast<int>(i), n, 1.0, 0, p.index.data(), p.value.data(),
                                        static_cast<int>(p.index.size())),
                "SDPConeSetASparseVecMat");
        }
      }
    }
    if (!rows_.empty()) {
      LPCone lpcone = nullptr;
      Check(DSDPCreateLPCone(dsdp, &lpcone), "DSDPCreateLPCone");
      Check(LPConeSetData(lpcone, static_cast<int>(rows_.size()), lp_start.data(), lp_row.data(), lp_value.data()),
            "LPConeSetData");
    }
    Check(DSDPSetGapTolerance(dsdp, options.gap_tolerance), "DSDPSetGapTolerance");
    Check(DSDPSetMaxIts(dsdp, options.max_iterations), "DSDPSetMaxIts");
    Check(DSDPSetZBar(dsdp, options.objective_upper_bound), "DSDPSetZBar");
    if (options.y0.size() == m)
      for (int i = 0; i < m; ++i) Check(DSDPSetY0(dsdp, i + 1, options.y0[i]), "DSDPSetY0");
    Check(DSDPSetup(dsdp), "DSDPSetup");
    Check(DSDPSolve(dsdp), "DSDPSolve");
    DSDPTerminationReason reason = CONTINUE_ITERATING;
    DSDPSolutionType type = DSDP_PDUNKNOWN;
    Check(DSDPStopReason(dsdp, &reason), "DSDPStopReason");
    Check(DSDPGetSolutionType(dsdp, &type), "DSDPGetSolutionType");
    solution.y.resize(m);
    Check(DSDPGetY(dsdp, solution.y.data(), m), "DSDPGetY");
    // The best upper bound DSDP proved (its potential reduction keeps it; the
    // objective of the X reconstructed by DSDPComputeX can be looser).
    Check(DSDPGetPPObjective(dsdp, &solution.primal_objective), "DSDPGetPPObjective");
    Check(DSDPGetDObjective(dsdp, &solution.dual_objective), "DSDPGetDObjective");
    Check(DSDPGetIts(dsdp, &solution.iterations), "DSDPGetIts");
    solution.feasible = type == DSDP_PDFEASIBLE;
    solution.stopped_on_gap = reason == DSDP_CONVERGED;
    solution.status = std::string(StopReasonText(reason)) + ", " + SolutionTypeText(type);
  } catch (...) {
    DSDPDestroy(dsdp);
    throw;
  }
  DSDPDestroy(dsdp);
  return solution;
}

SdpSolution SolveWithDsdp(const internal::QuadraticSdp& problem, Eigen::VectorXd* u, const SdpSolverOptions& options) {
  const int n = problem.n_variables();
  SdpProblem sdp(n + 1);  // y = (u, t)
  Eigen::VectorXd b = Eigen::VectorXd::Zero(n + 1);
  b[n] = -1.0;
  sdp.SetObjective(b);
  Eigen::MatrixXd C0 = Eigen::MatrixXd::Identity(n + 1, n + 1);
  C0(0, 0) = 0.0;
  C0.col(0).tail(n) = -problem.z;
  C0.row(0).tail(n) = -problem.z.transpose();
  const int epigraph = sdp.AddBlock(C0);
  sdp.AddBlockEntry(epigraph, n, 0, 0, -1.0);
  for (int k = 0; k < n; ++k)
    for (int i = 0; i < n; ++i)
      if (problem.R(i, k) != 0.0) sdp.AddBlockEntry(epigraph, k, i + 1, 0, -problem.R(i, k));
  for (const internal::LmiBlock& block : problem.blocks) {
    const int j = sdp.AddBlock(block.C);
    for (size_t v = 0; v < block.variables.size(); ++v)
      for (int r = 0; r < block.C.rows(); ++r)
        for (int c = 0; c <= r; ++c)
          if (block.B[v](r, c) != 0.0) sdp.AddBlockEntry(j, block.variables[v], r, c, -block.B[v](r, c));
  }
  for (const internal::LinearInequality& row : problem.rows) {
    std::vector<std::pair<int, double>> a;
    for (const auto& [i, coefficient] : row.a) a.emplace_back(i, -coefficient);
    sdp.AddLinearRow(row.c, a);
  }
  SdpSolution solution = sdp.Solve(options);
  *u = solution.y.head(n);
  return solution;
}

}  // namespace idbench::test
