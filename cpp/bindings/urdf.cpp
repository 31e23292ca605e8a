// robokin.urdf_tree's and Chain.from_urdf's core: urdfdom's parser on a document's text (what a
// path or string gives, and the warnings, are robokin._urdf's), and the URDF tree's classes.
#include "bindings.hpp"

#include "robokin/urdf.hpp"

#include <pybind11/stl.h>

#include <optional>
#include <string>
#include <vector>

namespace robokin::bind {
namespace py = pybind11;

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
  // What was accepted but changed comes back as text: robokin._urdf warns with it at the caller's line.
  m.def(
      "chain_from_urdf",
      [](const py::bytes& xml, std::optional<std::string> base, std::optional<std::string> tip) {
        std::vector<std::string> warnings;
        Chain chain = chain_from_urdf(std::string(xml), base, tip, &warnings);
        return py::make_tuple(std::move(chain), warnings);
      },
      py::arg("xml"), py::arg("base"), py::arg("tip"), "(chain, warnings) of a URDF document. Use Chain.from_urdf.");
  m.def(
      "urdf_tree",
      [](const py::bytes& xml) {
        std::vector<std::string> warnings;
        UrdfTree tree = urdf_tree(std::string(xml), &warnings);
        return py::make_tuple(std::move(tree), warnings);
      },
      py::arg("xml"), "(tree, warnings) of a URDF document. Use robokin.urdf_tree.");
}

}  // namespace robokin::bind
