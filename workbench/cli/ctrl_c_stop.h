// Ctrl-C during a long run (design, identify): while a CtrlCStop lives,
// SIGINT sets the stop flag the library watches (DesignControl,
// IdentifyControl) instead of ending the process; once it is destroyed,
// SIGINT ends the process again.
#pragma once

#include <atomic>

namespace idbench::cli {

class CtrlCStop {
 public:
  CtrlCStop();
  ~CtrlCStop();
  CtrlCStop(const CtrlCStop&) = delete;
  CtrlCStop& operator=(const CtrlCStop&) = delete;

  // Set once Ctrl-C was pressed.
  const std::atomic<bool>* flag() const;
};

}  // namespace idbench::cli
