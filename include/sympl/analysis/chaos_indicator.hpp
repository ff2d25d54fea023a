#pragma once
// MEGNO, the mean exponential growth of nearby orbits (Cincotta & Simo 2000,
// A&AS 147, 205; Cincotta, Giordano & Simo 2003, Physica D 182, 151), from the
// tangent map of the numerical flow.
//
// A tangent vector delta rides along with the state as the derivative part of
// dual numbers (dual.hpp): each kick and drift of the stepper, applied to
// q + eps*delta_q and p + eps*delta_p, advances delta by exactly the
// linearization of that kick or drift. So delta is the tangent map of the
// method itself, not of the exact flow: the indicator describes the orbit the
// program computes.
//
//     Y(t)   = (2/t) * integral_0^t  s * d ln|delta(s)|
//     <Y>(t) = (1/t) * integral_0^t  Y(s) ds
//
// sampled every Delta = k*dt: the first integral as the sum of t_j times the
// growth of ln|delta| over (t_{j-1}, t_j], the second as the mean of the Y_j.
// Theory (Cincotta et al. 2003): <Y> -> 2 on quasi-periodic orbits (|delta|
// grows linearly), -> 0 on isochronous ones such as the harmonic oscillator
// (|delta| stays bounded), and grows like lambda*t/2 on chaotic orbits with
// Lyapunov exponent lambda.
#include <cmath>
#include <cstddef>

#include "../parallel/batch.hpp"

namespace sympl {

template <class S = double>
struct megno_accumulator {
    S weighted_growth = S(0);  // sum_j t_j * (ln|delta_j| - ln|delta_{j-1}|)
    S sum_y = S(0);            // sum_j Y_j
    S last_log_norm = S(0);    // ln|delta| at the last sample (delta starts as a unit vector)
    S y = S(0);                // Y at the last sample
    std::size_t samples = 0;

    // One sample at time t > 0 after the start, where ln|delta| = log_norm.
    void add(const S& t, const S& log_norm) {
        weighted_growth += t * (log_norm - last_log_norm);
        last_log_norm = log_norm;
        y = S(2) * weighted_growth / t;
        sum_y += y;
        ++samples;
    }

    // <Y> over the samples so far (NaN before the first).
    S mean() const { return samples ? sum_y / S(double(samples)) : S(std::nan("")); }
};

}  // namespace sympl
