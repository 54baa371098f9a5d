// Fuzzes trajectory files (--trajectory, --held-out, compare): text starting
// with '{' as JSON, any other as CSV, read through the same path as a file
// argument (LoadTrajectoryArg, with its checks of the motion). A trajectory
// or one std::invalid_argument, never a crash, a hang, another exception or
// a leak.
#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>

#include "idbench/engine/puma560.h"
#include "idbench/workbench/formats/trajectory_file.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const idbench::RobotModel robot = idbench::MakePuma560();
  static const std::string base =
      (std::filesystem::temp_directory_path() / ("idbench_trajectory_fuzzer_" + std::to_string(::getpid()))).string();
  const std::string path = base + (size > 0 && data[0] == '{' ? ".json" : ".csv");
  std::ofstream(path, std::ios::binary).write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  try {
    const auto motion = idbench::LoadTrajectoryArg(path, robot, idbench::BuiltinMotionOptions{});
    idbench::JointState state(motion->n_dof());
    motion->Evaluate(0.5 * motion->duration(), &state);
  } catch (const std::invalid_argument&) {
  }
  std::filesystem::remove(path);
  return 0;
}
