// A scene's [system] of formulas as a registry entry (formula_entry.hpp).
#include "formulas/formula_entry.hpp"

#include <cmath>
#include <map>
#include <mutex>

#include <Eigen/Core>

#include "formulas/formula_code.hpp"
#include "output/format.hpp"

namespace sympl::app::formulas {

namespace {

// A formula's degree in p, lowest and highest, where it is a polynomial in p.
struct degree {
    bool polynomial = true;
    int low = 0, high = 0;
};

degree degree_in_p(const node& n) {
    const auto of = [&](std::size_t k) { return degree_in_p(*n.children[k]); };
    const auto constant = [](const degree& d) { return d.polynomial && d.high == 0; };
    switch (n.kind) {
        case node::p: return {true, 1, 1};
        case node::add:
        case node::subtract: {
            const degree a = of(0), b = of(1);
            return {a.polynomial && b.polynomial, std::min(a.low, b.low), std::max(a.high, b.high)};
        }
        case node::multiply: {
            const degree a = of(0), b = of(1);
            return {a.polynomial && b.polynomial, a.low + b.low, a.high + b.high};
        }
        case node::divide: {
            const degree a = of(0), b = of(1);
            return constant(b) ? a : degree{false};
        }
        case node::negate: return of(0);
        case node::power: {
            const degree a = of(0), b = of(1);
            const node& e = *n.children[1];
            if (e.kind == node::number && e.value == std::floor(e.value) && e.value >= 0 && e.value <= 16)
                return {a.polynomial, a.low * int(e.value), a.high * int(e.value)};
            return constant(a) && constant(b) ? degree{} : degree{false};
        }
        case node::call: return constant(of(0)) ? degree{} : degree{false};
        case node::sum: return of(2);
        default: return {};  // numbers, parameters, indices, q
    }
}

std::vector<double> in_order(const names& known, const parameter_values& v) {
    std::vector<double> k;
    for (const auto& name : known.parameters) k.push_back(v.at(name));
    return k;
}

std::string described(const formula_definition& d) {
    if (d.H) return "H = " + d.H->text + " (a scene's formula)";
    return "T = " + d.T->text + ", V = " + d.V->text + " (a scene's formulas)";
}

}  // namespace

bool quadratic_in_p(const formula& T) {
    const degree d = degree_in_p(*T.root);
    return d.polynomial && d.low == 2 && d.high == 2;
}

system_entry formula_entry(formula_definition d) {
    system_entry e;
    e.name = d.name;
    e.description = described(d);
    for (std::size_t k = 0; k < d.known.parameters.size(); ++k)
        e.parameters.push_back(any(d.known.parameters[k], d.parameter_values[k], "a parameter of the formulas"));
    e.coordinate_names = d.known.q_names;
    e.kinetic_not_quadratic = !d.H && !quadratic_in_p(*d.T);
    auto shared = std::make_shared<const formula_definition>(std::move(d));
    e.build = [shared](const parameter_values& v) {
        std::vector<double> x0 = shared->q0;
        x0.insert(x0.end(), shared->p0.begin(), shared->p0.end());
        return formula_runnable(prepare(shared->T, shared->V, shared->H, in_order(shared->known, v), x0), x0);
    };
    if (shared->period)
        e.period = {"the scene's period = " + shared->period->text, [shared](const parameter_values& v) {
                        const Eigen::VectorXd none;
                        return evaluate<double>(*shared->period, in_order(shared->known, v), none, none);
                    }};
    return e;
}

std::shared_ptr<const prepared_formulas> prepare(std::shared_ptr<const formula> T, std::shared_ptr<const formula> V,
                                                 std::shared_ptr<const formula> H, std::vector<double> parameters,
                                                 const std::vector<double>& x0) {
    auto f = std::make_shared<prepared_formulas>();
    f->T = std::move(T), f->V = std::move(V), f->H = std::move(H);
    f->parameters = std::move(parameters);
    f->dimension = long(x0.size() / 2);
    const Eigen::VectorXd q = Eigen::Map<const Eigen::VectorXd>(x0.data(), f->dimension),
                          p = Eigen::Map<const Eigen::VectorXd>(x0.data() + f->dimension, f->dimension);
    // Every index and bound checked, every value finite, at x0 (the
    // interpreter checks each index it reads).
    const auto finite_at_x0 = [&](const formula& g, const char* what) {
        const double v = evaluate<double>(g, f->parameters, q, p);
        if (!std::isfinite(v))
            throw formula_error(1, std::string(what) + " = " + shortest(v) + " at the initial state; expected a finite "
                                                                              "value");
        return v;
    };
    const std::string source = f->H ? general_source(*f->H) : separable_source(*f->T, *f->V);
    const double reference = f->H ? finite_at_x0(*f->H, "H") : finite_at_x0(*f->T, "T") + finite_at_x0(*f->V, "V");

    // One compilation per distinct source in a run: an ensemble over a
    // parameter, or the report's many runs, reuse it (the parameters are
    // arguments of the compiled functions).
    static std::mutex mutex;
    static std::map<std::string, compiled_or_reason> compiled;
    compiled_or_reason c;
    {
        std::lock_guard lock(mutex);
        auto found = compiled.find(source);
        if (found == compiled.end()) found = compiled.emplace(source, compile_c(source)).first;
        c = found->second;
    }
    f->code = c.code;
    f->interpreted_because = c.reason;
    if (f->code) {
        const auto take = [&]<class R>(compiled_functions<R>& out, const char* suffix) {
            const auto fn = [&](const char* name) { return f->code->function(std::string(name) + suffix); };
            if (f->H) {
                out.H = reinterpret_cast<value_of_qp<R>>(fn("sympl_H"));
                out.dH_dq = reinterpret_cast<gradient_of_qp<R>>(fn("sympl_dH_dq"));
                out.dH_dp = reinterpret_cast<gradient_of_qp<R>>(fn("sympl_dH_dp"));
            } else {
                out.T = reinterpret_cast<value_of_p<R>>(fn("sympl_T"));
                out.V = reinterpret_cast<value_of_p<R>>(fn("sympl_V"));
                out.velocity = reinterpret_cast<gradient_of_x<R>>(fn("sympl_velocity"));
                out.force = reinterpret_cast<gradient_of_x<R>>(fn("sympl_force"));
            }
        };
        take(f->d, "_d");
        take(f->l, "_l");
        // The machine code computes what the interpreter does, in its order:
        // the same bits at x0, or the interpreter is used.
        const double compiled_value = f->H ? f->d.H(q.data(), p.data(), f->parameters.data())
                                           : f->d.T(p.data(), f->parameters.data()) +
                                                 f->d.V(q.data(), f->parameters.data());
        if (compiled_value != reference) {
            f->interpreted_because = "the compiled formulas give " + shortest(compiled_value) + " at x0 where the "
                                     "interpreter gives " + shortest(reference);
            f->code = nullptr;
        }
    }
    return f;
}

}  // namespace sympl::app::formulas
