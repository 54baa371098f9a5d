#include "idbench/workbench/reports/plots.h"

#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <utility>

#include "idbench/ident/per_body_regressor.h"

namespace idbench {
namespace {

// Rows 0, k, 2k, … of a matrix (empty stays empty).
Eigen::MatrixXd EveryKthRow(const Eigen::MatrixXd& m, int k) {
  if (m.size() == 0) return m;
  Eigen::MatrixXd out((m.rows() + k - 1) / k, m.cols());
  for (Eigen::Index i = 0; i < out.rows(); ++i) out.row(i) = m.row(i * k);
  return out;
}

PlotAxes SignalAxes(const std::string& title, const std::string& y_label, const std::vector<double>& t,
                    const Eigen::MatrixXd& values, const std::string& x_label,
                    const std::vector<std::string>& joint_names) {
  PlotAxes axes;
  axes.title = title;
  axes.y_label = y_label;
  axes.x_label = x_label;
  for (Eigen::Index j = 0; j < values.cols(); ++j) {
    PlotSeries s;
    s.label = JointLabel(joint_names, j);
    s.x = t;
    s.y.assign(values.col(j).data(), values.col(j).data() + values.rows());
    axes.series.push_back(std::move(s));
  }
  return axes;
}

}  // namespace

JointSignals SignalsOf(const SimulationLog& log, int max_samples) {
  const int n = static_cast<int>(log.steps.size()), k = std::max(1, (n + max_samples - 1) / max_samples);
  JointSignals s;
  const int m = (n + k - 1) / k, n_dof = n ? static_cast<int>(log.steps[0].q.size()) : 0;
  s.q.resize(m, n_dof), s.qd.resize(m, n_dof), s.qdd.resize(m, n_dof), s.tau.resize(m, n_dof);
  for (int i = 0; i < m; ++i) {
    const LogStep& step = log.steps[static_cast<size_t>(i * k)];
    s.t.push_back(step.t);
    s.q.row(i) = step.q.transpose(), s.qd.row(i) = step.qd.transpose();
    s.qdd.row(i) = step.qdd.transpose(), s.tau.row(i) = step.tau.transpose();
  }
  return s;
}

JointSignals SignalsOf(const JointLog& log, int max_samples) {
  const int k = std::max(1, (log.n_samples() + max_samples - 1) / max_samples);
  JointSignals s;
  for (Eigen::Index i = 0; i < log.t.size(); i += k) s.t.push_back(log.t[i]);
  s.q = EveryKthRow(log.q, k), s.qd = EveryKthRow(log.qd, k), s.qdd = EveryKthRow(log.qdd, k);
  s.tau = EveryKthRow(log.tau, k);
  return s;
}

std::vector<std::string> JointNames(const RobotModel& model) {
  std::vector<std::string> names;
  for (const Link& link : model.links()) names.push_back(link.joint_name);
  return names;
}

std::string JointLabel(const std::vector<std::string>& joint_names, Eigen::Index j) {
  const bool named = j < static_cast<Eigen::Index>(joint_names.size()) && !joint_names[static_cast<size_t>(j)].empty();
  return named ? joint_names[static_cast<size_t>(j)] : "joint " + std::to_string(j + 1);
}

PlotFigure JointSignalsPlot(const JointSignals& signals, const std::vector<std::string>& joint_names) {
  PlotFigure figure;
  figure.width = 720, figure.height = 760;
  figure.axes.push_back(SignalAxes("Joint positions", "q [rad]", signals.t, signals.q, "", joint_names));
  if (signals.qd.size() > 0) {
    figure.axes.push_back(SignalAxes("Joint velocities", "qd [rad/s]", signals.t, signals.qd, "", joint_names));
    figure.axes.push_back(SignalAxes("Joint accelerations", "qdd [rad/s²]", signals.t, signals.qdd, "", joint_names));
  }
  figure.axes.push_back(SignalAxes("Joint torques", "τ [N m]", signals.t, signals.tau, "t [s]", joint_names));
  return figure;
}

PlotFigure TorqueComparisonPlot(const TorqueSeries& series, const TorquePlotLabels& labels, int max_samples) {
  const Eigen::Index n_kept = series.t.size(), n_dof = series.measured.cols();
  const int k = std::max(1, static_cast<int>((n_kept + max_samples - 1) / max_samples));
  std::vector<double> t;
  for (Eigen::Index i = 0; i < n_kept; i += k) t.push_back(series.t[i]);
  const Eigen::MatrixXd measured = EveryKthRow(series.measured, k), predicted = EveryKthRow(series.predicted, k);
  PlotFigure figure;
  figure.columns = n_dof > 1 ? 2 : 1;
  const Eigen::Index rows = (n_dof + figure.columns - 1) / figure.columns;
  figure.width = 900, figure.height = 220.0 * static_cast<double>(std::max<Eigen::Index>(1, rows));
  for (Eigen::Index j = 0; j < n_dof; ++j) {
    PlotAxes axes;
    axes.title = JointLabel(labels.joint_names, j) + ", " + labels.log;
    axes.y_label = "τ [N m]";
    axes.x_label = "t [s]";
    for (const auto& [label, values] :
         {std::pair{labels.measured.c_str(), &measured}, std::pair{"predicted", &predicted}}) {
      PlotSeries s;
      s.label = label;
      s.x = t;
      s.y.assign(values->col(j).data(), values->col(j).data() + values->rows());
      axes.series.push_back(std::move(s));
    }
    figure.axes.push_back(std::move(axes));
  }
  return figure;
}

PlotFigure ParameterPlot(const std::string& title, const std::string& reference_label,
                         const std::vector<ParameterEstimate>& parameters) {
  PlotAxes axes;
  axes.title = title;
  axes.y_label = "value [SI units]";
  PlotSeries reference{reference_label, {}, {}, {}, PlotSeries::Style::kBars};
  PlotSeries estimate{"identified ± error bar", {}, {}, {}, PlotSeries::Style::kMarkers};
  bool positive = true;
  for (size_t i = 0; i < parameters.size(); ++i) {
    const ParameterEstimate& p = parameters[i];
    axes.categories.push_back(p.name);
    reference.x.push_back(static_cast<double>(i)), reference.y.push_back(p.reference);
    estimate.x.push_back(static_cast<double>(i)), estimate.y.push_back(p.estimate);
    estimate.y_error.push_back(p.error_bar);
    positive &= p.reference > 0.0 && (!std::isfinite(p.estimate) || p.estimate > 0.0);
  }
  axes.log_y = positive && !parameters.empty();
  axes.series = {reference, estimate};
  PlotFigure figure;
  figure.width = std::max(720.0, 18.0 * static_cast<double>(parameters.size()) + 120.0);
  figure.height = 420;
  figure.axes.push_back(axes);
  return figure;
}

std::vector<ParameterEstimate> RunParameterEstimates(const PerBodyIdentificationResult& result) {
  std::vector<ParameterEstimate> out;
  for (const BodyResult& body : result.bodies) {
    for (const ParameterResult& p : body.parameters) {
      out.push_back({body.name + "." + p.name, p.true_value, p.identified, std::abs(p.abs_error)});
    }
  }
  return out;
}

Eigen::VectorXd NormalizedSingularValues(const Eigen::MatrixXd& A) {
  // Columns negligible against the largest (rounding noise of a column that
  // is zero in exact arithmetic) count as zero, as in the identifier.
  Eigen::MatrixXd scaled = A;
  const double largest = A.size() ? A.colwise().norm().maxCoeff() : 0.0;
  for (Eigen::Index c = 0; c < scaled.cols(); ++c) {
    const double norm = scaled.col(c).norm();
    if (norm > 1e-9 * largest) scaled.col(c) /= norm;
    else scaled.col(c).setZero();
  }
  return Eigen::JacobiSVD<Eigen::MatrixXd>(scaled).singularValues();
}

PlotFigure SpectrumPlot(const std::string& title, const std::vector<Spectrum>& spectra) {
  PlotAxes axes;
  axes.title = title;
  axes.x_label = "index (largest first)";
  axes.y_label = "singular value";
  axes.log_y = true;
  // Short spectra as numbered categories (σ1, σ2, …), long ones as lines.
  Eigen::Index longest = 0;
  for (const Spectrum& s : spectra) longest = std::max(longest, s.singular_values.size());
  const bool categories = longest <= 12;
  for (Eigen::Index i = 0; categories && i < longest; ++i) axes.categories.push_back("σ" + std::to_string(i + 1));
  for (const Spectrum& s : spectra) {
    PlotSeries series{s.label, {}, {}, {}, categories ? PlotSeries::Style::kMarkers : PlotSeries::Style::kLine};
    for (Eigen::Index i = 0; i < s.singular_values.size(); ++i) {
      series.x.push_back(static_cast<double>(categories ? i : i + 1));
      series.y.push_back(s.singular_values[i]);
    }
    axes.series.push_back(std::move(series));
  }
  PlotFigure figure;
  figure.height = 380;
  figure.axes.push_back(axes);
  return figure;
}

std::vector<Spectrum> RunEulerSpectra(const RobotModel& model, const SimulationLog& log,
                                      const std::vector<int>& steps) {
  std::vector<Spectrum> spectra;
  for (int body = 0; body < model.n_links(); ++body) {
    Eigen::MatrixXd K(3 * static_cast<Eigen::Index>(steps.size()), 3);
    for (size_t s = 0; s < steps.size(); ++s) {
      K.middleRows<3>(3 * static_cast<Eigen::Index>(s)) =
          ComputePerBodyRows(model, body, log.steps[static_cast<size_t>(steps[s])]).euler_regressor;
    }
    spectra.push_back({model.link(body).name, NormalizedSingularValues(K)});
  }
  return spectra;
}

MotionSummary SummarizeMotion(const std::string& name, const std::vector<Spectrum>& spectra, double max_rel_error) {
  MotionSummary m{name, 0.0, 0.0, max_rel_error};
  for (const Spectrum& s : spectra) {
    // Identifiable directions: singular values above the rank tolerance.
    const double tol = s.singular_values.size() ? 1e-10 * s.singular_values.maxCoeff() : 0.0;
    double smallest = INFINITY;
    for (double sigma : s.singular_values) {
      if (sigma <= tol) continue;
      smallest = std::min(smallest, sigma);
      m.log10_det += 2.0 * std::log10(sigma);
    }
    if (std::isfinite(smallest)) m.cond = std::max(m.cond, s.singular_values.maxCoeff() / smallest);
  }
  return m;
}

PlotFigure MotionComparisonPlot(const std::vector<MotionSummary>& motions, const MotionPlotTitles& titles) {
  PlotFigure figure;
  figure.columns = 3;
  figure.height = 300;
  PlotAxes cond{titles.cond, "", "cond", true, {}, {}};
  PlotAxes det{titles.log_det, "", "log10 det", false, {}, {}};
  PlotAxes error{titles.error, "", "relative error", true, {}, {}};
  PlotSeries c{"", {}, {}, {}, PlotSeries::Style::kBars}, d = c, e = c;
  for (size_t i = 0; i < motions.size(); ++i) {
    for (PlotAxes* axes : {&cond, &det, &error}) axes->categories.push_back(motions[i].name);
    c.x.push_back(double(i)), d.x.push_back(double(i)), e.x.push_back(double(i));
    c.y.push_back(motions[i].cond), d.y.push_back(motions[i].log10_det), e.y.push_back(motions[i].max_rel_error);
  }
  cond.series = {c}, det.series = {d}, error.series = {e};
  figure.axes = {cond, det, error};
  return figure;
}

BoxSummary SummarizeBox(std::vector<double> values) {
  values.erase(std::remove_if(values.begin(), values.end(), [](double v) { return !std::isfinite(v); }),
               values.end());
  BoxSummary box;
  if (values.empty()) {
    const double nan = std::nan("");
    box = {nan, nan, nan, nan, nan, {}};
    return box;
  }
  std::sort(values.begin(), values.end());
  const auto quantile = [&](double p) {
    const double h = (static_cast<double>(values.size()) - 1.0) * p;
    const size_t lo = static_cast<size_t>(std::floor(h));
    const size_t hi = std::min(lo + 1, values.size() - 1);
    return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
  };
  box.q1 = quantile(0.25);
  box.median = quantile(0.5);
  box.q3 = quantile(0.75);
  const double reach = 1.5 * (box.q3 - box.q1);
  box.whisker_low = box.q1;
  box.whisker_high = box.q3;
  for (double v : values) {
    if (v < box.q1 - reach || v > box.q3 + reach) {
      box.outliers.push_back(v);
    } else {
      box.whisker_low = std::min(box.whisker_low, v);
      box.whisker_high = std::max(box.whisker_high, v);
    }
  }
  return box;
}

PlotFigure BenchmarkErrorPlot(const BenchmarkResult& result) {
  // The plot draws lines, markers and bars: a box is a line series' closed
  // outline, its median and whiskers, the boxes apart by NaN.
  constexpr double kHalfWidth = 0.25;
  const double nan = std::nan("");
  PlotFigure figure;
  for (NoisePreset preset : result.presets) {
    PlotAxes axes;
    axes.title = "noise preset " + std::string(kNoisePresetNames.Name(preset));
    axes.y_label = "parameter error";
    axes.log_y = true;
    PlotSeries boxes{"quartiles, median, whiskers (1.5 IQR)", {}, {}, {}, PlotSeries::Style::kLine};
    PlotSeries outliers{"beyond the whiskers", {}, {}, {}, PlotSeries::Style::kMarkers};
    for (size_t e = 0; e < result.estimators.size(); ++e) {
      axes.categories.emplace_back(ToString(result.estimators[e]));
      std::vector<double> errors;
      for (const BenchmarkTrial& trial : result.trials_run) {
        if (trial.preset == preset && !trial.estimates.at(e).diverged) {
          errors.push_back(trial.estimates[e].parameter_error);
        }
      }
      const BoxSummary box = SummarizeBox(errors);
      const double x = static_cast<double>(e), l = x - kHalfWidth, r = x + kHalfWidth;
      const std::vector<std::pair<double, double>> points{
          {l, box.q1}, {r, box.q1}, {r, box.q3}, {l, box.q3}, {l, box.q1}, {nan, nan},           // box
          {l, box.median}, {r, box.median}, {nan, nan},                                           // median
          {x, box.q3}, {x, box.whisker_high}, {nan, nan}, {x, box.q1}, {x, box.whisker_low},       // whiskers
          {nan, nan}, {x - 0.1, box.whisker_high}, {x + 0.1, box.whisker_high}, {nan, nan},
          {x - 0.1, box.whisker_low}, {x + 0.1, box.whisker_low}, {nan, nan}};
      for (const auto& [px, py] : points) {
        boxes.x.push_back(px);
        boxes.y.push_back(py);
      }
      for (double v : box.outliers) {
        outliers.x.push_back(x);
        outliers.y.push_back(v);
      }
    }
    axes.series = {boxes, outliers};
    figure.axes.push_back(std::move(axes));
  }
  figure.columns = static_cast<int>(figure.axes.size());
  figure.width = 360.0 * figure.columns;
  figure.height = 360.0;
  return figure;
}

}  // namespace idbench
