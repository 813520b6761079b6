// The flute that passed a fixed angle last before flute j, from the flutes' arrival times under
// docs/conventions.md (φ_q = θ + q·2π/N, θ growing with time): flute q is at angle ψ when
// θ = ψ − q·2π/N, so the last one before j is the q with the smallest positive (θ_j − θ_q) mod 2π.
// The runout tests take the pairing from here instead of writing an index by hand.
#pragma once

#include <cmath>

inline int flute_before(int j, int N) {
  const double two_pi = 2.0 * std::acos(-1.0), psi = 1.0;
  const double tj = psi - j * two_pi / N;
  int best = j;
  double gap = two_pi;
  for (int q = 0; q < N; ++q) {
    const double d = std::fmod(tj - (psi - q * two_pi / N) + 4.0 * two_pi, two_pi);
    if (q != j && d > 1e-12 && d < gap) gap = d, best = q;
  }
  return best;
}
