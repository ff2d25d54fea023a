#pragma once
// A carried list (carried_state.hpp) restored into the stepper itself, for
// steppers restore_carried_list should not copy whole: those that hold the
// caller's H or system (a lambda that captures cannot be assigned) or
// workspaces far larger than what they carry. A list that does not fit is
// undone by reading back the list the stepper carried before, which its own
// fields always accept: the stepper is left as it was in all it carries.
#include <span>
#include <vector>

#include "carried_state.hpp"

namespace sympl::detail {

template <class S, class T>
void read_carried_in_place(T& t, std::span<const S> values, const char* who) {
    carried_reader<S> r{values, who};
    carried_part(t, r);
    r.done();
}

template <class S, class T>
void restore_carried_in_place(T& t, std::span<const S> values, const char* who) {
    const std::vector<S> before = carried_list<S>(t);
    try {
        read_carried_in_place(t, values, who);
    } catch (...) {
        read_carried_in_place(t, std::span<const S>(before), who);
        throw;
    }
}

}  // namespace sympl::detail
