// Pickling of the module's classes (issue 18), so that multiprocessing, concurrent.futures and
// joblib can send them between processes: a class's state is the tuple of its fields, in the
// order listed; a nested class goes through its own pickle, Eigen members as NumPy arrays, optional
// members as None or a value, and enums by their names (to_string), which survive a reordering of
// the enumerators. Unpickling default-constructs the object and sets every field, so each class
// pickled here must be default-constructible with public fields, as the library's results are.
#pragma once

#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

namespace spdfit::python {

/// Refuses a state that does not have `size` fields, naming the class (`what`), so that a pickle
/// from another version of the module fails with a message rather than a garbled object.
inline void check_state(const pybind11::tuple& state, std::size_t size, const char* what) {
  if (state.size() != size) {
    throw std::runtime_error(std::string("cannot unpickle ") + what + ": expected " + std::to_string(size) +
                             " fields, got " + std::to_string(state.size()));
  }
}

/// The enumerator among `values` whose to_string is `name`; a name that is none of them (a state
/// from another version, or edited) is refused with a message naming the class and the field.
template <typename Enum, std::size_t N>
Enum enum_from(const std::string& name, const std::array<Enum, N>& values, const char* what, const char* field) {
  for (Enum value : values) {
    if (std::string_view(to_string(value)) == name) return value;
  }
  throw std::runtime_error(std::string("cannot unpickle ") + what + ": unknown " + field + " '" + name + "'");
}

/// One entry of a state: `get` reads it from the object, `set` writes it back from the state.
template <typename Get, typename Set>
struct StateField {
  Get get;  ///< (const Class&) -> a value pybind11 converts to Python
  Set set;  ///< (Class&, const pybind11::object&) -> void
};

template <typename Get, typename Set>
StateField<Get, Set> state_field(Get get, Set set) {
  return {std::move(get), std::move(set)};
}

/// A data member, converted by pybind11 as the attribute getters convert it.
template <typename Class, typename Member>
auto state_field(Member Class::*member) {
  return state_field([member](const Class& object) { return object.*member; },
                     [member](Class& object, const pybind11::object& value) { object.*member = value.cast<Member>(); });
}

/// An enum data member, by its name; `values` lists every enumerator, `field` names it in errors.
template <typename Class, typename Enum, std::size_t N>
auto enum_field(Enum Class::*member, const std::array<Enum, N>& values, const char* what, const char* field) {
  return state_field([member](const Class& object) { return std::string(to_string(object.*member)); },
                     [member, values, what, field](Class& object, const pybind11::object& value) {
                       object.*member = enum_from(value.cast<std::string>(), values, what, field);
                     });
}

namespace detail {
template <typename Class, std::size_t... I, typename... Fields>
Class from_state(const pybind11::tuple& state, std::index_sequence<I...>, const Fields&... fields) {
  Class object;
  (fields.set(object, pybind11::object(state[I])), ...);
  return object;
}
}  // namespace detail

/// The py::pickle of `Class` whose state is the tuple of `fields` (state_field, enum_field), in
/// order; `what` is the class's name in the message for a state of the wrong length.
template <typename Class, typename... Fields>
auto pickle_fields(const char* what, Fields... fields) {
  return pybind11::pickle(
      [fields...](const Class& object) { return pybind11::make_tuple(fields.get(object)...); },
      [fields..., what](const pybind11::tuple& state) {
        check_state(state, sizeof...(Fields), what);
        return detail::from_state<Class>(state, std::index_sequence_for<Fields...>{}, fields...);
      });
}

}  // namespace spdfit::python
