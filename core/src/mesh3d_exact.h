// Tessera: active Voronoi vertex model.  SPDX-License-Identifier: GPL-2.0-or-later
//
// Correct rounding of a GMP rational to a double (mesh3d_exact.cpp): GMP's
// own mpq_get_d truncates towards zero.  Internal to the core; tested on its
// own.
#pragma once

#include <gmp.h>

namespace tessera {
namespace detail3 {

// The double nearest q, ties to even (as IEEE 754 rounds); subnormal
// results rounded at their own precision, overflow to +-infinity.
double nearest_double(mpq_srcptr q);

} // namespace detail3
} // namespace tessera
