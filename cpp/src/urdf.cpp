#include "robokin/urdf.hpp"

#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <urdf_parser/urdf_parser.h>

#include <limits>
#include <stdexcept>

namespace robokin {

namespace {

// kdl_parser puts each joint's axis through the URDF joint origin (a non-zero KDL joint origin).
// Rewritten here with the origin as a fixed segment and the joint through the origin of its own
// segment: the same motion (rotation about the same line), in the form Chain's fast path expects.
KDL::Chain normalised(const KDL::Chain& in) {
  KDL::Chain out;
  for (const KDL::Segment& seg : in.segments) {
    const KDL::Joint& j = seg.getJoint();
    if (j.getType() == KDL::Joint::Fixed || j.JointOrigin().Norm() == 0.0) {
      out.addSegment(seg);
      continue;
    }
    const KDL::Vector o = j.JointOrigin();
    out.addSegment(KDL::Segment(seg.getName() + "_joint_origin", KDL::Joint(KDL::Joint::Fixed),
                                KDL::Frame(o)));
    const KDL::Joint moved(j.getName(), KDL::Vector::Zero(), j.JointAxis(), j.getType());
    out.addSegment(KDL::Segment(seg.getName(), moved, KDL::Frame(-o) * seg.pose(0.0)));
  }
  return out;
}

}  // namespace

Chain chain_from_urdf(const std::string& xml, const std::string& base, const std::string& tip) {
  const urdf::ModelInterfaceSharedPtr model = urdf::parseURDF(xml);
  if (!model) throw std::invalid_argument("path_or_string: not a valid URDF document");
  if (!model->getLink(base)) throw std::invalid_argument("base: no link named '" + base + "' in the URDF");
  if (!model->getLink(tip)) throw std::invalid_argument("tip: no link named '" + tip + "' in the URDF");
  KDL::Tree tree;
  if (!kdl_parser::treeFromUrdfModel(*model, tree))
    throw std::invalid_argument("path_or_string: kdl_parser could not build a tree from the URDF");
  KDL::Chain chain;
  if (!tree.getChain(base, tip, chain))
    throw std::invalid_argument("base, tip: no chain from '" + base + "' to '" + tip + "'");
  const double inf = std::numeric_limits<double>::infinity();
  const int n = static_cast<int>(chain.getNrOfJoints());
  if (n == 0) throw std::invalid_argument("base, tip: no moving joint between '" + base + "' and '" + tip + "'");
  Vector lower(n), upper(n);
  int j = 0;
  for (const KDL::Segment& seg : chain.segments) {
    if (seg.getJoint().getType() == KDL::Joint::Fixed) continue;
    lower(j) = -inf;
    upper(j) = inf;
    const urdf::JointConstSharedPtr joint = model->getJoint(seg.getJoint().getName());
    if (joint && joint->limits && joint->type != urdf::Joint::CONTINUOUS &&
        joint->limits->lower < joint->limits->upper) {
      lower(j) = joint->limits->lower;
      upper(j) = joint->limits->upper;
    }
    ++j;
  }
  return Chain(normalised(chain), lower, upper);
}

}  // namespace robokin
