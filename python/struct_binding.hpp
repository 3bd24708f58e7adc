#pragma once
// A library's settings struct as a Python class whose attributes are its fields: the defaults a
// new object holds are the struct's default member values (nothing typed again here), a word
// field (an enum with its library table of words) reads and writes its word, an effect mask its
// list of effect names. The class gets a keyword constructor (Scene(gravity=0, law="linear"))
// through powderbed._structs.configure, which also checks the names and types.
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <fmt/format.h>

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

#include "powderbed/bed/errors.hpp"
#include "powderbed/bed/option_words.hpp"

namespace powderbed::python {

namespace py = pybind11;

// The word of `value` in `words` (the tables list every value of their enum).
template <class E, std::size_t N>
std::string word_of(E value, const bed::OptionWord<E> (&words)[N]) {
  for (const bed::OptionWord<E>& w : words)
    if (w.value == value) return std::string(w.text);
  return "?";
}

template <class T>
class StructBinding {
 public:
  StructBinding(py::module_& m, const char* name, const char* doc) : cls_(m, name, doc) {
    cls_.def(py::init([](const py::kwargs& fields) { return configured(fields); }),
             "Every field at the library's default, then the keyword arguments (a nested "
             "struct's field takes a dict of its fields).");
    cls_.def("__copy__", [](const T& t) { return T(t); });
    cls_.def("__deepcopy__", [](const T& t, const py::dict&) { return T(t); });
  }

  template <class V>
  StructBinding& field(const char* name, V T::*member, const char* doc) {
    cls_.def_readwrite(name, member, doc);
    names_.push_back(name);
    return *this;
  }

  // An enum field as one of its words; a word outside the table raises InputError naming the
  // field and the words accepted (bed::parse_word).
  template <class E, std::size_t N>
  StructBinding& word(const char* name, E T::*member, const bed::OptionWord<E> (&words)[N],
                      const char* doc) {
    const auto* table = &words;
    cls_.def_property(
        name, [member, table](const T& t) { return word_of(t.*member, *table); },
        [member, table, name](T& t, const std::string& text) {
          t.*member = bed::parse_word(text, name, *table);
        },
        doc);
    names_.push_back(name);
    return *this;
  }

  // An enum field whose library has a parser and a namer rather than a table.
  template <class E>
  StructBinding& word(const char* name, E T::*member, E (*parse)(const std::string&, const std::string&),
                      const char* (*name_of)(E), const char* doc) {
    cls_.def_property(
        name, [member, name_of](const T& t) { return std::string(name_of(t.*member)); },
        [member, parse, name](T& t, const std::string& text) { t.*member = parse(text, name); },
        doc);
    names_.push_back(name);
    return *this;
  }

  // A field written in another form than the struct holds it (packgen's phases as their text),
  // through the getter and setter given.
  template <class Get, class Set>
  StructBinding& property(const char* name, Get get, Set set, const char* doc) {
    cls_.def_property(name, get, set, doc);
    names_.push_back(name);
    return *this;
  }

  // A bit mask of effects as the list of the names of its bits, from the library's effect
  // table (rows of {bit, name}); an unknown name raises InputError listing the table's names.
  template <class Row, std::size_t N>
  StructBinding& effects(const char* name, unsigned T::*member, const Row (&rows)[N],
                         const char* doc) {
    const auto* table = &rows;
    cls_.def_property(
        name,
        [member, table](const T& t) {
          std::vector<std::string> on;
          for (const Row& row : *table)
            if ((t.*member & static_cast<unsigned>(row_bit(row))) != 0) on.emplace_back(row.name);
          return on;
        },
        [member, table, name](T& t, const std::vector<std::string>& names) {
          unsigned mask = 0;
          for (const std::string& n : names) mask |= bit_named(*table, n, name);
          t.*member = mask;
        },
        doc);
    names_.push_back(name);
    return *this;
  }

  // The field names (for configure's checks and repr), after every field is declared.
  py::class_<T>& done() {
    cls_.attr("_fields") = py::tuple(py::cast(names_));
    cls_.def("__repr__", [](const py::object& self) {
      std::string text = py::str(self.get_type().attr("__name__")).cast<std::string>() + "(";
      const auto names = self.attr("_fields").cast<std::vector<std::string>>();
      for (std::size_t k = 0; k < names.size(); ++k)
        text += (k ? ", " : "") + names[k] + "=" + py::repr(self.attr(names[k].c_str())).cast<std::string>();
      return text + ")";
    });
    return cls_;
  }

 private:
  // dem's rows name their bit `bit`, thermal's `effect`.
  template <class Row>
  static auto row_bit(const Row& row) -> decltype(row.bit) { return row.bit; }
  template <class Row>
  static auto row_bit(const Row& row) -> decltype(row.effect) { return row.effect; }

  template <class Row, std::size_t N>
  static unsigned bit_named(const Row (&rows)[N], const std::string& text, const char* option) {
    std::vector<std::string_view> accepted;
    for (const Row& row : rows) {
      if (text == row.name) return static_cast<unsigned>(row_bit(row));
      accepted.emplace_back(row.name);
    }
    throw InputError(fmt::format("{}: '{}' is not an effect (accepted: a list of {})", option, text,
                                 fmt::join(accepted, ", ")));
  }

  // A T at its defaults with `fields` set through a Python view of it (the view borrows the
  // object, so the attribute setters above and configure's checks apply), returned by value.
  static T configured(const py::kwargs& fields) {
    T t;
    if (fields.empty()) return t;
    const py::object view = py::cast(&t, py::return_value_policy::reference);
    py::module_::import("powderbed._structs").attr("configure")(view, **fields);
    return t;
  }

  py::class_<T> cls_;
  std::vector<std::string> names_;
};

}  // namespace powderbed::python
