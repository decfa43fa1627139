#include "contact_model/SubModelRegistry.h"

#include <stdexcept>
#include <type_traits>

#include "contact_model/ContactModel.h"

#include "contact_model/CohesionSjkr.h"
#include "contact_model/DampingApproach.h"
#include "contact_model/NormalHaloSpring.h"
#include "contact_model/RollingEpsd.h"
#include "contact_model/TangentialHistory.h"
#include "contact_model/TangentialViscous.h"

namespace spacetree::contact_model {

namespace {
template <class Model>
std::unique_ptr<SubModel> make(const ContactParameters& p) {
  return std::make_unique<Model>(p);
}
// Model::kHistorySize, or 0 for a class that declares none
template <class Model, class = void>
struct HistoryOf {
  static constexpr int value = 0;
};
template <class Model>
struct HistoryOf<Model, std::void_t<decltype(Model::kHistorySize)>> {
  static constexpr int value = Model::kHistorySize;
};
// One registry line: slot, keyword, class, summary.
#define SUB_MODEL(slot, keyword, Model, summary) \
  { slot, keyword, &make<Model>, HistoryOf<Model>::value, summary }
}  // namespace

const std::vector<SubModelEntry>& subModelRegistry() {
  static const std::vector<SubModelEntry> registry = {
      SUB_MODEL(Slot::Normal, "halo", NormalHaloSpring, "halo spring S (eps - d/2), paper eq. (1)"),
      SUB_MODEL(Slot::Damping, "approach", DampingApproach,
                "2 D sqrt(m_eff) |v_n| while approaching, paper eq. (1)"),
      SUB_MODEL(Slot::Tangential, "viscous", TangentialViscous, "min(gamma |v_t|, mu F), no history"),
      SUB_MODEL(Slot::Tangential, "history", TangentialHistory,
                "spring k_t xi + dashpot, capped at mu F (static friction)"),
      SUB_MODEL(Slot::Rolling, "epsd", RollingEpsd,
                "spring k_r + dashpot on the relative rolling, capped at mu_r R_r F"),
      SUB_MODEL(Slot::Cohesion, "sjkr", CohesionSjkr, "2 pi R* eps k_c while the halos overlap"),
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

int historySizeOf(const ContactModelSpec& spec) {
  int size = 0;
  for (Slot s : kAllSlots)
    if (const SubModelEntry* e = findSubModel(s, spec[s])) size += e->historySize;
  return size;
}

std::unique_ptr<SubModel> createSubModel(Slot slot, const std::string& keyword,
                                         const ContactParameters& parameters) {
  const SubModelEntry* entry = findSubModel(slot, keyword);
  if (!entry) return nullptr;
  std::unique_ptr<SubModel> model = entry->create(parameters);
  if (model->slot() != slot || model->historySize() != entry->historySize)
    throw std::logic_error("sub-model registered in the wrong slot or with another history size");
  return model;
}

}  // namespace spacetree::contact_model
