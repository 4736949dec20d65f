#include "bullet_cloth.hpp"

#include <BulletSoftBody/btSoftBodyHelpers.h>
#include <BulletSoftBody/btSoftBodyRigidBodyCollisionConfiguration.h>
#include <BulletSoftBody/btSoftRigidDynamicsWorld.h>
#include <btBulletDynamicsCommon.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <vector>

#include "core/math/check.hpp"

namespace felt::peers {
namespace {

btVector3 to_bullet(const Vec3& v) {
  return btVector3(static_cast<btScalar>(v.x()), static_cast<btScalar>(v.y()),
                   static_cast<btScalar>(v.z()));
}

/// The links Felt's grid has beyond CreatePatch's: each cell's second diagonal (CreatePatch
/// links one, alternating), at the patch's material, and bend links between particles two
/// apart along rows and columns, at kLST = 0.1.
void append_felt_links(btSoftBody& cloth, std::uint32_t n) {
  btSoftBody::Material* bend = cloth.appendMaterial();
  bend->m_kLST = 0.1;
  const auto index = [n](std::uint32_t i, std::uint32_t j) { return static_cast<int>(j * n + i); };
  for (std::uint32_t j = 0; j < n; ++j) {
    for (std::uint32_t i = 0; i < n; ++i) {
      if (i + 1 < n && j + 1 < n) {
        if ((i + j) & 1) {
          cloth.appendLink(index(i + 1, j), index(i, j + 1), cloth.m_materials[0]);
        } else {
          cloth.appendLink(index(i, j), index(i + 1, j + 1), cloth.m_materials[0]);
        }
      }
      if (i + 2 < n) cloth.appendLink(index(i, j), index(i + 2, j), bend);
      if (j + 2 < n) cloth.appendLink(index(i, j), index(i, j + 2), bend);
    }
  }
}

}  // namespace

Outcome run_bullet(std::uint32_t n, const BulletConfig& config) {
  btSoftBodyRigidBodyCollisionConfiguration collision;
  btCollisionDispatcher dispatcher(&collision);
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btSoftRigidDynamicsWorld world(&dispatcher, &broadphase, &solver, &collision);
  world.setGravity(btVector3(0, static_cast<btScalar>(-kGravity), 0));
  btSoftBodyWorldInfo& info = world.getWorldInfo();
  info.m_gravity = world.getGravity();
  info.air_density = 0;  // no aerodynamics: the damping is kDP's alone, as Felt's is its drag
  info.m_sparsesdf.Initialize();

  const int side = static_cast<int>(n);
  // corner00 → corner10 is the node index's fast direction, corner00 → corner01 the slow one
  std::unique_ptr<btSoftBody> cloth(btSoftBodyHelpers::CreatePatch(
      info, to_bullet(rest_position(n, 0, 0)), to_bullet(rest_position(n, n - 1, 0)),
      to_bullet(rest_position(n, 0, n - 1)), to_bullet(rest_position(n, n - 1, n - 1)), side, side,
      1 + 2 /* pin corner00 and corner10 */, true /* diagonal links */));
  FELT_CHECK(cloth->m_nodes.size() == side * side);
  FELT_CHECK((cloth->m_nodes[side + 1].m_x - to_bullet(rest_position(n, 1, 1))).length() < 1e-6);
  append_felt_links(*cloth, n);
  // structural, both diagonals of every cell and bend: Felt's grid's springs
  FELT_CHECK(cloth->m_links.size() ==
             2 * side * (side - 1) + 2 * (side - 1) * (side - 1) + 2 * side * (side - 2));
  cloth->m_cfg.piterations = config.iterations;
  cloth->m_cfg.kDP = static_cast<btScalar>(1 - std::exp(-kDampingRate * config.step));
  cloth->setTotalMass(static_cast<btScalar>(kMass));
  world.addSoftBody(cloth.get());

  const long steps = std::lround(kSeconds / config.step);
  const auto start = std::chrono::steady_clock::now();
  for (long s = 0; s < steps; ++s) world.stepSimulation(static_cast<btScalar>(config.step), 0);
  const std::chrono::duration<double> wall = std::chrono::steady_clock::now() - start;
  world.removeSoftBody(cloth.get());

  std::vector<Vec3> x;
  x.reserve(cloth->m_nodes.size());
  for (int p = 0; p < cloth->m_nodes.size(); ++p) {
    const btVector3& q = cloth->m_nodes[p].m_x;
    x.emplace_back(q.x(), q.y(), q.z());
  }
  Outcome outcome;
  outcome.wall_per_sim_s = wall.count() / kSeconds;
  outcome.max_strain = max_structural_strain(n, x);
  outcome.sag_error = sag_error(x);
  outcome.ok = intact(outcome.max_strain, x);
  return outcome;
}

}  // namespace felt::peers
