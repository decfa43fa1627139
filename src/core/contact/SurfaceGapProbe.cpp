#include "contact/SurfaceGapProbe.h"

#include <cmath>
#include <stdexcept>

namespace spacetree::contact {

namespace {
// band classes: 2 eps * kGrowth^k (a probe may use a band up to kGrowth times the one asked for)
constexpr double kGrowth = 1.25;
constexpr int kMaxClass = 400;  // 2 eps * 1.25^400: far beyond any body
}  // namespace

double surfaceClosingSpeedBound(const Eigen::Vector3d& velocityI, const Eigen::Vector3d& angularVelocityI,
                                double boundingRadiusI, const Eigen::Vector3d& velocityJ,
                                const Eigen::Vector3d& angularVelocityJ, double boundingRadiusJ) {
  return (velocityJ - velocityI).norm() + angularVelocityI.norm() * boundingRadiusI +
         angularVelocityJ.norm() * boundingRadiusJ;
}

SurfaceGapProbe::SurfaceGapProbe(MeshContactOptions options) : options_(std::move(options)) {
  if (!(options_.epsilon > 0.0) || !std::isfinite(options_.epsilon))
    throw std::invalid_argument("SurfaceGapProbe: epsilon (the halo) must be > 0");
  options_.deduplicate = false;
  validateMeshContactOptions(options_);
}

MeshContactFinder& SurfaceGapProbe::finderFor(double band) {
  const double ratio = band / (2.0 * options_.epsilon);
  int k = ratio > 1.0 ? int(std::ceil(std::log(ratio) / std::log(kGrowth) - 1e-12)) : 0;
  if (k > kMaxClass) throw std::invalid_argument("SurfaceGapProbe: band too wide for the halo");
  // rounding of the logarithm: make sure the class covers the band
  while (2.0 * options_.epsilon * std::pow(kGrowth, k) < band) ++k;
  if (std::size_t(k) >= finders_.size()) finders_.resize(std::size_t(k) + 1);
  if (!finders_[std::size_t(k)]) {
    MeshContactOptions widened = options_;
    widened.epsilon = options_.epsilon * std::pow(kGrowth, k);
    finders_[std::size_t(k)] = std::make_unique<MeshContactFinder>(widened);
  }
  return *finders_[std::size_t(k)];
}

std::optional<ContactPoint> SurfaceGapProbe::nearest(const geometry::RigidShape& first,
                                                     const Pose& firstPose,
                                                     const geometry::RigidShape& second,
                                                     const Pose& secondPose, double band,
                                                     MeshContactStatistics* statistics) {
  if (!(band >= 2.0 * options_.epsilon) || !std::isfinite(band))
    throw std::invalid_argument("SurfaceGapProbe: band must be finite and >= 2 eps");
  ++probes_;
  found_.clear();
  finderFor(band).find(first, firstPose, second, secondPose, found_, statistics);
  std::optional<ContactPoint> best;
  for (const ContactPoint& c : found_)
    if (c.distance < band && (!best || c.distance < best->distance)) best = c;
  if (best) best->penetration = options_.epsilon - 0.5 * best->distance;
  return best;
}

}  // namespace spacetree::contact
