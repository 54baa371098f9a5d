// Helpers shared by the URDF tests (tests/engine/urdf_*_test.cc, rpy_test.cc,
// mesh_uri_test.cc): comparisons, hand-written rotations and URDF pieces,
// and expectations on what a load refuses.
#pragma once

#include <gtest/gtest.h>

#include <Eigen/Core>
#include <cmath>
#include <limits>
#include <map>
#include <numbers>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "idbench/engine/urdf.h"

namespace idbench::urdf_testing {

constexpr double kPi = std::numbers::pi;
constexpr double kInf = std::numeric_limits<double>::infinity();

// ---- Comparison helpers ----

// max |actual − expected| ≤ tol · max |expected| (exact match for zero).
template <typename A, typename B>
inline void ExpectNear(const A& actual, const B& expected, double tol, const std::string& what) {
  const double scale = expected.cwiseAbs().maxCoeff();
  EXPECT_LE((actual - expected).cwiseAbs().maxCoeff(), tol * scale)
      << what << "\nactual:\n" << actual << "\nexpected:\n" << expected;
}

// Relative comparison; infinities must match exactly.
inline void ExpectNear(double actual, double expected, double tol, const std::string& what) {
  if (std::isinf(expected)) {
    EXPECT_EQ(actual, expected) << what;
  } else {
    EXPECT_NEAR(actual, expected, tol * std::abs(expected)) << what;
  }
}

// Everything URDF can express: names, tree, joint frames, axes, limits
// (except qdd_max), friction (not rotor inertia), mass properties, shapes.
inline void ExpectModelsNear(const RobotModel& actual, const RobotModel& expected, double tol,
                      bool compare_joint_names = true) {
  EXPECT_EQ(actual.name(), expected.name());
  ASSERT_EQ(actual.n_links(), expected.n_links());
  for (int i = 0; i < expected.n_links(); ++i) {
    const Link& a = actual.link(i);
    const Link& e = expected.link(i);
    const std::string where = "link " + e.name + ": ";
    EXPECT_EQ(a.name, e.name);
    if (compare_joint_names) {
      EXPECT_EQ(a.joint_name, e.joint_name) << where;
    }
    EXPECT_EQ(a.parent, e.parent) << where;
    ExpectNear(a.X_PJ.linear(), e.X_PJ.linear(), tol, where + "R_PJ");
    if (e.X_PJ.translation().isZero(0.0)) {
      EXPECT_TRUE(a.X_PJ.translation().isZero(0.0)) << where << a.X_PJ.translation().transpose();
    } else {
      ExpectNear(a.X_PJ.translation(), e.X_PJ.translation(), tol, where + "p_PJ");
    }
    ExpectNear(a.axis_J, e.axis_J, tol, where + "axis_J");
    ExpectNear(a.limits.q_min, e.limits.q_min, tol, where + "q_min");
    ExpectNear(a.limits.q_max, e.limits.q_max, tol, where + "q_max");
    ExpectNear(a.limits.qd_max, e.limits.qd_max, tol, where + "qd_max");
    ExpectNear(a.limits.tau_max, e.limits.tau_max, tol, where + "tau_max");
    EXPECT_EQ(a.limits.qdd_max, kInf) << where;
    ExpectNear(a.dynamics.viscous, e.dynamics.viscous, tol, where + "viscous");
    ExpectNear(a.dynamics.coulomb, e.dynamics.coulomb, tol, where + "coulomb");
    ExpectNear(a.inertia.mass, e.inertia.mass, tol, where + "mass");
    ExpectNear(a.inertia.p_BoBcm_B, e.inertia.p_BoBcm_B, tol, where + "p_BoBcm_B");
    ExpectNear(a.inertia.I_Bcm_B, e.inertia.I_Bcm_B, tol, where + "I_Bcm_B");
    ASSERT_EQ(a.shapes.size(), e.shapes.size()) << where;
    for (size_t k = 0; k < e.shapes.size(); ++k) {
      const std::string shape = where + "shape " + std::to_string(k) + " ";
      EXPECT_EQ(a.shapes[k].kind, e.shapes[k].kind) << shape;
      ExpectNear(a.shapes[k].size, e.shapes[k].size, tol, shape + "size");
      ExpectNear(a.shapes[k].X_BG.linear(), e.shapes[k].X_BG.linear(), tol, shape + "R_BG");
      ExpectNear(a.shapes[k].X_BG.translation(), e.shapes[k].X_BG.translation(), tol, shape + "p_BG");
    }
  }
}

// Elementary rotations written out by hand, independent of Eigen::AngleAxis.
inline Eigen::Matrix3d Rx(double a) {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a);
  return R;
}
inline Eigen::Matrix3d Ry(double a) {
  Eigen::Matrix3d R;
  R << std::cos(a), 0, std::sin(a), 0, 1, 0, -std::sin(a), 0, std::cos(a);
  return R;
}
inline Eigen::Matrix3d Rz(double a) {
  Eigen::Matrix3d R;
  R << std::cos(a), -std::sin(a), 0, std::sin(a), std::cos(a), 0, 0, 0, 1;
  return R;
}

// ---- Hand-written URDF pieces ----

// The warnings other than the geometry check's (a centre of mass outside its
// link's shapes): for fixtures whose shapes are placed freely.
inline std::vector<std::string> WithoutGeometryWarnings(const std::vector<std::string>& warnings) {
  std::vector<std::string> out;
  for (const std::string& w : warnings)
    if (w.find("outside the box around its shapes") == std::string::npos) out.push_back(w);
  return out;
}

inline std::string Robot(const std::string& body) { return "<robot name=\"r\">\n" + body + "</robot>\n"; }

inline std::string BareLink(const std::string& name) { return "<link name=\"" + name + "\"/>\n"; }

// A link with one inertial: the given mass and inertia (ixx ixy ixz iyy iyz izz).
inline std::string MassLink(const std::string& name, const std::string& mass = "1",
                     const std::string& inertia = "0.1 0 0 0.1 0 0.1") {
  std::istringstream in(inertia);
  std::string v[6];
  for (std::string& s : v) in >> s;
  return "<link name=\"" + name + "\"><inertial><mass value=\"" + mass + "\"/><inertia ixx=\"" + v[0] +
         "\" ixy=\"" + v[1] + "\" ixz=\"" + v[2] + "\" iyy=\"" + v[3] + "\" iyz=\"" + v[4] + "\" izz=\"" +
         v[5] + "\"/></inertial></link>\n";
}

inline const std::string kLimit = "<limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"2\"/>";

inline std::string Joint(const std::string& name, const std::string& type, const std::string& parent,
                  const std::string& child, const std::string& extra = kLimit) {
  return "<joint name=\"" + name + "\" type=\"" + type + "\"><parent link=\"" + parent +
         "\"/><child link=\"" + child + "\"/>" + extra + "</joint>\n";
}

inline UrdfLoadOptions Options(std::map<std::string, double> locked_joints, std::string tip_link = "") {
  UrdfLoadOptions options;
  options.locked_joints = std::move(locked_joints);
  options.tip_link = std::move(tip_link);
  return options;
}

// Loading `xml` must throw std::invalid_argument whose message contains
// every one of `fragments`.
inline void ExpectRejected(const std::string& xml, const std::vector<std::string>& fragments,
                    const std::string& source = "<string>") {
  try {
    LoadUrdfString(xml, source);
    ADD_FAILURE() << "expected std::invalid_argument for:\n" << xml;
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(source + ":", 0), 0u) << message;  // "SOURCE: " or "SOURCE:LINE: "
    for (const std::string& fragment : fragments) {
      EXPECT_NE(message.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << message;
    }
  }
}

inline void ExpectContains(const std::string& text, const std::vector<std::string>& fragments) {
  for (const std::string& fragment : fragments) {
    EXPECT_NE(text.find(fragment), std::string::npos) << "'" << fragment << "' not in: " << text;
  }
}

// Loading with `options` must throw std::invalid_argument whose message
// contains every fragment.
inline void ExpectRejectedWith(const std::string& xml, const UrdfLoadOptions& options,
                        const std::vector<std::string>& fragments) {
  try {
    LoadUrdfString(xml, "vendor.urdf", "", options);
    ADD_FAILURE() << "expected std::invalid_argument";
  } catch (const std::invalid_argument& e) {
    EXPECT_EQ(std::string(e.what()).rfind("vendor.urdf: ", 0), 0u) << e.what();
    ExpectContains(e.what(), fragments);
  }
}

}  // namespace idbench::urdf_testing
