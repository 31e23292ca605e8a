// A chain's evaluation path: the chain rewritten for the lane kernel (fk_lanes.hpp), built once
// when the chain is made and shared, read-only, by its copies (Chain holds it behind a pointer to
// const: copying a chain copies the pointer; const calls from many threads only read it).
#pragma once

#include "robokin/chain.hpp"

#include <kdl/chain.hpp>

#include <vector>

namespace robokin {

namespace kernel {

// A constant frame applied on the right (T <- T * F); move / turn say whether its translation /
// rotation differ from the identity (the evaluation skips what changes nothing).
struct Fixed {
  Rigid F;
  bool move = false, turn = false;
  static Fixed of(const Rigid& F);
};

// Joint motion (a rotation about the local z axis, or a translation along `axis`), then a fixed
// frame. The masks say which products can be non-zero at this point of the chain, from the zeros
// of the base, the axes and the fixed frames (e.g. a planar chain's rotations leave the third row
// alone): bit i of `rows` turns row i of R in the joint's rotation; bit 3 i + k of `slide` adds
// R(i, k) axis(k) to p(i), of `move` R(i, k) after.p(k); bit i of `turn` turns row i by after.R.
struct Link {
  bool prismatic;
  double scale;
  Eigen::Vector3d axis;
  Fixed after;
  unsigned rows = 7, slide = 0, move = 0, turn = 0;
};

// base * Mz(s_1 q_1) * after_1 * ... * Mz(s_n q_n) * after_n (fk_path.cpp says how).
struct FkPath {
  Rigid base;  // fixed frame before the first joint's motion
  std::vector<Link> links;
  bool turns = false;  // every joint revolute of scale 1: its motion is its angle's turn (fk_few_turns)
  int dof() const { return static_cast<int>(links.size()); }
};

// The path of a chain with at least one joint.
FkPath build_fk_path(const KDL::Chain& chain);

// The kernel's entry points for many configurations (fk_batch.cpp): Chain::fk_few, fk_few_turns, fk_batch.
// A single configuration's (fk) is inline in fk_lanes.hpp.
void fk_few(const FkPath& path, const double* q, int count, Rigid* out);
void fk_few_turns(const FkPath& path, const double* q, const double* c, const double* s, int count, Rigid* out);
bool fk_batch(const FkPath& path, const double* q, long count, double* out, FkOutput what, Progress* progress);

}  // namespace kernel

}  // namespace robokin
