#include "ctrl_c_stop.h"

#include <csignal>

namespace idbench::cli {
namespace {

std::atomic<bool> g_stop_requested{false};
extern "C" void RequestStop(int) { g_stop_requested = true; }

}  // namespace

CtrlCStop::CtrlCStop() {
  g_stop_requested = false;
  std::signal(SIGINT, RequestStop);
}

CtrlCStop::~CtrlCStop() { std::signal(SIGINT, SIG_DFL); }

const std::atomic<bool>* CtrlCStop::flag() const { return &g_stop_requested; }

}  // namespace idbench::cli
