// The step log as CSV, one row per simulation step, header-named columns:
//   t, q1..qn, qd1..qdn, qdd1..qddn, tau1..taun,
//   per body Bi: Bi_lambda0..3, Bi_lambda_d0..3, Bi_lambda_dd0..3 (Λ, Λ', Λ''),
//     Bi_w1..3, Bi_wd1..3 (ω, ω̇ in body axes), Bi_a1..3 (centroid acceleration, world),
//   per hinge Ok: Ok_F1..3, Ok_M1..3 (force, and moment about the hinge point,
//     from the inboard onto the outboard body, world axes).
// Units: SI (s, rad, N, m). Numbers are shortest round-trip decimals.
#pragma once

#include <string>

#include "idbench/engine/robot_model.h"
#include "idbench/engine/simulation.h"

namespace idbench {

std::string FormatLogCsv(const RobotModel& model, const SimulationLog& log);

}  // namespace idbench
