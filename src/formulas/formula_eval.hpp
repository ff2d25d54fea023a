#pragma once
// A formula's value (formula.hpp) on any scalar type S: double for the runs,
// long double, and the library's dual and reverse-mode numbers, through
// which the gradients are taken. Indices (q[i], sum bounds) are integers,
// computed in double and checked: an index outside 0..n-1, or one that is no
// integer, is a formula_error at its column.
#include <cmath>
#include <string>
#include <vector>

#include "formulas/formula.hpp"

namespace sympl::app::formulas {

namespace detail {

// An integer-valued part (an index, a sum's bound): numbers, parameters,
// indices and arithmetic on them.
inline long integer_of(const node& n, const std::vector<double>& parameters, const std::vector<long>& indices);

inline double plain(const node& n, const std::vector<double>& parameters, const std::vector<long>& indices) {
    const auto a = [&](std::size_t k) { return plain(*n.children[k], parameters, indices); };
    switch (n.kind) {
        case node::number: return n.value;
        case node::parameter: return parameters.at(n.slot);
        case node::index: return double(indices.at(n.slot));
        case node::add: return a(0) + a(1);
        case node::subtract: return a(0) - a(1);
        case node::multiply: return a(0) * a(1);
        case node::divide: return a(0) / a(1);
        case node::negate: return -a(0);
        case node::power: return std::pow(a(0), a(1));
        default:
            throw formula_error(n.column, "an index or a sum's bound depends on q or p, or calls a function; "
                                          "expected integers, parameters and the enclosing sums' indices");
    }
}

inline long integer_of(const node& n, const std::vector<double>& parameters, const std::vector<long>& indices) {
    const double v = plain(n, parameters, indices);
    if (!(std::fabs(v) < 1e15) || v != std::floor(v))
        throw formula_error(n.column, "an index or a sum's bound of " + std::to_string(v) + "; expected an integer");
    return long(v);
}

template <class S, class V>
S value(const node& n, const std::vector<double>& parameters, const V& q, const V& p, std::vector<long>& indices) {
    using std::sin, std::cos, std::tan, std::sinh, std::cosh, std::tanh, std::exp, std::log, std::sqrt, std::abs,
        std::atan, std::pow;
    const auto a = [&](std::size_t k) -> S { return value<S>(*n.children[k], parameters, q, p, indices); };
    switch (n.kind) {
        case node::number: return S(n.value);
        case node::parameter: return S(parameters.at(n.slot));
        case node::index: return S(double(indices.at(n.slot)));
        case node::q:
        case node::p: {
            const V& x = n.kind == node::q ? q : p;
            const long k = n.indexed ? integer_of(*n.children[0], parameters, indices) : long(n.slot);
            if (k < 0 || k >= long(x.size()))
                throw formula_error(n.column, std::string(n.kind == node::q ? "q" : "p") + "[" + std::to_string(k) +
                                                  "] outside 0.." + std::to_string(long(x.size()) - 1));
            return x[k];
        }
        case node::add: return a(0) + a(1);
        case node::subtract: return a(0) - a(1);
        case node::multiply: return a(0) * a(1);
        case node::divide: return a(0) / a(1);
        case node::negate: return -a(0);
        case node::power: {
            // An integer exponent as repeated products: exact for q^2, and
            // defined for negative bases, as the scene means it.
            const node& e = *n.children[1];
            if (e.kind == node::number && e.value == std::floor(e.value) && std::fabs(e.value) <= 16) {
                const S base = a(0);
                S r(1.0);
                for (int k = 0; k < int(std::fabs(e.value)); ++k) r = r * base;
                return e.value < 0 ? S(1.0) / r : r;
            }
            return pow(a(0), a(1));
        }
        case node::call: {
            const S x = a(0);
            switch (n.function) {
                case 0: return sin(x);
                case 1: return cos(x);
                case 2: return tan(x);
                case 3: return sinh(x);
                case 4: return cosh(x);
                case 5: return tanh(x);
                case 6: return exp(x);
                case 7: return log(x);
                case 8: return sqrt(x);
                case 9: return abs(x);
                case 10: return atan(x);
            }
            throw formula_error(n.column, "unknown function");
        }
        case node::sum: {
            const long first = integer_of(*n.children[0], parameters, indices);
            const long last = integer_of(*n.children[1], parameters, indices);
            S total(0.0);
            indices.push_back(first);
            for (long i = first; i <= last; ++i) {
                indices.back() = i;
                total = total + value<S>(*n.children[2], parameters, q, p, indices);
            }
            indices.pop_back();
            return total;
        }
    }
    throw formula_error(n.column, "unknown node");
}

}  // namespace detail

// The formula at (q, p) with the parameters' values in their order.
template <class S, class V>
S evaluate(const formula& f, const std::vector<double>& parameters, const V& q, const V& p) {
    std::vector<long> indices;
    return detail::value<S>(*f.root, parameters, q, p, indices);
}

}  // namespace sympl::app::formulas
