#pragma once
// The damping ratio zeta of deposit's contact laws (c = 2 zeta sqrt(m* k_n), k_n the contact
// stiffness dF/d delta: hertz_normal.hpp, linear_normal.hpp) as the inputs of LAMMPS and
// LIGGGHTS that give the same dashpot (docs/decks.md "Damping"; measured in
// docs/results/deck-damping.md by bench/studies/deck_damping.py).

namespace powderbed::bed {

// LAMMPS pair granular `damping tsuji` (Tsuji, Tanaka & Ishida 1992): eta_n = alpha(e)
// sqrt(m* K), K = k for hooke and 4/3 E* a (a = sqrt(R* delta)) for hertz, with
// alpha(e) = 1.2728 - 4.2783 e + 11.087 e^2 - 22.348 e^3 + 27.467 e^4 - 18.022 e^5 + 4.8218 e^6.
double tsuji_alpha(double restitution);
// The input e that makes LAMMPS's dashpot ours: alpha(e) = zeta sqrt(6) for Hertz
// (2 zeta sqrt(2 E* a) = alpha sqrt(4/3 E* a)) and 2 zeta for the linear law. alpha falls from
// 1.2728 at e = 0 to 3e-4 at e = 1, so zeta above 1.2728 / sqrt(6) = 0.5196 (Hertz) or 0.6364
// (linear) has no input, nor zeta below 3e-4 / sqrt(6) (use damping velocity 0 for zeta = 0):
// throws InputError naming `option` then. The input is not the restitution coefficient LAMMPS
// then gives (Tsuji's alpha is a fit): e = 0.71 in gives 0.795 out for Hertz.
double lammps_tsuji_input(double zeta, bool hertz, const char* option);
// The largest zeta lammps_tsuji_input accepts.
double lammps_tsuji_max_zeta(bool hertz);

// LIGGGHTS 3.8 `model hertz` (normal_model_hertz.h): gamma_n = -2 sqrt(5/6) beta sqrt(S_n m*),
// S_n = 2 E* a = our k_n, beta = ln e / sqrt(ln^2 e + pi^2): ours for beta = -zeta / sqrt(5/6),
// i.e. e = exp(-pi b / sqrt(1 - b^2)), b = zeta / sqrt(5/6) (zeta < sqrt(5/6) = 0.9129;
// zeta = 0.1: e = 0.707351). Throws InputError naming `option` for zeta outside [0, 0.9129).
double liggghts_hertz_restitution(double zeta, const char* option);

}  // namespace powderbed::bed
