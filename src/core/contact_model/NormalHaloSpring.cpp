#include "contact_model/NormalHaloSpring.h"

namespace spacetree::contact_model {

NormalHaloSpring::NormalHaloSpring(const ContactParameters& p)
    : spring_(p.require("stiffness", "normal halo", true)) {}

}  // namespace spacetree::contact_model
