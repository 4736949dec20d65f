#pragma once
// The peer benchmark's cloth in Felt: a grid cloth (structural springs k, shear k/4, bend
// k/40, with the scenes' default spring damping) stepped by a World with its health check.

#include <string>

#include "peer_cloth.hpp"

namespace felt::peers {

struct FeltConfig {
  std::string integrator;  ///< a name make_integrator knows
  Real stiffness;          ///< k of the structural springs, N/m
  Real step;               ///< the world's step h, s
  int substeps = 1;        ///< xpbd's substeps per step
  int iterations = 0;      ///< projective_dynamics' iterations per step (0: its default)
  Real chebyshev_rho = 0;  ///< and its acceleration
};

Outcome run_felt(std::uint32_t n, const FeltConfig& config);

}  // namespace felt::peers
