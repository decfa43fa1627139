#include "contact_model/SubModelRegistry.h"

#include <stdexcept>

#include "contact_model/DampingApproach.h"
#include "contact_model/NormalHaloSpring.h"
#include "contact_model/TangentialViscous.h"

namespace spacetree::contact_model {

namespace {
template <class Model>
std::unique_ptr<SubModel> make(const ContactParameters& p) {
  return std::make_unique<Model>(p);
}
}  // namespace

const std::vector<SubModelEntry>& subModelRegistry() {
  static const std::vector<SubModelEntry> registry = {
      {Slot::Normal, "halo", &make<NormalHaloSpring>, "halo spring S (eps - d/2), paper eq. (1)"},
      {Slot::Damping, "approach", &make<DampingApproach>,
       "2 D sqrt(m_eff) |v_n| while approaching, paper eq. (1)"},
      {Slot::Tangential, "viscous", &make<TangentialViscous>, "min(gamma |v_t|, mu F), no history"},
  };
  return registry;
}

const char* slotName(Slot slot) {
  switch (slot) {
    case Slot::Normal: return "normal";
    case Slot::Damping: return "damping";
    case Slot::Tangential: return "tangential";
    case Slot::Rolling: return "rolling";
    case Slot::Cohesion: return "cohesion";
  }
  return "?";
}

std::string subModelKeywords(Slot slot) {
  std::string words = slot == Slot::Normal ? "" : "none";
  for (const SubModelEntry& e : subModelRegistry())
    if (e.slot == slot) words += (words.empty() ? "" : ", ") + std::string(e.keyword);
  return words;
}

const SubModelEntry* findSubModel(Slot slot, const std::string& keyword) {
  if (keyword == "none" && slot != Slot::Normal) return nullptr;
  for (const SubModelEntry& e : subModelRegistry())
    if (e.slot == slot && keyword == e.keyword) return &e;
  throw std::invalid_argument(std::string("unknown ") + slotName(slot) + " sub-model '" + keyword +
                              "' (one of: " + subModelKeywords(slot) + ")");
}

std::unique_ptr<SubModel> createSubModel(Slot slot, const std::string& keyword,
                                         const ContactParameters& parameters) {
  const SubModelEntry* entry = findSubModel(slot, keyword);
  if (!entry) return nullptr;
  std::unique_ptr<SubModel> model = entry->create(parameters);
  if (model->slot() != slot) throw std::logic_error("sub-model registered in the wrong slot");
  return model;
}

}  // namespace spacetree::contact_model
