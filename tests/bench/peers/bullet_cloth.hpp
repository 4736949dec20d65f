#pragma once
// The peer benchmark's cloth in Bullet's soft body, with the links of Felt's grid: structural
// and both diagonals of every cell at the default material (kLST = 1, the stiffest), bend links
// two apart along rows and columns at kLST = 0.1. Made by btSoftBodyHelpers::CreatePatch (with
// its diagonals) plus the links it lacks, stepped by a btSoftRigidDynamicsWorld at fixed steps.

#include "peer_cloth.hpp"

namespace felt::peers {

struct BulletConfig {
  Real step;       ///< s, one stepSimulation call per step
  int iterations;  ///< btSoftBody::Config::piterations, the position solver's passes per step
};

Outcome run_bullet(std::uint32_t n, const BulletConfig& config);

}  // namespace felt::peers
