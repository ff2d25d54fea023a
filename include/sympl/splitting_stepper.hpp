#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/core/splitting_stepper.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/splitting_stepper.hpp> is deprecated: include <sympl/core/splitting_stepper.hpp>")
#endif
#include "core/splitting_stepper.hpp"
