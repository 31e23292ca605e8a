// robokin.Chain.from_urdf: added to the Chain class registered by chain.cpp.
#include "arrays.hpp"
#include "bindings.hpp"

#include "robokin/urdf.hpp"

#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

namespace robokin::bind {
namespace {

// XML text when the argument looks like a document, else the contents of the file it names.
std::string urdf_text(py::handle obj) {
  py::object os = py::module_::import("os");
  if (!py::isinstance<py::str>(obj) && !py::isinstance(obj, os.attr("PathLike")))
    fail("path_or_string: expected a path or a URDF string");
  const std::string s = py::cast<std::string>(os.attr("fspath")(obj));
  const size_t first = s.find_first_not_of(" \t\r\n");
  if (first == std::string::npos) fail("path_or_string: the URDF document is empty (an empty string)");
  if (s[first] == '<') return s;
  std::error_code ec;
  if (std::filesystem::is_directory(s, ec)) fail("path_or_string: '" + s + "' is a directory, not a URDF file");
  std::ifstream in(s);
  if (!in) fail("path_or_string: no readable file '" + s + "' (and not a URDF string)");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace

void bind_urdf(py::module_& m) {
  py::object chain_class = m.attr("Chain");
  py::cpp_function from_urdf(
      [](py::handle path_or_string, const std::string& base, const std::string& tip) {
        const std::string xml = urdf_text(path_or_string);
        std::vector<std::string> warnings;
        Chain chain = chain_from_urdf(xml, base, tip, &warnings);
        // What was accepted but changed: a robokin.URDFWarning each (an exception when the
        // warnings filter says so).
        if (!warnings.empty()) {
          const py::object category = py::module_::import("robokin.errors").attr("URDFWarning");
          for (const std::string& w : warnings)
            if (PyErr_WarnEx(category.ptr(), w.c_str(), 1) < 0) throw py::error_already_set();
        }
        return chain;
      },
      py::name("from_urdf"), py::arg("path_or_string"), py::arg("base"), py::arg("tip"),
      "Builds the chain from link `base` to link `tip` of a URDF file or string, with the joint\n"
      "limits read from the file (continuous joints unlimited). A bad file is a ValueError saying why.");
  chain_class.attr("from_urdf") = py::reinterpret_steal<py::object>(PyStaticMethod_New(from_urdf.ptr()));
}

}  // namespace robokin::bind
