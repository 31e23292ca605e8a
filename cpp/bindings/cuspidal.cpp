// Cuspidality of 3R arms: the Cuspidality result and the call (use robokin.cuspidal, which checks
// the arguments).
#include "arrays.hpp"
#include "bindings.hpp"
#include "options.hpp"
#include "progress.hpp"
#include "results.hpp"

#include <pybind11/typing.h>

#include "robokin/cuspidal.hpp"

namespace robokin::bind {
namespace {

// point and path: None where no posture change was found, else the array.
template <class M>
py::typing::Optional<py::array_t<double>> none_or_array(const M& a) {
  if (a.size() == 0) return py::none();
  if constexpr (M::ColsAtCompileTime == 1) return array_of(a.data(), {a.rows()});
  else return array_of(a.data(), {a.rows(), a.cols()});
}

template <class M>
void restore_none_or_array(M& a, py::handle v, const char* field) {
  if (v.is_none()) return a.resize(0, M::ColsAtCompileTime == 1 ? 1 : 3);
  const auto x = aligned_array<double>(v);
  const bool column = M::ColsAtCompileTime == 1;
  if (!x || x.ndim() != (column ? 1 : 2) || (column ? x.shape(0) != 3 : x.shape(1) != 3))
    fail(std::string("Cuspidality state: ") + field + " is not None or an array of the result's shape");
  a = Eigen::Map<const M>(x.data(), x.shape(0), column ? 1 : 3);
}

}  // namespace

void bind_cuspidal(py::module_& m) {
  OptionsClass<CuspidalOptions>(m, "CuspidalOptions", "The options of robokin.cuspidal.").fields();
  const char* doc = "Result of robokin.cuspidal: whether a 3R arm is cuspidal, with the evidence.";
  ResultClass<Cuspidality>(m, "Cuspidality", doc, false)
      .fields()
      .value_as("point", [](const Cuspidality& c) { return none_or_array(c.point); },
                [](Cuspidality& c, py::handle v) { restore_none_or_array(c.point, v, "point"); },
                "For a cuspidal arm, a tool point (3,) with two solutions in one aspect (else None).")
      .value_as("path", [](const Cuspidality& c) { return none_or_array(c.path); },
                [](Cuspidality& c, py::handle v) { restore_none_or_array(c.path, v, "path"); },
                "For a cuspidal arm, (m, 3) joint configurations from one of those solutions to the other, det J "
                "of one sign all along (checked at 9 points of each step, its ends included), else None.")
      .done_with([](py::class_<Cuspidality>& cls) {
        cls.def_property_readonly("evidence", [](py::handle self) { return printed("cuspidality_evidence", self); },
                                  "One sentence saying why.");
      });
  m.def(
      "cuspidal",
      [](const Chain& chain, const py::kwargs& kwargs) {
        const CuspidalOptions o = options_arg<CuspidalOptions>(kwargs);
        return released([&] { return cuspidal(chain, o); });
      },
      py::arg("chain"));
}

}  // namespace robokin::bind
