// robokin.Chain.from_urdf (added to the class bind_chain makes) and robokin.urdf_tree.
#include "arrays.hpp"
#include "bindings.hpp"

#include "robokin/urdf.hpp"

#include <pybind11/stl.h>

#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <vector>

namespace robokin::bind {
namespace {

constexpr char kUrdfSourceText[] = "str | bytes | os.PathLike";
using UrdfSource = Typed<kUrdfSourceText>;
constexpr char kLinkNameText[] = "str | None";
using LinkName = Typed<kLinkNameText>;

std::string type_name_of(py::handle obj) { return py::str(py::type::handle_of(obj).attr("__name__")); }

bool starts_a_document(const std::string& s) {
  const size_t first = s.find_first_not_of(" \t\r\n");
  return first != std::string::npos && s[first] == '<';
}

std::string read_file(const std::string& path) {
  if (path.find_first_not_of(" \t\r\n") == std::string::npos)
    fail("path_or_string: the URDF document is empty (an empty string)");
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) fail("path_or_string: '" + path + "' is a directory, not a URDF file");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail("path_or_string: no readable file '" + path + "' (and not a URDF string)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// The XML text of from_urdf's and urdf_tree's argument. A str or bytes whose first non-blank
// character is '<' is the document itself (bytes handed to the parser as they are); any other str
// or bytes, and every os.PathLike, names a file (bytes decoded with os.fsdecode, as Python's own
// file functions do).
std::string urdf_text(py::handle obj) {
  const py::module_ os = py::module_::import("os");
  const bool text = py::isinstance<py::str>(obj) || py::isinstance<py::bytes>(obj);
  if (!text && !py::isinstance(obj, os.attr("PathLike")))
    throw py::type_error("path_or_string: expected a URDF document or a path to one (str, bytes or os.PathLike), got " +
                         type_name_of(obj));
  if (text) {
    const std::string s = py::cast<std::string>(obj);  // a str as UTF-8, bytes as they are
    if (starts_a_document(s)) return s;
  }
  return read_file(py::cast<std::string>(os.attr("fsdecode")(obj)));
}

std::optional<std::string> link_name(py::handle obj, const char* name) {
  if (obj.is_none()) return std::nullopt;
  if (!py::isinstance<py::str>(obj))
    throw py::type_error(std::string(name) + ": expected a link name (str) or None, got " + type_name_of(obj));
  return py::cast<std::string>(obj);
}

// What was accepted but changed: a robokin.URDFWarning each (an exception when the warnings filter
// says so).
void warn(const std::vector<std::string>& warnings) {
  if (warnings.empty()) return;
  const py::object category = py::module_::import("robokin.errors").attr("URDFWarning");
  for (const std::string& w : warnings)
    if (PyErr_WarnEx(category.ptr(), w.c_str(), 1) < 0) throw py::error_already_set();
}

Chain from_urdf(UrdfSource path_or_string, LinkName base, LinkName tip) {
  const std::string xml = urdf_text(path_or_string);
  const std::optional<std::string> base_link = link_name(base, "base"), tip_link = link_name(tip, "tip");
  std::vector<std::string> warnings;
  Chain chain = chain_from_urdf(xml, base_link, tip_link, &warnings);
  warn(warnings);
  return chain;
}

UrdfTree tree(UrdfSource path_or_string) {
  const std::string xml = urdf_text(path_or_string);
  std::vector<std::string> warnings;
  UrdfTree t = urdf_tree(xml, &warnings);
  warn(warnings);
  return t;
}

}  // namespace

void bind_urdf(py::module_& m) {
  py::class_<UrdfJoint>(m, "UrdfJoint", "One joint of a URDF: its name, type and the links it joins.")
      .def_readonly("name", &UrdfJoint::name, "The joint's name.")
      .def_readonly("type", &UrdfJoint::type,
                    "'revolute', 'continuous', 'prismatic', 'fixed', 'floating' or 'planar'.")
      .def_readonly("parent", &UrdfJoint::parent, "The parent link's name.")
      .def_readonly("child", &UrdfJoint::child, "The child link's name.")
      .def("__repr__", [](py::handle self) { return printed("urdf_joint_repr", self); });
  py::class_<UrdfTree>(m, "UrdfTree",
                       "The links and joints of a URDF and the chain Chain.from_urdf builds by default\n"
                       "(robokin.urdf_tree).")
      .def_readonly("name", &UrdfTree::name, "The robot's name.")
      .def_readonly("root", &UrdfTree::root, "The root link (the one no joint has as its child).")
      .def_readonly("links", &UrdfTree::links,
                    "Every link's name, depth-first from the root (children by joint name).")
      .def_readonly("joints", &UrdfTree::joints, "Every joint (UrdfJoint), in the same order: each before its child.")
      .def_readonly("base", &UrdfTree::base, "The default base: the root link.")
      .def_property_readonly(
          "tip", [](const UrdfTree& t) { return t.tip.empty() ? std::nullopt : std::optional<std::string>(t.tip); },
          "The default tip, or None when several branches tie (see tips) or no joint moves.")
      .def_readonly("tips", &UrdfTree::tips, "The end of each longest branch below the root, sorted by name.")
      .def_readonly("movable", &UrdfTree::movable, "Movable joints from the root to each of tips.")
      .def("__repr__", [](py::handle self) { return printed("urdf_tree_repr", self); });
  m.def("urdf_tree", &tree, py::arg("path_or_string"),
        "The links and joints of a URDF file or string and the default base and tip of Chain.from_urdf.\n\n"
        "path_or_string: as Chain.from_urdf takes it. Returns a UrdfTree: links depth-first from the root,\n"
        "joints (name, type, parent, child) in the same order, root, base (the root), tip (None when the\n"
        "longest branches tie: tips lists their ends). Raises ValueError for a bad document, TypeError for\n"
        "an argument of the wrong kind; robokin.URDFWarning for what urdfdom accepted but warned about.");
}

void def_chain_from_urdf(py::class_<Chain>& cls) {
  cls.def_static(
      "from_urdf", &from_urdf, py::arg("path_or_string"), py::arg("base") = py::none(), py::arg("tip") = py::none(),
      "Builds the chain from link `base` to link `tip` of a URDF file or string, with the file's joint\n"
      "limits (continuous joints unlimited) and names (joint_names, link_names).\n\n"
      "path_or_string: a str or bytes whose first non-blank character is '<' is the document itself\n"
      "  (bytes handed to the parser as they are); any other str or bytes, and any os.PathLike, is the\n"
      "  path of a file (bytes decoded with os.fsdecode).\n"
      "base: the chain's first link; None: the root link (the one no joint has as its child).\n"
      "tip: the chain's last link; None: the end of the longest branch below base. Longest means the\n"
      "  most movable (revolute, continuous, prismatic) joints. The links that many movable joints\n"
      "  below base must all follow the same last movable joint, else ValueError naming the end of each\n"
      "  branch (a two-armed robot: pass tip=). Among them the tip is the link with the most joints (the\n"
      "  fixed flange or tool0 after the last movable joint), or, when several have that many, the\n"
      "  deepest link they all hang from. Fixed leaves off other links (a 'base' frame) have fewer\n"
      "  movable joints and never compete. robokin.urdf_tree shows the choice.\n\n"
      "Raises ValueError saying what is wrong with the file, the links or the chain between them;\n"
      "TypeError for an argument of the wrong kind. Emits robokin.URDFWarning for what was accepted but\n"
      "changed (a joint with lower == upper limit taken as unlimited, urdfdom's warnings).");
}

}  // namespace robokin::bind
