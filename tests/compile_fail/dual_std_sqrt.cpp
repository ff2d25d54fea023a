// Must not compile: std::sqrt on a dual would drop its derivatives. The build
// stops with a message that says how to call the dual overload instead.
#include <cmath>

#include <sympl/core/dual.hpp>

int main() {
    const sympl::dual<double, 1> x = sympl::dual<double, 1>::variable(2.0, 0);
    return std::sqrt(x) > 1.0 ? 0 : 1;
}
