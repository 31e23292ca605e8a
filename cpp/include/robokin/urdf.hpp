// Serial chains from URDF robot descriptions (urdfdom parses the XML; the KDL tree is built here).
#pragma once

#include "robokin/chain.hpp"

#include <optional>
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
// file (continuous joints are unlimited) and its names (Chain::joint_names, link_names). Without
// `base`, the root link; without `tip`, the end of the longest branch below base (UrdfTree::tip
// says how it is chosen; a tie between branches is an error naming their ends). Throws
// std::invalid_argument naming what is wrong and why: the reason urdfdom gives for a document it
// rejects (its console output is captured, never printed), a link with two parents, limits with
// lower > upper, a mimic (not fixed), floating or planar joint between base and tip, a non-finite or huge
// origin, a zero axis, unknown links, no joint between the links. Chains of any length load (the
// tree is built without recursion). Messages about what was accepted but changed (a joint whose
// lower and upper limits are equal, taken as unlimited as the URDF default lower = upper = 0 means;
// urdfdom's warnings) are appended to `warnings`.
Chain chain_from_urdf(const std::string& xml, const std::optional<std::string>& base = std::nullopt,
                      const std::optional<std::string>& tip = std::nullopt,
                      std::vector<std::string>* warnings = nullptr);

// One joint of a URDF as the file gives it: its type is one of revolute, continuous, prismatic,
// fixed, floating, planar.
struct UrdfJoint {
  std::string name, type, parent, child;
};

// The links and joints of a URDF document, and the chain chain_from_urdf builds by default.
//   links: every link, depth-first from the root (children in urdfdom's order: by joint name);
//   joints: every joint, in the same order (each just before its child link);
//   base: the root link (the default base);
//   tips: the end of each longest branch below the root. Longest means the most movable
//     (revolute, continuous, prismatic) joints; the links that many movable joints below the root
//     form one branch per last movable joint on their way. Within a branch the end is the link
//     with the most joints (fixed ones after the last movable joint: a flange, tool0), or, when
//     several have that many, the deepest link they all hang from;
//   tip: the default tip, tips[0] when there is exactly one branch; empty when several branches
//     tie (from_urdf then asks for a tip) or no joint below the root moves.
struct UrdfTree {
  std::string name, root, base, tip;
  std::vector<std::string> links, tips;
  std::vector<UrdfJoint> joints;
  int movable = 0;  // movable joints from base to each of tips
};

// The tree of the URDF document `xml` (errors and warnings as chain_from_urdf's).
UrdfTree urdf_tree(const std::string& xml, std::vector<std::string>* warnings = nullptr);

}  // namespace robokin
