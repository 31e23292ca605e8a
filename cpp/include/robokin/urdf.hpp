// Serial chains from URDF robot descriptions (kdl_parser + urdfdom, Debian's packages).
#pragma once

#include "robokin/chain.hpp"

#include <string>

namespace robokin {

// The chain from link `base` to link `tip` of the URDF document `xml`, with the joint limits of the
// file (continuous joints, and joints without limits, are unlimited). Throws std::invalid_argument
// naming what is wrong (the XML, an unknown link, no joint between the links).
Chain chain_from_urdf(const std::string& xml, const std::string& base, const std::string& tip);

}  // namespace robokin
