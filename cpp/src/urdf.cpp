#include "robokin/urdf.hpp"

#include <kdl/tree.hpp>
#include <kdl_parser/kdl_parser.hpp>
#include <urdf_parser/urdf_parser.h>

#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace robokin {

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
    // urdfdom accepts <axis xyz="0 0 0">; KDL turns an axis shorter than its epsilon (1e-6) into
    // NaN poses.
    const double axis_norm = joint ? std::hypot(joint->axis.x, joint->axis.y, joint->axis.z) : 1.0;
    if (!(axis_norm > 1e-6) || !std::isfinite(axis_norm))
      throw std::invalid_argument("path_or_string: joint '" + joint->name + "' has a zero axis (norm <= 1e-6)");
    if (joint && joint->limits && joint->type != urdf::Joint::CONTINUOUS &&
        joint->limits->lower < joint->limits->upper) {
      lower(j) = joint->limits->lower;
      upper(j) = joint->limits->upper;
    }
    ++j;
  }
  return Chain(std::move(chain), lower, upper);
}

}  // namespace robokin
