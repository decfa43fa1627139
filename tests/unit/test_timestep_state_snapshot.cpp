// TimestepStateSnapshot: each source is copied at its own moment of the step, and a rollback
// restores all of them or none (a refused rollback must not leave the atoms undone and the
// contact history not, or the other way round).
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "dynamics/TimestepStateSnapshot.h"

using spacetree::TimestepStateSnapshot;
using spacetree::TimestepStateSource;
using Moment = TimestepStateSource::Moment;

namespace {

// A piece of state (one number) that the simulation changes between save and restore.
class CountingSource : public TimestepStateSource {
 public:
  CountingSource(std::string name, Moment moment, std::vector<std::string>& calls)
      : name_(std::move(name)), moment_(moment), calls_(calls) {}
  double state = 0.0;
  bool canRestore = true;

  Moment moment() const override { return moment_; }
  void save() override {
    saved_ = state;
    calls_.push_back("save " + name_);
  }
  bool restorable() override {
    calls_.push_back("restorable? " + name_);
    return canRestore;
  }
  void restore() override {
    state = saved_;
    calls_.push_back("restore " + name_);
  }

 private:
  std::string name_;
  Moment moment_;
  std::vector<std::string>& calls_;
  double saved_ = -1.0;
};

const auto kOneRank = [](bool ok) { return ok; };

}  // namespace

TEST(TimestepStateSnapshot, EachSourceIsSavedAtItsMomentOfTheStep) {
  std::vector<std::string> calls;
  CountingSource atoms("atoms", Moment::StepStart, calls);
  CountingSource contacts("contacts", Moment::BeforeForces, calls);
  TimestepStateSnapshot snapshot;
  snapshot.add(&atoms);
  snapshot.add(&contacts);

  atoms.state = 1.0;
  contacts.state = 10.0;
  snapshot.save(Moment::StepStart);      // end of the step before
  atoms.state = 2.0;                      // initial_integrate moves the atoms
  contacts.state = 20.0;                  // re-neighbouring refills the contact history
  snapshot.save(Moment::BeforeForces);   // pre_force
  atoms.state = 3.0;                      // the forces and final_integrate of the rejected step
  contacts.state = 30.0;

  ASSERT_TRUE(snapshot.restore(kOneRank));
  EXPECT_EQ(atoms.state, 1.0) << "the atoms go back to the start of the step";
  EXPECT_EQ(contacts.state, 20.0) << "the contact history goes back to just before the forces";
  EXPECT_EQ(calls, (std::vector<std::string>{"save atoms", "save contacts", "restorable? atoms",
                                             "restorable? contacts", "restore atoms", "restore contacts"}));
}

TEST(TimestepStateSnapshot, OneRefusingSourceRestoresNothingButAllAreAsked) {
  std::vector<std::string> calls;
  CountingSource atoms("atoms", Moment::StepStart, calls);
  CountingSource walls("walls", Moment::StepStart, calls);
  CountingSource contacts("contacts", Moment::BeforeForces, calls);
  TimestepStateSnapshot snapshot;
  snapshot.add(&atoms);
  snapshot.add(&walls);
  snapshot.add(&contacts);
  snapshot.save(Moment::StepStart);
  snapshot.save(Moment::BeforeForces);
  atoms.state = walls.state = contacts.state = 5.0;
  atoms.canRestore = false;   // e.g. an atom was deleted during the step
  calls.clear();

  EXPECT_FALSE(snapshot.restore(kOneRank));
  EXPECT_EQ(atoms.state, 5.0);
  EXPECT_EQ(walls.state, 5.0);
  EXPECT_EQ(contacts.state, 5.0);
  // every source is asked even after a refusal: one that communicates must be called on every rank
  EXPECT_EQ(calls, (std::vector<std::string>{"restorable? atoms", "restorable? walls", "restorable? contacts"}));
}

TEST(TimestepStateSnapshot, AnotherRankRefusingRestoresNothingHere) {
  std::vector<std::string> calls;
  CountingSource atoms("atoms", Moment::StepStart, calls);
  TimestepStateSnapshot snapshot;
  snapshot.add(&atoms);
  snapshot.save(Moment::StepStart);
  atoms.state = 7.0;
  bool seen = false;
  EXPECT_FALSE(snapshot.restore([&](bool ok) { seen = ok; return false; }));
  EXPECT_TRUE(seen) << "this rank's own answer is handed to the reduction";
  EXPECT_EQ(atoms.state, 7.0);
  EXPECT_TRUE(snapshot.restore(kOneRank));
  EXPECT_EQ(atoms.state, 0.0);
}

TEST(TimestepStateSnapshot, RejectsNullAndTwiceAddedSources) {
  std::vector<std::string> calls;
  CountingSource atoms("atoms", Moment::StepStart, calls);
  TimestepStateSnapshot snapshot;
  EXPECT_THROW(snapshot.add(nullptr), std::invalid_argument);
  snapshot.add(&atoms);
  EXPECT_THROW(snapshot.add(&atoms), std::invalid_argument);
  EXPECT_EQ(snapshot.size(), 1u);
  snapshot.clear();
  EXPECT_EQ(snapshot.size(), 0u);
}
