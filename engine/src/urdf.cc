#include "idbench/engine/urdf.h"

#include <console_bridge/console.h>
#include <urdf_parser/urdf_parser.h>

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <cstdlib>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "idbench/engine/input_file.h"
#include "idbench/engine/link_bounding_box.h"
#include "idbench/engine/printable_text.h"
#include "urdf_document.h"

namespace idbench {
namespace {

// A name or path from the file as a message shows it: escaped, and cut only
// beyond the length of a long path (a mesh's package:// URI must stay whole
// for the user to find it; 64 bytes cut the KUKA's).
constexpr std::size_t kMaxQuotedBytes = 1024;
// Beyond any robot link: the largest <inertial> mass [kg], inertia entry
// [kg m²] and centre-of-mass offset from the link frame [m] a file may give.
constexpr double kMaxMass = 1e6;
constexpr double kMaxInertia = 1e8;
constexpr double kMaxOffset = 1e3;
std::string Quote(const std::string& name) { return "'" + PrintableText(name, kMaxQuotedBytes) + "'"; }

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

// The file a URDF <mesh filename> names:
//   package://P/rest → D/P/rest for each D in ROS_PACKAGE_PATH (':'-separated);
//     then, walking up from the URDF's directory, A/rest for an ancestor A
//     named P, or A/P/rest (a package next to or above the URDF);
//   file:///abs → /abs; an absolute path as is; a relative path against the
//   URDF's directory.
// The first candidate that exists (a regular file or not: LoadTriangleMesh
// says what is wrong with it); nullopt otherwise, with every candidate in
// *looked.
std::optional<std::filesystem::path> ResolveMeshUri(const std::string& uri, const std::filesystem::path& base_directory,
                                                    std::vector<std::string>* looked) {
  namespace fs = std::filesystem;
  std::vector<fs::path> candidates;
  const std::string package = "package://", file = "file://";
  if (uri.rfind(package, 0) == 0) {
    const std::string rest = uri.substr(package.size());
    const size_t slash = rest.find('/');
    const std::string name = rest.substr(0, slash), inside = slash == std::string::npos ? "" : rest.substr(slash + 1);
    if (const char* paths = std::getenv("ROS_PACKAGE_PATH")) {
      std::stringstream list(paths);
      for (std::string dir; std::getline(list, dir, ':');) {
        if (!dir.empty()) candidates.push_back(fs::path(dir) / name / inside);
      }
    }
    std::error_code error;
    for (fs::path a = fs::absolute(base_directory, error); !a.empty(); a = a.parent_path()) {
      if (a.filename() == name) candidates.push_back(a / inside);
      candidates.push_back(a / name / inside);
      if (a == a.parent_path()) break;
    }
  } else if (uri.rfind(file, 0) == 0) {
    candidates.push_back(fs::path(uri.substr(file.size())));
  } else if (fs::path(uri).is_absolute()) {
    candidates.push_back(fs::path(uri));
  } else {
    candidates.push_back(base_directory / uri);
  }
  for (const fs::path& c : candidates) {
    std::error_code error;
    if (fs::exists(c, error)) return fs::absolute(c, error).lexically_normal();
    looked->push_back(c.string());
  }
  return std::nullopt;
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

// A number as a message shows it (6 significant digits).
std::string Format(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// What --lock takes for a joint: "NAME=VALUE", or "NAME=0" for a floating or
// planar joint (only its <origin> can be held).
std::string LockArgument(const urdf::Joint& joint) {
  const bool origin_only = joint.type == urdf::Joint::FLOATING || joint.type == urdf::Joint::PLANAR;
  return joint.name + (origin_only ? "=0" : "=VALUE");
}

// Names quoted and separated by ", ".
std::string QuotedList(const std::vector<std::string>& names) {
  std::string list;
  for (const std::string& name : names) list += (list.empty() ? "" : ", ") + Quote(name);
  return list;
}

// Chooses the chain of a urdfdom tree (the joints that become the model's
// degrees of freedom), then walks it from the root, merging every link held
// rigidly (fixed or locked joints) into the chain link above it.
class Loader {
 public:
  Loader(const urdf::ModelInterface& urdf, std::string source, std::filesystem::path base_directory,
         const UrdfLoadOptions& options)
      : urdf_(urdf), source_(std::move(source)), base_directory_(std::move(base_directory)), options_(options) {}

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
      RobotModel model(urdf_.getName(), std::move(links));
      for (std::string& w : InertiaWarnings(model)) warnings_.push_back(source_ + ": " + w);
      for (const Link& link : model.links()) {
        const std::optional<CenterOfMassGeometryCheck> check = CheckCenterOfMassInGeometry(link);
        if (!check || !check->contradicts()) continue;
        warnings_.push_back(source_ + ": link " + Quote(link.name) + ": its centre of mass (<inertial> origin) lies " +
                            Format(check->distance) + " m outside the box around its shapes (near: within " +
                            Format(check->tolerance) + " m): the shapes may not be placed in the frame of its "
                            "inertial; identification does not bound this link's centre of mass by its shapes");
      }
      return UrdfLoadResult{std::move(model), std::move(warnings_)};
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
      const std::string where = "--lock " + name + "=" + Format(value) + ": ";
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
        Fail("--tip " + tip + ": no link " + Quote(tip) + " in the file; links: " + QuotedList(names));
      }
      if (tip == root.name) {
        Fail("--tip " + tip + ": " + Quote(tip) + " is the root link (the ground); pass the arm's last link");
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
           "belongs to the arm: pass --lock " + LockArgument(joint) + " to hold it (the chain then continues "
           "through it), or --tip LINK to end the chain above it");
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
           "; pass --tip LINK with the arm's last link (one of these, or " + Quote(fork->name) +
           " to hold every branch below it); the joints off the chain are then locked at 0 (or at --lock "
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
               Quote(root.name) + " to " + Quote(tip->name) + "; idbench identifies revolute chains: pass --lock " +
               LockArgument(joint) + " to hold it, or a --tip above it");
      }
    }
    if (chain_.empty()) {
      Fail("no revolute or continuous joint between the root link " + Quote(root.name) + " and " +
           Quote(tip->name) + " (--tip); nothing to identify: pass the arm's last link");
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
      if (options_.locked_joints.contains(joint.name)) out << " by --lock";
      out << ", into " << (locked.into.empty() ? "the ground" : "link " + Quote(locked.into)) << ")";
    }
    out << "; --lock JOINT=VALUE holds a joint at another value, --tip LINK chooses another end of the chain";
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
      for (const urdf::VisualSharedPtr& visual : Visuals(*member)) {
        if (visual->geometry == nullptr) continue;
        if (auto shape = ReadShape(*visual->geometry, X_BL * ToIsometry(visual->origin), where)) {
          link->shapes.push_back(std::move(*shape));
        }
      }
      for (const urdf::CollisionSharedPtr& collision : Collisions(*member)) {
        if (collision->geometry == nullptr) continue;
        if (auto shape = ReadShape(*collision->geometry, X_BL * ToIsometry(collision->origin), where)) {
          link->collision_shapes.push_back(std::move(*shape));
        }
      }
    }

    // The lumped body needs a mass.
    const std::string where = "link " + Quote(moving.name) + ": ";
    link->inertia = Lump(parts);
    if (!(link->inertia.mass > 0.0)) {
      Fail(where + "mass must be > 0, got " + Format(link->inertia.mass) + " (" +
           (parts.empty() ? "no <inertial>" : "the <inertial> <mass>") + " on it and the links held to it); give " +
           "it an <inertial> with an estimate of its mass (a prior that identification replaces), or hold joint " +
           Quote(link->joint_name) + " with --lock " + link->joint_name + "=VALUE");
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

  static std::vector<urdf::VisualSharedPtr> Visuals(const urdf::Link& link) {
    if (!link.visual_array.empty()) return link.visual_array;
    if (link.visual != nullptr) return {link.visual};
    return {};
  }
  static std::vector<urdf::CollisionSharedPtr> Collisions(const urdf::Link& link) {
    if (!link.collision_array.empty()) return link.collision_array;
    if (link.collision != nullptr) return {link.collision};
    return {};
  }

  // A <visual> or <collision> geometry placed at X_BG; nullopt (with a
  // warning) for a mesh that cannot be found or read.
  std::optional<Shape> ReadShape(const urdf::Geometry& geometry, const Eigen::Isometry3d& X_BG,
                                 const std::string& where) {
    Shape shape;
    shape.X_BG = X_BG;
    switch (geometry.type) {
      case urdf::Geometry::BOX: {
        const urdf::Vector3& dim = static_cast<const urdf::Box&>(geometry).dim;
        shape.kind = Shape::Kind::kBox;
        shape.size = Eigen::Vector3d(dim.x, dim.y, dim.z);
        break;
      }
      case urdf::Geometry::CYLINDER: {
        const auto& cylinder = static_cast<const urdf::Cylinder&>(geometry);
        shape.kind = Shape::Kind::kCylinder;
        shape.size = Eigen::Vector3d(cylinder.radius, cylinder.radius, cylinder.length);
        break;
      }
      case urdf::Geometry::SPHERE: {
        const double radius = static_cast<const urdf::Sphere&>(geometry).radius;
        shape.kind = Shape::Kind::kSphere;
        shape.size = Eigen::Vector3d::Constant(radius);
        break;
      }
      case urdf::Geometry::MESH: {
        const auto& mesh = static_cast<const urdf::Mesh&>(geometry);
        shape.kind = Shape::Kind::kMesh;
        shape.size = Eigen::Vector3d(mesh.scale.x, mesh.scale.y, mesh.scale.z);
        shape.mesh_uri = mesh.filename;
        shape.mesh = Mesh(mesh.filename, shape.size, where, &shape.mesh_uri);
        if (shape.mesh == nullptr) return std::nullopt;
        break;
      }
      default:
        return std::nullopt;
    }
    return shape;
  }

  // The mesh a <mesh filename> names, read once per file and scale; null with
  // a warning when it cannot be found or read (the link then lacks that shape).
  // A relative path in *uri is made absolute (so that a URDF written
  // elsewhere still finds it).
  std::shared_ptr<const TriangleMesh> Mesh(const std::string& uri, const Eigen::Vector3d& scale,
                                           const std::string& where, std::string* written_uri) {
    std::vector<std::string> looked;
    const std::optional<std::filesystem::path> path = ResolveMeshUri(uri, base_directory_, &looked);
    if (!path) {
      std::string places;
      for (const std::string& p : looked) places += (places.empty() ? "" : ", ") + p;
      warnings_.push_back(where + "mesh " + Quote(uri) + " not found (looked in " + places +
                          "; set ROS_PACKAGE_PATH for package:// names); shape skipped");
      return nullptr;
    }
    if (uri.find("://") == std::string::npos && std::filesystem::path(uri).is_relative()) *written_uri = path->string();
    const std::string key = path->string() + " " + std::to_string(scale.x()) + " " + std::to_string(scale.y()) +
                            " " + std::to_string(scale.z());
    // A file read (or refused, with its one warning) once: a mesh used by a
    // <visual> and a <collision> is not read or reported twice.
    if (const auto it = meshes_.find(key); it != meshes_.end()) return it->second;
    std::shared_ptr<const TriangleMesh>& mesh = meshes_[key];
    try {
      mesh = std::make_shared<const TriangleMesh>(LoadTriangleMesh(path->string(), scale));
    } catch (const std::exception& e) {
      warnings_.push_back(where + e.what() + "; the shapes using it are skipped");
    }
    return mesh;
  }

  const urdf::ModelInterface& urdf_;
  std::string source_;
  std::filesystem::path base_directory_;  // relative mesh paths start here
  const UrdfLoadOptions& options_;
  std::set<std::string> chain_;           // names of the joints that are the model's degrees of freedom
  std::vector<Locked> locked_;            // joints held still, in the order they were merged
  std::vector<std::string> warnings_;
  std::map<std::string, std::shared_ptr<const TriangleMesh>> meshes_;  // by path and scale; null: refused
};

// ---- Writing ----

// 17 significant digits: parses back to the same double. −0 is written as 0.
std::string Number(double value) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.17g", value == 0.0 ? 0.0 : value);
  return buffer;
}

std::string Numbers(const Eigen::Vector3d& v) {
  return Number(v.x()) + " " + Number(v.y()) + " " + Number(v.z());
}


std::string Attribute(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + EscapeXml(value) + "\"";
}

std::string Origin(const Eigen::Isometry3d& X) {
  return "<origin" + Attribute("xyz", Numbers(X.translation())) +
         Attribute("rpy", Numbers(RpyFromRotation(X.linear()))) + "/>";
}

// A name not in `taken`: `base`, else `base_1`, `base_2`, ...
std::string UniqueName(const std::string& base, const std::set<std::string>& taken) {
  if (!taken.contains(base)) return base;
  for (int k = 1;; ++k) {
    const std::string name = base + "_" + std::to_string(k);
    if (!taken.contains(name)) return name;
  }
}

// <visual> or <collision> with the shape's origin and geometry.
std::string ShapeElement(const std::string& tag, const Shape& shape) {
  std::ostringstream out;
  out << "    <" << tag << ">\n"
      << "      " << Origin(shape.X_BG) << "\n"
      << "      <geometry>";
  switch (shape.kind) {
    case Shape::Kind::kBox: out << "<box" << Attribute("size", Numbers(shape.size)) << "/>"; break;
    case Shape::Kind::kCylinder:
      out << "<cylinder" << Attribute("radius", Number(shape.size.x())) << Attribute("length", Number(shape.size.z()))
          << "/>";
      break;
    case Shape::Kind::kSphere: out << "<sphere" << Attribute("radius", Number(shape.size.x())) << "/>"; break;
    case Shape::Kind::kMesh:
      out << "<mesh" << Attribute("filename", shape.mesh_uri) << Attribute("scale", Numbers(shape.size)) << "/>";
      break;
  }
  out << "</geometry>\n"
      << "    </" << tag << ">\n";
  return out.str();
}

}  // namespace

Eigen::Matrix3d RotationFromRpy(const Eigen::Vector3d& rpy) {
  return (Eigen::AngleAxisd(rpy.z(), Eigen::Vector3d::UnitZ()) *
          Eigen::AngleAxisd(rpy.y(), Eigen::Vector3d::UnitY()) *
          Eigen::AngleAxisd(rpy.x(), Eigen::Vector3d::UnitX()))
      .toRotationMatrix();
}

Eigen::Vector3d RpyFromRotation(const Eigen::Matrix3d& R) {
  // R = Rz(y)·Ry(p)·Rx(r) has first column (cy·cp, sy·cp, −sp). Take yaw from
  // it (arbitrary, here 0, when cp = 0), then read pitch and roll from
  // M = Rz(y)ᵀ·R = Ry(p)·Rx(r) = [cp  sp·sr  sp·cr; 0  cr  −sr; −sp  cp·sr  cp·cr].
  // Near gimbal lock the yaw is poorly determined, but M's entries used here
  // have magnitude ~1 or are exact given that yaw, so Rz(y)·Ry(p)·Rx(r)
  // reproduces R to rounding for every pitch.
  const double yaw = std::atan2(R(1, 0), R(0, 0));
  const Eigen::Matrix3d M = Eigen::AngleAxisd(-yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix() * R;
  const double pitch = std::atan2(-M(2, 0), M(0, 0));
  const double roll = std::atan2(-M(1, 2), M(1, 1));
  return Eigen::Vector3d(roll, pitch, yaw);
}

bool UrdfLoadOptions::IsValid(std::string* why) const {
  for (const auto& [name, value] : locked_joints) {
    if (name.empty()) {
      *why = "--lock: a joint name is empty";
      return false;
    }
    if (!std::isfinite(value)) {
      *why = "--lock " + name + ": expected a finite value, got " + Format(value);
      return false;
    }
  }
  return true;
}

bool AddJointLock(const std::string& text, UrdfLoadOptions* options, std::string* why) {
  const auto fail = [&](const std::string& what) {
    *why = "--lock '" + text + "': " + what;
    return false;
  };
  const size_t equals = text.find('=');
  if (equals == std::string::npos || equals == 0) {
    return fail("expected JOINT=VALUE (VALUE in rad, or in m for a prismatic joint)");
  }
  const std::string name = text.substr(0, equals), number = text.substr(equals + 1);
  char* end = nullptr;
  const double value = std::strtod(number.c_str(), &end);
  if (number.empty() || end != number.c_str() + number.size() || !std::isfinite(value)) {
    return fail("expected a finite number after '=', got '" + number + "'");
  }
  if (!options->locked_joints.emplace(name, value).second) return fail("joint " + Quote(name) + " is locked twice");
  return true;
}

UrdfLoadResult LoadUrdfString(const std::string& xml, const std::string& source_name,
                               const std::string& base_directory, const UrdfLoadOptions& options) {
  // urdfdom reports why a file is invalid through console_bridge: keep the
  // first error for our one message instead of letting it print.
  struct FirstError : console_bridge::OutputHandler {
    std::string text;
    void log(const std::string& message, console_bridge::LogLevel level, const char*, int) override {
      if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR && text.empty()) text = message;
    }
  } first_error;
  internal::CheckUrdfDocument(xml, source_name);
  console_bridge::useOutputHandler(&first_error);
  urdf::ModelInterfaceSharedPtr urdf;
  try {
    urdf = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    console_bridge::restorePreviousOutputHandler();
    throw std::invalid_argument(source_name + ": not a valid URDF (" + e.what() + ")");
  }
  console_bridge::restorePreviousOutputHandler();
  // urdfdom logs an element it cannot parse and loads the rest without it:
  // any error it logs refuses the file.
  if (urdf == nullptr || urdf->getRoot() == nullptr || !first_error.text.empty()) {
    throw std::invalid_argument(source_name + ": not a valid URDF" +
                                (first_error.text.empty() ? "" : " (" + first_error.text + ")"));
  }
  return Loader(*urdf, source_name, std::filesystem::path(base_directory.empty() ? "." : base_directory), options)
      .Load();
}

UrdfLoadResult LoadUrdfFile(const std::string& path, const UrdfLoadOptions& options) {
  return LoadUrdfString(ReadInputFile(path), path, std::filesystem::path(path).parent_path().string(), options);
}

std::string WriteUrdf(const RobotModel& model) {
  // Names: URDF needs unique link and joint names; the ground gets a fresh one.
  std::set<std::string> link_names;
  std::set<std::string> joint_names;
  for (const Link& link : model.links()) {
    if (!link_names.insert(link.name).second) {
      throw std::invalid_argument("WriteUrdf: link " + Quote(link.name) +
                                  ": duplicate link name; URDF needs unique names");
    }
    if (!link.joint_name.empty() && !joint_names.insert(link.joint_name).second) {
      throw std::invalid_argument("WriteUrdf: link " + Quote(link.name) + ": duplicate joint name " +
                                  Quote(link.joint_name) + "; URDF needs unique names");
    }
  }
  std::string ground = "base";
  if (link_names.contains(ground)) ground = "world";
  ground = UniqueName(ground, link_names);
  std::vector<std::string> joint_name(static_cast<size_t>(model.n_links()));
  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);
    std::string& name = joint_name[static_cast<size_t>(i)];
    name = link.joint_name.empty() ? UniqueName(link.name + "_joint", joint_names) : link.joint_name;
    joint_names.insert(name);
  }

  std::ostringstream out;
  out << "<?xml version=\"1.0\"?>\n"
      << "<!-- Written by idbench::WriteUrdf. Not expressible in URDF and so not written:\n"
      << "     rotor inertia, acceleration limits, gravity. -->\n"
      << "<robot" << Attribute("name", model.name()) << ">\n"
      << "  <link" << Attribute("name", ground) << "/>\n";

  for (int i = 0; i < model.n_links(); ++i) {
    const Link& link = model.link(i);

    // The link: mass properties at the COM, then its shapes.
    const LinkInertia& inertia = link.inertia;
    const Eigen::Matrix3d& I = inertia.I_Bcm_B;
    out << "  <link" << Attribute("name", link.name) << ">\n"
        << "    <inertial>\n"
        << "      <origin" << Attribute("xyz", Numbers(inertia.p_BoBcm_B)) << " rpy=\"0 0 0\"/>\n"
        << "      <mass" << Attribute("value", Number(inertia.mass)) << "/>\n"
        << "      <inertia" << Attribute("ixx", Number(I(0, 0))) << Attribute("ixy", Number(I(0, 1)))
        << Attribute("ixz", Number(I(0, 2))) << Attribute("iyy", Number(I(1, 1)))
        << Attribute("iyz", Number(I(1, 2))) << Attribute("izz", Number(I(2, 2))) << "/>\n"
        << "    </inertial>\n";
    for (const Shape& shape : link.shapes) out << ShapeElement("visual", shape);
    for (const Shape& shape : link.collision_shapes) out << ShapeElement("collision", shape);
    out << "  </link>\n";

    // Its inboard joint. Infinite velocity/effort are written as 0, which the
    // loader (and the URDF convention) reads as "not given".
    const JointLimits& limits = link.limits;
    const bool bounded = std::isfinite(limits.q_min) && std::isfinite(limits.q_max);
    if (!bounded && (std::isfinite(limits.q_min) || std::isfinite(limits.q_max))) {
      throw std::invalid_argument("WriteUrdf: link " + Quote(link.name) +
                                  ": URDF cannot express a one-sided joint limit (q_min = " +
                                  Number(limits.q_min) + ", q_max = " + Number(limits.q_max) + ")");
    }
    const auto finite_or_zero = [](double value) { return std::isfinite(value) ? value : 0.0; };
    const std::string parent = link.parent < 0 ? ground : model.link(link.parent).name;
    out << "  <joint" << Attribute("name", joint_name[static_cast<size_t>(i)])
        << Attribute("type", bounded ? "revolute" : "continuous") << ">\n"
        << "    <parent" << Attribute("link", parent) << "/>\n"
        << "    <child" << Attribute("link", link.name) << "/>\n"
        << "    " << Origin(link.X_PJ) << "\n"
        << "    <axis" << Attribute("xyz", Numbers(link.axis_J)) << "/>\n";
    if (bounded || std::isfinite(limits.qd_max) || std::isfinite(limits.tau_max)) {
      out << "    <limit";
      if (bounded) out << Attribute("lower", Number(limits.q_min)) << Attribute("upper", Number(limits.q_max));
      out << Attribute("effort", Number(finite_or_zero(limits.tau_max)))
          << Attribute("velocity", Number(finite_or_zero(limits.qd_max))) << "/>\n";
    }
    if (link.dynamics.viscous != 0.0 || link.dynamics.coulomb != 0.0) {
      out << "    <dynamics" << Attribute("damping", Number(link.dynamics.viscous))
          << Attribute("friction", Number(link.dynamics.coulomb)) << "/>\n";
    }
    out << "  </joint>\n";
  }
  out << "</robot>\n";
  return out.str();
}

std::string EscapeXml(const std::string& text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

}  // namespace idbench
