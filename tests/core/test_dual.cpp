#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

#include <sympl/core/dual.hpp>

namespace test_core_test_dual {  // one per file: the tests build in batches (CMakeLists.txt)

using sympl::dual;
using sympl::pi_of;
using sympl::primal;

TEST_CASE("dual: derivatives of elementary functions equal their closed forms") {
    const double x = 0.7;
    using D = dual<double, 1>;
    const D v = D::variable(x, 0);
    auto near = [](double a, double b) { return std::fabs(a - b) <= 1e-15 * (1 + std::fabs(b)); };
    CHECK(near(sqrt(v).grad[0], 0.5 / std::sqrt(x)));
    CHECK(near(sin(v).grad[0], std::cos(x)));
    CHECK(near(cos(v).grad[0], -std::sin(x)));
    CHECK(near(exp(v).grad[0], std::exp(x)));
    CHECK(near(log(v).grad[0], 1 / x));
    CHECK(near(tanh(v).grad[0], 1 - std::tanh(x) * std::tanh(x)));
    CHECK(near(pow(v, 3.5).grad[0], 3.5 * std::pow(x, 2.5)));
    CHECK(near((v * v / (1.0 + v)).grad[0], (2 * x * (1 + x) - x * x) / ((1 + x) * (1 + x))));
    CHECK(near((2.0 - v / 4.0).grad[0], -0.25));
}

TEST_CASE("dual: several directions and nesting give second derivatives") {
    using D2 = dual<double, 2>;
    const D2 x = D2::variable(0.3, 0), y = D2::variable(-1.1, 1);
    const D2 f = x * x * y + sin(x * y);  // df/dx = 2xy + y cos(xy), df/dy = x^2 + x cos(xy)
    CHECK(f.grad[0] == doctest::Approx(2 * 0.3 * -1.1 + -1.1 * std::cos(-0.33)).epsilon(1e-15));
    CHECK(f.grad[1] == doctest::Approx(0.09 + 0.3 * std::cos(-0.33)).epsilon(1e-15));
    // d2/dx2 of sin(x) = -sin(x), by a dual of duals.
    using D = dual<double, 1>;
    using DD = dual<D, 1>;
    const DD z = DD::variable(D::variable(0.4, 0), 0);
    const DD s = sin(z);
    CHECK(s.grad[0].grad[0] == doctest::Approx(-std::sin(0.4)).epsilon(1e-15));
    CHECK(sympl::primal(s) == doctest::Approx(std::sin(0.4)));
}

namespace {
// Central difference of f at x: truncation ~ h^2 |f'''| / 6, rounding ~ eps / h.
double central_difference(const auto& f, double x) {
    const double h = 1e-5 * (1 + std::fabs(x));
    return (f(x + h) - f(x - h)) / (2 * h);
}
}  // namespace

TEST_CASE("dual: every <cmath> function a potential may use agrees with finite differences") {
    using D = dual<double, 1>;
    const auto check = [](const char* name, auto&& f, double x) {
        CAPTURE(name);
        CAPTURE(x);
        const D y = f(D::variable(x, 0));
        const double fd = central_difference([&](double v) { return f(D(v)).value; }, x);
        CHECK(std::fabs(y.grad[0] - fd) <= 1e-8 * (1 + std::fabs(fd)));
    };
    for (double x : {0.3, -0.6}) {
        check("asin", [](const auto& v) { return asin(v); }, x);
        check("acos", [](const auto& v) { return acos(v); }, x);
        check("atan", [](const auto& v) { return atan(v); }, x);
        check("asinh", [](const auto& v) { return asinh(v); }, x);
        check("atanh", [](const auto& v) { return atanh(v); }, x);
        check("cbrt", [](const auto& v) { return cbrt(v); }, x);
        check("log1p", [](const auto& v) { return log1p(v); }, x);
        check("expm1", [](const auto& v) { return expm1(v); }, x);
        check("exp2", [](const auto& v) { return exp2(v); }, x);
        check("abs", [](const auto& v) { return abs(v); }, x);
        check("fabs", [](const auto& v) { return fabs(v); }, x);
        check("atan2(x, 0.7)", [](const auto& v) { return atan2(v, 0.7); }, x);
        check("atan2(0.7, x)", [](const auto& v) { return atan2(0.7, v); }, x);
        check("atan2(x, x^2 + 1)", [](const auto& v) { return atan2(v, v * v + 1.0); }, x);
        check("hypot(x, 0.7)", [](const auto& v) { return hypot(v, 0.7); }, x);
        check("hypot(0.7, x)", [](const auto& v) { return hypot(0.7, v); }, x);
        check("hypot(x, 2x)", [](const auto& v) { return hypot(v, 2.0 * v); }, x);
        check("pow(x, 3)", [](const auto& v) { return pow(v, 3); }, x);      // int exponent, negative base
        check("pow(x, 2.0)", [](const auto& v) { return pow(v, 2.0); }, x);  // double exponent
        check("pow(2.5, x)", [](const auto& v) { return pow(2.5, v); }, x);  // plain base, dual exponent
        check("pow(x, D(3))", [](const auto& v) { return pow(v, D(3.0)); }, x);  // constant dual exponent
    }
    for (double x : {0.3, 1.7}) {
        check("pow(x, x)", [](const auto& v) { return pow(v, v); }, x);
        check("pow(x, 1.5f)", [](const auto& v) { return pow(v, 1.5f); }, x);
        check("log2", [](const auto& v) { return log2(v); }, x);
        check("log10", [](const auto& v) { return log10(v); }, x);
        check("sqrt", [](const auto& v) { return sqrt(v); }, x);
    }
    check("acosh", [](const auto& v) { return acosh(v); }, 1.8);
}

TEST_CASE("dual: pi_of<S>() is std::numbers' pi, and a dual number's has the primal pi and no derivative") {
    CHECK(pi_of<double>() == std::numbers::pi);
    CHECK(pi_of<float>() == std::numbers::pi_v<float>);
    CHECK(pi_of<long double>() == std::numbers::pi_v<long double>);
    const auto d = pi_of<dual<dual<long double, 2>, 1>>();
    CHECK(primal(d) == std::numbers::pi_v<long double>);
    CHECK(d.grad[0].value == 0);
    CHECK(d.value.grad[1] == 0);
}

}  // namespace test_core_test_dual
