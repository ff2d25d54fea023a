// A scene's [system] of formulas as a registry entry (formula_entry.hpp).
#include "formulas/formula_entry.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <mutex>
#include <set>

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

namespace {

// For a T quadratic in p, dT/dp = M^-1 p is linear: M^-1 is the identity
// (unit masses, T = sum p_i^2 / 2) if it maps c e_i to c e_i, bit for bit,
// for every i. Drifts then move q by p itself (erased_system.hpp). Above
// 4096 degrees of freedom the n probes of n components are not spent.
bool velocity_is_identity(const prepared_formulas& f) {
    if (f.dimension > 4096) return false;
    const separable_formulas sys(std::shared_ptr<const prepared_formulas>(&f, [](const prepared_formulas*) {}));
    Eigen::VectorXd p = Eigen::VectorXd::Zero(f.dimension), v(f.dimension);
    for (long i = 0; i < f.dimension; ++i) {
        p[i] = 0.8125 + 0.0625 * double(i % 7);
        sys.velocity(p, v);
        if (v != p) return false;
        p[i] = 0;
    }
    return true;
}

}  // namespace

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
        runnable_system r =
            formula_runnable(prepare(shared->T, shared->V, shared->H, in_order(shared->known, v), x0), x0);
        if (!shared->exact.empty())
            r.exact = [shared, k = in_order(shared->known, v)](double t) {
                std::vector<double> with_t = k, x;
                with_t.push_back(t);
                const Eigen::VectorXd none;
                for (const auto& f : shared->exact) x.push_back(evaluate<double>(*f, with_t, none, none));
                return x;
            };
        return r;
    };
    e.exact = !shared->exact.empty();
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
    f->velocity_is_p = !f->H && quadratic_in_p(*f->T) && velocity_is_identity(*f);
    return f;
}

}  // namespace sympl::app::formulas

namespace sympl::app::formulas {

namespace {

// A name a formula can use (formula.hpp), of at most 64 characters.
bool is_name(const std::string& s) {
    return !s.empty() && s.size() <= 64 && name_start(s[0]) && std::all_of(s.begin(), s.end(), name_char);
}

// A system's name: it names output files and rows.
bool is_system_name(const std::string& s) {
    if (s.empty() || s.size() > 64 || !std::isalpha(static_cast<unsigned char>(s[0]))) return false;
    for (char c : s)
        if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-')) return false;
    return true;
}

// The exact solution's formulas: one per component of q and of p, of t and
// the parameters alone, and through the initial state at t = 0 (to 1e-9 of
// each value's size: a mistyped solution is refused, not trusted).
void read_exact(const formula_texts& t, formula_definition& d, std::string& definition) {
    if (t.exact_q.empty() && t.exact_p.empty()) return;
    const std::size_t n = t.q0.size();
    for (const auto& [key, list] : {std::pair{"exact_q", &t.exact_q}, std::pair{"exact_p", &t.exact_p}})
        if (list->size() != n)
            throw formula_input_error(key, 0, std::string("'system.") + key + "' has " + std::to_string(list->size()) +
                                                  " formulas for " + std::to_string(n) +
                                                  " degrees of freedom; expected one each, in exact_q and exact_p");
    names with_t = d.known;
    if (std::find(with_t.parameters.begin(), with_t.parameters.end(), "t") != with_t.parameters.end() ||
        std::find(with_t.q_names.begin(), with_t.q_names.end(), "t") != with_t.q_names.end() ||
        std::find(with_t.p_names.begin(), with_t.p_names.end(), "t") != with_t.p_names.end())
        throw formula_input_error("exact_q", 0, "the exact solution is a formula of t, and 't' names a parameter or a "
                                                "coordinate; expected 't' free for the time");
    with_t.parameters.push_back("t");
    std::vector<double> at_start = d.parameter_values;
    at_start.push_back(0.0);
    const Eigen::VectorXd none;
    for (std::size_t k = 0; k < 2 * n; ++k) {
        const bool is_q = k < n;
        const std::string key = std::string(is_q ? "exact_q" : "exact_p") + "[" + std::to_string(k % n) + "]";
        const std::string& text = (is_q ? t.exact_q : t.exact_p)[k % n];
        definition += "\n" + key + "=" + text;
        try {
            auto f = std::make_shared<formula>(parse(text, with_t));
            if (f->uses_q || f->uses_p)
                throw formula_error(1, key + " uses " + (f->uses_q ? "q" : "p") +
                                           "; expected a formula of t and the parameters alone");
            const double v = evaluate<double>(*f, at_start, none, none), x = is_q ? t.q0[k] : t.p0[k - n];
            if (!(std::fabs(v - x) <= 1e-9 * std::max(1.0, std::fabs(x))))
                throw formula_input_error(key, 0, key + " = " + shortest(v) + " at t = 0 where the initial " +
                                                      (is_q ? "q" : "p") + "[" + std::to_string(k % n) + "] is " +
                                                      shortest(x) + "; expected the solution through the initial state");
            d.exact.push_back(std::move(f));
        } catch (const formula_error& e) {
            throw formula_input_error(key, e.column, e.what());
        }
    }
}

}  // namespace

const system_entry& define_formula_system(const formula_texts& t) {
    const auto fail = [](const std::string& key, const std::string& what) -> void {
        throw formula_input_error(key, 0, what);
    };
    if (!is_system_name(t.name))
        fail("name", "system.name = '" + t.name + "'; expected letters, digits, '_' and '-', starting with a letter, "
                     "at most 64");
    const std::size_t n = t.q0.size();
    if (n == 0 || t.p0.size() != n)
        fail("initial", "initial q has " + std::to_string(n) + " values and p has " + std::to_string(t.p0.size()) +
                            "; expected the same number, at least one");
    if (n > std::size_t(largest_chain))
        fail("initial", std::to_string(n) + " degrees of freedom; expected at most " + shortest(largest_chain));
    for (double v : t.q0) if (!std::isfinite(v)) fail("initial", "initial q holds " + shortest(v) + "; expected finite values");
    for (double v : t.p0) if (!std::isfinite(v)) fail("initial", "initial p holds " + shortest(v) + "; expected finite values");

    formula_definition d;
    d.name = t.name;
    // Every name a formula may use, each once.
    std::set<std::string> taken{"q", "p"};
    for (const auto& f : function_names()) taken.insert(f);
    const auto claim = [&](const std::string& key, const std::string& name, const std::string& what) {
        if (!is_name(name))
            fail(key, what + " '" + name + "' is not a name; expected letters, digits and '_', not starting with a "
                             "digit, at most 64");
        if (!taken.insert(name).second)
            fail(key, what + " '" + name + "' is already a name (q, p, a function, a coordinate or a parameter); "
                             "expected a name of its own");
    };
    for (const auto& [name, value] : t.parameters) {
        claim("parameters", name, "parameter");
        if (!std::isfinite(value)) fail("parameters", "parameter " + name + " = " + shortest(value) + "; expected a finite number");
        d.known.parameters.push_back(name);
        d.parameter_values.push_back(value);
    }
    if (!t.momenta.empty() && t.coordinates.empty())
        fail("momenta", "'system.momenta' without 'system.coordinates'; expected both, or neither (q[i] and p[i])");
    if (!t.coordinates.empty()) {
        if (t.coordinates.size() != n)
            fail("coordinates", "'system.coordinates' has " + std::to_string(t.coordinates.size()) + " names for " +
                                    std::to_string(n) + " degrees of freedom (the initial q); expected one name each");
        if (!t.momenta.empty() && t.momenta.size() != n)
            fail("momenta", "'system.momenta' has " + std::to_string(t.momenta.size()) + " names for " +
                                std::to_string(n) + " degrees of freedom (the initial q); expected one name each");
        for (const auto& name : t.coordinates) claim("coordinates", name, "coordinate");
        d.known.q_names = t.coordinates;
        for (std::size_t k = 0; k < n; ++k) {
            const std::string name = t.momenta.empty() ? "p" + t.coordinates[k] : t.momenta[k];
            claim(t.momenta.empty() ? "coordinates" : "momenta", name, "momentum");
            d.known.p_names.push_back(name);
        }
    }
    d.known.dimension = n;
    d.q0 = t.q0;
    d.p0 = t.p0;

    const bool has_H = !t.H.empty(), has_T = !t.T.empty(), has_V = !t.V.empty();
    if (has_H && (has_T || has_V)) fail("H", "[system] has H and T or V; expected T and V (a separable H) or H alone");
    if (!has_H && !(has_T && has_V))
        fail(has_T ? "T" : has_V ? "V" : "name",
             "[system] has " + std::string(has_T ? "T but no V" : has_V ? "V but no T" : "no T, V or H") +
                 "; expected T and V, or H");
    const Eigen::VectorXd q0 = Eigen::Map<const Eigen::VectorXd>(t.q0.data(), Eigen::Index(n)),
                          p0 = Eigen::Map<const Eigen::VectorXd>(t.p0.data(), Eigen::Index(n));
    std::string definition = d.name;
    // One formula: parsed, held to the variables it may use, and finite at
    // the initial state (which checks every index it reads).
    const auto read = [&](const std::string& text, const char* key, bool q_allowed,
                          bool p_allowed) -> std::shared_ptr<const formula> {
        definition += std::string("\n") + key + "=" + text;
        try {
            auto f = std::make_shared<formula>(parse(text, d.known));
            if (f->uses_q && !q_allowed)
                throw formula_error(1, std::string(key) + " uses q; expected " +
                                           (p_allowed ? "T(p) alone (write H = ... for a non-separable system)"
                                                      : "a formula of the parameters alone"));
            if (f->uses_p && !p_allowed)
                throw formula_error(1, std::string(key) + " uses p; expected " +
                                           (q_allowed ? "V(q) alone (write H = ... for a non-separable system)"
                                                      : "a formula of the parameters alone"));
            const double v = evaluate<double>(*f, d.parameter_values, q0, p0);
            if (!std::isfinite(v))
                throw formula_input_error(key, 0, std::string(key) + " = " + shortest(v) +
                                                      " at the initial state; expected a finite value");
            return f;
        } catch (const formula_error& e) {
            throw formula_input_error(key, e.column, e.what());
        }
    };
    if (has_H) {
        d.H = read(t.H, "H", true, true);
    } else {
        d.T = read(t.T, "T", false, true);
        d.V = read(t.V, "V", true, false);
    }
    if (!t.period.empty()) {
        d.period = read(t.period, "period", false, false);
        const Eigen::VectorXd none;
        const double v = evaluate<double>(*d.period, d.parameter_values, none, none);
        if (!(v > 0)) throw formula_input_error("period", 0, "period = " + shortest(v) + "; expected a value > 0");
    }
    read_exact(t, d, definition);
    for (std::size_t k = 0; k < d.known.parameters.size(); ++k)
        definition += "\n" + d.known.parameters[k] + "=" + shortest(d.parameter_values[k]);
    for (const auto& names : {d.known.q_names, d.known.p_names})
        for (const auto& name : names) definition += "\n" + name;
    for (double v : t.q0) definition += "\n" + shortest(v);
    for (double v : t.p0) definition += "\n" + shortest(v);
    try {
        return add_scene_system(formula_entry(std::move(d)), definition);
    } catch (const invalid_argument& e) {
        throw formula_input_error("name", 0, e.what());
    }
}

}  // namespace sympl::app::formulas
