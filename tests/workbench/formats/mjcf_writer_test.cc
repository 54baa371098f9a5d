// WriteMjcf against MuJoCo itself: the file loads with mj_loadXML, and
// mj_inverse's joint torques (constraints off, so no frictionloss, limits or
// contacts) equal idbench's RNEA plus rotor inertia and viscous friction at
// random states, for the built-in robots with random drive values (links
// whose moments break the triangle inequality as balanceinertia makes them), under a
// tilted gravity, and for the KUKA LWR4+ URDF with its STL meshes (from
// ../shared, skipped when absent).
#include "idbench/workbench/formats/mjcf_writer.h"

#include <gtest/gtest.h>
#include <mujoco/mujoco.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <random>

#include "idbench/engine/inverse_dynamics.h"
#include "idbench/engine/robot_library.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;

const fs::path kKukaUrdf =
    fs::path(IDBENCH_SOURCE_DIR) / ".." / "shared" / "data" / "kuka_lwr4" / "lwr_description" / "urdf" / "kuka_lwr4.urdf";

struct MjModelDeleter {
  void operator()(mjModel* m) const { mj_deleteModel(m); }
};
struct MjDataDeleter {
  void operator()(mjData* d) const { mj_deleteData(d); }
};

// The MJCF loaded by MuJoCo (from a file, as a user loads it); fails the test with MuJoCo's message.
std::unique_ptr<mjModel, MjModelDeleter> LoadInMujoco(const std::string& xml, const std::string& name) {
  const fs::path path = fs::path(::testing::TempDir()) / (name + ".xml");
  std::ofstream(path) << xml;
  char error[1000] = "";
  std::unique_ptr<mjModel, MjModelDeleter> m(mj_loadXML(path.c_str(), nullptr, error, sizeof error));
  EXPECT_TRUE(m) << name << ": " << error;
  return m;
}

// The model with random rotor inertia, viscous and Coulomb friction per joint, and gravity g_W.
RobotModel WithDriveValues(const RobotModel& model, const Eigen::Vector3d& g_W, std::mt19937* rng) {
  std::uniform_real_distribution<double> u(0.1, 2.0);
  std::vector<Link> links = model.links();
  for (Link& link : links) link.dynamics = {.viscous = u(*rng), .coulomb = u(*rng), .rotor_inertia = 0.1 * u(*rng)};
  return RobotModel(model.name(), links, g_W);
}

// What MuJoCo's balanceinertia makes of the model: the principal moments of
// links that break the triangle inequality replaced by their mean (MuJoCo's
// documentation of the compiler attribute).
RobotModel Balanced(const RobotModel& model) {
  std::vector<Link> links = model.links();
  for (Link& link : links)
    if (ViolatesTriangleInequality(link.inertia.I_Bcm_B))
      link.inertia.I_Bcm_B = link.inertia.I_Bcm_B.trace() / 3.0 * Eigen::Matrix3d::Identity();
  return RobotModel(model.name(), links, model.gravity_W());
}

// Largest ‖τ_MuJoCo − τ_idbench‖∞ / ‖τ_idbench‖∞ over random states.
double MaxRelativeDifference(const RobotModel& model, const std::string& name, int states = 20) {
  auto m = LoadInMujoco(WriteMjcf(model), name);
  if (!m) return INFINITY;
  EXPECT_EQ(m->nv, model.n_dof());
  m->opt.disableflags |= mjDSBL_CONSTRAINT;  // no frictionloss (Coulomb), limits or contacts
  std::unique_ptr<mjData, MjDataDeleter> d(mj_makeData(m.get()));
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  RobotData data(model);
  const RobotModel balanced = Balanced(model);
  double worst = 0.0;
  for (int s = 0; s < states; ++s) {
    Eigen::VectorXd q(model.n_dof()), qd(model.n_dof()), qdd(model.n_dof());
    for (int j = 0; j < model.n_dof(); ++j) {
      const JointLimits& l = model.link(j).limits;
      const double lo = std::isfinite(l.q_min) ? l.q_min : -M_PI, hi = std::isfinite(l.q_max) ? l.q_max : M_PI;
      q[j] = lo + (hi - lo) * 0.5 * (1.0 + u(rng));
      qd[j] = 2.0 * u(rng);
      qdd[j] = 5.0 * u(rng);
    }
    // MuJoCo's dofs by joint name (its order is the body tree's).
    std::vector<int> dof(static_cast<size_t>(model.n_dof()));
    for (int j = 0; j < model.n_dof(); ++j) {
      const int id = mj_name2id(m.get(), mjOBJ_JOINT, model.link(j).joint_name.c_str());
      EXPECT_GE(id, 0) << model.link(j).joint_name;
      if (id < 0) return INFINITY;
      dof[static_cast<size_t>(j)] = m->jnt_dofadr[id];
      d->qpos[m->jnt_qposadr[id]] = q[j];
      d->qvel[m->jnt_dofadr[id]] = qd[j];
      d->qacc[m->jnt_dofadr[id]] = qdd[j];
    }
    mj_inverse(m.get(), d.get());
    Eigen::VectorXd tau = InverseDynamics(balanced, q, qd, qdd, &data);
    // Without Coulomb: frictionloss is a constraint, off here.
    for (int j = 0; j < model.n_dof(); ++j)
      tau[j] += model.link(j).dynamics.viscous * qd[j] + model.link(j).dynamics.rotor_inertia * qdd[j];
    double diff = 0.0;
    for (int j = 0; j < model.n_dof(); ++j)
      diff = std::max(diff, std::abs(d->qfrc_inverse[dof[static_cast<size_t>(j)]] - tau[j]));
    worst = std::max(worst, diff / tau.cwiseAbs().maxCoeff());
  }
  return worst;
}

TEST(MjcfWriterTest, MujocoInverseDynamicsOfBuiltinRobotsEqualsIdbenchs) {
  std::mt19937 rng(3);
  for (const std::string& name : BuiltinRobotNames()) {
    const RobotModel model = LoadRobot(name).model;
    int unbalanced = 0;
    for (const Link& link : model.links()) unbalanced += ViolatesTriangleInequality(link.inertia.I_Bcm_B) ? 1 : 0;
    if (unbalanced > 0) std::printf("%s: %d links balanced by MuJoCo (balanceinertia)\n", name.c_str(), unbalanced);
    const double plain = MaxRelativeDifference(model, name);
    const double driven = MaxRelativeDifference(WithDriveValues(model, model.gravity_W(), &rng), name + "_driven");
    const double tilted =
        MaxRelativeDifference(WithDriveValues(model, Eigen::Vector3d(1.5, -2.0, -9.3), &rng), name + "_tilted");
    std::printf("%s: max relative difference %.3g (file), %.3g (drive values), %.3g (tilted gravity)\n",
                name.c_str(), plain, driven, tilted);
    EXPECT_LE(plain, 1e-9) << name;
    EXPECT_LE(driven, 1e-9) << name;
    EXPECT_LE(tilted, 1e-9) << name;
  }
}

TEST(MjcfWriterTest, MujocoLoadsTheKukaWithItsMeshesAndAgrees) {
  if (!fs::exists(kKukaUrdf))
    GTEST_SKIP() << "KUKA LWR4+ URDF not found at " << kKukaUrdf.string()
                 << " (../shared/data/kuka_lwr4 beside the checkout; not part of the project)";
  const RobotModel model = LoadRobot(kKukaUrdf.string()).model;
  int meshes = 0;
  for (const Link& link : model.links())
    for (const Shape& shape : link.shapes) meshes += shape.kind == Shape::Kind::kMesh ? 1 : 0;
  for (const GroundLink& link : model.ground())  // the table the arm stands on
    for (const Shape& shape : link.shapes) meshes += shape.kind == Shape::Kind::kMesh ? 1 : 0;
  ASSERT_GT(meshes, 0);
  auto m = LoadInMujoco(WriteMjcf(model), "kuka_meshes");
  ASSERT_TRUE(m);
  EXPECT_EQ(m->nmesh, meshes);
  std::mt19937 rng(5);
  const double plain = MaxRelativeDifference(model, "kuka");
  const double driven = MaxRelativeDifference(WithDriveValues(model, model.gravity_W(), &rng), "kuka_driven");
  std::printf("kuka_lwr4: %d meshes; max relative difference %.3g (file), %.3g (drive values)\n", meshes, plain, driven);
  EXPECT_LE(plain, 1e-9);
  EXPECT_LE(driven, 1e-9);
}

// The ground links (issue 35: the table and pedestal an arm stands on) are
// bodies welded to the world with their shapes where the URDF has them;
// MuJoCo's inverse dynamics is unchanged by them. Truth: table_arm.urdf.
TEST(MjcfWriterTest, GroundLinksAreStaticBodiesWithTheirShapes) {
  const RobotModel model = LoadRobot(IDBENCH_SOURCE_DIR "/tests/data/table_arm/table_arm.urdf").model;
  ASSERT_EQ(model.ground().size(), 3u);
  auto m = LoadInMujoco(WriteMjcf(model), "table_arm");
  ASSERT_TRUE(m);
  auto body = [&](const char* name) {
    const int id = mj_name2id(m.get(), mjOBJ_BODY, name);
    EXPECT_GE(id, 0) << name;
    return id;
  };
  const int table = body("table"), pedestal = body("pedestal"), lamp = body("lamp");
  ASSERT_GE(table, 0);
  ASSERT_GE(pedestal, 0);
  ASSERT_GE(lamp, 0);
  for (int id : {table, pedestal, lamp}) EXPECT_EQ(m->body_weldid[id], 0);  // welded to the world: no joint
  // The table: a 2 x 2 x 0.5 m box centred 0.25 m up, drawn and colliding (two geoms).
  ASSERT_EQ(m->body_geomnum[table], 2);
  for (int g = m->body_geomadr[table]; g < m->body_geomadr[table] + 2; ++g) {
    EXPECT_EQ(m->geom_type[g], mjGEOM_BOX);
    EXPECT_NEAR(m->geom_size[3 * g + 0], 1.0, 1e-12);
    EXPECT_NEAR(m->geom_size[3 * g + 2], 0.25, 1e-12);
    EXPECT_NEAR(m->geom_pos[3 * g + 2], 0.25, 1e-12);
  }
  // The lamp: a sphere of 0.1 m at (5, 0, 2), collision only (contacts on).
  ASSERT_EQ(m->body_geomnum[lamp], 1);
  const int g = m->body_geomadr[lamp];
  EXPECT_EQ(m->geom_type[g], mjGEOM_SPHERE);
  EXPECT_NEAR(m->geom_pos[3 * g + 0], 5.0, 1e-12);
  EXPECT_NEAR(m->geom_pos[3 * g + 2], 2.0, 1e-12);
  EXPECT_NE(m->geom_contype[g], 0);
  EXPECT_EQ(m->nv, 3);
  EXPECT_LE(MaxRelativeDifference(model, "table_arm_dynamics"), 1e-9);
}

TEST(MjcfWriterTest, WritesDriveValuesAndRanges) {
  std::vector<Link> links = LoadRobot("paper6r").model.links();
  links[0].limits.q_min = -1.25;
  links[0].limits.q_max = 2.5;
  links[0].dynamics = {.viscous = 0.75, .coulomb = 1.5, .rotor_inertia = 0.125};
  const RobotModel model("r", links);
  auto m = LoadInMujoco(WriteMjcf(model), "values");
  ASSERT_TRUE(m);
  const int id = mj_name2id(m.get(), mjOBJ_JOINT, links[0].joint_name.c_str());
  ASSERT_GE(id, 0);
  EXPECT_EQ(m->jnt_limited[id], 1);
  EXPECT_EQ(m->jnt_range[2 * id], -1.25);
  EXPECT_EQ(m->jnt_range[2 * id + 1], 2.5);
  EXPECT_EQ(m->dof_damping[m->jnt_dofadr[id]], 0.75);
  EXPECT_EQ(m->dof_frictionloss[m->jnt_dofadr[id]], 1.5);
  EXPECT_EQ(m->dof_armature[m->jnt_dofadr[id]], 0.125);
  EXPECT_EQ(m->body_mass[1], links[0].inertia.mass);
}

TEST(MjcfWriterTest, OneSidedLimitNamesTheLink) {
  std::vector<Link> links = LoadRobot("paper6r").model.links();
  links[1].limits.q_min = -1.0;
  links[1].limits.q_max = JointLimits::kInf;
  try {
    WriteMjcf(RobotModel("r", links));
    FAIL() << "no throw";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("link '" + links[1].name + "'"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace idbench
