#include "idbench/engine/bullet_simulation.h"

#include <BulletCollision/BroadphaseCollision/btDbvtBroadphase.h>
#include <BulletCollision/CollisionDispatch/btCollisionDispatcher.h>
#include <BulletCollision/CollisionDispatch/btDefaultCollisionConfiguration.h>
#include <BulletDynamics/Featherstone/btMultiBody.h>
#include <BulletDynamics/Featherstone/btMultiBodyConstraintSolver.h>
#include <BulletDynamics/Featherstone/btMultiBodyDynamicsWorld.h>
#include <BulletDynamics/Featherstone/btMultiBodyInplaceSolverIslandCallback.h>
#include <BulletDynamics/Featherstone/btMultiBodyJointFeedback.h>

#include <Eigen/Eigenvalues>
#include <stdexcept>

static_assert(sizeof(btScalar) == sizeof(double), "idbench needs Bullet in double precision (bullet-float64)");

namespace idbench {
namespace {

btVector3 ToBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d FromBt(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }
btMatrix3x3 ToBt(const Eigen::Matrix3d& m) {
  return btMatrix3x3(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0), m(2, 1), m(2, 2));
}
Eigen::Matrix3d FromBt(const btMatrix3x3& m) {
  Eigen::Matrix3d out;
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) out(r, c) = m[r][c];
  return out;
}

// A world whose joint-feedback pass can be left out, and, corrected, only
// adds the constraint forces.
//
// Stock Bullet 3.24 re-runs the articulated-body algorithm in
// solveInternalConstraints with isConstraintPass = true and adds its result to
// the feedback of the first pass; that second pass still sees the joint torques
// and the (already updated) joint velocities. Running it with both zeroed
// leaves exactly the response to the constraint forces. The pass changes no
// velocity (a constraint pass applies no Δv of its own), so a step that only
// wants the accelerations skips it (feedback_pass = false): ~30 % of a step.
class FeedbackWorld : public btMultiBodyDynamicsWorld {
 public:
  FeedbackWorld(JointFeedbackMode mode, btDispatcher* dispatcher, btBroadphaseInterface* broadphase,
                btMultiBodyConstraintSolver* solver, btCollisionConfiguration* config)
      : btMultiBodyDynamicsWorld(dispatcher, broadphase, solver, config), mode_(mode) {}

  bool feedback_pass = true;

  void solveInternalConstraints(btContactSolverInfo& solver_info) override {
    if (feedback_pass && mode_ == JointFeedbackMode::kStock) {
      btMultiBodyDynamicsWorld::solveInternalConstraints(solver_info);
      return;
    }
    m_solverMultiBodyIslandCallback->processConstraints();
    m_constraintSolver->allSolved(solver_info, m_debugDrawer);
    for (int b = 0; b < m_multiBodies.size() && feedback_pass; ++b) {
      btMultiBody* body = m_multiBodies[b];
      if (!body->internalNeedsJointFeedback() || body->isUsingRK4Integration()) continue;
      const int n = body->getNumLinks();
      saved_qd_.resize(n);
      saved_tau_.resize(n);
      for (int i = 0; i < n; ++i) {
        saved_qd_[i] = body->getJointVel(i);
        saved_tau_[i] = body->getJointTorque(i);
        body->setJointVel(i, 0.0);
        body->getJointTorqueMultiDof(i)[0] = 0.0;
      }
      m_scratch_r.resize(n + 1);
      m_scratch_v.resize(n + 1);
      m_scratch_m.resize(n + 1);
      body->computeAccelerationsArticulatedBodyAlgorithmMultiDof(
          solver_info.m_timeStep, m_scratch_r, m_scratch_v, m_scratch_m, /*isConstraintPass=*/true,
          getSolverInfo().m_jointFeedbackInWorldSpace, getSolverInfo().m_jointFeedbackInJointFrame);
      for (int i = 0; i < n; ++i) {
        body->setJointVel(i, saved_qd_[i]);
        body->getJointTorqueMultiDof(i)[0] = saved_tau_[i];
      }
    }
    for (int b = 0; b < m_multiBodies.size(); ++b) m_multiBodies[b]->processDeltaVeeMultiDof2();
  }

 private:
  JointFeedbackMode mode_;
  btAlignedObjectArray<btScalar> saved_qd_, saved_tau_;
};

// Bullet's link frame K is the principal frame at the centre of mass.
struct PrincipalFrame {
  Eigen::Matrix3d R_BK;        // principal axes in B (right-handed)
  Eigen::Vector3d inertia_K;   // principal moments [kg m²]
};

PrincipalFrame ComputePrincipalFrame(const LinkInertia& inertia) {
  const Eigen::Matrix3d& I = inertia.I_Bcm_B;
  PrincipalFrame frame;
  // Keep B's axes when the tensor is already diagonal (paper6r, most URDFs).
  if ((I - Eigen::Matrix3d(I.diagonal().asDiagonal())).norm() <= 1e-15 * I.norm()) {
    frame.R_BK.setIdentity();
    frame.inertia_K = I.diagonal();
    return frame;
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(I);
  frame.R_BK = eig.eigenvectors();
  if (frame.R_BK.determinant() < 0.0) frame.R_BK.col(2) *= -1.0;
  frame.inertia_K = eig.eigenvalues();
  return frame;
}

}  // namespace

struct BulletSimulation::Impl {
  btDefaultCollisionConfiguration collision_config;
  btCollisionDispatcher dispatcher{&collision_config};
  btDbvtBroadphase broadphase;
  btMultiBodyConstraintSolver solver;
  std::unique_ptr<FeedbackWorld> world;
  std::unique_ptr<btMultiBody> body;
  btAlignedObjectArray<btMultiBodyJointFeedback> feedback;
  std::vector<PrincipalFrame> frames;
  // The last Accelerations's q, and InverseMassMatrix's workspace.
  Eigen::VectorXd accelerations_q;
  btAlignedObjectArray<btScalar> unit_torque, delta, scratch_r;
  btAlignedObjectArray<btVector3> scratch_v;
  btAlignedObjectArray<btQuaternion> world_to_local;
  btAlignedObjectArray<btVector3> local_origin;
};

BulletSimulation::BulletSimulation(const RobotModel& model, JointFeedbackMode feedback_mode)
    : model_(model), impl_(std::make_unique<Impl>()), feedback_(static_cast<size_t>(model.n_links())) {
  Impl& s = *impl_;
  s.world = std::make_unique<FeedbackWorld>(feedback_mode, &s.dispatcher, &s.broadphase, &s.solver, &s.collision_config);
  s.world->setGravity(ToBt(model.gravity_W()));
  s.world->getSolverInfo().m_jointFeedbackInWorldSpace = true;
  s.world->getSolverInfo().m_jointFeedbackInJointFrame = true;

  const int n = model.n_links();
  s.body = std::make_unique<btMultiBody>(n, 0.0, btVector3(0, 0, 0), /*fixedBase=*/true, /*canSleep=*/false);
  s.body->setBasePos(btVector3(0, 0, 0));
  s.body->setWorldToBaseRot(btQuaternion::getIdentity());
  s.feedback.resize(n);
  for (int i = 0; i < n; ++i) s.frames.push_back(ComputePrincipalFrame(model.link(i).inertia));

  for (int i = 0; i < n; ++i) {
    const Link& link = model.link(i);
    const PrincipalFrame& child = s.frames[static_cast<size_t>(i)];
    // Parent's principal frame (the ground: world frame at the origin).
    Eigen::Matrix3d R_PKp = Eigen::Matrix3d::Identity();
    Eigen::Vector3d p_PoPcm_P = Eigen::Vector3d::Zero();
    if (link.parent >= 0) {
      R_PKp = s.frames[static_cast<size_t>(link.parent)].R_BK;
      p_PoPcm_P = model.link(link.parent).inertia.p_BoBcm_B;
    }
    // At q = 0, B = J: R_KpK = R_PKpᵀ · R_PJ · R_BK; Bullet wants the rotation
    // taking parent-frame vectors to this frame, R_KKp.
    const Eigen::Matrix3d R_KpK = R_PKp.transpose() * link.X_PJ.linear() * child.R_BK;
    btQuaternion rot_parent_to_this;
    ToBt(Eigen::Matrix3d(R_KpK.transpose())).getRotation(rot_parent_to_this);
    const Eigen::Vector3d axis_K = child.R_BK.transpose() * link.axis_J;
    const Eigen::Vector3d p_PcmJo_Kp = R_PKp.transpose() * (link.X_PJ.translation() - p_PoPcm_P);
    const Eigen::Vector3d p_JoBcm_K = child.R_BK.transpose() * link.inertia.p_BoBcm_B;
    s.body->setupRevolute(i, link.inertia.mass, ToBt(child.inertia_K), link.parent, rot_parent_to_this,
                          ToBt(axis_K), ToBt(p_PcmJo_Kp), ToBt(p_JoBcm_K), /*disableParentCollision=*/true);
    s.body->getLink(i).m_jointFeedback = &s.feedback[i];
  }
  s.body->finalizeMultiDof();
  // Bullet's defaults that would break consistency with the model.
  s.body->setLinearDamping(0.0);
  s.body->setAngularDamping(0.0);
  s.body->setUseGyroTerm(true);
  s.body->setMaxCoordinateVelocity(1e30);
  s.world->addMultiBody(s.body.get());
  s.world->forwardKinematics();
}

BulletSimulation::~BulletSimulation() {
  if (impl_ && impl_->world) impl_->world->removeMultiBody(impl_->body.get());
}

void BulletSimulation::SetState(const Eigen::VectorXd& q, const Eigen::VectorXd& qd) {
  const int n = model_.n_dof();
  if (q.size() != n || qd.size() != n) {
    throw std::invalid_argument("BulletSimulation::SetState: expected " + std::to_string(n) +
                                " joint values, got " + std::to_string(q.size()) + " and " +
                                std::to_string(qd.size()));
  }
  for (int i = 0; i < n; ++i) {
    impl_->body->setJointPos(i, q[i]);
    impl_->body->setJointVel(i, qd[i]);
  }
  impl_->world->forwardKinematics();
}

void BulletSimulation::GetState(Eigen::VectorXd* q, Eigen::VectorXd* qd) const {
  const int n = model_.n_dof();
  q->resize(n);
  qd->resize(n);
  for (int i = 0; i < n; ++i) {
    (*q)[i] = impl_->body->getJointPos(i);
    (*qd)[i] = impl_->body->getJointVel(i);
  }
}

void BulletSimulation::Step(const Eigen::VectorXd& tau, double dt) { StepWith(tau, dt, /*feedback=*/true); }

void BulletSimulation::Accelerations(const Eigen::VectorXd& q, const Eigen::VectorXd& qd, const Eigen::VectorXd& tau,
                                     double dt, Eigen::VectorXd* qdd, bool feedback) {
  const int n = model_.n_dof();
  if (q.size() != n || qd.size() != n) {
    throw std::invalid_argument("BulletSimulation::Accelerations: expected " + std::to_string(n) +
                                " joint values, got " + std::to_string(q.size()) + " and " + std::to_string(qd.size()));
  }
  // The state as SetState sets it, without its forward kinematics: the step
  // starts with its own.
  for (int i = 0; i < n; ++i) {
    impl_->body->setJointPos(i, q[i]);
    impl_->body->setJointVel(i, qd[i]);
  }
  StepWith(tau, dt, feedback);
  impl_->accelerations_q = q;
  // Semi-implicit Euler: qd_after = qd + dt·qdd(q, qd, tau), so the step's
  // velocity change is Bullet's acceleration at the state.
  qdd->resize(n);
  for (int i = 0; i < n; ++i) (*qdd)[i] = (impl_->body->getJointVel(i) - qd[i]) / dt;
}

void BulletSimulation::InverseMassMatrix(Eigen::MatrixXd* M_inverse) {
  Impl& s = *impl_;
  const int n = model_.n_dof();
  if (s.accelerations_q.size() != n) {
    throw std::logic_error("BulletSimulation::InverseMassMatrix: needs an Accelerations call first");
  }
  // The step moved q, and with it the link caches the factors are read with
  // (m_cachedRVector, the parent rotations in m_matrixBuf): back to its q.
  for (int i = 0; i < n; ++i) s.body->setJointPos(i, s.accelerations_q[i]);
  s.body->forwardKinematics(s.world_to_local, s.local_origin);
  s.unit_torque.resize(6 + n);
  s.delta.resize(6 + n);
  for (int k = 0; k < 6 + n; ++k) s.unit_torque[k] = 0.0;
  M_inverse->resize(n, n);
  for (int j = 0; j < n; ++j) {
    s.unit_torque[6 + j] = 1.0;
    s.body->calcAccelerationDeltasMultiDof(&s.unit_torque[0], &s.delta[0], s.scratch_r, s.scratch_v);
    s.unit_torque[6 + j] = 0.0;
    for (int i = 0; i < n; ++i) (*M_inverse)(i, j) = s.delta[6 + i];
  }
}

void BulletSimulation::StepWith(const Eigen::VectorXd& tau, double dt, bool feedback) {
  Impl& s = *impl_;
  const int n = model_.n_dof();
  if (tau.size() != n) {
    throw std::invalid_argument("BulletSimulation::Step: expected " + std::to_string(n) + " joint torques, got " +
                                std::to_string(tau.size()));
  }
  for (int i = 0; i < n; ++i) s.body->getJointTorqueMultiDof(i)[0] = tau[i];
  s.world->feedback_pass = feedback;
  if (s.world->stepSimulation(dt, /*maxSubSteps=*/0) != 1) {
    throw std::invalid_argument("BulletSimulation::Step: Bullet did not step with dt = " + std::to_string(dt));
  }
  if (!feedback) return;
  // m_topVec is the force, m_bottomVec the moment; world axes, about the pivot.
  for (int i = 0; i < n; ++i) {
    const btSpatialForceVector& reaction = s.feedback[i].m_reactionForces;
    feedback_[static_cast<size_t>(i)].f_W = FromBt(reaction.m_topVec);
    feedback_[static_cast<size_t>(i)].m_Bo_W = FromBt(reaction.m_bottomVec);
  }
}

Eigen::Isometry3d BulletSimulation::LinkPose(int i) const {
  impl_->world->forwardKinematics();  // refresh the cached link transforms

  const btTransform& X_WK = impl_->body->getLink(i).m_cachedWorldTransform;
  const PrincipalFrame& frame = impl_->frames.at(static_cast<size_t>(i));
  Eigen::Isometry3d X_WB = Eigen::Isometry3d::Identity();
  X_WB.linear() = FromBt(X_WK.getBasis()) * frame.R_BK.transpose();
  X_WB.translation() = FromBt(X_WK.getOrigin()) - X_WB.linear() * model_.link(i).inertia.p_BoBcm_B;
  return X_WB;
}

}  // namespace idbench
