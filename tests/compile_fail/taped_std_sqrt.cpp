// Must not compile: std::sqrt on a taped number would drop its derivatives.
// The build stops with a message that says how to call its overload instead.
#include <cmath>

#include <sympl/core/reverse_mode.hpp>

int main() {
    const sympl::taped<double> x(2.0);
    return std::sqrt(x) > 1.0 ? 0 : 1;
}
