#include "urdf_chain_builder.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "idbench/engine/link_bounding_box.h"
#include "urdf_messages.h"
#include "urdf_shape_reader.h"

namespace idbench::internal {
namespace {

// Beyond any robot link (urdf.h).
constexpr double kMaxMass = kMaxLinkMass;
constexpr double kMaxInertia = kMaxLinkInertia;
constexpr double kMaxOffset = kMaxLinkComOffset;

Eigen::Isometry3d ToIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
                   .normalized()
                   .toRotationMatrix();
  X.translation() = Eigen::Vector3d(pose.position.x, pose.position.y, pose.position.z);
  return X;
}

bool IsMoving(const urdf::Joint& joint) {
  return joint.type == urdf::Joint::REVOLUTE || joint.type == urdf::Joint::CONTINUOUS;
}

// Mass properties of one URDF link, expressed in the frame B of the idbench
// link it is merged into.
struct PointInertia {
  double mass = 0.0;
  Eigen::Vector3d p_BoLcm_B = Eigen::Vector3d::Zero();
  Eigen::Matrix3d I_Lcm_B = Eigen::Matrix3d::Zero();
};

// Lumps rigidly attached masses into one: total mass, mass-weighted COM and
// I_Bcm = Σ R·I·Rᵀ + m·(|d|²·1 − d·dᵀ), d = p_Lcm − p_Bcm (parallel axes).
// Weights m_i/m make a single part reproduce its COM bit for bit.
LinkInertia Lump(const std::vector<PointInertia>& parts) {
  LinkInertia lumped;
  for (const PointInertia& part : parts) lumped.mass += part.mass;
  if (!(lumped.mass > 0.0)) return lumped;
  for (const PointInertia& part : parts) lumped.p_BoBcm_B += (part.mass / lumped.mass) * part.p_BoLcm_B;
  for (const PointInertia& part : parts) {
    const Eigen::Vector3d d = part.p_BoLcm_B - lumped.p_BoBcm_B;
    lumped.I_Bcm_B += part.I_Lcm_B +
                      part.mass * (d.squaredNorm() * Eigen::Matrix3d::Identity() - d * d.transpose());
  }
  return lumped;
}

const char* TypeName(const urdf::Joint& joint) {
  switch (joint.type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown-type";
  }
}

// What --lock takes for a joint: "NAME=VALUE", or "NAME=0" for a floating or
// planar joint (only its <origin> can be held).
std::string LockArgument(const urdf::Joint& joint) {
  const bool origin_only = joint.type == urdf::Joint::FLOATING || joint.type == urdf::Joint::PLANAR;
  return joint.name + (origin_only ? "=0" : "=VALUE");
}

// Names quoted and separated by ", ".
// Chooses the chain of a urdfdom tree (the joints that become the model's
// degrees of freedom), then walks it from the root, merging every link held
// rigidly (fixed or locked joints) into the chain link above it.
class UrdfChainBuilder {
 public:
  UrdfChainBuilder(const urdf::ModelInterface& urdf, std::string source, std::filesystem::path base_directory,
                   const UrdfLoadOptions& options)
      : urdf_(urdf), source_(std::move(source)), options_(options), shapes_(std::move(base_directory), &warnings_) {}

  UrdfLoadResult Load() {
    const urdf::LinkConstSharedPtr root = urdf_.getRoot();
    CheckOptions(*root);
    const urdf::LinkConstSharedPtr tip =
        options_.tip_link.empty() ? AutomaticTip(root) : urdf_.getLink(options_.tip_link);
    ChooseChain(*root, tip);

    // The ground group (root and all held to it), then one group per chain
    // joint, each hanging from the previous one.
    std::vector<Link> links;
    Group group = CollectGroup(root, "");
    std::vector<GroundLink> ground = ReadGround(group);
    while (group.next_joint != nullptr) {
      const urdf::Joint& joint = *group.next_joint;
      const urdf::LinkConstSharedPtr child = urdf_.getLink(joint.child_link_name);
      Link link;
      link.name = child->name;
      link.joint_name = joint.name;
      link.parent = static_cast<int>(links.size()) - 1;
      link.X_PJ = group.next_joint_X_BL * ToIsometry(joint.parent_to_joint_origin_transform);
      ReadJoint(joint, &link);

      group = CollectGroup(child, child->name);
      ReadBody(*child, group, &link);
      links.push_back(std::move(link));
    }
    if (!locked_.empty()) warnings_.push_back(source_ + ": " + LockedWarning(root->name, tip->name));

    try {
      RobotModel model(urdf_.getName(), std::move(links), RobotModel::StandardGravity_W(), std::move(ground));
      for (std::string& w : InertiaWarnings(model)) warnings_.push_back(source_ + ": " + w);
      for (const Link& link : model.links()) {
        const std::optional<CenterOfMassGeometryCheck> check = CheckCenterOfMassInGeometry(link);
        if (!check || !check->contradicts()) continue;
        warnings_.push_back(source_ + ": link " + Quote(link.name) + ": its centre of mass (<inertial> origin) lies " +
                            Format(check->distance) + " m outside the box around its shapes (near: within " +
                            Format(check->tolerance) + " m): the shapes may not be placed in the frame of its "
                            "inertial; identification does not bound this link's centre of mass by its shapes");
      }
      return UrdfLoadResult{std::move(model), std::move(warnings_), {}};
    } catch (const std::invalid_argument& e) {
      Fail(e.what());
    }
  }

 private:
  // What a joint is to the chain: a degree of freedom (revolute, continuous),
  // rigid (fixed or locked) or another kind (prismatic, floating, planar).
  enum class Role { kDof, kRigid, kOther };

  // A URDF link and everything held rigidly to it, with their poses in the
  // frame B of the first one, and the chain joint leaving the group (if any).
  struct Group {
    std::vector<std::pair<urdf::LinkConstSharedPtr, Eigen::Isometry3d>> members;  // (L, X_BL)
    const urdf::Joint* next_joint = nullptr;
    Eigen::Isometry3d next_joint_X_BL = Eigen::Isometry3d::Identity();  // its parent L in B
  };

  // A joint off the chain (or locked on it), held at `value`.
  struct Locked {
    const urdf::Joint* joint;
    double value;      // [rad] or [m]
    std::string into;  // the chain link it is merged into; empty: the ground
  };

  [[noreturn]] void Fail(const std::string& what) const {
    throw std::invalid_argument(source_ + ": " + what);
  }

  Role RoleOf(const urdf::Joint& joint) const {
    if (joint.type == urdf::Joint::FIXED || options_.locked_joints.contains(joint.name)) return Role::kRigid;
    return IsMoving(joint) ? Role::kDof : Role::kOther;
  }

  // Names of the joints that --lock can take (every joint but fixed ones).
  std::string LockableJoints() const {
    std::vector<std::string> names;
    for (const auto& [name, joint] : urdf_.joints_) {
      if (joint->type != urdf::Joint::FIXED) names.push_back(name);
    }
    return names.empty() ? "none" : QuotedList(names);
  }

  // --lock names joints of the file at values within their limits; --tip
  // names a link other than the root.
  void CheckOptions(const urdf::Link& root) const {
    std::string why;
    if (!options_.IsValid(&why)) Fail(why);
    for (const auto& [name, value] : options_.locked_joints) {
      const std::string where = "locked_joints " + name + "=" + Format(value) + ": ";
      const urdf::JointConstSharedPtr joint = urdf_.getJoint(name);
      if (joint == nullptr) {
        Fail(where + "no joint " + Quote(name) + " in the file; joints that can be locked: " + LockableJoints());
      }
      const std::string type = TypeName(*joint);
      if (joint->type == urdf::Joint::FIXED) {
        Fail(where + "joint " + Quote(name) + " is fixed already; joints that can be locked: " + LockableJoints());
      }
      if ((joint->type == urdf::Joint::FLOATING || joint->type == urdf::Joint::PLANAR) && value != 0.0) {
        Fail(where + "joint " + Quote(name) + " is " + type + "; it can only be locked at 0 (its <origin>)");
      }
      const bool limited = (joint->type == urdf::Joint::REVOLUTE || joint->type == urdf::Joint::PRISMATIC) &&
                           joint->limits != nullptr && joint->limits->lower < joint->limits->upper;
      if (limited && !(value >= joint->limits->lower && value <= joint->limits->upper)) {
        const char* unit = joint->type == urdf::Joint::PRISMATIC ? " m" : " rad";
        Fail(where + "outside the <limit> of " + type + " joint " + Quote(name) + ", [" +
             Format(joint->limits->lower) + ", " + Format(joint->limits->upper) + "]" + unit +
             "; pass a value within it");
      }
    }
    const std::string& tip = options_.tip_link;
    if (!tip.empty()) {
      if (urdf_.getLink(tip) == nullptr) {
        std::vector<std::string> names;
        for (const auto& [name, link] : urdf_.links_) names.push_back(name);
        Fail("tip_link " + tip + ": no link " + Quote(tip) + " in the file; links: " + QuotedList(names));
      }
      if (tip == root.name) {
        Fail("tip_link " + tip + ": " + Quote(tip) + " is the root link (the ground); pass the arm's last link");
      }
    }
  }

  // Whether a degree-of-freedom joint hangs anywhere below `link` (through
  // joints of any role). The links form a tree (CheckUrdfDocument), so the
  // walks here end; they use their own stack, not the call stack, so a long
  // chain cannot overflow it.
  bool HasDofBelow(const urdf::Link& link) const {
    std::vector<const urdf::Link*> stack{&link};
    while (!stack.empty()) {
      const urdf::Link& l = *stack.back();
      stack.pop_back();
      for (const urdf::JointSharedPtr& joint : l.child_joints) {
        if (RoleOf(*joint) == Role::kDof) return true;
      }
      for (const urdf::LinkSharedPtr& child : l.child_links) stack.push_back(child.get());
    }
    return false;
  }

  // Depth first from `link` through degree-of-freedom and rigid joints:
  // appends the degree-of-freedom joints with none below them to *ends (after
  // those below their siblings before them), and the other-kind joints with a
  // degree of freedom below them to *blocked.
  void FindEnds(const urdf::Link& link, std::vector<const urdf::Joint*>* ends,
                std::vector<const urdf::Joint*>* blocked) const {
    // One frame per link on the current path: the next child joint to look
    // at, whether a degree of freedom was reached below, and the joint it
    // hangs from.
    struct Frame {
      const urdf::Link* link;
      size_t next = 0;
      bool reached = false;
      const urdf::Joint* via = nullptr;
    };
    std::vector<Frame> path{{&link}};
    while (!path.empty()) {
      Frame& frame = path.back();
      if (frame.next < frame.link->child_joints.size()) {
        const urdf::Joint* joint = frame.link->child_joints[frame.next++].get();
        const urdf::Link& child = *urdf_.getLink(joint->child_link_name);
        if (RoleOf(*joint) != Role::kOther) {
          path.push_back({&child, 0, false, joint});
        } else if (HasDofBelow(child)) {
          blocked->push_back(joint);
        }
        continue;
      }
      // All below this link seen: report to the link above.
      const Frame done = frame;
      path.pop_back();
      if (done.via == nullptr) break;
      const bool dof = RoleOf(*done.via) == Role::kDof;
      if (dof && !done.reached) ends->push_back(done.via);
      path.back().reached = path.back().reached || done.reached || dof;
    }
  }

  // The first other-kind joint below `link` (null if none), looking at a
  // link's joints before those below its children.
  const urdf::Joint* FindOtherJoint(const urdf::Link& link) const {
    std::vector<const urdf::Link*> stack{&link};
    while (!stack.empty()) {
      const urdf::Link& l = *stack.back();
      stack.pop_back();
      for (const urdf::JointSharedPtr& joint : l.child_joints) {
        if (RoleOf(*joint) == Role::kOther) return joint.get();
      }
      for (auto it = l.child_links.rbegin(); it != l.child_links.rend(); ++it) stack.push_back(it->get());
    }
    return nullptr;
  }

  // The links from the root (first) to `link` (last).
  static std::vector<urdf::LinkConstSharedPtr> PathFromRoot(urdf::LinkConstSharedPtr link) {
    std::vector<urdf::LinkConstSharedPtr> path;
    for (; link != nullptr; link = link->getParent()) path.push_back(link);
    return {path.rbegin(), path.rend()};
  }

  // The end of the chain without --tip: the child link of the one
  // degree-of-freedom joint that has no other below it (see urdf.h).
  urdf::LinkConstSharedPtr AutomaticTip(const urdf::LinkConstSharedPtr& root) const {
    std::vector<const urdf::Joint*> ends, blocked;
    FindEnds(*root, &ends, &blocked);
    if (!blocked.empty()) {
      const urdf::Joint& joint = *blocked.front();
      Fail("joint " + Quote(joint.name) + " (" + TypeName(joint) +
           ") carries revolute joints; idbench identifies revolute chains and cannot tell whether this joint "
           "belongs to the arm: pass locked_joints " + LockArgument(joint) + " to hold it (the chain then continues "
           "through it), or tip_link LINK to end the chain above it");
    }
    if (ends.empty()) {
      std::string message =
          "no revolute or continuous joint below the root link " + Quote(root->name) + "; nothing to identify";
      if (const urdf::Joint* other = FindOtherJoint(*root)) {
        message += " (joint " + Quote(other->name) + ": " + TypeName(*other) +
                   " joints are not supported; idbench identifies revolute chains)";
      }
      Fail(message);
    }
    if (ends.size() > 1) {
      // Where the ends' paths from the root diverge: their last common link.
      std::vector<std::vector<urdf::LinkConstSharedPtr>> paths;
      for (const urdf::Joint* end : ends) paths.push_back(PathFromRoot(urdf_.getLink(end->child_link_name)));
      urdf::LinkConstSharedPtr fork = root;
      for (size_t k = 0;; ++k) {
        bool common = true;
        for (const auto& path : paths) common = common && k < path.size() && path[k] == paths[0][k];
        if (!common) break;
        fork = paths[0][k];
      }
      std::string candidates;
      for (const urdf::Joint* end : ends) {
        candidates += (candidates.empty() ? "" : ", ") + Quote(end->child_link_name) + " (joint " +
                      Quote(end->name) + ")";
      }
      Fail("link " + Quote(fork->name) + ": the robot branches into " + std::to_string(ends.size()) +
           " chains of revolute joints, ending at links " + candidates +
           "; pass tip_link LINK with the arm's last link (one of these, or " + Quote(fork->name) +
           " to hold every branch below it); the joints off the chain are then locked at 0 (or at locked_joints "
           "JOINT=VALUE) and their links merged into the chain");
    }
    return urdf_.getLink(ends.front()->child_link_name);
  }

  // The degrees of freedom on the path from the root to `tip`, into chain_.
  void ChooseChain(const urdf::Link& root, const urdf::LinkConstSharedPtr& tip) {
    const std::vector<urdf::LinkConstSharedPtr> path = PathFromRoot(tip);
    for (size_t k = 1; k < path.size(); ++k) {
      const urdf::Joint& joint = *path[k]->parent_joint;
      switch (RoleOf(joint)) {
        case Role::kDof: chain_.insert(joint.name); break;
        case Role::kRigid: break;
        case Role::kOther:
          Fail("joint " + Quote(joint.name) + ": " + TypeName(joint) + " joint on the chain from the root link " +
               Quote(root.name) + " to " + Quote(tip->name) + "; idbench identifies revolute chains: pass locked_joints " +
               LockArgument(joint) + " to hold it, or a tip_link above it");
      }
    }
    if (chain_.empty()) {
      Fail("no revolute or continuous joint between the root link " + Quote(root.name) + " and " +
           Quote(tip->name) + " (tip_link); nothing to identify: pass the arm's last link");
    }
  }

  // The value a joint off the chain is held at: --lock's, else for a <mimic>
  // joint multiplier·(leader's value) + offset (a chain joint's value is 0),
  // else 0.
  double LockValue(const urdf::Joint& joint, int depth = 0) const {
    if (const auto it = options_.locked_joints.find(joint.name); it != options_.locked_joints.end()) {
      return it->second;
    }
    if (joint.mimic != nullptr && depth < 32) {
      const urdf::JointConstSharedPtr leader = urdf_.getJoint(joint.mimic->joint_name);
      const double leader_value =
          leader == nullptr || chain_.contains(leader->name) ? 0.0 : LockValue(*leader, depth + 1);
      return joint.mimic->multiplier * leader_value + joint.mimic->offset;
    }
    return 0.0;
  }

  // X_JC of a joint held at `value`: a turn about (revolute, continuous) or a
  // shift along (prismatic) its axis; floating and planar joints stay at 0.
  Eigen::Isometry3d LockedMotion(const urdf::Joint& joint, double value) const {
    Eigen::Isometry3d X_JC = Eigen::Isometry3d::Identity();
    const bool turns = IsMoving(joint), shifts = joint.type == urdf::Joint::PRISMATIC;
    if (value == 0.0 || !(turns || shifts)) return X_JC;
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || !(axis.norm() > 1e-12)) {
      Fail("joint " + Quote(joint.name) + ": <axis> must be nonzero to lock the joint at " + Format(value) +
           "; give its direction, e.g. <axis xyz=\"0 0 1\"/>");
    }
    if (turns) X_JC.linear() = Eigen::AngleAxisd(value, axis.normalized()).toRotationMatrix();
    if (shifts) X_JC.translation() = value * axis.normalized();
    return X_JC;
  }

  // The group of `first`: every link reached through joints that are not on
  // the chain (fixed ones, and the others locked, recorded in locked_ as
  // merged `into`), in depth-first, urdfdom child order; the chain joint
  // leaving it ends it.
  Group CollectGroup(const urdf::LinkConstSharedPtr& first, const std::string& into) {
    struct Visit {
      urdf::LinkConstSharedPtr link;
      Eigen::Isometry3d X_BL;
      const urdf::Joint* locked = nullptr;  // the joint it hangs from, when locked
      double value = 0.0;
    };
    Group group;
    std::vector<Visit> stack{{first, Eigen::Isometry3d::Identity()}};
    while (!stack.empty()) {
      const Visit visit = stack.back();
      stack.pop_back();
      group.members.emplace_back(visit.link, visit.X_BL);
      if (visit.locked != nullptr) locked_.push_back({visit.locked, visit.value, into});
      for (auto it = visit.link->child_joints.rbegin(); it != visit.link->child_joints.rend(); ++it) {
        const urdf::Joint& joint = **it;
        if (chain_.contains(joint.name)) {
          group.next_joint = &joint;
          group.next_joint_X_BL = visit.X_BL;
          continue;
        }
        Visit child{urdf_.getLink(joint.child_link_name), visit.X_BL * ToIsometry(joint.parent_to_joint_origin_transform)};
        if (joint.type != urdf::Joint::FIXED) {
          child.locked = &joint;
          child.value = LockValue(joint);
          child.X_BL = child.X_BL * LockedMotion(joint, child.value);
        }
        stack.push_back(child);
      }
    }
    return group;
  }

  // One line for every locked joint: type, value, where its links went.
  std::string LockedWarning(const std::string& root, const std::string& tip) const {
    std::ostringstream out;
    out << "locked " << locked_.size() << (locked_.size() == 1 ? " joint" : " joints")
        << " and merged the links they carry into the chain " << Quote(root) << " → " << Quote(tip) << ": ";
    for (size_t k = 0; k < locked_.size(); ++k) {
      const Locked& locked = locked_[k];
      const urdf::Joint& joint = *locked.joint;
      out << (k > 0 ? ", " : "") << Quote(joint.name) << " (" << TypeName(joint);
      if (joint.mimic != nullptr) out << ", mimics " << Quote(joint.mimic->joint_name);
      if (IsMoving(joint)) {
        out << ", at " << locked.value << " rad";
      } else if (joint.type == urdf::Joint::PRISMATIC) {
        out << ", at " << locked.value << " m";
      } else {
        out << ", at its <origin>";
      }
      if (options_.locked_joints.contains(joint.name)) out << " by locked_joints";
      out << ", into " << (locked.into.empty() ? "the ground" : "link " + Quote(locked.into)) << ")";
    }
    out << "; locked_joints JOINT=VALUE holds a joint at another value, tip_link LINK chooses another end of the chain";
    return out.str();
  }

  // Axis, limits and friction of a revolute or continuous joint.
  void ReadJoint(const urdf::Joint& joint, Link* link) {
    const std::string where = "joint " + Quote(joint.name) + ": ";
    const Eigen::Vector3d axis(joint.axis.x, joint.axis.y, joint.axis.z);
    if (!axis.allFinite() || !(axis.norm() > 1e-12)) {
      Fail(where + "<axis> must be nonzero; give the axis direction, e.g. <axis xyz=\"0 0 1\"/>");
    }
    link->axis_J = axis.normalized();

    if (joint.limits != nullptr) {
      const urdf::JointLimits& limits = *joint.limits;
      if (joint.type == urdf::Joint::REVOLUTE) {
        if (!(limits.lower < limits.upper)) {
          std::ostringstream message;
          message << where << "<limit> needs lower < upper, got lower = " << limits.lower
                  << ", upper = " << limits.upper << "; correct them (or make the joint continuous)";
          Fail(message.str());
        }
        link->limits.q_min = limits.lower;
        link->limits.q_max = limits.upper;
      }
      if (limits.velocity > 0.0) link->limits.qd_max = limits.velocity;
      if (limits.effort > 0.0) link->limits.tau_max = limits.effort;
    }
    if (joint.dynamics != nullptr) {
      if (!(joint.dynamics->damping >= 0.0 && joint.dynamics->friction >= 0.0)) {
        Fail(where + "<dynamics> damping and friction must be >= 0, got damping = " +
             Format(joint.dynamics->damping) + ", friction = " + Format(joint.dynamics->friction));
      }
      link->dynamics.viscous = joint.dynamics->damping;
      link->dynamics.coulomb = joint.dynamics->friction;
    }
    if (joint.mimic != nullptr) {
      warnings_.push_back(where + "<mimic> ignored; the joint is loaded as independent");
    }
  }

  // The visuals and collisions of `member` (a link held rigidly to a chain
  // link or to the ground), placed by X_BL, appended to *shapes and *collisions.
  void ReadShapes(const urdf::Link& member, const Eigen::Isometry3d& X_BL, std::vector<Shape>* shapes,
                  std::vector<Shape>* collisions) {
    const std::string where = "link " + Quote(member.name) + ": ";
    for (const urdf::VisualSharedPtr& visual : UrdfShapeReader::Visuals(member)) {
      if (visual->geometry == nullptr) continue;
      if (auto shape = shapes_.ReadShape(*visual->geometry, X_BL * ToIsometry(visual->origin), where)) {
        shapes->push_back(std::move(*shape));
      }
    }
    for (const urdf::CollisionSharedPtr& collision : UrdfShapeReader::Collisions(member)) {
      if (collision->geometry == nullptr) continue;
      if (auto shape = shapes_.ReadShape(*collision->geometry, X_BL * ToIsometry(collision->origin), where)) {
        collisions->push_back(std::move(*shape));
      }
    }
  }

  // The ground group's links with shapes (the root's frame is the base frame).
  std::vector<GroundLink> ReadGround(const Group& group) {
    std::vector<GroundLink> ground;
    for (const auto& [member, X_RL] : group.members) {
      GroundLink link;
      link.name = member->name;
      ReadShapes(*member, X_RL, &link.shapes, &link.collision_shapes);
      if (!link.shapes.empty() || !link.collision_shapes.empty()) ground.push_back(std::move(link));
    }
    return ground;
  }

  // Lumped mass properties and shapes of the group hanging from `moving`.
  void ReadBody(const urdf::Link& moving, const Group& group, Link* link) {
    std::vector<PointInertia> parts;
    for (const auto& [member, X_BL] : group.members) {
      const std::string where = "link " + Quote(member->name) + ": ";
      if (member->inertial != nullptr) {
        const urdf::Inertial& inertial = *member->inertial;
        Eigen::Matrix3d I_Lcm_I;
        I_Lcm_I << inertial.ixx, inertial.ixy, inertial.ixz,  //
            inertial.ixy, inertial.iyy, inertial.iyz,         //
            inertial.ixz, inertial.iyz, inertial.izz;
        if (!(std::isfinite(inertial.mass) && inertial.mass >= 0.0)) {
          Fail(where + "<inertial>/<mass> must be >= 0, got " + Format(inertial.mass) + "; correct it in the file");
        }
        if (!I_Lcm_I.allFinite()) Fail(where + "<inertial>/<inertia> has an entry that is not a finite number");
        // Finite but absurd values (1e200 kg) overflow the dynamics' sums and
        // leave identification without a scale: refused at load.
        if (inertial.mass > kMaxMass) {
          Fail(where + "<inertial>/<mass> is " + Format(inertial.mass) + " kg, beyond any robot link (at most " +
               Format(kMaxMass) + " kg); correct it in the file");
        }
        if (I_Lcm_I.cwiseAbs().maxCoeff() > kMaxInertia) {
          Fail(where + "<inertial>/<inertia> has an entry of " + Format(I_Lcm_I.cwiseAbs().maxCoeff()) +
               " kg m², beyond any robot link (at most " + Format(kMaxInertia) + " kg m²); correct ixx..izz in the file");
        }
        if (!(ToIsometry(inertial.origin).translation().norm() <= kMaxOffset)) {
          Fail(where + "<inertial>/<origin> xyz is " + Format(ToIsometry(inertial.origin).translation().norm()) +
               " m from the link frame, beyond any robot link (at most " + Format(kMaxOffset) +
               " m); correct it in the file");
        }
        const Eigen::Vector3d moments = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(I_Lcm_I).eigenvalues();
        if (moments.minCoeff() < -1e-12 * I_Lcm_I.norm()) {
          Fail(where + "<inertial>/<inertia> is not positive semidefinite: principal moments " + Format(moments[0]) +
               ", " + Format(moments[1]) + ", " + Format(moments[2]) +
               " kg m², and no body has a negative one; correct ixx..izz (all zero loads as a point mass, with a "
               "warning)");
        }
        // X_BI: the inertial frame I (origin at the COM) in B.
        const Eigen::Isometry3d X_BI = X_BL * ToIsometry(inertial.origin);
        PointInertia part;
        part.mass = inertial.mass;
        part.p_BoLcm_B = X_BI.translation();
        part.I_Lcm_B = X_BI.linear() * I_Lcm_I * X_BI.linear().transpose();
        parts.push_back(part);
      }
      ReadShapes(*member, X_BL, &link->shapes, &link->collision_shapes);
    }

    // The lumped body needs a mass.
    const std::string where = "link " + Quote(moving.name) + ": ";
    link->inertia = Lump(parts);
    if (!(link->inertia.mass > 0.0)) {
      Fail(where + "mass must be > 0, got " + Format(link->inertia.mass) + " (" +
           (parts.empty() ? "no <inertial>" : "the <inertial> <mass>") + " on it and the links held to it); give " +
           "it an <inertial> with an estimate of its mass (a prior that identification replaces), or hold joint " +
           Quote(link->joint_name) + " with locked_joints " + link->joint_name + "=VALUE");
    }

    // An inertia that is not positive definite (a point mass, a rod) is only
    // a prior: its principal moments are raised to those of a 1 cm sphere.
    Eigen::Matrix3d& I = link->inertia.I_Bcm_B;
    I = 0.5 * (I + I.transpose()).eval();
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(I);
    const Eigen::Vector3d moments = eigen.eigenvalues();  // ascending
    if (!(moments[0] > 1e-12 * moments[2])) {
      constexpr double kRadius = 0.01;  // [m]
      const double floor = 0.4 * link->inertia.mass * kRadius * kRadius;
      const Eigen::Vector3d raised = moments.cwiseMax(floor);
      I = eigen.eigenvectors() * raised.asDiagonal() * eigen.eigenvectors().transpose();
      I = 0.5 * (I + I.transpose()).eval();
      std::ostringstream message;
      message << source_ << ": " << where << "mass " << link->inertia.mass
              << " kg with an inertia that is not positive definite (principal moments about its centre of mass "
              << moments[0] << ", " << moments[1] << ", " << moments[2]
              << " kg m², from <inertial>/<inertia> of it and the links held to it); the file's values are only a "
              << "prior, which identification replaces: loaded with the moments below " << floor
              << " kg m² (a uniform 1 cm sphere of this mass) raised to it: " << raised[0] << ", " << raised[1] << ", "
              << raised[2] << " kg m²";
      warnings_.push_back(message.str());
    }
  }

  const urdf::ModelInterface& urdf_;
  std::string source_;
  const UrdfLoadOptions& options_;
  std::set<std::string> chain_;           // names of the joints that are the model's degrees of freedom
  std::vector<Locked> locked_;            // joints held still, in the order they were merged
  std::vector<std::string> warnings_;
  UrdfShapeReader shapes_;               // the visuals' and collisions' shapes; warns into warnings_
};

}  // namespace

UrdfLoadResult BuildUrdfChain(const urdf::ModelInterface& urdf, const std::string& source,
                              const std::filesystem::path& base_directory, const UrdfLoadOptions& options) {
  return UrdfChainBuilder(urdf, source, base_directory, options).Load();
}

}  // namespace idbench::internal
