#pragma once
// A contact rendered against a local model, with the surface giving under the client's own push
// before the server's answer shows it (issue 26; Schuwerk, Xu, Freund & Steinbach 2015 send the
// object's local stiffness with the model for this). Near the contact the surface is a spring of
// stiffness k_o (LocalModelBody::stiffness) in series with the proxy's k_p: a push F on the
// device holds the surface F / k_o in, and the device feels the series stiffness
// k_eff = k_p k_o / (k_p + k_o). The model already shows the surface held in by the push it was
// cut under, F_m (LocalModel::push); the god-object, against that copy, feels F_god = k_p (p − x).
// Only the change of the push moves the surface further: s = (F − F_m) / k_o with
// F = F_god − k_p s, so s = (F_god − F_m) / (k_p + k_o) along −n, and F = F_god − k_p s
// (= k_eff × the depth below the unpushed surface, whatever push the model was cut under).

#include "core/haptics/haptic_contact.hpp"
#include "core/math/types.hpp"

namespace felt {

/// `contact` (a god-object's against a model cut under `model_push`) with its proxy, contact
/// point and force moved by the surface's give, for a proxy of stiffness `proxy_stiffness` on a
/// surface of stiffness `surface_stiffness` (N/m): unchanged when free, or when either stiffness
/// is not positive (unknown: the copy is taken as rigid).
inline HapticContact yielding_contact(HapticContact contact, const Vec3& model_push,
                                      Real proxy_stiffness, Real surface_stiffness) {
  const Vec3& n = contact.normal;
  if (!contact.in_contact || !(proxy_stiffness > 0) || !(surface_stiffness > 0) ||
      !(n.squaredNorm() > 0)) {
    return contact;
  }
  const Real give =
      (contact.force.dot(n) - model_push.dot(n)) / (proxy_stiffness + surface_stiffness);
  contact.proxy -= give * n;
  contact.contact_point -= give * n;
  contact.force -= proxy_stiffness * give * n;
  return contact;
}

}  // namespace felt
