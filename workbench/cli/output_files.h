// The files a command writes into its output directory (--out), gathered and
// then written together, as run, compare and design end: the directory
// created first, the command's own files, the report's when --report asked,
// all written atomically as one set, then the "wrote ..." line on stdout.
//
//   OutputFiles out(options.out_dir);
//   out.Add("compare.json", FormatCompareJson(options, report));
//   if (with_report) out.AddReport(MakeCompareReportContent(options, report));
//   out.Write("wrote " + out.Path("compare.json").string() + " and compare.csv");
#pragma once

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "idbench/workbench/reports/report_command.h"

namespace idbench::cli {

class OutputFiles {
 public:
  // Creates `dir` (and parents) when missing; throws std::runtime_error naming
  // it when it cannot be (EnsureOutputDirectory).
  explicit OutputFiles(std::filesystem::path dir);

  const std::filesystem::path& dir() const { return dir_; }
  // dir/name.
  std::filesystem::path Path(const std::string& name) const { return dir_ / name; }

  // A file `name` in the directory, written by Write.
  void Add(const std::string& name, std::string content);
  // report.html, report.pdf and the plots (FormatReportFiles).
  void AddReport(const ReportContent& content);

  // Writes every file added as one set (WriteFilesAtomically); then, when
  // `wrote` is not empty, prints it as a line on stdout.
  void Write(const std::string& wrote = "") const;

 private:
  std::filesystem::path dir_;
  std::vector<std::pair<std::filesystem::path, std::string>> files_;
};

}  // namespace idbench::cli
