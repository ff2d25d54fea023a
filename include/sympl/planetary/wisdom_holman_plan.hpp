#pragma once
// The options of the Wisdom-Holman stepper (corrector order, kernel,
// coordinates) and the plan they make of a table: the sub-steps a step runs
// (the kernel in place of the leapfrog's kick) and the corrector's weights,
// checked once, by the stepper's constructor and by the program before a
// run. Citations as in corrector.hpp and kernels.hpp; the coordinates:
// Duncan, Levison & Lee 1998 (AJ 116, 2067), Wisdom & Holman 1991 (AJ 102, 1528).
#include <string>
#include <vector>

#include "../core/error.hpp"
#include "../core/table.hpp"
#include "corrector.hpp"
#include "kernels.hpp"

namespace sympl {

// The coordinates of the splitting: democratic heliocentric (Duncan, Levison
// & Lee 1998) or Jacobi (Wisdom & Holman 1991).
enum class wh_coordinates { democratic_heliocentric, jacobi };

inline std::string coordinates_name(wh_coordinates c) {
    switch (c) {
        case wh_coordinates::democratic_heliocentric: return "democratic_heliocentric";
        case wh_coordinates::jacobi: return "jacobi";
    }
    return "unknown (" + std::to_string(int(c)) + ")";
}

// Options of wisdom_holman_stepper.
struct wisdom_holman_options {
    // 0: none; 3, 5, 7, 9, 11 or 17: the symplectic corrector of that order
    // (symmetric tables; corrector_weights).
    int corrector_order = 0;
    // The drift-kick-drift leapfrog's kernel; wh_kernel::composition with a
    // corrector leaves O(eps h^(2K+2) + eps^2 h^4) (leapfrog_dkd only).
    // wh_kernel::lazy: the same in Jacobi coordinates at one Kepler drift and
    // two interaction evaluations a step.
    wh_kernel kernel = wh_kernel::kick;
    wh_coordinates coordinates = wh_coordinates::democratic_heliocentric;
};

// What one Wisdom-Holman step of `method` with `options` runs: its sub-steps
// (the kernel in place of the leapfrog's kick) and its corrector's weights.
// An invalid_argument, starting with `who`, when they do not fit: a
// force-gradient table, a corrector or kernel on a table that is not the
// leapfrog (the kernel: drift-kick-drift only), an order or kernel unknown.
// The stepper's constructor and the program (before a run) both ask it.
struct wisdom_holman_plan {
    std::vector<substep> substeps;
    std::vector<coefficient> corrector;  // c_1..c_K, empty without a corrector
    bool lazy_kernel = false;            // the kick of weight 1 is the lazy kernel's
};

inline wisdom_holman_plan plan_wisdom_holman(const table& method, const wisdom_holman_options& options,
                                             const std::string& who) {
    const std::string prefix = who + ": ";
    if (options.coordinates != wh_coordinates::democratic_heliocentric && options.coordinates != wh_coordinates::jacobi)
        throw invalid_argument(prefix + "coordinates " + coordinates_name(options.coordinates) +
                               "; expected democratic_heliocentric or jacobi");
    if (method.has_force_gradient())
        throw invalid_argument(prefix + "table '" + method.name() +
                               "' has force-gradient kicks; expected a table of plain kicks and drifts");
    wisdom_holman_plan plan{method.substeps(), {}};
    const auto& ops = plan.substeps;
    const auto is = [&](substep::kind_t outer) {
        return ops.size() == 3 && ops[0].kind == outer && ops[0].weight == 0.5L && ops[1].weight == 1 &&
               ops[2].weight == 0.5L;
    };
    if (options.corrector_order != 0) {
        // The corrector undoes a table's error terms first order in the
        // perturbation (docs/planetary.md): the leapfrogs'
        // weights are tabulated, any other symmetric table's solved for.
        try {
            if (is(substep::kick) || is(substep::drift))
                plan.corrector = corrector_weights(options.corrector_order, is(substep::kick)
                                                                                ? leapfrog_kernel::kick_drift_kick
                                                                                : leapfrog_kernel::drift_kick_drift);
            else
                plan.corrector = corrector_weights(options.corrector_order, method);
        } catch (const invalid_argument& e) {
            throw invalid_argument(prefix + e.what());
        }
    }
    if (options.kernel != wh_kernel::kick) {
        // The kernel replaces the middle kick of drift(h/2) kick(h) drift(h/2).
        const std::string kernel = "kernel " + kernel_name(options.kernel);
        if (options.kernel != wh_kernel::composition && options.kernel != wh_kernel::lazy)
            throw invalid_argument(prefix + kernel + "; expected kick, composition or lazy");
        if (options.kernel == wh_kernel::lazy && options.coordinates != wh_coordinates::jacobi)
            throw invalid_argument(prefix + kernel + " in " + coordinates_name(options.coordinates) +
                                   " coordinates; expected coordinates jacobi (the kernel needs an interaction "
                                   "that is a function of the positions alone)");
        if (!is(substep::drift))
            throw invalid_argument(prefix + kernel + " with table '" + method.name() +
                                   "'; expected the drift-kick-drift leapfrog with weights 1/2, 1, 1/2 "
                                   "(leapfrog_dkd, saba_1)");
        std::vector<substep> with_kernel{{substep::drift, 0.5L}};
        for (const substep& o : kernel_substeps(options.kernel)) with_kernel.push_back(o);
        with_kernel.push_back({substep::drift, 0.5L});
        plan.substeps = detail::canonical(with_kernel);  // drift(5/8) ... drift(3/8)
        plan.lazy_kernel = options.kernel == wh_kernel::lazy;
    }
    return plan;
}

}  // namespace sympl
