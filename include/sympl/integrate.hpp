#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/drivers/fixed_step.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/integrate.hpp> is deprecated: include <sympl/drivers/fixed_step.hpp>")
#endif
#include "drivers/fixed_step.hpp"
