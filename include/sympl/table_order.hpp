#pragma once
// Deprecated since sympl 0.2's layout: include <sympl/analysis/table_order.hpp> instead.
// This forwarding header will be removed in sympl 0.3 (docs/layout.md).
#ifndef SYMPL_NO_DEPRECATED_INCLUDE_NOTE
#pragma message("<sympl/table_order.hpp> is deprecated: include <sympl/analysis/table_order.hpp>")
#endif
#include "analysis/table_order.hpp"
