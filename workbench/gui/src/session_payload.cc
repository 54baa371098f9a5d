// The session's payload job (`idbench payload`'s library call on
// Session::payload) and its export, as the command line writes the files.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>

#include "idbench/engine/robot_library.h"
#include "idbench/gui/session.h"
#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::gui {

void Session::StartPayload() {
  // The logs are read as the Log tab reads them (columns, angle unit, drive
  // gains) on the session's one mounting (the Design tab's base pose): one
  // table of log-reading options, as the command line's flags are one.
  PayloadOptions options = payload;
  options.format = identify.format;
  options.base_pose = design.design.base_pose;
  std::string why;
  if (!options.IsValid(&why)) return Error("payload: " + why);
  StartJob(JobKind::kPayload, [this, options](const std::atomic<bool>&) {
    // The identified robot is the payload's own (not the session's robot),
    // mounted as payload's command line mounts it.
    UrdfLoadResult loaded = idbench::LoadRobot(options.robot);
    auto model = std::make_shared<const RobotModel>(MountRobot(loaded.model, options.base_pose));
    std::string problem;
    if (!options.IsValidFor(*model, &problem)) throw std::invalid_argument(problem);
    auto summary = std::make_shared<PayloadSummary>(RunPayload(*model, options));
    return std::function<void()>([this, options, model, summary] {
      payload_summary_ = std::move(*summary);
      payload_estimated_with_ = options;
      payload_model_ = model;
      for (const std::string& w : payload_summary_->warnings) Info("warning: " + w);
      Info("payload: " + payload_summary_->BriefReport());
      if (!payload_summary_->good()) Error("payload: " + std::string(PayloadStatusName(payload_summary_->status)) +
                                           ": " + payload_summary_->message);
    });
  });
}

bool Session::ExportPayload() {
  if (!payload_summary_) {
    Error("export: no payload estimated yet");
    return false;
  }
  // Into the folder the tab shows now; the rest as estimated.
  PayloadOptions options = payload_estimated_with_;
  options.out_dir = payload.out_dir;
  std::string why;
  if (!IsUsableOutputDirectory(options.out_dir, "out_dir", &why)) {
    Error("export: payload: " + why);
    return false;
  }
  try {
    EnsureOutputDirectory(options.out_dir);
    const auto files = PayloadFiles(*payload_model_, options, *payload_summary_);
    WriteFilesAtomically(files);
    for (const auto& [path, text] : files) Info("exported " + path.string());
  } catch (const std::exception& e) {
    Error(std::string("export: payload: ") + e.what());
    return false;
  }
  if (!WritesPayloadUrdf(options, *payload_summary_)) {
    Error("export: payload.urdf.xml not written: " + std::string(PayloadStatusName(payload_summary_->status)) +
          (payload_summary_->message.empty() ? "" : ": " + payload_summary_->message));
    return false;
  }
  return true;
}

std::vector<PayloadRow> Session::PayloadRows() const {
  std::vector<PayloadRow> rows;
  if (!payload_summary_) return rows;
  const PayloadEstimate& e = payload_summary_->estimate;
  const Eigen::Matrix<double, 10, 1> quantities = PayloadQuantities(e.body);
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 10; ++k) {
    PayloadRow row;
    row.name = PayloadQuantityNames()[static_cast<size_t>(k)];
    row.unit = k == 0 ? "kg" : k < 4 ? "m" : "kg m2";
    // A quantity the motion does not determine has no number, only why.
    if (!e.identifiable[static_cast<size_t>(k)]) {
      row.value = row.sigma = kNaN;
      row.value_text = row.status = "not identifiable";
      row.sigma_text = "-";
      row.reason = e.not_identifiable_reason[static_cast<size_t>(k)];
      rows.push_back(row);
      continue;
    }
    row.value = quantities[k];
    row.sigma = e.sigma[k];
    char text[64];
    std::snprintf(text, sizeof text, "%.6g", row.value);
    row.value_text = text;
    std::snprintf(text, sizeof text, "%.3g", row.sigma);
    row.sigma_text = text;
    // The verdict's bound on this quantity's σ (payload_estimator.h).
    const double bound = payload_estimated_with_.max_relative_sigma * PayloadQuantityScale(e.body, k);
    // (Not judged where the scale needs a quantity the motion does not determine.)
    row.status = !std::isfinite(bound) || row.sigma <= bound ? "determined" : "poorly determined";
    rows.push_back(row);
  }
  return rows;
}

}  // namespace idbench::gui
