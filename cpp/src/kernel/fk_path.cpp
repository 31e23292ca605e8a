// Building a chain's evaluation path (fk_path.hpp) from its KDL segments.
#include "fk_path.hpp"

#include <algorithm>
#include <cmath>

namespace robokin {

namespace kernel {

namespace {

// A rotation whose z axis is `axis` (exactly the identity for +z, as in DH chains).
Rigid frame_with_z(const Eigen::Vector3d& axis) {
  Rigid g;
  const Eigen::Vector3d z = axis.normalized();
  if (z.isApprox(Eigen::Vector3d::UnitZ(), 1e-15)) return g;
  const Eigen::Vector3d helper =
      std::abs(z.x()) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  const Eigen::Vector3d y = z.cross(helper).normalized();
  g.R.col(0) = y.cross(z);
  g.R.col(1) = y;
  g.R.col(2) = z;
  return g;
}

// Follows which entries of R can be non-zero along the chain (nz), starting from the base.
void build_masks(FkPath& path) {
  bool nz[3][3];
  for (int i = 0; i < 3; ++i)
    for (int k = 0; k < 3; ++k) nz[i][k] = path.base.R(i, k) != 0.0;
  for (Link& link : path.links) {
    link.rows = link.slide = link.move = link.turn = 0;
    for (int i = 0; i < 3; ++i) {
      if (link.prismatic) {
        for (int k = 0; k < 3; ++k)
          if (nz[i][k] && link.axis(k) != 0.0) link.slide |= 1u << (3 * i + k);
      } else if (nz[i][0] || nz[i][1]) {
        link.rows |= 1u << i;
        nz[i][0] = nz[i][1] = true;
      }
    }
    const Fixed& f = link.after;
    for (int i = 0; i < 3; ++i) {
      for (int k = 0; k < 3; ++k)
        if (f.move && nz[i][k] && f.F.p(k) != 0.0) link.move |= 1u << (3 * i + k);
      if (f.turn && (nz[i][0] || nz[i][1] || nz[i][2])) {
        link.turn |= 1u << i;
        bool row[3];
        for (int j = 0; j < 3; ++j) {
          row[j] = false;
          for (int k = 0; k < 3; ++k) row[j] = row[j] || (nz[i][k] && f.F.R(k, j) != 0.0);
        }
        for (int j = 0; j < 3; ++j) nz[i][j] = row[j];
      }
    }
  }
}

}  // namespace

Fixed Fixed::of(const Rigid& F) {
  Fixed f;
  f.F = F;
  f.move = !F.p.isZero(0.0);
  f.turn = F.R != Eigen::Matrix3d::Identity();
  return f;
}

// Rewrites the chain as base * Mz(s_1 q_1) * after_1 * ... * Mz(s_n q_n) * after_n, where Mz is a
// rotation about (or translation along) the local z axis: each joint then costs one sin/cos pair
// and one rigid product.
FkPath build_fk_path(const KDL::Chain& chain) {
  FkPath path;
  std::vector<Link>& links = path.links;
  Rigid since_motion;  // fixed transform accumulated since the last joint motion
  for (const KDL::Segment& seg : chain.segments) {
    const KDL::Joint& joint = seg.getJoint();
    if (joint.getType() == KDL::Joint::Fixed) {
      since_motion = since_motion * Rigid::from_kdl(seg.pose(0.0));
      continue;
    }
    const bool prismatic = joint.getType() >= KDL::Joint::TransAxis;
    const KDL::Vector a = joint.JointAxis();
    const Eigen::Vector3d axis(a.x(), a.y(), a.z());
    // KDL: joint.pose(q) = Frame(Rot(axis, scale q + offset), origin), so joint.pose(q) =
    // P0 * G Mz(scale q) G^-1 with G a rotation taking z to the axis (no translation).
    // A prismatic joint slides along its axis as it is (no turn to z and back).
    const Rigid G = prismatic ? Rigid() : frame_with_z(axis);
    const Rigid P0 = Rigid::from_kdl(joint.pose(0.0)), P1 = Rigid::from_kdl(joint.pose(1.0));
    // The joint's scale: how far one unit of q moves it (1 for every chain robokin builds).
    double scale;
    if (prismatic) {
      scale = (P1.p - P0.p).dot(axis.normalized());
    } else {
      const Eigen::Matrix3d rel = P0.R.transpose() * P1.R;
      const Eigen::Vector3d w(rel(2, 1) - rel(1, 2), rel(0, 2) - rel(2, 0), rel(1, 0) - rel(0, 1));
      scale = std::atan2(0.5 * w.dot(axis.normalized()), 0.5 * (rel.trace() - 1.0));
    }
    if (std::abs(scale - 1.0) < 1e-12) scale = 1.0;
    const Rigid before = since_motion * P0 * G;
    if (links.empty()) path.base = before;
    else links.back().after = Fixed::of(before);
    links.push_back({prismatic, scale, prismatic ? axis.normalized() : Eigen::Vector3d::UnitZ(), Fixed()});
    since_motion = G.inverse() * P0.inverse() * Rigid::from_kdl(seg.pose(0.0));
  }
  links.back().after = Fixed::of(since_motion);
  path.turns = std::all_of(links.begin(), links.end(), [](const Link& l) { return !l.prismatic && l.scale == 1.0; });
  build_masks(path);
  return path;
}

}  // namespace kernel

}  // namespace robokin
