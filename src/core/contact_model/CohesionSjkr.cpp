#include "contact_model/CohesionSjkr.h"

#include <cmath>

namespace spacetree::contact_model {

CohesionSjkr::CohesionSjkr(const ContactParameters& p)
    : pullOff_(2.0 * M_PI * p.require("characteristicRadius", "cohesion sjkr", true) *
               p.require("haloDepth", "cohesion sjkr", true) *
               p.require("cohesionEnergyDensity", "cohesion sjkr")) {}

}  // namespace spacetree::contact_model
