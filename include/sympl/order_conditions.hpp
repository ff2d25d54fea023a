#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/analysis/order_conditions.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/order_conditions.hpp> is deprecated: include <sympl/analysis/order_conditions.hpp>")
#endif
#include "analysis/order_conditions.hpp"
