#include "contact_model/ContactModel.h"

#include <stdexcept>

#include "contact_model/SubModelRegistry.h"

namespace spacetree::contact_model {

std::string& ContactModelSpec::operator[](Slot slot) {
  switch (slot) {
    case Slot::Normal: return normal;
    case Slot::Damping: return damping;
    case Slot::Tangential: return tangential;
    case Slot::Rolling: return rolling;
    case Slot::Cohesion: return cohesion;
  }
  throw std::logic_error("ContactModelSpec: bad slot");
}

const std::string& ContactModelSpec::operator[](Slot slot) const {
  return const_cast<ContactModelSpec&>(*this)[slot];
}

void ContactModelSpec::validate() const {
  for (Slot s : kAllSlots) findSubModel(s, (*this)[s]);
}

std::string ContactModelSpec::describe() const {
  std::string out;
  for (Slot s : kAllSlots)
    if ((*this)[s] != "none") out += (out.empty() ? "" : " ") + std::string(slotName(s)) + " " + (*this)[s];
  return out;
}

namespace {
template <class Base>
std::unique_ptr<Base> build(Slot slot, const std::string& keyword, const ContactParameters& p,
                            int& historySize) {
  std::unique_ptr<SubModel> made = createSubModel(slot, keyword, p);
  if (!made) return nullptr;
  made->setHistoryOffset(historySize);
  historySize += made->historySize();
  return std::unique_ptr<Base>(static_cast<Base*>(made.release()));
}
}  // namespace

ContactModel::ContactModel(const ContactModelSpec& spec, const ContactParameters& p) : spec_(spec) {
  normal_ = build<NormalSubModel>(Slot::Normal, spec.normal, p, historySize_);
  damping_ = build<DampingSubModel>(Slot::Damping, spec.damping, p, historySize_);
  tangential_ = build<TangentialSubModel>(Slot::Tangential, spec.tangential, p, historySize_);
  rolling_ = build<RollingSubModel>(Slot::Rolling, spec.rolling, p, historySize_);
  cohesion_ = build<CohesionSubModel>(Slot::Cohesion, spec.cohesion, p, historySize_);
}

ContactModelTable::ContactModelTable(int types, const ContactModelSpec& spec,
                                     const std::function<ContactParameters(int, int)>& parametersOf,
                                     const std::function<bool(int, int)>& active)
    : types_(types), spec_(spec) {
  if (types < 1) throw std::invalid_argument("ContactModelTable: needs at least one type");
  spec.validate();
  models_.assign(std::size_t(types) * std::size_t(types), nullptr);
  for (int i = 1; i <= types; ++i)
    for (int j = i; j <= types; ++j) {
      if (active && !active(i, j)) continue;
      std::shared_ptr<const ContactModel> model;
      try {
        model = std::make_shared<const ContactModel>(spec_, parametersOf(i, j));
      } catch (const std::invalid_argument& e) {
        throw std::invalid_argument("type pair " + std::to_string(i) + " " + std::to_string(j) +
                                    ": " + e.what());
      }
      historySize_ = model->historySize();  // the same for every pair (one spec)
      models_[std::size_t(i - 1) * std::size_t(types) + std::size_t(j - 1)] = model;
      models_[std::size_t(j - 1) * std::size_t(types) + std::size_t(i - 1)] = model;
    }
}

}  // namespace spacetree::contact_model
