// Boost.Odeint's bulirsch_stoer's private history (odeint_bulirsch_stoer_state.hpp).
//
// An explicit instantiation may name private members: "the usual access
// checking rules do not apply to names in a declaration of an explicit
// instantiation" (C++20 [temp.spec.general]/6). A class template so
// instantiated with a pointer to a member defines a friend function, found by
// its tag, that hands the pointer out. The instantiations are made once, here
// (an explicit instantiation definition may appear only once in a program).
#include "running/odeint_bulirsch_stoer_state.hpp"

#include <cmath>
#include <type_traits>
#include <vector>

namespace sympl::app {

namespace {

template <class Tag, typename Tag::type Member>
struct bulirsch_stoer_member_door {
    friend typename Tag::type member_pointer(Tag) { return Member; }
};

struct bs_order_tag {
    using type = std::size_t bulirsch_stoer_vector::*;
    friend type member_pointer(bs_order_tag);
};
struct bs_first_tag {
    using type = bool bulirsch_stoer_vector::*;
    friend type member_pointer(bs_first_tag);
};
struct bs_rejected_tag {
    using type = bool bulirsch_stoer_vector::*;
    friend type member_pointer(bs_rejected_tag);
};
struct bs_proposed_step_tag {
    using type = double bulirsch_stoer_vector::*;
    friend type member_pointer(bs_proposed_step_tag);
};

// In the template's own namespace, as an explicit instantiation must be.
template struct bulirsch_stoer_member_door<bs_order_tag, &bulirsch_stoer_vector::m_current_k_opt>;
template struct bulirsch_stoer_member_door<bs_first_tag, &bulirsch_stoer_vector::m_first>;
template struct bulirsch_stoer_member_door<bs_rejected_tag, &bulirsch_stoer_vector::m_last_step_rejected>;
template struct bulirsch_stoer_member_door<bs_proposed_step_tag, &bulirsch_stoer_vector::m_dt_last>;

}  // namespace

namespace {
// The four fields in order; reading, they are checked, the stepper's tables
// sized by a try on a zero field, and then they are set.
template <class History, class List>
void walk(History& h, List& l) {
    constexpr bool reading = !std::is_const_v<History>;
    bulirsch_stoer_vector& s = h.stepper;  // a reference member: the writer reads it only
    double order = double(s.*member_pointer(bs_order_tag{}));
    bool first = s.*member_pointer(bs_first_tag{}), rejected = s.*member_pointer(bs_rejected_tag{});
    double proposed_step = s.*member_pointer(bs_proposed_step_tag{});
    l.number(order);
    l.flag(first);
    l.flag(rejected);
    l.number(proposed_step);
    if constexpr (reading) {
        // Boost keeps the order within 2 .. k_max - 1 (4 after a reset).
        const double highest = double(bulirsch_stoer_vector::m_k_max - 1);
        l.check((order >= 2 && order <= highest) && double(std::size_t(order)) == order,
                "holds a Boost.Odeint bulirsch_stoer order outside 2..7");
        l.check(std::isfinite(proposed_step), "holds a Boost.Odeint bulirsch_stoer step that is not finite");
        std::vector<double> y(h.size, 0.0);
        double t = 0, dt = 1;
        s.try_step([](const std::vector<double>&, std::vector<double>& dydt, double) { dydt.assign(dydt.size(), 0.0); },
                   y, t, dt);
        s.*member_pointer(bs_order_tag{}) = std::size_t(order);
        s.*member_pointer(bs_first_tag{}) = first;
        s.*member_pointer(bs_rejected_tag{}) = rejected;
        s.*member_pointer(bs_proposed_step_tag{}) = proposed_step;
    }
}
}  // namespace

void bulirsch_stoer_history::fields(const bulirsch_stoer_history& h, sympl::detail::carried_writer<double>& l) {
    walk(h, l);
}
void bulirsch_stoer_history::fields(bulirsch_stoer_history& h, sympl::detail::carried_reader<double>& l) { walk(h, l); }

}  // namespace sympl::app
