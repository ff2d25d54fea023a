#include <doctest/doctest.h>

#include <cmath>

#include <sympl/dual.hpp>

using sympl::dual;

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
