#include "idbench/logs/simulation_log_csv.h"

#include "number_format.h"

namespace idbench {
namespace {

void Append(std::string* out, double value) {
  AppendShortest(out, value);
  out->push_back(',');
}

template <typename Vec>
void AppendAll(std::string* out, const Vec& v) {
  for (int k = 0; k < v.size(); ++k) Append(out, v[k]);
}

}  // namespace

std::string FormatLogCsv(const RobotModel& model, const SimulationLog& log) {
  const int n = model.n_dof();
  std::string out = "t";
  for (const char* prefix : {"q", "qd", "qdd", "tau"})
    for (int j = 1; j <= n; ++j) out += "," + std::string(prefix) + std::to_string(j);
  for (int i = 0; i < n; ++i) {
    const std::string b = "," + model.link(i).name + "_";
    for (const char* q : {"lambda", "lambda_d", "lambda_dd"})
      for (int k = 0; k < 4; ++k) out += b + q + std::to_string(k);
    for (const char* v : {"w", "wd", "a"})
      for (int k = 1; k <= 3; ++k) out += b + v + std::to_string(k);
  }
  for (int i = 0; i < n; ++i) {
    const std::string h = "," + model.link(i).joint_name + "_";
    for (const char* v : {"F", "M"})
      for (int k = 1; k <= 3; ++k) out += h + v + std::to_string(k);
  }
  out += '\n';
  out.reserve(out.size() * (log.steps.size() + 1) * 3);

  for (const LogStep& step : log.steps) {
    Append(&out, step.t);
    AppendAll(&out, step.q);
    AppendAll(&out, step.qd);
    AppendAll(&out, step.qdd);
    AppendAll(&out, step.tau);
    for (const BodySample& body : step.body) {
      AppendAll(&out, body.quaternion.lambda);
      AppendAll(&out, body.quaternion.lambda_d);
      AppendAll(&out, body.quaternion.lambda_dd);
      AppendAll(&out, body.w_B);
      AppendAll(&out, body.wd_B);
      AppendAll(&out, body.a_WBcm_W);
    }
    for (const HingeWrench& hinge : step.hinge) {
      AppendAll(&out, hinge.f_W);
      AppendAll(&out, hinge.m_Bo_W);
    }
    out.back() = '\n';
  }
  return out;
}

}  // namespace idbench
