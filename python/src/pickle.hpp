// Pickling of the module's classes, so that multiprocessing, concurrent.futures and joblib can
// send them between processes. Every state is (kPickleFormat, payload): the format's number,
// refused with a message when it is another (a pickle of another version of spdfit), and
//  - for the library's results (FitResult and its parts, NearestResult, LinearSystemResult,
//    MethodIdentification): their exact JSON, the library's own rendering (spdfit/render.hpp,
//    JsonStyle::Exact: every double bit for bit, +-inf and NaN included);
//  - for the other classes: the tuple of their fields in the order listed (pickle_fields), a
//    nested class through its own pickle, Eigen members as NumPy arrays, optional members as None
//    or a value, enums by their names (to_string), which survive a reordering of the enumerators.
// Unpickling default-constructs the object and sets every field, so each class pickled here must
// be default-constructible with public fields, as the library's results are. enable_every_protocol
// makes protocols 0 and 1 (and copy.copy) build the object the same way as protocols 2-5 do.
#pragma once

#include <pybind11/pybind11.h>

#include <array>
#include <cstddef>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "spdfit/render.hpp"

namespace spdfit::python {

/// The number of the pickles' format: one more whenever a state changes. Pickles made before
/// states had a number are format 0.
inline constexpr int kPickleFormat = 2;

/// Raises pickle.UnpicklingError with `message` (what pickle.loads raises for a bad pickle).
[[noreturn]] void refuse_state(const std::string& message);

/// The payload of `state`, (kPickleFormat, payload); a state of another format, or of none (a
/// pickle made before states had a number), is refused naming the class (`what`) and both formats.
pybind11::object checked_payload(const pybind11::tuple& state, const char* what);

/// Refuses a tuple that does not have `size` fields, naming the class (`what`), so that a changed
/// state fails with a message rather than a garbled object.
void check_state(const pybind11::tuple& state, std::size_t size, const char* what);

/// Makes every pickled class of `module` and its submodules (those with __setstate__) pickle under
/// every protocol, 0 to 5, and copy with copy.copy and copy.deepcopy: its __reduce__ builds the
/// object as protocol 2 does (cls.__new__, then __setstate__ with the state), where protocols 0
/// and 1 would call object.__new__ on it, which aborts for a pybind11 class. Call it once, after
/// every class is bound.
void enable_every_protocol(pybind11::module_& module);

/// The enumerator among `values` whose to_string is `name`; a name that is none of them (a state
/// from another version, or edited) is refused with a message naming the class and the field.
template <typename Enum, std::size_t N>
Enum enum_from(const std::string& name, const std::array<Enum, N>& values, const char* what, const char* field) {
  for (Enum value : values) {
    if (std::string_view(to_string(value)) == name) return value;
  }
  refuse_state(std::string("cannot unpickle ") + what + ": unknown " + field + " '" + name + "'");
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

/// The py::pickle of `Class` whose payload is the tuple of `fields` (state_field, enum_field), in
/// order; `what` is the class's name in the messages.
template <typename Class, typename... Fields>
auto pickle_fields(const char* what, Fields... fields) {
  return pybind11::pickle(
      [fields...](const Class& object) {
        return pybind11::make_tuple(kPickleFormat, pybind11::make_tuple(fields.get(object)...));
      },
      [fields..., what](const pybind11::tuple& state) {
        const auto payload = checked_payload(state, what).cast<pybind11::tuple>();
        check_state(payload, sizeof...(Fields), what);
        return detail::from_state<Class>(payload, std::index_sequence_for<Fields...>{}, fields...);
      });
}

/// The object from its exact JSON (from_json), a text that is not one refused naming the class.
template <typename Class>
Class object_from_json(const pybind11::object& payload, const char* what) {
  if (!pybind11::isinstance<pybind11::str>(payload)) {
    refuse_state(std::string("cannot unpickle ") + what + ": its state is not the library's JSON text");
  }
  try {
    return from_json<Class>(payload.cast<std::string>());
  } catch (const std::invalid_argument& e) {
    refuse_state(std::string("cannot unpickle ") + e.what());  // from_json's message names the class
  }
}

/// The py::pickle of a library result whose payload is its exact JSON (to_json, JsonStyle::Exact):
/// `render` is the to_json that writes it.
template <typename Class, typename Render>
auto pickle_json(const char* what, Render render) {
  return pybind11::pickle(
      [render](const Class& object) { return pybind11::make_tuple(kPickleFormat, render(object, JsonStyle::Exact)); },
      [what](const pybind11::tuple& state) { return object_from_json<Class>(checked_payload(state, what), what); });
}

/// "Name(key=value, ...)" from the library's JSON of an object (JsonStyle::Contract): its fields as
/// Python literals (None, True, lists), a repr that shows every field the rendering has.
std::string repr_from_json(const char* name, const std::string& json);

}  // namespace spdfit::python
