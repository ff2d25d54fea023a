#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/methods/classic_steppers.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/classic_steppers.hpp> is deprecated: include <sympl/methods/classic_steppers.hpp>")
#endif
#include "methods/classic_steppers.hpp"
