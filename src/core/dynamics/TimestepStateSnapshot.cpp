#include "dynamics/TimestepStateSnapshot.h"

#include <stdexcept>

namespace spacetree {

void TimestepStateSnapshot::add(TimestepStateSource* source) {
  if (!source) throw std::invalid_argument("TimestepStateSnapshot::add: null source");
  for (const TimestepStateSource* s : sources_)
    if (s == source) throw std::invalid_argument("TimestepStateSnapshot::add: source added twice");
  sources_.push_back(source);
}

void TimestepStateSnapshot::save(TimestepStateSource::Moment moment) {
  for (TimestepStateSource* s : sources_)
    if (s->moment() == moment) s->save();
}

bool TimestepStateSnapshot::restore(const std::function<bool(bool)>& allAgree) {
  bool ok = true;
  for (TimestepStateSource* s : sources_) ok = s->restorable() && ok;   // asks all of them
  if (!allAgree(ok)) return false;
  for (TimestepStateSource* s : sources_) s->restore();
  return true;
}

}  // namespace spacetree
