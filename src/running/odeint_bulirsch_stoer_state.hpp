#pragma once
// What Boost.Odeint's bulirsch_stoer carries from one try_step to the next,
// written to a checkpoint's carried list and read back on resume. Boost 1.74
// keeps it private: the order it expects to converge at (m_current_k_opt),
// whether it is at its first step (m_first, which accepts convergence at any
// order), whether its last try was rejected (m_last_step_rejected, which
// forbids raising the order) and the step it proposed (m_dt_last; a try with
// another step resets the other three). Everything else it holds is rebuilt
// at every try (the extrapolation tables) or constant, so with these four
// restored a run goes on bit for bit (tests/program/test_kill_and_resume.cpp),
// and a checkpointed run gives the bits of one without checkpoints, whatever
// the checkpoint interval (a reset at each checkpoint would not).
//
// The reading is compiled for one stepper type (odeint_bulirsch_stoer_state.cpp):
// a checkpointed run holds its state in a std::vector<double>. The std::array
// state of the other runs gives the same bits (tests/program/test_method_kinds.cpp).
#include <cstddef>
#include <vector>

#include <boost/numeric/odeint/stepper/bulirsch_stoer.hpp>
#include <sympl/core/carried_state.hpp>

namespace sympl::app {

using bulirsch_stoer_vector = boost::numeric::odeint::bulirsch_stoer<std::vector<double>>;

// Its history as a part of a carried list (core/carried_state.hpp): the
// order, the first-step flag, the rejected flag and the proposed step. Read
// back into a stepper for states of `size` numbers, the stepper first makes
// one try on a zero field (its first try sizes its tables and resets the
// four, which would undo a restore made before it); an order outside 2..7,
// a flag not 0 or 1 or a step that is not finite is refused.
struct bulirsch_stoer_history {
    bulirsch_stoer_vector& stepper;
    std::size_t size;
    template <class Self, class List>
    static void carried_fields(Self& self, List& l) {
        fields(self, l);
    }
    // The one list, walked by both (odeint_bulirsch_stoer_state.cpp).
    static void fields(const bulirsch_stoer_history& h, sympl::detail::carried_writer<double>& l);
    static void fields(bulirsch_stoer_history& h, sympl::detail::carried_reader<double>& l);
};

}  // namespace sympl::app
