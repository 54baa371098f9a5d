#include "log_reading_flags.h"

#include "common_flags.h"

namespace idbench::cli {

void AddDriveGainsFlag(CLI::App* command, JointLogFormat* format) {
  command->add_option("--drive-gains", format->drive_gains,
                      "Drive gains K1,...,Kn [N m/A]: tau = K*i from the current columns i1..in")->delimiter(',');
}

void AddFilterFlags(CLI::App* command, LogFilterOptions* filter) {
  command->add_option("--filter-cutoff", filter->cutoff_hz, "Butterworth cutoff for logs without qd/qdd [Hz]")
      ->capture_default_str();
  command->add_option("--filter-order", filter->order, "Butterworth order")->capture_default_str();
}

void AddLogReadingFlags(CLI::App* command, JointLogFormat* format, std::vector<std::string>* friction,
                        CoulombFields coulomb, LogFilterOptions* filter, double* max_gap_s) {
  // Split here, not by CLI11 (which drops empty items: `t,q1,,q3` would read
  // as t,q1,q3 and blame a missing q2); an empty item is then named.
  command->add_option_function<std::string>("--columns", [format](const std::string& list) {
        format->columns.clear();
        size_t start = 0;
        for (size_t comma = list.find(','); ; comma = list.find(',', start)) {
          format->columns.push_back(list.substr(start, comma == std::string::npos ? comma : comma - start));
          if (comma == std::string::npos) break;
          start = comma + 1;
        }
      },
                      "Column names in file order: t,q1..q6,qd1..qd6,i1..i6,_ ... (with a header of idbench's names: agree with "
                      "it, or name a subset, matched by name; other header names are renamed in order)")
      ->type_name("NAMES");
  command->add_option("--topic", format->topic,
                      "For a ROS 2 bag: the sensor_msgs/msg/JointState topic to read (default: the bag's only one)")
      ->type_name("TOPIC");
  command->add_option("--angle-unit", format->angle_unit, "Unit of q, qd, qdd in the logs: rad or deg")
      ->capture_default_str();
  command->add_flag("--torque-held", format->torque_held,
                    "The logged torques (or currents) are commands held to the next sample (zero-order hold): each "
                    "is read as the mean of its hold and the previous one's");
  if (friction) {
    AddFrictionFlag(command, friction, "Friction terms: none or viscous,coulomb,offset,rotor");
    command->add_option("--coulomb-smoothing", *coulomb.smoothing,
                        "Coulomb tanh(qd/v) transition velocity v [rad/s]; 0 = sign")->capture_default_str();
    command->add_option("--coulomb-min-speed", *coulomb.min_speed,
                        "Speed below which a sample's Coulomb column is 0 [rad/s]: Fc from moving samples only; 0 = off")
        ->capture_default_str();
  }
  AddFilterFlags(command, filter);
  command->add_option("--max-gap", *max_gap_s, "Longest time step resampled [s]; 0 = 10 median steps")
      ->capture_default_str();
}

}  // namespace idbench::cli
