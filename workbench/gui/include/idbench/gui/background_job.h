// One piece of work on its own thread, so that the window never waits for it:
// the work computes, then hands back what to apply to the session, which the
// UI thread runs when it collects the job (results never touch the session
// from the worker). A job can be asked to stop; the work decides how.
#pragma once

#include <atomic>
#include <functional>
#include <mutex>
#include <string>
#include <thread>

namespace idbench::gui {

class BackgroundJob {
 public:
  // Runs on the worker thread; returns what the UI thread applies. A thrown
  // exception's what() becomes the job's error.
  using Work = std::function<std::function<void()>(const std::atomic<bool>& stop)>;

  BackgroundJob() = default;
  ~BackgroundJob();  // asks the work to stop and waits for it
  BackgroundJob(const BackgroundJob&) = delete;
  BackgroundJob& operator=(const BackgroundJob&) = delete;

  // Starts the work unless a job is already running (then returns false).
  bool Start(Work work);
  // Sets the stop flag the work sees.
  void RequestStop() { stop_ = true; }
  // Started and not yet collected.
  bool running() const { return thread_.joinable(); }

  // On the UI thread: when the work has finished, joins it and returns true
  // once, with *apply (success) or *error (the exception's message) set.
  bool Collect(std::function<void()>* apply, std::string* error);
  // Blocks until the work has finished (for shutdown and tests), then Collect.
  bool Wait(std::function<void()>* apply, std::string* error);

 private:
  std::thread thread_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  std::mutex mutex_;            // guards apply_, error_
  std::function<void()> apply_;
  std::string error_;
};

}  // namespace idbench::gui
