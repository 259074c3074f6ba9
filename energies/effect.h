// A built effect: what stands for "the contact effect" once its terms are in
// the incremental potential. An effect factory (energies/effect_registry.h)
// returns one; the simulation owns them (sim/simulation.h) and an effect built
// later finds the ones it works with through TermBuilder::FindEffect (friction
// finds contact), as the output finds contact's obstacles through
// Simulation::FindEffect. A factory that only returns a summary line (the
// original form, still registered as it was) stands behind a SummaryEffect.
#pragma once

#include <memory>
#include <string>
#include <typeinfo>
#include <utility>
#include <vector>

namespace ipstep {

class Effect {
 public:
  virtual ~Effect() = default;
  // One line for the "active effects" report ("springs: 760 hookean").
  virtual std::string Summary() const = 0;
};

// An effect that leaves nothing behind but its summary line.
class SummaryEffect final : public Effect {
 public:
  explicit SummaryEffect(std::string summary) : summary_(std::move(summary)) {}
  std::string Summary() const override { return summary_; }

 private:
  std::string summary_;
};

// The effects of one simulation, in the order they were built, each under the
// name the scene lists it by.
class EffectList {
 public:
  void Add(std::string name, std::unique_ptr<Effect> effect) {
    entries_.push_back({std::move(name), std::move(effect)});
  }
  // The effect listed as `name`, or null.
  const Effect* Find(const std::string& name) const {
    for (const Entry& e : entries_) {
      if (e.name == name) return e.effect.get();
    }
    return nullptr;
  }
  // The effect of exactly type T (not a type derived from it), or null.
  template <class T>
  T* Find() const {
    for (const Entry& e : entries_) {
      if (typeid(*e.effect) == typeid(T)) return static_cast<T*>(e.effect.get());
    }
    return nullptr;
  }
  int size() const { return static_cast<int>(entries_.size()); }
  const std::string& name(int i) const { return entries_[i].name; }
  const Effect& effect(int i) const { return *entries_[i].effect; }

 private:
  struct Entry {
    std::string name;
    std::unique_ptr<Effect> effect;
  };
  std::vector<Entry> entries_;
};

}  // namespace ipstep
