// Copyright (C) 2026 fsai developers
//
// The lip load of the 1D tract (A9) and of the FE tract that ends at the
// lips (A11).
#pragma once

namespace fsai::acoustics
{
/// The flanged piston's load at low ka as a resistance in parallel with an
/// inertance, per unit area of an opening of area A (A9, A11):
/// r = 2 · 0.8216² ρ0 c0 and m = 0.8216 ρ0 a, a = √(A/π), so that the
/// reactance is A7's flanged 0.8216 ka and the resistance ω²m²/r =
/// ρ0 c0 (ka)²/2 (per unit area; divide by A for the lumped R, L_r)
struct PistonLoad
{
  double resistance; ///< r [Pa s/m]
  double inertance;  ///< m [kg/m²]
};
PistonLoad flanged_piston(double area, double c0, double rho0);
} // namespace fsai::acoustics
