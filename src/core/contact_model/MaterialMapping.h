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
// for one material). Its dashpot acts in both directions (the normal one only while the bodies
// approach), so it takes the damping ratio with which a dashpot acting throughout gives the
// normal restitution e: zeta_t = -ln e / sqrt(pi^2 + ln^2 e) (the ratio of LIGGGHTS' and LAMMPS'
// linear dashpots), D_t = zeta_t sqrt(k_t). (The approach-only ratio is 3.7 times larger at
// e = 0.3: a tangential dashpot that strong on a contact point of a rotating grain exceeds the
// integrator's stability limit at the time step the springs allow.)
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

// D_t of the tangential dashpot for the normal spring S, its damping D and k_t (above).
double tangentialDampingFor(double stiffness, double damping, double tangentialStiffness);

// Largest stable step of an oscillator of angular frequency omega and damping ratio zeta
// integrated as LIGGGHTS' nve integrators do (half kick, drift, forces from the half-step
// velocity, half kick: leapfrog with the dashpot one half step behind): 2 (sqrt(1 + zeta^2) -
// zeta) / omega (the roots of z^2 - (2 - 2 zeta omega dt - omega^2 dt^2) z + 1 - 2 zeta omega dt
// stay in the unit circle); 2 / omega without damping.
double dampedStableStep(double omega, double zeta);

// One contact point of a type pair: normal oscillation m_eff x'' = -(S/2) x (x = 2 eps - d, the
// halo overlap) damped while approaching (m_eff of a central impact: the contact time and the
// restitution), and the stable step of both oscillations, normal and tangential (k_t, D_t), on
// the lightest contact point of the pair, pointMass (translation and rotation: 1/m = sum over
// the bodies of 1/m_b + l^2/I_b, l the lever arm, I the smallest principal moment; Contact.h).
struct ContactTiming {
  double normalFrequency = 0.0;      // omega_n = sqrt(S / (2 m_eff)) [1/s]
  double dampingRatio = 0.0;         // zeta = D sqrt(2 / S)
  double contactTime = 0.0;          // impact to separation [s]
  double tangentialFrequency = 0.0;  // omega_t = sqrt(k_t / pointMass) [1/s], 0 without a spring
  // min of dampedStableStep over the normal (sqrt(S / (2 pointMass)), zeta) and the tangential
  // (omega_t, D_t / sqrt(k_t)) oscillation [s]
  double stableStep = 0.0;
};
// effectiveMass > 0, pointMass in (0, effectiveMass]; tangentialStiffness 0 when there is no
// tangential spring.
ContactTiming contactTiming(double stiffness, double damping, double effectiveMass,
                            double tangentialStiffness, double tangentialDamping, double pointMass);

}  // namespace spacetree::contact_model
