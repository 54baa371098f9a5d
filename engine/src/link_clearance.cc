#include "idbench/engine/link_clearance.h"

#include "hull_climb.h"

#include <BulletCollision/CollisionShapes/btBoxShape.h>
#include <BulletCollision/CollisionShapes/btConvexHullShape.h>
#include <BulletCollision/CollisionShapes/btCylinderShape.h>
#include <BulletCollision/CollisionShapes/btSphereShape.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkEpaPenetrationDepthSolver.h>
#include <BulletCollision/NarrowPhaseCollision/btGjkPairDetector.h>
#include <BulletCollision/NarrowPhaseCollision/btPointCollector.h>
#include <BulletCollision/NarrowPhaseCollision/btVoronoiSimplexSolver.h>

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <optional>
#include <stdexcept>

namespace idbench {
namespace {

btVector3 ToBt(const Eigen::Vector3d& v) { return btVector3(v.x(), v.y(), v.z()); }
Eigen::Vector3d FromBt(const btVector3& v) { return Eigen::Vector3d(v.x(), v.y(), v.z()); }

btTransform ToBt(const Eigen::Matrix3d& R, const Eigen::Vector3d& p) {
  btMatrix3x3 basis(R(0, 0), R(0, 1), R(0, 2), R(1, 0), R(1, 1), R(1, 2), R(2, 0), R(2, 1), R(2, 2));
  return btTransform(basis, ToBt(p));
}

// A mesh hull as GJK sees it, its support point found by climbing the
// hull's edges (internal::HullClimb) from the one this object last returned
// instead of btConvexHullShape's scan of every point: the same point set and
// margin, so the same shape. One lives for one GJK/EPA query (its warm start
// is the query's own, so shapes stay shared between threads). Its shape type
// is CUSTOM_CONVEX_SHAPE_TYPE, for which Bullet's non-virtual support and
// margin calls fall through to these virtual ones.
class ClimbingHullShape final : public btConvexInternalShape {
 public:
  ClimbingHullShape(const internal::HullClimb& hull, btScalar margin) : hull_(hull) {
    m_shapeType = CUSTOM_CONVEX_SHAPE_TYPE;
    setMargin(margin);
  }
  btVector3 localGetSupportingVertexWithoutMargin(const btVector3& d) const override {
    return ToBt(hull_.vertex(hull_.Support(Eigen::Vector3d(d.x(), d.y(), d.z()), &last_)));
  }
  void batchedUnitVectorGetSupportingVertexWithoutMargin(const btVector3* d, btVector3* out, int n) const override {
    for (int i = 0; i < n; ++i) out[i] = localGetSupportingVertexWithoutMargin(d[i]);
  }
  void calculateLocalInertia(btScalar, btVector3& inertia) const override { inertia.setZero(); }
  const char* getName() const override { return "ClimbingHull"; }

 private:
  const internal::HullClimb& hull_;
  mutable int last_ = -1;  // the last support vertex: the next climb's start
};

// The distance between the segments p1–q1 and p2–q2 (Ericson, Real-Time
// Collision Detection, 5.1.9).
double SegmentDistance(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                       const Eigen::Vector3d& q2) {
  constexpr double kEps = 1e-18;
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p1 - p2;
  const double a = d1.squaredNorm(), e = d2.squaredNorm(), f = d2.dot(r);
  double s = 0.0, t = 0.0;
  if (a <= kEps && e <= kEps) return r.norm();
  if (a <= kEps) {
    t = std::clamp(f / e, 0.0, 1.0);
  } else {
    const double c = d1.dot(r);
    if (e <= kEps) {
      s = std::clamp(-c / a, 0.0, 1.0);
    } else {
      const double b = d1.dot(d2), denom = a * e - b * b;
      s = denom > 0.0 ? std::clamp((b * f - c * e) / denom, 0.0, 1.0) : 0.0;
      t = (b * s + f) / e;
      if (t < 0.0) t = 0.0, s = std::clamp(-c / a, 0.0, 1.0);
      else if (t > 1.0) t = 1.0, s = std::clamp((b - c) / a, 0.0, 1.0);
    }
  }
  return (p1 + s * d1 - (p2 + t * d2)).norm();
}

// The distance from p to the segment a–b.
double PointSegmentDistance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  const Eigen::Vector3d d = b - a;
  const double dd = d.squaredNorm();
  const double t = dd > 0.0 ? std::clamp((p - a).dot(d) / dd, 0.0, 1.0) : 0.0;
  return (p - a - t * d).norm();
}

}  // namespace

ClearanceOther ClearancePair::other() const {
  return link_b >= 0        ? ClearanceOther::kLink
         : obstacle >= 0    ? ClearanceOther::kObstacle
         : ground_link >= 0 ? ClearanceOther::kGroundLink
                            : ClearanceOther::kFloor;
}

std::string ClearancePair::Other(const RobotModel& model) const {
  switch (other()) {
    case ClearanceOther::kLink: return model.link(link_b).name;
    case ClearanceOther::kObstacle: return obstacle_name;
    case ClearanceOther::kGroundLink: return model.ground().at(static_cast<size_t>(ground_link)).name;
    case ClearanceOther::kFloor: break;
  }
  return "ground";
}

std::string ClearancePair::Name(const RobotModel& model) const { return model.link(link_a).name + "–" + Other(model); }

struct ClearanceModel::Impl {
  struct LinkShape {
    std::unique_ptr<btConvexShape> shape;
    Eigen::Isometry3d X_BG;
    // A mesh hull's edge graph, for GJK's support calls (ClimbingHullShape);
    // null (or not usable) for other shapes: Bullet's own support.
    std::unique_ptr<internal::HullClimb> climb;
    // A capsule holding the shape as GJK sees it (margin included): the
    // points within capsule_radius of the segment e0–e1 (in G).
    Eigen::Vector3d e0 = Eigen::Vector3d::Zero(), e1 = Eigen::Vector3d::Zero();
    double capsule_radius = 0.0;
  };
  std::vector<std::vector<LinkShape>> shapes;  // per link
  std::vector<std::vector<LinkShape>> obstacles;     // one shape each; X_BG is X_RO: the obstacle in the base frame
  std::vector<std::vector<LinkShape>> ground_links;  // per RobotModel::ground() link; X_BG in the base frame
  Eigen::Vector3d n_R = Eigen::Vector3d::UnitZ();  // the floor's normal in R (up)
  double floor_h = 0.0;                            // [m] height of R's origin above the floor

  // A shape as GJK checks it (1 mm inflated but a sphere, see the
  // constructor) and the radius of a sphere about its origin holding it.
  static LinkShape Convex(const Shape& s, const Eigen::Isometry3d& X_BG);

  // Closest points of two placed shapes: Pair on their hulls' climbing
  // support (ClimbingHullShape) where they have one.
  static Clearance Pair(const LinkShape& a, const btTransform& X_WA, const LinkShape& b, const btTransform& X_WB) {
    auto climbing = [](const LinkShape& s) -> std::optional<ClimbingHullShape> {
      if (!s.climb || !s.climb->usable()) return std::nullopt;
      return std::optional<ClimbingHullShape>(std::in_place, *s.climb, s.shape->getMargin());
    };
    const std::optional<ClimbingHullShape> ca = climbing(a), cb = climbing(b);
    return Pair(ca ? static_cast<const btConvexShape*>(&*ca) : a.shape.get(), X_WA,
                cb ? static_cast<const btConvexShape*>(&*cb) : b.shape.get(), X_WB);
  }

  // Closest points of two placed convex shapes; distance < 0 when overlapping.
  static Clearance Pair(const btConvexShape* a, const btTransform& X_WA, const btConvexShape* b,
                        const btTransform& X_WB) {
    btVoronoiSimplexSolver simplex;
    btGjkEpaPenetrationDepthSolver epa;
    btGjkPairDetector gjk(a, b, &simplex, &epa);
    btGjkPairDetector::ClosestPointInput input;
    input.m_transformA = X_WA;
    input.m_transformB = X_WB;
    btPointCollector out;
    gjk.getClosestPoints(input, out, nullptr);
    Clearance c;
    c.distance = out.m_distance;
    c.n_W = FromBt(out.m_normalOnBInWorld);  // from B towards A
    c.p_a_W = FromBt(out.m_pointInWorld) + c.n_W * c.distance;  // m_pointInWorld is on B
    return c;
  }

  // A mesh's convex hull for GJK, whose cost grows with the hull's points:
  // above kMaxHullPoints, the hull's support points in kHullDirections
  // directions (a Fibonacci sphere) instead — an inner hull — and *gap gets
  // how far the full hull reaches beyond it (GJK from each of its points), so
  // that the inner hull grown by *gap still holds the mesh.
  static std::unique_ptr<btConvexHullShape> MeshHull(const TriangleMesh& mesh, double* gap) {
    constexpr int kMaxHullPoints = 256, kHullDirections = 256;
    auto full = std::make_unique<btConvexHullShape>();
    for (const Eigen::Vector3d& v : mesh.vertices) full->addPoint(ToBt(v), false);
    full->recalcLocalAabb();
    full->optimizeConvexHull();
    *gap = 0.0;
    if (full->getNumPoints() <= kMaxHullPoints) return full;
    auto inner = std::make_unique<btConvexHullShape>();
    const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
    for (int k = 0; k < kHullDirections; ++k) {
      const double z = 1.0 - 2.0 * (k + 0.5) / kHullDirections, r = std::sqrt(1.0 - z * z);
      const btVector3 d(r * std::cos(golden * k), r * std::sin(golden * k), z);
      inner->addPoint(full->localGetSupportingVertexWithoutMargin(d), false);
    }
    inner->recalcLocalAabb();
    inner->optimizeConvexHull();
    inner->setMargin(0.0);
    const btSphereShape point(0.0);
    btTransform X_WP = btTransform::getIdentity();
    for (int k = 0; k < full->getNumPoints(); ++k) {
      X_WP.setOrigin(full->getPoints()[k]);
      *gap = std::max(*gap, Pair(&point, X_WP, inner.get(), btTransform::getIdentity()).distance);
    }
    return inner;
  }

  // Lowest point of a placed shape: the support point of its core along −z,
  // lowered by the margin (the rounded shell GJK sees, also for boxes, whose
  // own support point with margin is a larger box).
  Clearance Ground(const btConvexShape* a, const btTransform& X_WA) const {
    const btVector3 down_A = X_WA.getBasis().transpose() * ToBt(-n_R);
    const btVector3 lowest = X_WA * (a->localGetSupportingVertexWithoutMargin(down_A) + a->getMargin() * down_A);
    Clearance c;
    c.p_a_W = FromBt(lowest);
    c.distance = n_R.dot(c.p_a_W) + floor_h;
    c.n_W = n_R;
    return c;
  }

  // A shape's capsule segment placed by link (or, link < 0, an obstacle's in R).
  void Segment(const KinematicsData<double>& k, int link, const LinkShape& s, Eigen::Vector3d* a,
               Eigen::Vector3d* b) const {
    if (link < 0) {
      *a = s.X_BG * s.e0, *b = s.X_BG * s.e1;
      return;
    }
    const size_t i = static_cast<size_t>(link);
    const Eigen::Matrix3d R = k.R_WB[i] * s.X_BG.linear();
    const Eigen::Vector3d o = k.p_WBo_W[i] + k.R_WB[i] * s.X_BG.translation();
    *a = o + R * s.e0, *b = o + R * s.e1;
  }

  // A lower bound of the distance between shape sa of link a and the other
  // side's shape sb (link b ≥ 0, an obstacle, or the floor when sb is null):
  // their capsules' distance, less kBoundTolerance.
  double Bound(const KinematicsData<double>& k, const ClearancePair& pair, const LinkShape& sa,
               const LinkShape* sb) const {
    constexpr double kBoundTolerance = 1e-9;  // [m] rounding: never above GJK's distance
    Eigen::Vector3d a0, a1, b0, b1;
    Segment(k, pair.link_a, sa, &a0, &a1);
    if (!sb) return std::min(n_R.dot(a0), n_R.dot(a1)) + floor_h - sa.capsule_radius - kBoundTolerance;
    Segment(k, pair.link_b, *sb, &b0, &b1);
    return SegmentDistance(a0, a1, b0, b1) - sa.capsule_radius - sb->capsule_radius - kBoundTolerance;
  }

  // The other side's shapes: a link's (placed by its pose), an obstacle's or
  // a ground link's (placed in R); null for the floor.
  const std::vector<LinkShape>* OtherShapes(const ClearancePair& pair) const {
    switch (pair.other()) {
      case ClearanceOther::kLink: return &shapes[static_cast<size_t>(pair.link_b)];
      case ClearanceOther::kObstacle: return &obstacles[static_cast<size_t>(pair.obstacle)];
      case ClearanceOther::kGroundLink: return &ground_links[static_cast<size_t>(pair.ground_link)];
      case ClearanceOther::kFloor: break;
    }
    return nullptr;
  }

  // The pair's lower bound: the least over its shape pairs.
  double PairBound(const KinematicsData<double>& k, const ClearancePair& pair) const {
    double bound = std::numeric_limits<double>::infinity();
    const std::vector<LinkShape>* others = OtherShapes(pair);
    for (const LinkShape& sa : shapes[static_cast<size_t>(pair.link_a)]) {
      if (!others) {
        bound = std::min(bound, Bound(k, pair, sa, nullptr));
        continue;
      }
      for (const LinkShape& sb : *others) bound = std::min(bound, Bound(k, pair, sa, &sb));
    }
    return bound;
  }

  // The pair's clearance; shape pairs whose capsules are at least
  // `at_least` apart are not passed to GJK. When all are, the result is that
  // lower bound (distance ≥ at_least; points and normal unset).
  Clearance Compute(const KinematicsData<double>& k, const ClearancePair& pair,
                    double at_least = std::numeric_limits<double>::infinity()) const {
    Clearance best;
    best.distance = std::numeric_limits<double>::infinity();
    double bound = std::numeric_limits<double>::infinity();
    // A shape placed by its link's pose, or (link < 0) fixed in R.
    auto placed = [&](int link, const LinkShape& s) {
      if (link < 0) return ToBt(s.X_BG.linear(), s.X_BG.translation());
      const size_t i = static_cast<size_t>(link);
      return ToBt(k.R_WB[i] * s.X_BG.linear(), k.p_WBo_W[i] + k.R_WB[i] * s.X_BG.translation());
    };
    const bool prune = std::isfinite(at_least);
    const std::vector<LinkShape>* others = OtherShapes(pair);
    for (const LinkShape& sa : shapes[static_cast<size_t>(pair.link_a)]) {
      if (!others) {  // the floor: exact and cheap, no bound needed
        const Clearance c = Ground(sa.shape.get(), placed(pair.link_a, sa));
        if (c.distance < best.distance) best = c;
        continue;
      }
      for (const LinkShape& sb : *others) {
        const double lower = prune ? Bound(k, pair, sa, &sb) : -std::numeric_limits<double>::infinity();
        if (lower >= std::min(at_least, best.distance)) {
          bound = std::min(bound, lower);
          continue;
        }
        const Clearance c = Pair(sa, placed(pair.link_a, sa), sb, placed(pair.link_b, sb));
        if (c.distance < best.distance) best = c;
      }
    }
    if (!std::isfinite(best.distance)) best.distance = bound;  // every shape pair pruned
    return best;
  }
};

// Bullet keeps a margin around convex shapes (GJK works on the core and
// rounds it by the margin). Every shape but a sphere gets a 1 mm margin
// outside its true surface: boxes and cylinders are built 1 mm larger (Bullet
// takes the margin off their extents), mesh hulls are rounded by it. So each
// is its Minkowski sum with a 1 mm ball: never smaller than the shape, every
// distance at most 1 mm short per shape (conservative), corners included.
ClearanceModel::Impl::LinkShape ClearanceModel::Impl::Convex(const Shape& s, const Eigen::Isometry3d& X_BG) {
  constexpr double kMargin = 1e-3;
  std::unique_ptr<btConvexShape> shape;
  double gap = 0.0;  // a reduced mesh hull's extra margin
  switch (s.kind) {
    case Shape::Kind::kCylinder:
      shape = std::make_unique<btCylinderShapeZ>(
          btVector3(s.size.x() + kMargin, s.size.y() + kMargin, 0.5 * s.size.z() + kMargin));
      break;
    case Shape::Kind::kBox:
      shape = std::make_unique<btBoxShape>(ToBt(0.5 * s.size + Eigen::Vector3d::Constant(kMargin)));
      break;
    case Shape::Kind::kSphere:
      shape = std::make_unique<btSphereShape>(s.size.x());
      break;
    case Shape::Kind::kMesh:  // its convex hull (reduced, with the gap added to the margin)
      shape = Impl::MeshHull(*s.mesh, &gap);
      break;
  }
  if (s.kind != Shape::Kind::kSphere) shape->setMargin(kMargin + gap);
  // The bounding capsule: along a box's longest side, a cylinder's axis, a
  // mesh's principal axis (through its vertices' centroid).
  LinkShape out{std::move(shape), X_BG, nullptr, Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero(), 0.0};
  if (s.kind == Shape::Kind::kMesh) {
    const auto* hull = static_cast<const btConvexHullShape*>(out.shape.get());
    std::vector<Eigen::Vector3d> points;
    for (int k = 0; k < hull->getNumPoints(); ++k) points.push_back(FromBt(hull->getUnscaledPoints()[k]));
    out.climb = std::make_unique<internal::HullClimb>(points);
  }
  switch (s.kind) {
    case Shape::Kind::kSphere:
      out.capsule_radius = s.size.x();
      break;
    case Shape::Kind::kCylinder:
      out.e0 = Eigen::Vector3d(0, 0, -(0.5 * s.size.z() + kMargin)), out.e1 = -out.e0;
      out.capsule_radius = s.size.x() + kMargin;
      break;
    case Shape::Kind::kBox: {
      const Eigen::Vector3d half = 0.5 * s.size + Eigen::Vector3d::Constant(kMargin);
      Eigen::Index axis = 0;
      half.maxCoeff(&axis);
      out.e1[axis] = half[axis], out.e0[axis] = -half[axis];
      Eigen::Vector3d across = half;
      across[axis] = 0.0;
      out.capsule_radius = across.norm();
      break;
    }
    case Shape::Kind::kMesh: {
      const std::vector<Eigen::Vector3d>& v = s.mesh->vertices;
      Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
      for (const Eigen::Vector3d& p : v) centroid += p;
      centroid /= static_cast<double>(v.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const Eigen::Vector3d& p : v) cov += (p - centroid) * (p - centroid).transpose();
      const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
      const Eigen::Vector3d axis = eig.eigenvectors().col(2);  // the largest eigenvalue's
      double lo = std::numeric_limits<double>::infinity(), hi = -lo;
      for (const Eigen::Vector3d& p : v) lo = std::min(lo, (p - centroid).dot(axis)), hi = std::max(hi, (p - centroid).dot(axis));
      out.e0 = centroid + lo * axis, out.e1 = centroid + hi * axis;
      for (const Eigen::Vector3d& p : v) out.capsule_radius = std::max(out.capsule_radius, PointSegmentDistance(p, out.e0, out.e1));
      // The inner hull's points are vertices of the mesh; GJK rounds it by the margin and the gap.
      out.capsule_radius += kMargin + gap;
      break;
    }
  }
  return out;
}

ClearanceModel::ClearanceModel(const RobotModel& model, double min_clearance, const Cell& scene,
                               const BasePose& base)
    : impl_(std::make_unique<Impl>()), min_clearance_(min_clearance) {
  if (!(min_clearance >= 0.0) || !std::isfinite(min_clearance)) {
    throw std::invalid_argument("clearance must be finite and >= 0 m");
  }
  std::string why;
  if (!scene.IsValid(&why)) throw std::invalid_argument("scene: " + why);
  if (!base.IsValid(&why)) throw std::invalid_argument(why);
  // Each link's and each ground link's shapes (meshes without vertices skipped).
  auto convex_shapes = [](const std::vector<Shape>& from) {
    std::vector<Impl::LinkShape> out;
    for (const Shape& s : from) {
      if (s.kind == Shape::Kind::kMesh && (s.mesh == nullptr || s.mesh->vertices.empty())) continue;
      out.push_back(Impl::Convex(s, s.X_BG));
    }
    return out;
  };
  for (const Link& link : model.links()) impl_->shapes.push_back(convex_shapes(link.CollisionShapes()));
  for (const GroundLink& link : model.ground()) impl_->ground_links.push_back(convex_shapes(link.CollisionShapes()));
  // The cell in the base frame R.
  const Eigen::Isometry3d X_WR = base.X_WR(), X_RW = X_WR.inverse();
  impl_->n_R = X_WR.linear().transpose() * Eigen::Vector3d::UnitZ();
  impl_->floor_h = X_WR.translation().z();
  for (const Obstacle& o : scene.obstacles) {
    impl_->obstacles.emplace_back();
    impl_->obstacles.back().push_back(Impl::Convex(o.shape, X_RW * o.X_WO));
  }
  // Candidate pairs: every pair of links with shapes, each link with the
  // cell and with the ground links, but those in contact by construction and
  // those out of reach (link_clearance.h).
  KinematicsData<double> home(model);
  const Eigen::VectorXd zero = Eigen::VectorXd::Zero(model.n_dof());
  ComputeKinematicsT<double>(model, zero, zero, zero, &home);
  constexpr double kTouching = 0.0;  // [m] measured (1 mm inflated shapes): a true gap under 2 mm
  // Whether no joint can change link a's height: all joints to it turn about
  // the world's vertical (then every point of it keeps its height).
  auto height_fixed = [&](int a) {
    for (int j = a; j >= 0; j = model.link(j).parent) {
      if (std::abs(home.axis_W[static_cast<size_t>(j)].dot(impl_->n_R)) < 1.0 - 1e-9) return false;
    }
    return true;
  };
  // The farthest point of a link's shapes (as GJK sees them) from its origin.
  auto shapes_radius = [&](int link) {
    double r = 0.0;
    for (const Impl::LinkShape& sh : impl_->shapes[static_cast<size_t>(link)]) {
      r = std::max({r, (sh.X_BG * sh.e0).norm() + sh.capsule_radius, (sh.X_BG * sh.e1).norm() + sh.capsule_radius});
    }
    return r;
  };
  // Whether ground link g is out of link a's reach: at any pose, every point
  // of a is within shapes_radius + the hinge-to-hinge lengths of the origin
  // of its chain's first link, a point fixed in R; the ground link's
  // capsules are farther than that (and the clearance) from it.
  auto out_of_reach = [&](int a, int g, double* apart) {
    double reach = shapes_radius(a);
    int first = a;
    for (; model.link(first).parent >= 0; first = model.link(first).parent) {
      reach += model.link(first).X_PJ.translation().norm();
    }
    const Eigen::Vector3d o_R = model.link(first).X_PJ.translation();
    double nearest = std::numeric_limits<double>::infinity();
    for (const Impl::LinkShape& sh : impl_->ground_links[static_cast<size_t>(g)]) {
      nearest = std::min(nearest, PointSegmentDistance(o_R, sh.X_BG * sh.e0, sh.X_BG * sh.e1) - sh.capsule_radius);
    }
    *apart = nearest - reach;
    return *apart > min_clearance;
  };
  // Link a's candidates: the obstacles, the floor, the ground links, the links before it.
  auto candidates = [&](int a) {
    std::vector<ClearancePair> out;
    ClearancePair pair;
    pair.link_a = a;
    for (int o = 0; o < static_cast<int>(scene.obstacles.size()); ++o) {
      pair.obstacle = o, pair.obstacle_name = scene.ObstacleName(o);
      out.push_back(pair);
    }
    pair.obstacle = -1, pair.obstacle_name.clear();
    if (scene.floor) out.push_back(pair);
    for (int g = 0; g < static_cast<int>(impl_->ground_links.size()); ++g) {
      if (impl_->ground_links[static_cast<size_t>(g)].empty()) continue;
      pair.ground_link = g;
      out.push_back(pair);
    }
    pair.ground_link = -1;
    for (int b = 0; b < a; ++b) {
      if (impl_->shapes[static_cast<size_t>(b)].empty()) continue;
      pair.link_b = b;
      out.push_back(pair);
    }
    return out;
  };
  char buf[160];
  for (int a = 0; a < model.n_links(); ++a) {
    if (impl_->shapes[static_cast<size_t>(a)].empty()) continue;
    for (ClearancePair& pair : candidates(a)) {
      const ClearanceOther other = pair.other();
      const bool hinged = other == ClearanceOther::kLink ? model.link(a).parent == pair.link_b
                                                         : other == ClearanceOther::kGroundLink && model.link(a).parent < 0;
      if (hinged) {
        excluded_.push_back(pair.Name(model) + ": joined by joint '" + model.link(a).joint_name + "'");
        continue;
      }
      if (double apart = 0.0; other == ClearanceOther::kGroundLink && out_of_reach(a, pair.ground_link, &apart)) {
        std::snprintf(buf, sizeof buf, ": out of reach (over %.3g m apart at any pose)", apart);
        excluded_.push_back(pair.Name(model) + buf);
        continue;
      }
      const double d = impl_->Compute(home, pair).distance;
      if (d <= kTouching && other == ClearanceOther::kLink) {
        std::snprintf(buf, sizeof buf, ": in contact at q = 0 (%.3g m), by construction", d);
        excluded_.push_back(pair.Name(model) + buf);
        continue;
      }
      // Only the floor's distance is the same at every pose of a link that
      // turns about the vertical: an obstacle or a ground link beside it is not.
      if (d <= kTouching && other == ClearanceOther::kFloor && height_fixed(a)) {
        std::snprintf(buf, sizeof buf, ": on the ground at q = 0 (%.3g m) and no joint raises it (a base on the floor)",
                      d);
        excluded_.push_back(pair.Name(model) + buf);
        continue;
      }
      pair.home_distance = d;
      pair.reach.assign(static_cast<size_t>(model.n_dof()), 0.0);
      for (int side = 0; side < 2; ++side) {
        const int link = side == 0 ? a : pair.link_b;
        const int other_link = side == 0 ? pair.link_b : a;
        if (link < 0) continue;
        // The farthest point of the link's shapes from its origin, then from
        // each joint up its chain (adding the fixed hinge-to-hinge lengths).
        double r = shapes_radius(link);
        for (int j = link; j >= 0; j = model.link(j).parent) {
          bool shared = false;  // a joint on the other side's chain too
          for (int o = other_link; o >= 0; o = model.link(o).parent) shared = shared || o == j;
          if (!shared) pair.reach[static_cast<size_t>(j)] += r;
          r += model.link(j).X_PJ.translation().norm();
        }
      }
      // An obstacle is where the cell puts it, not a part of the robot that
      // q = 0 may overlap by construction: its pairs keep the full clearance,
      // but for a link resting on it at q = 0 that no joint raises (a base
      // on a table top, a link beside a post), held at its distance there.
      // Every other pair may not come closer than it is at q = 0.
      const bool by_epa = d <= kTouching && other != ClearanceOther::kFloor;  // a penetration depth
      const double held = d - (by_epa ? kContactTolerance : kHomeTolerance);
      pair.minimum = other != ClearanceOther::kObstacle       ? std::min(min_clearance, held)
                     : d <= kTouching && height_fixed(a) ? held
                                                         : min_clearance;
      pairs_.push_back(pair);
    }
  }
}

int ClearanceModel::n_held_at_home() const {
  return static_cast<int>(std::count_if(pairs_.begin(), pairs_.end(),
                                        [&](const ClearancePair& p) { return p.minimum < min_clearance_; }));
}

ClearanceModel::~ClearanceModel() = default;
ClearanceModel::ClearanceModel(ClearanceModel&&) noexcept = default;
ClearanceModel& ClearanceModel::operator=(ClearanceModel&&) noexcept = default;

void ClearanceModel::Compute(const KinematicsData<double>& k, std::vector<Clearance>* out,
                             const std::vector<double>* at_least) const {
  out->resize(pairs_.size());
  for (size_t i = 0; i < pairs_.size(); ++i) {
    (*out)[i] = at_least ? impl_->Compute(k, pairs_[i], (*at_least)[i]) : impl_->Compute(k, pairs_[i]);
  }
}

Clearance ClearanceModel::ComputePair(const KinematicsData<double>& k, int i, double at_least) const {
  return impl_->Compute(k, pairs_.at(static_cast<size_t>(i)), at_least);
}

double ClearanceModel::LowerBound(const KinematicsData<double>& k, int i) const {
  return impl_->PairBound(k, pairs_.at(static_cast<size_t>(i)));
}

Eigen::VectorXd ClearanceModel::DistanceGradient(const RobotModel& model, const KinematicsData<double>& k,
                                                 const ClearancePair& pair, const Clearance& c) const {
  // d = nᵀ (p_a − p_b); a point fixed in a link moves by s_j × (p − o_j) per
  // unit q_j of every joint j on its chain.
  Eigen::VectorXd g = Eigen::VectorXd::Zero(model.n_dof());
  const Eigen::Vector3d p_b = c.p_a_W - c.distance * c.n_W;
  for (int j = pair.link_a; j >= 0; j = model.link(j).parent) {
    const size_t jj = static_cast<size_t>(j);
    g[j] += c.n_W.dot(k.axis_W[jj].cross(c.p_a_W - k.p_WBo_W[jj]));
  }
  for (int j = pair.link_b; j >= 0; j = model.link(j).parent) {
    const size_t jj = static_cast<size_t>(j);
    g[j] -= c.n_W.dot(k.axis_W[jj].cross(p_b - k.p_WBo_W[jj]));
  }
  return g;
}

}  // namespace idbench
