// Keyword -> sub-model factory, one table for all slots (SubModelRegistry.cpp). Adding an
// effect is one file (the sub-model class) plus one line in that table. The keyword `none` of a
// slot is not in the table: it means that slot is not built (nor evaluated). The normal slot
// cannot be `none`.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "contact_model/ContactParameters.h"
#include "contact_model/SubModel.h"

namespace spacetree::contact_model {

struct SubModelEntry {
  Slot slot;
  const char* keyword;
  std::unique_ptr<SubModel> (*create)(const ContactParameters&);
  int historySize;      // the class's kHistorySize (0 if it declares none)
  const char* summary;  // one line for error messages and docs
};

const std::vector<SubModelEntry>& subModelRegistry();

// The entry of `keyword` in `slot`; nullptr for "none" (not for the normal slot). Throws
// std::invalid_argument "unknown <slot> sub-model '<keyword>' (one of: none, a, b)" otherwise.
const SubModelEntry* findSubModel(Slot slot, const std::string& keyword);

// The keywords a slot accepts, "none" first where allowed, comma separated.
std::string subModelKeywords(Slot slot);

// Doubles of per-contact history the named sub-models keep together (known before any
// coefficient: a caller can set up the storage when the keywords are read).
int historySizeOf(const struct ContactModelSpec& spec);

// Builds the sub-model of `keyword` for one type pair (nullptr for none); throws as
// findSubModel and as the sub-model's constructor (a missing or negative coefficient).
std::unique_ptr<SubModel> createSubModel(Slot slot, const std::string& keyword,
                                         const ContactParameters& parameters);

}  // namespace spacetree::contact_model
