// URDF -> KDL chain. urdfdom parses the document; the KDL tree is built here, without recursion:
// kdl_parser's treeFromUrdfModel recurses once per link and overflows the stack (SIGSEGV) on
// chains of about 10,000 joints, and it prints through console_bridge (ROS colour codes on stderr).
#include "robokin/urdf.hpp"

#include <console_bridge/console.h>
#include <kdl/tree.hpp>
#include <urdf_parser/urdf_parser.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <mutex>
#include <stdexcept>
#include <map>
#include <unordered_set>
#include <utility>

namespace robokin {
namespace {

[[noreturn]] void bad(const std::string& message) { throw std::invalid_argument(message); }

// console_bridge's output while urdfdom parses: kept for the error message or the warnings, never
// printed. console_bridge's handler is global, so one parse at a time holds it.
class Capture : public console_bridge::OutputHandler {
 public:
  void log(const std::string& text, console_bridge::LogLevel level, const char*, int) override {
    std::string line = text;
    while (!line.empty() && (line.back() == '\n' || line.back() == ' ')) line.pop_back();
    if (level >= console_bridge::CONSOLE_BRIDGE_LOG_ERROR)
      errors.push_back(line);
    else if (level == console_bridge::CONSOLE_BRIDGE_LOG_WARN)
      warnings.push_back(line);
  }
  std::vector<std::string> errors, warnings;
};

std::mutex console_mutex;

urdf::ModelInterfaceSharedPtr parse(const std::string& xml, Capture& capture) {
  std::lock_guard<std::mutex> lock(console_mutex);
  console_bridge::useOutputHandler(&capture);
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& e) {
    capture.errors.push_back(e.what());
    model.reset();
  }
  console_bridge::restorePreviousOutputHandler();
  return model;
}

std::string joined(const std::vector<std::string>& lines) {
  std::string s;
  for (const std::string& line : lines) s += (s.empty() ? "" : "; ") + line;
  return s;
}

// The deepest nesting of elements in an XML text, scanned in one pass without recursion (comments,
// CDATA, declarations and quoted attribute values skipped); stops once past `limit`.
int xml_depth(const std::string& s, int limit) {
  int depth = 0, worst = 0;
  const size_t n = s.size();
  size_t i = 0;
  while ((i = s.find('<', i)) != std::string::npos) {
    const char* end_mark = nullptr;
    if (s.compare(i, 4, "<!--") == 0) end_mark = "-->";
    else if (s.compare(i, 9, "<![CDATA[") == 0) end_mark = "]]>";
    else if (i + 1 < n && (s[i + 1] == '?' || s[i + 1] == '!')) end_mark = ">";
    if (end_mark) {
      i = s.find(end_mark, i + 1);
      if (i == std::string::npos) break;
      ++i;
      continue;
    }
    size_t j = i + 1;
    char quote = 0;
    for (; j < n; ++j) {
      const char c = s[j];
      if (quote) {
        if (c == quote) quote = 0;
      } else if (c == '"' || c == '\'') {
        quote = c;
      } else if (c == '>') {
        break;
      }
    }
    if (j >= n) break;
    if (s[i + 1] == '/') {
      --depth;
    } else if (s[j - 1] != '/') {
      worst = std::max(worst, ++depth);
      if (worst > limit) return worst;
    }
    i = j + 1;
  }
  return worst;
}

const char* type_name(int type) {
  switch (type) {
    case urdf::Joint::REVOLUTE: return "revolute";
    case urdf::Joint::CONTINUOUS: return "continuous";
    case urdf::Joint::PRISMATIC: return "prismatic";
    case urdf::Joint::FLOATING: return "floating";
    case urdf::Joint::PLANAR: return "planar";
    case urdf::Joint::FIXED: return "fixed";
    default: return "unknown";
  }
}

std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Whether `s` is well-formed UTF-8 (no overlong forms, surrogates or code points past U+10FFFF).
bool utf8(const std::string& s) {
  for (size_t i = 0; i < s.size();) {
    const unsigned char c = static_cast<unsigned char>(s[i]);
    const int more = c < 0x80 ? 0 : (c >> 5) == 0x6 ? 1 : (c >> 4) == 0xE ? 2 : (c >> 3) == 0x1E ? 3 : -1;
    if (more < 0 || s.size() - i <= static_cast<size_t>(more)) return false;  // bad lead byte, or cut short
    unsigned long code = more == 0 ? c : c & (0x3F >> more);
    for (int k = 1; k <= more; ++k) {
      const unsigned char t = static_cast<unsigned char>(s[i + k]);
      if ((t >> 6) != 0x2) return false;
      code = (code << 6) | (t & 0x3F);
    }
    static constexpr unsigned long kLeast[] = {0, 0x80, 0x800, 0x10000};
    if (code < kLeast[more] || code > 0x10FFFF || (code >= 0xD800 && code <= 0xDFFF)) return false;
    i += 1 + more;
  }
  return true;
}

// A name as printable ASCII: other bytes as \xNN (for a message about a name that is not UTF-8).
std::string escaped(const std::string& s) {
  std::string out;
  for (const char ch : s) {
    const unsigned char c = static_cast<unsigned char>(ch);
    if (c >= 0x20 && c < 0x7F) {
      out += ch;
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", c);
      out += buf;
    }
  }
  return out;
}

// The names Python will show (chain and tree names, messages) are text: a document given as bytes
// in another encoding is refused here rather than failing later wherever a name is shown.
void check_names(const urdf::ModelInterface& model) {
  auto check = [](const std::string& name, const char* what) {
    if (!utf8(name)) bad(std::string("path_or_string: the ") + what + " name '" + escaped(name) + "' is not UTF-8 text");
  };
  check(model.getName(), "robot");
  for (const auto& [name, link] : model.links_) check(name, "link");
  for (const auto& [name, joint] : model.joints_) check(name, "joint");
}

std::string joint_label(const urdf::Joint& j) { return "joint '" + j.name + "'"; }

KDL::Frame origin_of(const urdf::Joint& j) {
  const urdf::Pose& p = j.parent_to_joint_origin_transform;
  const double xyz[3] = {p.position.x, p.position.y, p.position.z};
  const double q[4] = {p.rotation.x, p.rotation.y, p.rotation.z, p.rotation.w};
  for (double v : xyz) {
    if (!std::isfinite(v)) bad("path_or_string: " + joint_label(j) + " has a non-finite origin");
    if (std::abs(v) > kMaxUrdfLength)
      bad("path_or_string: " + joint_label(j) + " has an origin farther than 1e9 m (" + number(v) + ")");
  }
  for (double v : q)
    if (!std::isfinite(v)) bad("path_or_string: " + joint_label(j) + " has a non-finite origin rotation");
  return KDL::Frame(KDL::Rotation::Quaternion(q[0], q[1], q[2], q[3]), KDL::Vector(xyz[0], xyz[1], xyz[2]));
}

// The KDL joint and segment of a URDF joint, as kdl_parser builds them: the joint's origin and axis
// are expressed in the parent link's frame, the segment's tip is the joint frame. Floating and
// planar joints become fixed in the tree (KDL has no such joints); the chain refuses them. The
// record keeps the constructors' arguments (a pickled chain is rebuilt from them bit for bit).
SegmentRecord record_of(const urdf::Joint& j) {
  const KDL::Frame F = origin_of(j);
  SegmentRecord r;
  r.name = j.child_link_name;
  r.joint_name = j.name;
  r.tip = Rigid::from_kdl(F).matrix();
  switch (j.type) {
    case urdf::Joint::REVOLUTE:
    case urdf::Joint::CONTINUOUS:
    case urdf::Joint::PRISMATIC: {
      const KDL::Vector axis(j.axis.x, j.axis.y, j.axis.z);
      const double norm = axis.Norm();
      if (!std::isfinite(norm)) bad("path_or_string: " + joint_label(j) + " has a non-finite axis");
      // urdfdom accepts <axis xyz="0 0 0">; KDL turns an axis shorter than its epsilon (1e-6) into
      // NaN poses.
      if (!(norm > 1e-6)) bad("path_or_string: " + joint_label(j) + " has a zero axis (norm <= 1e-6)");
      r.type = j.type == urdf::Joint::PRISMATIC ? KDL::Joint::TransAxis : KDL::Joint::RotAxis;
      const KDL::Vector a = F.M * axis;
      r.origin = Eigen::Vector3d(F.p.x(), F.p.y(), F.p.z());
      r.axis = Eigen::Vector3d(a.x(), a.y(), a.z());
      return r;
    }
    default:
      r.type = KDL::Joint::Fixed;
      return r;
  }
}

KDL::Segment segment_of(const urdf::Joint& j) { return record_of(j).segment(); }

// Whether two KDL segments are the same numbers (what the chain's evaluation reads from them).
bool same_segment(const KDL::Segment& a, const KDL::Segment& b) {
  if (a.getJoint().getType() != b.getJoint().getType()) return false;
  const KDL::Vector xa = a.getJoint().JointAxis(), xb = b.getJoint().JointAxis();
  const KDL::Vector oa = a.getJoint().JointOrigin(), ob = b.getJoint().JointOrigin();
  for (int i = 0; i < 3; ++i)
    if (xa(i) != xb(i) || oa(i) != ob(i)) return false;
  auto same = [](const KDL::Frame& f, const KDL::Frame& g) {
    const Rigid x = Rigid::from_kdl(f), y = Rigid::from_kdl(g);
    return x.R == y.R && x.p == y.p;  // exactly (KDL's operator== may be built with a tolerance)
  };
  return same(a.pose(0.0), b.pose(0.0)) && same(a.pose(1.0), b.pose(1.0)) && same(a.getFrameToTip(), b.getFrameToTip());
}

// Every joint of the file: one parent per link (urdfdom keeps the last joint naming a child and
// drops the others without a word).
void check_tree(const urdf::ModelInterface& model) {
  for (const auto& [name, joint] : model.joints_) {
    if (!joint) continue;
    const urdf::LinkConstSharedPtr child = model.getLink(joint->child_link_name);
    if (child && child->parent_joint && child->parent_joint->name != name)
      bad("path_or_string: link '" + joint->child_link_name + "' has two parents (joints '" +
          child->parent_joint->name + "' and '" + name + "'): a URDF is a tree");
  }
}

bool movable(const urdf::Joint& j) {
  return j.type == urdf::Joint::REVOLUTE || j.type == urdf::Joint::CONTINUOUS || j.type == urdf::Joint::PRISMATIC;
}

// The document as urdfdom's model, checked to be one tree; urdfdom's warnings left in `capture`.
urdf::ModelInterfaceSharedPtr load(const std::string& xml, Capture& capture) {
  if (xml.find_first_not_of(" \t\r\n") == std::string::npos) bad("path_or_string: the URDF document is empty");
  if (xml_depth(xml, kMaxXmlDepth) > kMaxXmlDepth)
    bad("path_or_string: XML elements nested deeper than " + std::to_string(kMaxXmlDepth) + " levels (not a URDF)");
  const urdf::ModelInterfaceSharedPtr model = parse(xml, capture);
  if (!model) {
    const std::string why = capture.errors.empty() ? joined(capture.warnings) : joined(capture.errors);
    bad("path_or_string: not a valid URDF document: " + (why.empty() ? std::string("urdfdom gives no reason") : why));
  }
  check_names(*model);
  check_tree(*model);
  if (!model->getRoot()) bad("path_or_string: the URDF has no root link");
  return model;
}

// Calls visit(link, parent joint) for every link below `top` (not `top` itself), depth-first, a
// parent before its children and children in urdfdom's order; without recursion.
template <class Visit>
void each_below(const urdf::LinkConstSharedPtr& top, Visit visit) {
  std::vector<urdf::LinkConstSharedPtr> stack{top};
  std::unordered_set<const urdf::Link*> seen{top.get()};
  while (!stack.empty()) {
    const urdf::LinkConstSharedPtr link = stack.back();
    stack.pop_back();
    if (link != top) visit(*link, *link->parent_joint);
    for (auto child = link->child_links.rbegin(); child != link->child_links.rend(); ++child) {
      if (!*child || !(*child)->parent_joint) continue;
      if (!seen.insert(child->get()).second)
        bad("path_or_string: link '" + (*child)->name + "' is reached twice (a loop or two parents)");
      stack.push_back(*child);
    }
  }
}

// The ends of the longest branches below `base` (UrdfTree's rule), sorted by name, and how many
// movable joints lead to them (0 and no end when none moves).
struct Branches {
  int movable = 0;
  std::vector<std::string> ends;
};

Branches longest_branches(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& base) {
  // Per link below base: movable joints and joints from base, and the last movable joint on the way.
  struct Depth {
    int movable = 0, joints = 0;
    const urdf::Joint* last = nullptr;
  };
  std::map<const urdf::Link*, Depth> depth{{base.get(), {}}};
  std::vector<const urdf::Link*> deepest;  // the links with the most movable joints so far
  int best = 0;
  each_below(base, [&](const urdf::Link& link, const urdf::Joint& joint) {
    Depth d = depth.at(model.getLink(joint.parent_link_name).get());
    ++d.joints;
    if (movable(joint)) ++d.movable, d.last = &joint;
    depth[&link] = d;
    if (d.movable == 0 || d.movable < best) return;
    if (d.movable > best) best = d.movable, deepest.clear();
    deepest.push_back(&link);
  });
  // One branch per last movable joint: its links with the most joints, walked up together (they
  // are equally deep) to the deepest link they all hang from.
  std::map<const urdf::Joint*, std::vector<const urdf::Link*>> branches;
  for (const urdf::Link* link : deepest) {
    std::vector<const urdf::Link*>& ends = branches[depth.at(link).last];
    const int joints = depth.at(link).joints, held = ends.empty() ? -1 : depth.at(ends.front()).joints;
    if (joints > held) ends.clear();
    if (joints >= held) ends.push_back(link);
  }
  Branches out{best, {}};
  for (auto& [last, ends] : branches) {
    while (std::any_of(ends.begin(), ends.end(), [&](const urdf::Link* l) { return l != ends.front(); }))
      for (const urdf::Link*& l : ends) l = l->getParent().get();
    out.ends.push_back(ends.front()->name);
  }
  std::sort(out.ends.begin(), out.ends.end());
  return out;
}

std::string quoted_list(const std::vector<std::string>& names) {
  std::string s;
  for (size_t i = 0; i < names.size(); ++i)
    s += (i == 0 ? "" : i + 1 == names.size() ? " and " : ", ") + ("'" + names[i] + "'");
  return s;
}

// from_urdf's default tip below `base`: the end of the one longest branch.
std::string default_tip(const urdf::ModelInterface& model, const urdf::LinkConstSharedPtr& base) {
  const Branches b = longest_branches(model, base);
  if (b.ends.empty()) bad("tip: no movable joint below link '" + base->name + "': pass tip=...");
  if (b.ends.size() > 1)
    bad("tip: the longest branches from '" + base->name + "' end at " + quoted_list(b.ends) + " (" +
        std::to_string(b.movable) + " movable joint" + (b.movable == 1 ? "" : "s") + " each): pass tip=...");
  return b.ends.front();
}

KDL::Tree tree_of(const urdf::ModelInterface& model) {
  const urdf::LinkConstSharedPtr root = model.getRoot();
  KDL::Tree tree(root->name);
  each_below(root, [&](const urdf::Link& link, const urdf::Joint& joint) {
    if (!tree.addSegment(segment_of(joint), joint.parent_link_name))
      bad("path_or_string: could not add link '" + link.name + "' to the tree");
  });
  return tree;
}

}  // namespace

Chain chain_from_urdf(const std::string& xml, const std::optional<std::string>& base_arg,
                      const std::optional<std::string>& tip_arg, std::vector<std::string>* warnings) {
  Capture capture;
  const urdf::ModelInterfaceSharedPtr model = load(xml, capture);
  const std::string base = base_arg.value_or(model->getRoot()->name);
  const urdf::LinkConstSharedPtr base_link = model->getLink(base);
  if (!base_link) bad("base: no link named '" + base + "' in the URDF");
  const std::string tip = tip_arg ? *tip_arg : default_tip(*model, base_link);
  if (!model->getLink(tip)) bad("tip: no link named '" + tip + "' in the URDF");
  const KDL::Tree tree = tree_of(*model);
  KDL::Chain chain;
  if (!tree.getChain(base, tip, chain))
    bad("base, tip: no chain from '" + base + "' to '" + tip + "'");
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<std::string> notes = capture.warnings;
  const int n = static_cast<int>(chain.getNrOfJoints());
  Vector lower(std::max(n, 0)), upper(std::max(n, 0));
  int k = 0;
  std::vector<SegmentRecord> records;
  for (const KDL::Segment& seg : chain.segments) {
    // Joints between base and tip, also fixed ones (a floating or planar joint became fixed).
    const urdf::JointConstSharedPtr joint = model->getJoint(seg.getJoint().getName());
    // A segment of the tree is rebuilt from its joint's record; one KDL made on the way up from
    // base (base below the common ancestor) is read back from KDL's accessors.
    SegmentRecord record = SegmentRecord::of(seg);
    if (joint) {
      const SegmentRecord own = record_of(*joint);
      if (same_segment(own.segment(), seg)) record = own;
    }
    records.push_back(record);
    if (joint) {
      if (joint->type == urdf::Joint::FLOATING || joint->type == urdf::Joint::PLANAR)
        bad("path_or_string: " + joint_label(*joint) + " is " + type_name(joint->type) +
            ": a serial chain has revolute, continuous, prismatic and fixed joints only");
      // A fixed joint does not move, so a mimic tag on it (some files carry one) changes nothing.
      if (joint->mimic && joint->type != urdf::Joint::FIXED)
        bad("path_or_string: " + joint_label(*joint) + " mimics joint '" + joint->mimic->joint_name +
            "': mimic joints are not supported in a chain (it would move independently)");
    }
    if (seg.getJoint().getType() == KDL::Joint::Fixed) continue;
    lower(k) = -inf;
    upper(k) = inf;
    if (joint && joint->limits && joint->type != urdf::Joint::CONTINUOUS) {
      const double lo = joint->limits->lower, hi = joint->limits->upper;
      if (!std::isfinite(lo) || !std::isfinite(hi))
        bad("path_or_string: " + joint_label(*joint) + " has a non-finite limit");
      if (lo > hi)
        bad("path_or_string: " + joint_label(*joint) + " has its lower limit " + number(lo) +
            " above its upper limit " + number(hi));
      if (lo < hi) {
        lower(k) = lo;
        upper(k) = hi;
      } else {
        notes.push_back(joint_label(*joint) + " has lower == upper limit (" + number(lo) +
                        "): taken as unlimited (URDF's default when lower and upper are left out)");
      }
    }
    ++k;
  }
  if (n == 0) bad("base, tip: no moving joint between '" + base + "' and '" + tip + "'");
  if (warnings) warnings->insert(warnings->end(), notes.begin(), notes.end());
  return Chain::from_records(records, lower, upper, base);
}

UrdfTree urdf_tree(const std::string& xml, std::vector<std::string>* warnings) {
  Capture capture;
  const urdf::ModelInterfaceSharedPtr model = load(xml, capture);
  const urdf::LinkConstSharedPtr root = model->getRoot();
  UrdfTree tree;
  tree.name = model->getName();
  tree.root = tree.base = root->name;
  tree.links.push_back(root->name);
  each_below(root, [&](const urdf::Link& link, const urdf::Joint& joint) {
    tree.joints.push_back({joint.name, type_name(joint.type), joint.parent_link_name, joint.child_link_name});
    tree.links.push_back(link.name);
  });
  const Branches b = longest_branches(*model, root);
  tree.tips = b.ends;
  tree.movable = b.movable;
  if (b.ends.size() == 1) tree.tip = b.ends.front();
  if (warnings) warnings->insert(warnings->end(), capture.warnings.begin(), capture.warnings.end());
  return tree;
}

}  // namespace robokin
