#pragma once
/// \file option_sets.hpp
/// impactkit.SweepOptions, ContinuationOptions, CurveOptions, DiagramOptions,
/// MapOptions and BasinsOptions: a driver's keywords as a Python class, so
/// that a user sees the defaults (help() shows each field, its meaning and
/// its default) and reuses a set: `impactkit.sweep(system,
/// **impactkit.SweepOptions(steps=11))`.
///
/// Each class holds the library's option struct itself, its defaults those
/// of the struct default-constructed (the same object whose fields the
/// function's keyword defaults are): a default is never typed twice, and
/// test_options.py compares every class with its function's signature. The
/// fields are named like the function's keywords (`from_` for `from`), and
/// the class is a mapping of them (keys, [], to_dict) for `**`.
///
/// One binding for all: the area's source lists its keywords, each with an
/// accessor of the struct, and OptionSetBinding::Bind adds the properties,
/// the keyword constructor, the mapping and the repr.
#include <pybind11/pybind11.h>

#include <functional>
#include <memory>
#include <set>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace impactkit::python {

namespace py = pybind11;

/// The Python object of an option set: the library's struct, and which of
/// the function's required keywords (those without a default, a range's
/// ends) are not given yet. They are None until set: a double cannot be
/// None, and no value of the struct may stand for "not given", or `**`
/// would pass it in place of the caller's.
template <class Options>
struct OptionSet {
  Options options;
  std::set<std::string> unset;
};

/// The Python name of a field's type, for the TypeError of a wrong value.
template <class T>
constexpr const char* PythonTypeName() {
  if constexpr (std::is_same_v<T, bool>) {
    return "bool";
  } else if constexpr (std::is_integral_v<T>) {
    return "int";
  } else if constexpr (std::is_floating_point_v<T>) {
    return "float";
  } else {
    static_assert(std::is_same_v<T, std::string>, "a keyword is a bool, number or string");
    return "str";
  }
}

/// `value` as a T, converting as the function's keyword does (an int for a
/// float, ...); anything else raises TypeError naming the keyword, as a
/// wrong keyword type does.
template <class T>
T FromPython(const std::string& keyword, py::handle value) {
  try {
    return value.cast<T>();
  } catch (const py::cast_error&) {
    throw py::type_error(keyword + " must be " + PythonTypeName<T>() + ", got " +
                         Py_TYPE(value.ptr())->tp_name);
  }
}

/// The keywords of one driver, in the function's order, then Bind.
template <class Options>
class OptionSetBinding {
 public:
  using Set = OptionSet<Options>;

  /// `defaults`: the struct the function's keyword defaults come from.
  explicit OptionSetBinding(Options defaults) { defaults_.options = std::move(defaults); }

  /// A keyword held as it is in a field of the struct: `field` is a member
  /// pointer or a generic lambda `[](auto& o) -> auto& { return o.row.from; }`
  /// (readable from a const struct, so that the getter needs no cast).
  template <class Access>
  OptionSetBinding& Field(const char* keyword, Access field, const char* doc) {
    return Add(keyword, doc, false, FieldGetter(field), FieldSetter(keyword, field));
  }
  /// A keyword the function requires (no default): None until given.
  template <class Access>
  OptionSetBinding& Required(const char* keyword, Access field, const char* doc) {
    defaults_.unset.insert(keyword);
    return Add(keyword, doc, true, FieldGetter(field), FieldSetter(keyword, field));
  }
  /// A keyword the struct holds in another form (an enum the function names
  /// by a string): get(const Options&) -> T, put(Options&, const T&), which
  /// throws InvalidInput (ValueError) for a bad name.
  template <class Get, class Put>
  OptionSetBinding& Converted(const char* keyword, Get get, Put put, const char* doc) {
    using T = std::remove_cvref_t<std::invoke_result_t<Get, const Options&>>;
    return Add(
        keyword, doc, false, [get](const Options& o) { return py::cast(get(o)); },
        [put, name = std::string(keyword)](Options& o, py::handle value) {
          put(o, FromPython<T>(name, value));
        });
  }

  /// The class `name` in `module`: a property per keyword (its doc, then its
  /// default), the keyword constructor, the mapping of the keywords that
  /// are not None (keys, __getitem__, __iter__, __len__, to_dict) and a repr
  /// listing every field. `doc` says what the set is for.
  py::class_<Set> Bind(py::module_& module, const char* name, const std::string& doc) const {
    auto keywords = std::make_shared<const std::vector<Keyword>>(keywords_);
    const std::string class_name = name;
    const Set defaults = defaults_;
    const std::string class_doc = doc +
                                  "\n\nA mapping of the keywords that are not None (keys(), "
                                  "[keyword], to_dict()), for `**`. The defaults:\n" +
                                  Repr(class_name, *keywords, defaults);
    py::class_<Set> cls(module, name, class_doc.c_str());
    cls.def(py::init([keywords, class_name, defaults](const py::kwargs& kwargs) {
              Set set = defaults;
              for (const auto& [key, value] : kwargs) {
                const std::string keyword = py::str(key);
                const Keyword* found = Find(*keywords, keyword);
                // As Python's own functions say it.
                if (found == nullptr) {
                  throw py::type_error(class_name + "() got an unexpected keyword argument '" +
                                       keyword + "'");
                }
                Put(set, *found, value);
              }
              return set;
            }),
            "Keyword arguments set the fields of the same names; the others keep their "
            "defaults. An unknown keyword raises TypeError.");
    for (const Keyword& keyword : *keywords) {
      const std::string property_doc =
          keyword.doc + (keyword.required
                             ? " Required by the function: None (left out of the mapping) "
                               "until set."
                             : " Default: " + std::string(py::repr(Get(defaults, keyword))) + ".");
      cls.def_property(
          keyword.name.c_str(), [keyword](const Set& set) { return Get(set, keyword); },
          [keyword](Set& set, const py::object& value) { Put(set, keyword, value); },
          property_doc.c_str());
    }
    cls.def(
           "keys", [keywords](const Set& set) { return Keys(*keywords, set); },
           "The keywords whose value is not None, in the function's order.")
        .def(
            "__getitem__",
            [keywords](const Set& set, const std::string& key) {
              const Keyword* found = Find(*keywords, key);
              if (found != nullptr) {
                py::object value = Get(set, *found);
                if (!value.is_none()) return value;
              }
              throw py::key_error(key);
            },
            py::arg("key"), "The value of a keyword; KeyError when it is unknown or None.")
        .def(
            "__iter__", [keywords](const Set& set) { return py::iter(Keys(*keywords, set)); },
            "Iterates over keys().")
        .def(
            "__len__", [keywords](const Set& set) { return Keys(*keywords, set).size(); },
            "The number of keys().")
        .def(
            "to_dict",
            [keywords](const Set& set) {
              py::dict out;
              for (const Keyword& keyword : *keywords) {
                py::object value = Get(set, keyword);
                if (!value.is_none()) out[keyword.name.c_str()] = value;
              }
              return out;
            },
            "{keyword: value} of keys(): what `**` passes.")
        .def("__repr__",
             [keywords, class_name](const Set& set) { return Repr(class_name, *keywords, set); });
    return cls;
  }

 private:
  /// A keyword: read from and written to the struct, with Python values.
  struct Keyword {
    std::string name;
    std::string doc;
    bool required = false;
    std::function<py::object(const Options&)> get;
    std::function<void(Options&, py::handle)> put;
  };

  template <class Access>
  static auto FieldGetter(Access field) {
    return [field](const Options& o) { return py::cast(std::invoke(field, o)); };
  }
  template <class Access>
  static auto FieldSetter(const char* keyword, Access field) {
    using T = std::remove_cvref_t<std::invoke_result_t<Access, Options&>>;
    return [field, name = std::string(keyword)](Options& o, py::handle value) {
      std::invoke(field, o) = FromPython<T>(name, value);
    };
  }

  template <class Get, class Put>
  OptionSetBinding& Add(const char* keyword, const char* doc, bool required, Get get, Put put) {
    keywords_.push_back({keyword, doc, required, std::move(get), std::move(put)});
    return *this;
  }

  static const Keyword* Find(const std::vector<Keyword>& keywords, const std::string& name) {
    for (const Keyword& keyword : keywords) {
      if (keyword.name == name) return &keyword;
    }
    return nullptr;
  }
  static py::object Get(const Set& set, const Keyword& keyword) {
    if (keyword.required && set.unset.count(keyword.name) != 0) return py::none();
    return keyword.get(set.options);
  }
  /// None unsets a required keyword; any other value must fit the field.
  static void Put(Set& set, const Keyword& keyword, py::handle value) {
    if (keyword.required && value.is_none()) {
      set.unset.insert(keyword.name);
      return;
    }
    keyword.put(set.options, value);
    set.unset.erase(keyword.name);
  }
  static py::list Keys(const std::vector<Keyword>& keywords, const Set& set) {
    py::list keys;
    for (const Keyword& keyword : keywords) {
      if (!Get(set, keyword).is_none()) keys.append(keyword.name);
    }
    return keys;
  }
  /// "SweepOptions(parameter='omega', from_=0.1, ...)": every field, None too.
  static std::string Repr(const std::string& class_name, const std::vector<Keyword>& keywords,
                          const Set& set) {
    std::string out = class_name + "(";
    for (const Keyword& keyword : keywords) {
      if (&keyword != &keywords.front()) out += ", ";
      out += keyword.name + "=" + std::string(py::repr(Get(set, keyword)));
    }
    return out + ")";
  }

  Set defaults_;
  std::vector<Keyword> keywords_;
};

}  // namespace impactkit::python
