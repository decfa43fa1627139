#include "contact_model/MaterialMapping.h"

#include "contact_model/DampingApproach.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace spacetree::contact_model {

namespace {
void checkMaterial(double youngs, double poisson) {
  if (!(youngs > 0.0) || !std::isfinite(youngs))
    throw std::invalid_argument("youngsModulus must be a finite number > 0");
  if (!(poisson >= 0.0 && poisson < 0.5))
    throw std::invalid_argument("poissonsRatio must be in [0, 0.5)");
}
}  // namespace

double effectiveModulus(double youngsI, double poissonI, double youngsJ, double poissonJ) {
  checkMaterial(youngsI, poissonI);
  checkMaterial(youngsJ, poissonJ);
  return 1.0 / ((1.0 - poissonI * poissonI) / youngsI + (1.0 - poissonJ * poissonJ) / youngsJ);
}

double effectiveRadius(double radiusI, double radiusJ) {
  if (!(radiusI > 0.0) || !(radiusJ > 0.0))
    throw std::invalid_argument("effectiveRadius: radii must be > 0");
  if (std::isinf(radiusI) && std::isinf(radiusJ)) return std::numeric_limits<double>::infinity();
  if (std::isinf(radiusI)) return radiusJ;
  if (std::isinf(radiusJ)) return radiusI;
  return radiusI * radiusJ / (radiusI + radiusJ);
}

double haloStiffness(double effectiveModulus, double effectiveRadius) {
  return 4.0 * effectiveModulus * effectiveRadius;
}

double mindlinStiffnessRatio(double youngsI, double poissonI, double youngsJ, double poissonJ) {
  const double shearI = youngsI / (2.0 * (1.0 + poissonI)), shearJ = youngsJ / (2.0 * (1.0 + poissonJ));
  const double shear = 1.0 / ((2.0 - poissonI) / shearI + (2.0 - poissonJ) / shearJ);
  return 4.0 * shear / effectiveModulus(youngsI, poissonI, youngsJ, poissonJ);
}

double tangentialDampingFor(double stiffness, double damping, double tangentialStiffness) {
  if (!(stiffness > 0.0) || !(damping >= 0.0) || !(tangentialStiffness >= 0.0))
    throw std::invalid_argument("tangentialDampingFor: stiffnesses must be > 0, damping >= 0");
  const double e = springDashpotRestitution(damping * std::sqrt(2.0 / stiffness));
  if (!(e < 1.0)) return 0.0;
  const double logE = std::log(e);
  return -logE / std::sqrt(M_PI * M_PI + logE * logE) * std::sqrt(tangentialStiffness);
}

double dampedStableStep(double omega, double zeta) {
  if (!(omega > 0.0) || !(zeta >= 0.0))
    throw std::invalid_argument("dampedStableStep: omega must be > 0, zeta >= 0");
  return 2.0 * (std::sqrt(1.0 + zeta * zeta) - zeta) / omega;
}

ContactTiming contactTiming(double stiffness, double damping, double effectiveMass,
                            double tangentialStiffness, double tangentialDamping, double pointMass) {
  if (!(stiffness > 0.0) || !(effectiveMass > 0.0) || !(damping >= 0.0) || !(pointMass > 0.0) ||
      !(tangentialDamping >= 0.0))
    throw std::invalid_argument("contactTiming: stiffness and masses must be > 0, damping >= 0");
  ContactTiming t;
  const double omega = std::sqrt(stiffness / (2.0 * effectiveMass));
  const double zeta = damping * std::sqrt(2.0 / stiffness);
  t.normalFrequency = omega;
  t.dampingRatio = zeta;
  // compression (damped) until the overlap stops growing, then undamped release: a quarter period
  double compression;
  if (zeta < 1.0) {
    const double s = std::sqrt(1.0 - zeta * zeta);
    compression = std::atan2(s, zeta) / (omega * s);
  } else if (zeta == 1.0) {
    compression = 1.0 / omega;
  } else {
    const double s = std::sqrt(zeta * zeta - 1.0);
    compression = std::atanh(s / zeta) / (omega * s);
  }
  t.contactTime = compression + 0.5 * M_PI / omega;
  t.stableStep = dampedStableStep(std::sqrt(stiffness / (2.0 * pointMass)), zeta);
  if (tangentialStiffness > 0.0) {
    t.tangentialFrequency = std::sqrt(tangentialStiffness / pointMass);
    t.stableStep = std::min(t.stableStep, dampedStableStep(t.tangentialFrequency,
                                                           tangentialDamping / std::sqrt(tangentialStiffness)));
  }
  return t;
}

}  // namespace spacetree::contact_model
