// Serial chains from URDF robot descriptions (urdfdom parses the XML; the KDL tree is built here).
#pragma once

#include "robokin/chain.hpp"

#include <string>
#include <vector>

namespace robokin {

// Joint origins farther than this (metres, per coordinate) are refused: no robot is that large,
// and the FK / IK of such a chain would lose every digit of the rest of it.
constexpr double kMaxUrdfLength = 1e9;
// XML nested deeper than this is refused before urdfdom's recursive XML parser sees it (a URDF
// nests about five levels).
constexpr int kMaxXmlDepth = 1000;

// The chain from link `base` to link `tip` of the URDF document `xml`, with the joint limits of the
// file (continuous joints are unlimited). Throws std::invalid_argument naming what is wrong and
// why: the reason urdfdom gives for a document it rejects (its console output is captured, never
// printed), a link with two parents, limits with lower > upper, a mimic, floating or planar joint
// between base and tip, a non-finite or huge origin, a zero axis, unknown links, no joint between
// the links. Chains of any length load (the tree is built without recursion). Messages about what
// was accepted but changed (a joint whose lower and upper limits are equal, taken as unlimited as
// the URDF default lower = upper = 0 means; urdfdom's warnings) are appended to `warnings`.
Chain chain_from_urdf(const std::string& xml, const std::string& base, const std::string& tip,
                      std::vector<std::string>* warnings = nullptr);

}  // namespace robokin
