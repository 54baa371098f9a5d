#include "idbench/ident/per_body_identifier.h"

#include "idbench/engine/simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "idbench/engine/paper6r.h"
#include "idbench/excitation/builtin_motions.h"

namespace idbench {
namespace {

std::vector<int> Steps(const SimulationLog& log, std::initializer_list<double> times) {
  std::vector<int> steps;
  for (double t : times) steps.push_back(log.StepAt(t));
  return steps;
}

const ParameterResult& Param(const PerBodyIdentificationResult& r, int body, const std::string& name) {
  for (const ParameterResult& p : r.bodies[static_cast<size_t>(body)].parameters) {
    if (p.name == name) return p;
  }
  throw std::runtime_error("no parameter " + name);
}

void ExpectIdentifiedWithinTolerance(const PerBodyIdentificationResult& r, double tol) {
  for (const BodyResult& body : r.bodies) {
    for (const ParameterResult& p : body.parameters) {
      if (!p.identifiable) continue;
      EXPECT_LT(p.rel_error, tol) << body.name << "." << p.name;
    }
  }
  EXPECT_LT(r.max_rel_error, tol);
}

void ExpectB1Unidentifiable(const PerBodyIdentificationResult& r) {
  for (const char* name : {"m_e1", "m_e2", "J22", "J33"}) {
    const ParameterResult& p = Param(r, 0, name);
    EXPECT_FALSE(p.identifiable) << name;
    EXPECT_TRUE(std::isnan(p.identified)) << name;
    EXPECT_FALSE(p.reason.empty()) << name;
  }
  for (const char* name : {"m_e3", "m", "J11"}) EXPECT_TRUE(Param(r, 0, name).identifiable) << name;
}

class PerBodyIdentifierTest : public ::testing::Test {
 protected:
  RobotModel model_ = MakePaper6r();
};

TEST_F(PerBodyIdentifierTest, PaperExperimentRecoversTable1) {
  const auto motion = MakePaperMotion(6, 30.0 * std::numbers::pi / 180.0, 2.0);
  const SimulationLog log = Simulate(model_, *motion, SimulationOptions{});
  const PerBodyIdentificationResult r = IdentifyPerBody(model_, log, Steps(log, {0.3, 0.6, 0.9, 1.2, 1.5}));
  EXPECT_EQ(r.n_samples, 5);
  ExpectIdentifiedWithinTolerance(r, 1e-9);
  ExpectB1Unidentifiable(r);
  // Under the paper's motion (hinges 1, 2 only) B2..B6 identify all seven.
  for (int b = 1; b < 6; ++b) {
    for (const ParameterResult& p : r.bodies[static_cast<size_t>(b)].parameters) {
      EXPECT_TRUE(p.identifiable) << r.bodies[static_cast<size_t>(b)].name << "." << p.name << ": " << p.reason;
    }
  }
}

TEST_F(PerBodyIdentifierTest, GeneralMotionRecoversTable1) {
  const auto motion = MakeGeneralMotion(6, 2.0);
  const SimulationLog log = Simulate(model_, *motion, SimulationOptions{});
  const PerBodyIdentificationResult r = IdentifyPerBody(model_, log, Steps(log, {0.3, 0.6, 0.9, 1.2, 1.5}));
  ExpectIdentifiedWithinTolerance(r, 1e-9);
  ExpectB1Unidentifiable(r);
}

TEST_F(PerBodyIdentifierTest, AtRestOnlyGravityIsSeen) {
  // A single sample at t = 0 (from rest): no centripetal terms. B1 and B2
  // have their centroids on hinge 1's axis, and hinge 2 (about y) moves
  // them only along x, so nothing acts along e2 for them; B3..B6 get the
  // tangential acceleration of hinge 1 along e2.
  const auto motion = MakePaperMotion(6, 0.5, 2.0);
  const SimulationLog log = Simulate(model_, *motion, SimulationOptions{});
  const PerBodyIdentificationResult r = IdentifyPerBody(model_, log, {0});
  for (int b = 0; b < 6; ++b) {
    EXPECT_EQ(Param(r, b, "m_e2").identifiable, b >= 2) << "B" << b + 1;
    EXPECT_TRUE(Param(r, b, "m_e3").identifiable);
  }
  EXPECT_TRUE(Param(r, 0, "J11").identifiable);  // B1 spins about its own axis
}

TEST_F(PerBodyIdentifierTest, RejectsBadSamples) {
  const auto motion = MakePaperMotion(6, 0.5, 0.1);
  SimulationOptions options;
  options.duration = 0.1;
  const SimulationLog log = Simulate(model_, *motion, options);
  EXPECT_THROW(IdentifyPerBody(model_, log, {}), std::invalid_argument);
  EXPECT_THROW(IdentifyPerBody(model_, log, {100}), std::invalid_argument);
}

}  // namespace
}  // namespace idbench
