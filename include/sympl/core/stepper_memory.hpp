#pragma once
// What a stepper carries from one step to the next besides q and p, as one
// value: splitting_stepper's memory() and restore(), and the program's
// checkpoints, which hold it as std::vector<double> (no Eigen needed there).
#include <cstdint>

namespace sympl {

// What a run carries from one step to the next besides q and p: the last
// force and velocity (reused when q or p has not moved), the compensated
// summation's residuals, and the counters. Saved with the state after step k,
// it lets a run continue bit for bit, in this process or another (checkpoints).
template <class Vector>
struct stepper_memory {
    Vector force, velocity, q_error, p_error;  // residuals: empty unless compensated
    bool force_fresh = false, velocity_fresh = false;
    std::uint64_t force_evaluations = 0, velocity_evaluations = 0;
};

}  // namespace sympl
