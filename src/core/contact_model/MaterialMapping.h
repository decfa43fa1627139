// From the materials a LIGGGHTS user gives (youngsModulus, poissonsRatio per type;
// coefficientRestitution, coefficientFriction per type pair) to the coefficients of the halo
// contact model, and the contact time and stable time step those give.
//
// Stiffness. A halo spring is not Hertz: its force S (eps - d/2) is linear in the halo overlap
// and acts per contact point. It takes Hertz's effective quantities of the two bodies,
//   E* = 1 / ((1 - nu_i^2)/E_i + (1 - nu_j^2)/E_j),   R* = r_i r_j / (r_i + r_j),
// with r the volume-equivalent radius of a type's shape ((3V / 4pi)^(1/3); a fixed obstacle has
// r = infinity, so R* = r of the grain), and S = 4 E* R*. For two grains of one material and
// nu = 0 that is S = E r, the stiffness Yade's FrictPhys gives two spheres of radius r
// (kn = 2 E_i r_i E_j r_j / (E_i r_i + E_j r_j)), and against a wall of the same material twice
// that, as Hertz's stiffness at a given overlap (R* doubles). A grain resting on n contact points
// is held by n S.
//
// Damping: D from the restitution coefficient e (DampingApproach.h: one contact point, mass
// independent). Tangential spring: k_t = S * 4 G* / E*, Mindlin's ratio of tangential to normal
// stiffness, 1/G* = (2 - nu_i)/G_i + (2 - nu_j)/G_j, G = E / (2 (1 + nu)) (2 (1 - nu)/(2 - nu)
// for one material); its dashpot has the normal damping ratio: D_t = zeta sqrt(k_t).
#pragma once

namespace spacetree::contact_model {

// Hertz's effective modulus E* [Pa]; E > 0, 0 <= nu < 0.5 (std::invalid_argument otherwise).
double effectiveModulus(double youngsI, double poissonI, double youngsJ, double poissonJ);
// R* [m] of two radii, either may be infinite (a fixed obstacle); both > 0.
double effectiveRadius(double radiusI, double radiusJ);
// S = 4 E* R* [N/m].
double haloStiffness(double effectiveModulus, double effectiveRadius);
// 4 G* / E*: k_t / S.
double mindlinStiffnessRatio(double youngsI, double poissonI, double youngsJ, double poissonJ);

// One contact point of a type pair: normal oscillation m_eff x'' = -(S/2) x (x = 2 eps - d, the
// halo overlap) damped while approaching, and the tangential spring k_t against the tangential
// effective mass m_t (translation and rotation: 1/m_t = sum over the bodies of 1/m + l^2/I, l
// the lever arm, I the smallest principal moment).
struct ContactTiming {
  double normalFrequency = 0.0;      // omega_n = sqrt(S / (2 m_eff)) [1/s]
  double dampingRatio = 0.0;         // zeta = D sqrt(2 / S)
  double contactTime = 0.0;          // impact to separation [s]
  double tangentialFrequency = 0.0;  // omega_t = sqrt(k_t / m_t) [1/s], 0 without a spring
  double stableStep = 0.0;           // 2 / max(omega_n, omega_t) [s]: symplectic Euler's limit
};
// effectiveMass > 0; tangentialStiffness 0 when there is no tangential spring.
ContactTiming contactTiming(double stiffness, double damping, double effectiveMass,
                            double tangentialStiffness, double tangentialMass);

}  // namespace spacetree::contact_model
