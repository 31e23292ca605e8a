// Chain pickling and copies (a versioned state tuple rebuilt bit for bit), == on the kinematics,
// hash, and repr and the table str() shows (written in Python) (added to the class registered by chain.cpp).
#include "arrays.hpp"
#include "bindings.hpp"
#include "chain_parts.hpp"

#include "robokin/chain.hpp"

#include <pybind11/stl.h>

#include <string>
#include <vector>

namespace robokin::bind {
namespace {

// Version 2 added the base link's name to the "segments" layout; version 1 states still load.
constexpr int kChainStateVersion = 2;

py::tuple floats(const double* v, int count) {
  py::tuple t(count);
  for (int i = 0; i < count; ++i) t[i] = py::float_(v[i]);
  return t;
}

using RowMajor4 = Eigen::Matrix<double, 4, 4, Eigen::RowMajor>;

py::tuple matrix_rows(const Matrix4& m) { return floats(RowMajor4(m).data(), 16); }

// A state entry of `count` floats (exact: Python floats are doubles).
std::vector<double> floats_of(py::handle obj, size_t count, const char* what) {
  std::vector<double> v;
  try {
    v = py::cast<std::vector<double>>(obj);
  } catch (const py::cast_error&) {
    fail(std::string("Chain state: ") + what + " is not a sequence of numbers");
  }
  if (count && v.size() != count)
    fail(std::string("Chain state: ") + what + " has " + std::to_string(v.size()) + " numbers, expected " +
         std::to_string(count));
  return v;
}

Matrix4 matrix_of(py::handle obj, const char* what) {
  return Eigen::Map<const RowMajor4>(floats_of(obj, 16, what).data());
}

Vector vector_of(py::handle obj, const char* what) {
  const std::vector<double> v = floats_of(obj, 0, what);
  return Eigen::Map<const Vector>(v.data(), static_cast<Eigen::Index>(v.size()));
}

// ("robokin.Chain", version, "dh", rows, modified, tool, lower, upper) for a chain built from a DH
// table, ("robokin.Chain", version, "segments", records, lower, upper, base link name) otherwise
// (version 1: without the base link's name); a record is (segment name, joint name, KDL joint
// type, origin (3), axis (3), tip (16, row-major)).
py::tuple chain_state(const Chain& c) {
  const py::tuple lower = floats(c.lower().data(), c.dof()), upper = floats(c.upper().data(), c.dof());
  if (const DHTable* dh = c.dh()) {
    py::list rows;
    for (const DHRow& r : dh->rows)
      rows.append(py::make_tuple(r.a, r.alpha, r.d, r.theta, r.prismatic ? "P" : "R"));
    return py::make_tuple("robokin.Chain", kChainStateVersion, "dh", py::tuple(rows), dh->modified,
                          matrix_rows(dh->tool), lower, upper);
  }
  py::list records;
  for (const SegmentRecord& r : c.records())
    records.append(py::make_tuple(r.name, r.joint_name, r.type, floats(r.origin.data(), 3), floats(r.axis.data(), 3),
                                  matrix_rows(r.tip)));
  return py::make_tuple("robokin.Chain", kChainStateVersion, "segments", py::tuple(records), lower, upper,
                        c.base_name());
}

Chain chain_from_state(const py::tuple& t) {
  if (t.size() < 3 || !py::isinstance<py::str>(t[0]) || t[0].cast<std::string>() != "robokin.Chain")
    fail("Chain state: not a robokin.Chain state");
  const long version = py::isinstance<py::int_>(t[1]) ? t[1].cast<long>() : -1;
  if (version < 1 || version > kChainStateVersion)
    fail("Chain state: version " + py::repr(t[1]).cast<std::string>() + " is not supported (this robokin reads 1 to " +
         std::to_string(kChainStateVersion) + ")");
  const std::string kind = py::isinstance<py::str>(t[2]) ? t[2].cast<std::string>() : "";
  if (kind == "dh" && t.size() == 8) {
    std::vector<DHRow> rows;
    for (py::handle row : py::reinterpret_borrow<py::sequence>(t[3])) {
      const py::sequence r = py::reinterpret_borrow<py::sequence>(row);
      if (r.size() != 5) fail("Chain state: a DH row is not (a, alpha, d, theta, joint)");
      const std::vector<double> v = floats_of(py::make_tuple(r[0], r[1], r[2], r[3]), 4, "a DH row");
      DHRow d{v[0], v[1], v[2], v[3], py::str(r[4]).cast<std::string>() == "P"};
      rows.push_back(d);
    }
    return Chain::from_dh(rows, t[4].cast<bool>(), matrix_of(t[5], "tool"), vector_of(t[6], "lower"),
                          vector_of(t[7], "upper"));
  }
  const size_t segments_size = version == 1 ? 6 : 7;
  if (kind == "segments" && t.size() == segments_size) {
    std::vector<SegmentRecord> records;
    for (py::handle rec : py::reinterpret_borrow<py::sequence>(t[3])) {
      const py::sequence r = py::reinterpret_borrow<py::sequence>(rec);
      if (r.size() != 6) fail("Chain state: a segment record is not (name, joint, type, origin, axis, tip)");
      SegmentRecord s;
      s.name = py::str(r[0]).cast<std::string>();
      s.joint_name = py::str(r[1]).cast<std::string>();
      s.type = r[2].cast<int>();
      const std::vector<double> o = floats_of(r[3], 3, "a joint origin"), a = floats_of(r[4], 3, "a joint axis");
      s.origin = Eigen::Vector3d(o[0], o[1], o[2]);
      s.axis = Eigen::Vector3d(a[0], a[1], a[2]);
      s.tip = matrix_of(r[5], "a segment tip");
      records.push_back(s);
    }
    const std::string base = version == 1 ? "" : py::str(t[6]).cast<std::string>();
    return Chain::from_records(records, vector_of(t[4], "lower"), vector_of(t[5], "upper"), base);
  }
  fail("Chain state: unknown layout '" + kind + "'");
}

}  // namespace

void def_chain_value(py::class_<Chain>& cls) {
  cls.def(py::pickle([](const Chain& c) { return chain_state(c); },
                     [](const py::tuple& t) {
                       try {
                         return chain_from_state(t);
                       } catch (const py::cast_error&) {
                         fail("Chain state: malformed");
                       }
                     }));
  cls.def(
      "__eq__", [](const Chain& a, const Chain& b) { return a.same_kinematics(b); }, py::is_operator(),
      "Same kinematics: joint types, limits and constant frames equal bit for bit (however built).");
  cls.def("__hash__", [](const Chain& c) { return c.kinematics_hash(); });
  // Text for people is written in Python, from the state above.
  cls.def("__repr__", [](py::handle self) { return printed("chain_repr", self); });
  const auto table = [](py::handle self) { return printed("table", self); };
  cls.def("table", table,
          "The kinematic table as text, as print(chain) shows it: a DH chain's rows (a, alpha, d, theta, joint\n"
          "type, lower and upper limits; standard or modified said), any other chain's segments (joint name,\n"
          "type, the frame after the joint at q = 0 as xyz and roll, pitch, yaw, the joint's axis in that\n"
          "frame, limits: a URDF joint's <origin>, <axis> and <limit>). Metres and degrees.");
  cls.def("__str__", table);
}

}  // namespace robokin::bind
