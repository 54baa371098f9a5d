// The tables `identify` prints: base parameters with σ, fit and validation.
#include "idbench/workbench/commands/identify_command.h"

#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "number_format.h"

namespace idbench {

namespace {

// The summary's sample count: "2000 samples" when the fit used every sample
// read; otherwise both counts and why they differ, "2000 samples read, 375
// used (qd, qdd from the filtered q; 250 filter-transient samples dropped at
// each end, then one in 4 kept)". A filtered log's derivatives are said
// either way. Of one log (IdentifiedLogPart), or of the report's logs.
std::string SamplesText(Eigen::Index n_samples, Eigen::Index n_samples_read, bool filtered,
                        const std::string& derivatives, const std::optional<ParallelFilter>& parallel_filter,
                        int decimation) {
  std::vector<std::string> why;
  if (filtered) why.push_back(derivatives);
  if (n_samples == n_samples_read) {
    return std::to_string(n_samples) + " samples" + (why.empty() ? "" : " (" + why.front() + ")");
  }
  std::string dropped;
  if (parallel_filter) {
    const ParallelFilter& pf = *parallel_filter;
    decimation = pf.filter.decimation;
    if (const Eigen::Index trim = ParallelFilterTrimSamples(pf.filter, pf.sample_rate_hz); trim > 0) {
      dropped = std::to_string(trim) + " filter-transient samples dropped at each end";
    }
  }
  if (decimation > 1) dropped += (dropped.empty() ? "" : ", then ") + std::string("one in ") + std::to_string(decimation) + " kept";
  if (!dropped.empty()) why.push_back(dropped);
  std::string text = std::to_string(n_samples_read) + " samples read, " + std::to_string(n_samples) + " used";
  for (size_t i = 0; i < why.size(); ++i) text += (i ? "; " : " (") + why[i];
  return why.empty() ? text : text + ")";
}

std::string SamplesText(const IdentifyReport& report) {
  return SamplesText(report.n_samples, report.n_samples_read, report.filtered, report.derivatives,
                     report.parallel_filter, report.prepared ? report.prepared->decimation : 1);
}

// A note per friction or rotor-inertia base parameter (Fv, Fc, Ia of a joint
// or motor: >= 0 in any drive) whose estimate is negative beyond 3 σ, naming
// a negative drive gain of that joint or motor (a current logged with the
// opposite sign turns its torque, and so these terms, around). Empty when
// there is none.
std::string NegativeFrictionNotes(const IdentifyOptions& options, const JointTorqueIdentification& id) {
  std::string out;
  for (int k = 0; k < id.base.n_base(); ++k) {
    const std::string& name = id.base.names[static_cast<size_t>(k)];
    const bool physical_sign = name.rfind("Fv", 0) == 0 || name.rfind("Fc", 0) == 0 || name.rfind("Ia", 0) == 0;
    if (!physical_sign || !(id.beta[k] < -3.0 * id.linear.sigma[k])) continue;
    const bool motor = name.size() > 2 && name[2] == 'm';
    const std::string number = name.substr(motor ? 3 : 2);
    if (number.empty() || number.find_first_not_of("0123456789") != std::string::npos) continue;  // a combination
    const size_t j = std::stoul(number) - 1;
    out += "sign: " + name + " = " + Format("%.4g", id.beta[k]) + " is negative; friction and rotor inertia are >= 0 ";
    const std::vector<double>& gains = options.format.drive_gains;
    if (j < gains.size() && gains[j] < 0.0) {
      out += "(the drive gain of " + std::string(motor ? "motor " : "joint ") + number + " is negative, " +
             Shortest(gains[j]) + " N m/A: if its current is logged with the same sign as its torque, give " +
             Shortest(-gains[j]) + ")\n";
    } else {
      out += "(is the torque of " + std::string(motor ? "motor " : "joint ") + number + " logged with the opposite sign?)\n";
    }
  }
  return out;
}

}  // namespace

std::string SigmaMethodText(const CovarianceSummary& c, const std::string& output) {
  if (c.method == CovarianceMethod::kWhite) return "sigma: as if the residual were white (too few samples for batch means)";
  // The median factor between the two σ: √(n / n_eff).
  const double factor = c.n_effective > 0.0 ? std::sqrt(static_cast<double>(c.n_samples) / c.n_effective) : std::nan("");
  char text[400];
  std::snprintf(text, sizeof(text),
                "sigma: from the residual as it is (coloured, per joint): batch means of the scores over %lld blocks of "
                "%lld samples; n_eff %.4g of %lld samples (sigma as if white, sigma_white in %s: %.3g "
                "times smaller, median)",
                static_cast<long long>(c.n_blocks), static_cast<long long>(c.block_samples), c.n_effective,
                static_cast<long long>(c.n_samples), output.c_str(), factor);
  return text;
}

std::string SigmaMethodText(const LinearFit& fit) { return SigmaMethodText(fit.covariance_method, "identified.json"); }

double RelativeSigmaPercent(double value, double sigma) {
  if (!std::isfinite(value) || !std::isfinite(sigma) || !(std::abs(value) > 3.0 * sigma)) return std::nan("");
  return 100.0 * sigma / std::abs(value);
}

std::string FormatIdentifyTables(const RobotModel& model, const IdentifyOptions& options,
                                 const IdentifyReport& report) {
  const JointTorqueIdentification& id = report.identification;
  std::string out;
  for (const std::string& note : report.notes) out += note + "\n";
  char line[512];
  if (report.parts.empty()) {
    out += "Joint-torque identification of " + model.name() + " from " + options.data + ": " + SamplesText(report) +
           ", " + std::to_string(id.base.n_base()) + " base parameters, estimator " +
           std::string(ToString(options.estimator)) + ", cond(W) = " + Format("%.4g", id.linear.cond) + "\n\n";
  } else {
    // Several logs: a line per log (its samples, its cond(W) alone), then the one fit.
    for (size_t i = 0; i < report.parts.size(); ++i) {
      const IdentifiedLogPart& p = report.parts[i];
      out += "log " + std::to_string(i + 1) + " of " + std::to_string(report.parts.size()) + ", " + p.path + ": " +
             SamplesText(p.n_samples, p.n_samples_read, p.filtered, p.derivatives, p.parallel_filter, p.decimation) +
             ", cond(W) = " + Format("%.4g", p.cond) + " alone\n";
    }
    out += "Joint-torque identification of " + model.name() + " from the " + std::to_string(report.parts.size()) +
           " logs stacked: " + std::to_string(report.n_samples) + " samples used, " +
           std::to_string(id.base.n_base()) + " base parameters, estimator " +
           std::string(ToString(options.estimator)) + ", cond(W) = " + Format("%.4g", id.linear.cond) + "\n\n";
  }
  std::snprintf(line, sizeof(line), "%4s  %14s  %14s  %11s  %8s  %-10s  %s\n", "#", "robot file", "identified", "sigma",
                "%sigma", "status", "base parameter");
  out += line;
  for (int k = 0; k < id.base.n_base(); ++k) {
    const ParameterStatus status = ClassifyParameter(id.beta[k], id.linear.sigma[k]);
    const char* name = id.base.names[static_cast<size_t>(k)].c_str();
    if (status == ParameterStatus::kNotIdentifiable) {
      std::snprintf(line, sizeof(line), "%4d  %14.6g  %14s  %11s  %8s  %-10s  %s\n", k + 1, id.beta_model[k], "-", "-",
                    "-", "not ident.", name);
    } else {
      std::snprintf(line, sizeof(line), "%4d  %14.6g  %14.6g  %11.3g  %8s  %-10s  %s\n", k + 1, id.beta_model[k],
                    id.beta[k], id.linear.sigma[k], Format("%.3g", RelativeSigmaPercent(id.beta[k], id.linear.sigma[k])).c_str(),
                    status == ParameterStatus::kIndistinguishableFromZero ? "~0" : ToString(status), name);
    }
    out += line;
  }
  out += "status: determined = sigma <= 10 % of the value; ~0 = |value| <= 3 sigma, indistinguishable from zero "
         "(%sigma '-': sigma itself is what is known)\n";
  out += NegativeFrictionNotes(options, id);
  if (report.closed_loop) {
    out += "estimator " + std::string(ToString(options.estimator)) + ": " + report.closed_loop->message +
           "; at its last iteration, " + SigmaMethodText(id.linear) + "\n";
  } else {
    out += SigmaMethodText(id.linear) + "\n";
    if (options.estimator == TorqueEstimator::kTls || options.estimator == TorqueEstimator::kIrls) {
      out += "estimator " + std::string(ToString(options.estimator)) + ": " + id.linear.solve.message + "\n";
    }
  }
  if (options.estimator == TorqueEstimator::kPhysicallyConsistent) {
    out += "sigma: of the least-squares estimate (the physically consistent one has no covariance of its own); "
           "%sigma: relative to the value shown\n";
  }
  if (id.linear.rank < id.base.n_base()) {
    const int n = id.base.n_base();
    const int missing = static_cast<int>(std::count(id.linear.identifiable.begin(), id.linear.identifiable.end(), false));
    std::snprintf(line, sizeof(line), "This log does not determine every base parameter: W has rank %d of %d (the "
                  "motion does not excite %d combinations); the %d parameters marked 'not ident.' take part in them "
                  "and get no value. The physically consistent fit keeps the robot file's values in those "
                  "directions.\n", id.linear.rank, n, n - id.linear.rank, missing);
    out += line;
  }
  auto joint_row = [&](const char* label, const Eigen::VectorXd& v) {
    out += label;
    for (int j = 0; j < v.size(); ++j) {
      std::snprintf(line, sizeof(line), "  %10.4g", v[j]);
      out += line;
    }
    out += '\n';
  };
  out += "\nTorque RMS per joint [N m]\n";
  joint_row("  fit       ", report.identification.fit.joint_rms);
  if (report.validation) joint_row("  validation", report.validation->joint_rms);
  std::string validation;
  if (report.validation) validation = ", validation " + Format("%.4g", report.validation->relative_error);
  if (report.validation_whole_file) {
    validation += " (validate_window " + Shortest(options.validate_window[0]) + "–" +
                  Shortest(options.validate_window[1]) + " s; whole file " +
                  Format("%.4g", report.validation_whole_file->relative_error) + ")";
  }
  std::snprintf(line, sizeof(line), "Relative torque error: fit %.4g%s\n", report.identification.fit.relative_error,
                validation.c_str());
  out += line;
  const PhysicallyConsistentFit& pc = id.consistent;
  std::snprintf(line, sizeof(line), "Physically consistent fit (SDP): cost %.6g vs OLS %.6g (the unconstrained "
                "optimum; +%.3g %%) and robot file %.6g; prior term %.3g; min pseudo-inertia eigenvalue %.3g; %s\n",
                pc.cost, pc.ols_cost, 100.0 * (pc.cost - pc.ols_cost) / pc.ols_cost, pc.start_cost, pc.prior_cost,
                pc.min_pseudo_inertia_eigenvalue.minCoeff(), pc.status.c_str());
  out += line;
  if (!pc.active_bounds.empty()) {
    out += "  on its bounds:";
    for (size_t k = 0; k < pc.active_bounds.size(); ++k) out += (k ? "; " : " ") + pc.active_bounds[k];
    out += '\n';
  }
  const PlausibleFitOptions bounds = MakePlausibleFitOptions(model, options.friction_model(), options.plausibility);
  for (int l = 0; l < model.n_links(); ++l) {
    const double outside = bounds.links[static_cast<size_t>(l)].com_outside_geometry;
    if (outside > 0.0) {
      out += "  no centre-of-mass bound on link '" + model.link(l).name + "': the file's centre of mass lies " +
             Format("%.3g", outside) + " m outside the box around its shapes\n";
    }
  }
  out += "Verdict: " + id.verdict.message + "\n";  // why, when refused: the command's one message
  return out;
}

}  // namespace idbench
