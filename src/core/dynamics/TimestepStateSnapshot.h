// The state a rolled-back step restores: the sources collected from the adapters (atoms, contact
// histories, pair styles and fixes with state of their own), saved each at its moment of the step
// and restored all together or not at all, so that a refused rollback leaves no part undone.
#pragma once

#include <cstddef>
#include <functional>
#include <vector>

#include "dynamics/TimestepStateSource.h"

namespace spacetree {

class TimestepStateSnapshot {
 public:
  void clear() { sources_.clear(); }
  // Not owned; restored in the order added (the atoms first, so that a source that reads
  // positions during its restore sees the restored ones).
  void add(TimestepStateSource* source);
  std::size_t size() const { return sources_.size(); }

  // save() of the sources that are copied at this moment of the step.
  void save(TimestepStateSource::Moment moment);

  // Asks every source whether it can restore (every one, so that each rank makes the same calls),
  // combines the answer with allAgree (the minimum over the ranks; identity for one process), and
  // only then restores the sources in the order added. Returns whether they were restored.
  bool restore(const std::function<bool(bool)>& allAgree);

 private:
  std::vector<TimestepStateSource*> sources_;
};

}  // namespace spacetree
