#include "idbench/gui/background_job.h"

#include <exception>

namespace idbench::gui {

BackgroundJob::~BackgroundJob() {
  stop_ = true;
  if (thread_.joinable()) thread_.join();
}

bool BackgroundJob::Start(Work work) {
  if (thread_.joinable()) return false;
  stop_ = false;
  finished_ = false;
  apply_ = nullptr;
  error_.clear();
  thread_ = std::thread([this, work = std::move(work)] {
    std::function<void()> apply;
    std::string error;
    try {
      apply = work(stop_);
    } catch (const std::exception& e) {
      error = e.what();
      if (error.empty()) error = "failed";
    } catch (...) {
      error = "failed with an unknown exception";
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      apply_ = std::move(apply);
      error_ = std::move(error);
    }
    finished_ = true;
  });
  return true;
}

bool BackgroundJob::Collect(std::function<void()>* apply, std::string* error) {
  if (!thread_.joinable() || !finished_) return false;
  thread_.join();
  const std::lock_guard<std::mutex> lock(mutex_);
  *apply = std::move(apply_);
  *error = std::move(error_);
  apply_ = nullptr;
  error_.clear();
  return true;
}

bool BackgroundJob::Wait(std::function<void()>* apply, std::string* error) {
  if (!thread_.joinable()) return false;
  thread_.join();
  const std::lock_guard<std::mutex> lock(mutex_);
  *apply = std::move(apply_);
  *error = std::move(error_);
  apply_ = nullptr;
  error_.clear();
  return true;
}

}  // namespace idbench::gui
