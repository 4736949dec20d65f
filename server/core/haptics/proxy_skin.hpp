#pragma once
// The skin between the god-object and what holds it. The proxy rests this far beyond its radius
// from what holds it, so rounding never puts it on the surface (whose side would then be
// unknown) and a slide along a face does not meet that face again. The reported proxy is moved
// back onto the radius: the force does not feel it.

#include "core/math/types.hpp"

namespace felt {

inline constexpr Real kProxySkin = 1e-6;

}  // namespace felt
