#pragma once
// A system whose force is a Python callable (docs/python.md, "A force of
// your own in Python"): H = sum_i p_i^2 / (2 m_i) + V(q), F = -dV/dq given
// by force(q), V by potential(q) where given (else no energy is watched).
// The slow path of the module: every force is a call into Python with the
// GIL taken. Stacked lanes run an ensemble in lockstep, one call for all of
// them: q arrives as an array of shape (lanes, n), the force returns the
// same shape, the potential one value per lane.
#include <pybind11/pybind11.h>

#include <cstddef>
#include <memory>
#include <vector>

#include "running/runnable_system.hpp"

namespace sympl::app::python {

struct force_callables {
    pybind11::object force, potential;  // potential: None for none
    std::vector<double> masses;         // one per degree of freedom of a lane
    std::size_t lanes = 1;
    // The first lane whose force came back not finite, or -1.
    mutable long first_bad_lane = -1;
};

// The runnable system of `lanes` stacked copies from x0 (q of every lane,
// then p of every lane): every splitting table, rk4, the RKN pairs and the
// Odeint steppers on the generic path; the methods that need the force's
// derivative or dual numbers (force-gradient tables, Gauss-Legendre, MEGNO)
// are refused by the system's form. Checks masses, sizes and that force and
// potential are finite at x0 before anything runs.
runnable_system callable_runnable(std::shared_ptr<const force_callables> c, std::vector<double> x0);

// An ensemble of stacked lanes (the rows of `starts`, q then p each) run by
// `method` (a splitting table) in lockstep: one force call for all rows per
// kick. The energy error of each row is taken every `sample_every` steps
// (one potential call), as the C++ ensembles sample it; a row whose error
// passes divergence_limit is marked unstable and the rest run on. A force
// that is not finite stops the run with the row named. Without a potential
// the errors are NaN.
std::vector<ensemble_row> callable_ensemble(const force_callables& one, const std::vector<std::vector<double>>& starts,
                                            const ensemble_request& rq);

// V of each lane at q (lanes * n numbers, lane by lane), one call.
std::vector<double> lane_potentials(const force_callables& c, const double* q, std::size_t n);

}  // namespace sympl::app::python
