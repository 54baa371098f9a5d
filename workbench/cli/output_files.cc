#include "output_files.h"

#include <cstdio>

#include "idbench/workbench/formats/atomic_file.h"

namespace idbench::cli {

OutputFiles::OutputFiles(std::filesystem::path dir) : dir_(std::move(dir)) { EnsureOutputDirectory(dir_); }

void OutputFiles::Add(const std::string& name, std::string content) {
  files_.emplace_back(dir_ / name, std::move(content));
}

void OutputFiles::AddReport(const ReportContent& content) {
  for (auto& file : FormatReportFiles(content, dir_)) files_.push_back(std::move(file));
}

void OutputFiles::Write(const std::string& wrote) const {
  WriteFilesAtomically(files_);
  if (!wrote.empty()) std::printf("%s\n", wrote.c_str());
}

}  // namespace idbench::cli
