// A scene's formula system made runnable (formula_entry.hpp): the library's
// templates instantiated once for the two formula types, type-erased into
// the generic path's systems, where every kind the generic path runs takes
// it; nothing is compiled for it per kind.
#include <utility>

#include "formulas/formula_entry.hpp"
#include "running/generic_path.hpp"
#include "running/run_context.hpp"

namespace sympl::app::formulas {

runnable_system formula_runnable(std::shared_ptr<const prepared_formulas> f, std::vector<double> x0) {
    runnable_system r;
    r.degrees_of_freedom = x0.size() / 2;
    r.hamiltonian = true;
    app::detail::generic_parts g;
    if (f->H) {
        general_formulas h(f);
        r.form = app::detail::form_of<general_system<general_formulas>>();
        r.energy = [h](const std::vector<double>& x) {
            const phase_space<double> s = from_stacked<phase_space<double>>(x);
            return double(h.energy(s.q, s.p));
        };
        g = app::detail::generic_general(erased_general::of(h), r.energy);
    } else {
        separable_formulas sys(f);
        r.form = app::detail::form_of<separable_formulas>();
        r.energy = [sys](const std::vector<double>& x) {
            const phase_space<double> s = from_stacked<phase_space<double>>(x);
            return double(sys.kinetic(s.p) + sys.potential(s.q));
        };
        g = app::detail::generic_separable(erased_separable::of(sys), r.energy);
    }
    r.form.quadratic_kinetic = !f->H && quadratic_in_p(*f->T);
    r.compiled = {.kinds = {}, .classic = {}, .extrapolated = false};  // every method on the generic path
    r.x0 = std::move(x0);
    r.runner = std::move(g.run);
    r.reference_method = std::move(g.reference_method);
    r.reference = std::move(g.reference);
    r.ensemble = std::move(g.ensemble);
    r.section = std::move(g.section);
    r.events = std::move(g.events);
    return r;
}

}  // namespace sympl::app::formulas
