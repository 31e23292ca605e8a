// What a chain is made of, kept to rebuild it bit for bit (SegmentRecord, Chain::from_records), and
// the comparison of two chains' kinematics.
#include "robokin/chain.hpp"

#include "kernel/fk_path.hpp"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <functional>
#include <stdexcept>
#include <string>

namespace robokin {
namespace {

KDL::Frame to_kdl(const Matrix4& m) {
  return KDL::Frame(KDL::Rotation(m(0, 0), m(0, 1), m(0, 2), m(1, 0), m(1, 1), m(1, 2), m(2, 0),
                                  m(2, 1), m(2, 2)),
                    KDL::Vector(m(0, 3), m(1, 3), m(2, 3)));
}

KDL::Vector to_kdl(const Eigen::Vector3d& v) { return KDL::Vector(v.x(), v.y(), v.z()); }

bool axis_joint(int type) { return type == KDL::Joint::RotAxis || type == KDL::Joint::TransAxis; }

bool same_bits(const double* a, const double* b, size_t count) { return std::memcmp(a, b, count * sizeof(double)) == 0; }

}  // namespace

KDL::Segment SegmentRecord::segment() const {
  if (type < KDL::Joint::RotAxis || type > KDL::Joint::Fixed)
    throw std::invalid_argument("segment record: joint type " + std::to_string(type) + " is not a KDL joint type");
  if (!origin.allFinite() || !axis.allFinite() || !tip.allFinite())
    throw std::invalid_argument("segment record: non-finite origin, axis or tip");
  const auto kind = static_cast<KDL::Joint::JointType>(type);
  if (axis_joint(type)) {
    // KDL turns an axis shorter than its epsilon (1e-6) into NaN poses.
    if (!(axis.norm() > 1e-6)) throw std::invalid_argument("segment record: zero joint axis");
    return KDL::Segment(name, KDL::Joint(joint_name, to_kdl(origin), to_kdl(axis), kind), to_kdl(tip));
  }
  return KDL::Segment(name, KDL::Joint(joint_name, kind), to_kdl(tip));
}

SegmentRecord SegmentRecord::of(const KDL::Segment& s) {
  SegmentRecord r;
  r.name = s.getName();
  r.joint_name = s.getJoint().getName();
  r.type = s.getJoint().getType();
  if (axis_joint(r.type)) {
    const KDL::Vector o = s.getJoint().JointOrigin(), a = s.getJoint().JointAxis();
    r.origin = Eigen::Vector3d(o.x(), o.y(), o.z());
    r.axis = Eigen::Vector3d(a.x(), a.y(), a.z());
  }
  r.tip = Rigid::from_kdl(s.getFrameToTip()).matrix();
  return r;
}

Chain Chain::from_records(const std::vector<SegmentRecord>& records, const Vector& lower, const Vector& upper,
                          const std::string& base_name) {
  KDL::Chain c;
  for (const SegmentRecord& r : records) c.addSegment(r.segment());
  Chain chain(std::move(c), lower, upper);
  chain.records_ = records;
  chain.base_name_ = base_name;
  return chain;
}

namespace {

std::string name_or(const std::string& name, const std::string& fallback) {
  return name.empty() || name == kUnnamed ? fallback : name;
}

}  // namespace

std::vector<std::string> Chain::joint_names() const {
  std::vector<std::string> names;
  for (const SegmentRecord& r : records_)
    if (r.type != KDL::Joint::Fixed) names.push_back(name_or(r.joint_name, "q" + std::to_string(names.size() + 1)));
  return names;
}

std::vector<std::string> Chain::link_names() const {
  std::vector<std::string> names{name_or(base_name_, "base")};
  for (const SegmentRecord& r : records_)
    if (r.type != KDL::Joint::Fixed) names.push_back(name_or(r.name, "link" + std::to_string(names.size())));
  // The last frame is the chain's end: trailing fixed segments (a flange, a tool) belong to it.
  names.back() = name_or(records_.back().name, "link" + std::to_string(dof_));
  return names;
}

bool Chain::named() const {
  if (!name_or(base_name_, "").empty()) return true;
  for (const SegmentRecord& r : records_)
    if (!name_or(r.name, "").empty() || !name_or(r.joint_name, "").empty()) return true;
  return false;
}

bool Chain::same_kinematics(const Chain& o) const {
  const std::vector<kernel::Link>&links = path_->links, &other = o.path_->links;
  if (dof_ != o.dof_ || links.size() != other.size()) return false;
  if (!same_bits(lower().data(), o.lower().data(), dof_) || !same_bits(upper().data(), o.upper().data(), dof_))
    return false;
  auto same_rigid = [](const Rigid& a, const Rigid& b) {
    return same_bits(a.R.data(), b.R.data(), 9) && same_bits(a.p.data(), b.p.data(), 3);
  };
  if (!same_rigid(path_->base, o.path_->base)) return false;
  for (size_t i = 0; i < links.size(); ++i) {
    const kernel::Link &a = links[i], &b = other[i];
    if (a.prismatic != b.prismatic || !same_bits(&a.scale, &b.scale, 1) || !same_rigid(a.after.F, b.after.F))
      return false;
  }
  return true;
}

std::size_t Chain::kinematics_hash() const {
  std::size_t h = std::hash<int>()(dof_);
  auto mix = [&h](const double* v, size_t count) {
    for (size_t k = 0; k < count; ++k) {
      std::uint64_t bits;
      std::memcpy(&bits, v + k, sizeof bits);
      h ^= std::hash<std::uint64_t>()(bits) + 0x9E3779B97F4A7C15ull + (h << 6) + (h >> 2);
    }
  };
  mix(lower().data(), dof_);
  mix(upper().data(), dof_);
  mix(path_->base.p.data(), 3);
  for (const kernel::Link& l : path_->links) {
    const double prismatic = l.prismatic ? 1.0 : 0.0;
    mix(&prismatic, 1);
    mix(&l.scale, 1);
    mix(l.after.F.p.data(), 3);
  }
  return h;
}

}  // namespace robokin
