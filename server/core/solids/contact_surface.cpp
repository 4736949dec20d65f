#include "core/solids/contact_surface.hpp"

#include <algorithm>

#include "core/math/check.hpp"

namespace felt {
namespace {

// relative difference of two pressures below which they count as equal
constexpr Real kTie = 1e-9;

bool resolvable(const PenetrationContact& contact) {
  return contact.depth.squaredNorm() > 0;
}

// where a node's ray hits its contact triangle, as weights of the corners: clamped into the
// triangle and summing to one, since a hit on an edge may stray outside by rounding
Vec3 hit_weights(const Vec3& barycentric) {
  const Vec3 w = barycentric.cwiseMax(0);
  const Real sum = w.sum();
  return sum > 0 ? Vec3(w / sum) : Vec3::Constant(Real{1} / 3);
}

// calls visit(corner, weight) for each corner of the contact triangle with a positive weight
template <class Visit>
void for_each_hit_corner(std::span<SolidBody> bodies, const PenetrationContact& contact,
                         Visit&& visit) {
  if (contact.triangle < 0) return;
  const Triangle& triangle = bodies[contact.penetrated_body].topology().surface[contact.triangle];
  const Vec3 w = hit_weights(contact.barycentric);
  for (int k = 0; k < 3; ++k) {
    if (w[k] > 0) visit(triangle[k], w[k]);
  }
}

// one node's displacements against several bodies, combined so that along the direction of
// each (largest first) only what the ones before it do not already provide is added
Vec3 combine(std::vector<Vec3>& parts) {
  std::sort(parts.begin(), parts.end(),
            [](const Vec3& a, const Vec3& b) { return a.squaredNorm() > b.squaredNorm(); });
  Vec3 total = Vec3::Zero();
  for (const Vec3& part : parts) {
    const Real length = part.norm();
    if (length == 0) break;
    const Vec3 direction = part / length;
    total += std::max(Real{0}, length - std::max(Real{0}, total.dot(direction))) * direction;
  }
  return total;
}

}  // namespace

void ContactSurface::resolve(std::span<SolidBody> bodies,
                             std::span<const PenetrationContact> contacts, int iterations,
                             SolidFriction friction, Real h, const Vec3& gravity) {
  FELT_CHECK(iterations >= 0);
  FELT_CHECK(h > 0);
  build_region(bodies, contacts);
  if (region_.empty()) return;
  compute_areas(bodies);
  // x_i^(1) = x_i + s_i / 2, then x_i^(k+1) = x_i^(k) ± s_i / 2^(k+1) (thesis 2 (6.5))
  move_region(bodies);
  Real step = 0.5;
  for (int k = 0; k < iterations; ++k) {
    step /= 2;
    for (std::size_t b = 0; b < bodies.size(); ++b) {
      if (involved_[b]) bodies[b].internal_forces(force_[b], in_region_[b]);
    }
    compare_pressures(bodies, contacts, step);
    move_region(bodies);
  }
  stop_approach(bodies, contacts);
  if (friction == SolidFriction::kRelativeCoulomb) {
    relative_coulomb_friction(bodies, contacts);
  } else {
    own_velocity_friction(bodies, h, gravity);
  }
}

void ContactSurface::build_region(std::span<SolidBody> bodies,
                                  std::span<const PenetrationContact> contacts) {
  region_.clear();
  entries_.clear();
  sources_.clear();
  region_of_.resize(bodies.size());
  in_region_.resize(bodies.size());
  involved_.assign(bodies.size(), 0);
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    region_of_[b].assign(bodies[b].node_count(), -1);
    in_region_[b].assign(bodies[b].node_count(), 0);
  }

  for (std::size_t c = 0; c < contacts.size(); ++c) {
    const PenetrationContact& contact = contacts[c];
    if (!resolvable(contact)) continue;
    const std::uint32_t own =
        entry_for(bodies, contact.body, contact.node, contact.penetrated_body);
    entries_[own].own_contact = static_cast<std::int64_t>(c);
    entries_[own].weighted_depths += contact.depth;
    entries_[own].weight += 1;
    // J_k of every corner k of T_i gains i, weighted by k's barycentric weight at i's hit
    for_each_hit_corner(bodies, contact, [&](std::uint32_t corner, Real w) {
      const std::uint32_t e = entry_for(bodies, contact.penetrated_body, corner, contact.body);
      entries_[e].weighted_depths -= w * contact.depth;
      entries_[e].weight += w;
      entries_[e].has_sources = true;
      sources_.push_back({e, contact.body, contact.node, w});
    });
  }
  // s_i = (Σ_{j∈J_i} w_j (−d_j) + d_i) / (Σ_{j∈J_i} w_j + 1) (thesis 2 §3.3 g); a node without
  // a depth of its own is not averaged with a zero vector
  for (ContactEntry& entry : entries_) {
    const Real denominator =
        entry.own_contact >= 0 ? entry.weight : std::max(Real{1}, entry.weight);
    entry.displacement = entry.weighted_depths / denominator;
  }
  // a node pressed only against pinned nodes takes the whole displacement: they do not give way
  for (const PressureSource& source : sources_) {
    if (bodies[source.body].inv_mass()[source.node] > 0) {
      entries_[source.entry].partner_gives_way = true;
    }
  }
  for (ContactEntry& entry : entries_) {
    if (!entry.has_sources) {
      const PenetrationContact& contact = contacts[entry.own_contact];
      for_each_hit_corner(bodies, contact, [&](std::uint32_t corner, Real) {
        if (bodies[contact.penetrated_body].inv_mass()[corner] > 0) entry.partner_gives_way = true;
      });
    }
    if (!entry.partner_gives_way) entry.fraction = 1;
  }
}

std::uint32_t ContactSurface::entry_for(std::span<SolidBody> bodies, std::uint32_t body,
                                        std::uint32_t node, std::uint32_t partner) {
  std::int32_t& region_node = region_of_[body][node];
  if (region_node < 0) {
    region_node = static_cast<std::int32_t>(region_.size());
    RegionNode added;
    added.body = body;
    added.node = node;
    added.start = bodies[body].positions()[node];
    region_.push_back(added);
    in_region_[body][node] = 1;
    involved_[body] = 1;
  }
  for (std::int32_t e = region_[region_node].first_entry; e >= 0; e = entries_[e].next) {
    if (entries_[e].partner == partner) return static_cast<std::uint32_t>(e);
  }
  ContactEntry entry;
  entry.region_node = static_cast<std::uint32_t>(region_node);
  entry.partner = partner;
  entry.next = region_[region_node].first_entry;
  region_[region_node].first_entry = static_cast<std::int32_t>(entries_.size());
  entries_.push_back(entry);
  return static_cast<std::uint32_t>(entries_.size() - 1);
}

void ContactSurface::compute_areas(std::span<SolidBody> bodies) {
  area_.resize(bodies.size());
  force_.resize(bodies.size());
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (!involved_[b]) continue;
    const std::vector<Vec3>& x = bodies[b].positions();
    std::vector<Real>& area = area_[b];
    area.assign(x.size(), 0);
    force_[b].resize(x.size());
    // area(O_i): the surface triangles around node i (thesis 2 §3.3 i)
    for (const Triangle& t : bodies[b].topology().surface) {
      const Real a = 0.5 * (x[t[1]] - x[t[0]]).cross(x[t[2]] - x[t[0]]).norm();
      for (std::uint32_t corner : t) area[corner] += a;
    }
    Real total = 0;
    std::size_t surface_nodes = 0;
    for (Real a : area) {
      if (a > 0) {
        total += a;
        ++surface_nodes;
      }
    }
    // a node with no surface around it (pushed in deep, or a collapsed surface) takes the
    // mean of the others, so its pressure stays comparable
    const Real mean = surface_nodes > 0 ? total / static_cast<Real>(surface_nodes) : 1;
    for (Real& a : area) {
      if (a == 0) a = mean;
    }
  }
}

void ContactSurface::compare_pressures(std::span<SolidBody> bodies,
                                       std::span<const PenetrationContact> contacts, Real step) {
  for (ContactEntry& entry : entries_) {
    entry.partner_pressure.setZero();
    entry.partner_weight = 0;
  }
  // p_i^B = Σ_{j∈J_i∩B} w_j p_j / Σ w_j
  for (const PressureSource& source : sources_) {
    ContactEntry& entry = entries_[source.entry];
    entry.partner_pressure += source.weight * pressure(source.body, source.node);
    entry.partner_weight += source.weight;
  }
  for (ContactEntry& entry : entries_) {
    if (!entry.partner_gives_way) continue;
    Vec3 partner = Vec3::Zero();
    if (entry.has_sources) {
      partner = entry.partner_pressure / entry.partner_weight;
    } else {
      // J_i ∩ B is empty: the pressures at the corners of T_i, at i's hit point
      const PenetrationContact& contact = contacts[entry.own_contact];
      for_each_hit_corner(bodies, contact, [&](std::uint32_t corner, Real w) {
        partner += w * pressure(contact.penetrated_body, corner);
      });
    }
    const RegionNode& node = region_[entry.region_node];
    const Vec3 own = pressure(node.body, node.node);
    // internal forces push against the compression: the node follows the net pressure on it;
    // a difference at rounding level (a symmetric contact) is a tie, and the node stays
    const Real net = (own + partner).dot(entry.displacement);
    const Real scale = (own - partner).dot(entry.displacement);
    if (std::abs(net) <= kTie * std::abs(scale)) continue;
    entry.fraction += net > 0 ? step : -step;
  }
}

void ContactSurface::move_region(std::span<SolidBody> bodies) {
  for (RegionNode& node : region_) {
    SolidBody& body = bodies[node.body];
    if (body.inv_mass()[node.node] == 0) continue;
    combined_.clear();
    for (std::int32_t e = node.first_entry; e >= 0; e = entries_[e].next) {
      combined_.push_back(entries_[e].fraction * entries_[e].displacement);
    }
    body.positions()[node.node] = node.start + combine(combined_);
  }
}

ContactSurface::Kinematics ContactSurface::kinematics(std::span<SolidBody> bodies,
                                                      const PenetrationContact& contact) const {
  const auto motion = [&](std::uint32_t body, std::uint32_t node) {
    return bodies[body].positions()[node] - bodies[body].previous_positions()[node];
  };
  Kinematics k;
  k.normal = contact.depth.normalized();
  k.relative = motion(contact.body, contact.node);
  k.inverse_mass = bodies[contact.body].inv_mass()[contact.node];
  for_each_hit_corner(bodies, contact, [&](std::uint32_t corner, Real w) {
    k.relative -= w * motion(contact.penetrated_body, corner);
    k.inverse_mass += w * w * bodies[contact.penetrated_body].inv_mass()[corner];
  });
  return k;
}

void ContactSurface::apply_impulse(std::span<SolidBody> bodies, const PenetrationContact& contact,
                                   const Vec3& impulse, bool to_previous_positions) {
  const auto change = [&](SolidBody& body, std::uint32_t node, const Vec3& motion) {
    if (to_previous_positions) {
      body.previous_positions()[node] -= body.inv_mass()[node] * motion;
    } else {
      body.positions()[node] += body.inv_mass()[node] * motion;
    }
  };
  change(bodies[contact.body], contact.node, impulse);
  for_each_hit_corner(bodies, contact, [&](std::uint32_t corner, Real w) {
    change(bodies[contact.penetrated_body], corner, -w * impulse);
  });
}

void ContactSurface::stop_approach(std::span<SolidBody> bodies,
                                   std::span<const PenetrationContact> contacts) {
  // the contact surface is a correction of positions, not a motion: the previous positions
  // move with the nodes, so it neither bounces nor changes the momentum
  for (const RegionNode& node : region_) {
    SolidBody& body = bodies[node.body];
    body.previous_positions()[node.node] += body.positions()[node.node] - node.start;
  }
  normal_motion_.assign(contacts.size(), 0);
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (!resolvable(contacts[c])) continue;
    const Kinematics k = kinematics(bodies, contacts[c]);
    const Real approach = -k.relative.dot(k.normal);
    if (approach <= 0 || k.inverse_mass == 0) continue;
    // a perfectly inelastic normal impulse, equal and opposite on the node and T_i
    apply_impulse(bodies, contacts[c], approach / k.inverse_mass * k.normal, true);
    normal_motion_[c] = approach;
  }
}

void ContactSurface::relative_coulomb_friction(std::span<SolidBody> bodies,
                                               std::span<const PenetrationContact> contacts) {
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (normal_motion_[c] == 0) continue;
    const PenetrationContact& contact = contacts[c];
    const Real mu = mixed_friction(bodies[contact.body].material().friction,
                                   bodies[contact.penetrated_body].material().friction);
    if (mu == 0) continue;
    const Kinematics k = kinematics(bodies, contact);
    const Vec3 tangential = k.relative - k.relative.dot(k.normal) * k.normal;
    const Real slide = tangential.norm();
    if (slide == 0) continue;
    // Coulomb: the tangential impulse is at most μ times the normal one; it may stop the
    // slide, never reverse it. It moves the positions, so a stopped node stays where it was.
    const Real stopped = std::min(slide, mu * normal_motion_[c]);
    apply_impulse(bodies, contact, -stopped / (slide * k.inverse_mass) * tangential, false);
  }
}

void ContactSurface::own_velocity_friction(std::span<SolidBody> bodies, Real h,
                                           const Vec3& gravity) {
  for (std::size_t b = 0; b < bodies.size(); ++b) {
    if (involved_[b]) bodies[b].internal_forces(force_[b], in_region_[b]);
  }
  for (const RegionNode& node : region_) {
    SolidBody& body = bodies[node.body];
    const Real inverse_mass = body.inv_mass()[node.node];
    if (inverse_mass == 0) continue;
    Vec3& x = body.positions()[node.node];
    const Vec3 motion = x - body.previous_positions()[node.node];
    const Real distance = motion.norm();
    if (distance == 0) continue;
    // f_i^r = −μ |f_i| v_i / |v_i| (thesis 2 (6.3)) over the step, with f_i the internal force
    // and gravity; it may stop the node, never reverse it
    const Vec3 force = force_[node.body][node.node] + body.mass(node.node) * gravity;
    const Real slowdown =
        std::min(distance, body.material().friction * force.norm() * inverse_mass * h * h);
    x -= slowdown / distance * motion;
  }
}

}  // namespace felt
