// The contact effect once built (energies/effect.h): the one object that
// stands for a scene's IPC contact. It owns the contact state
// (contact/contact_state.h: the pairs and their barrier and friction terms,
// kappa, the friction lags, the obstacles and their time) and knows the
// contact filter (contact/contact_filter.h), the step filter that keeps the
// iterates free of penetration with that state and that the incremental
// potential owns. The effects built after it (friction,
// contact/contact_effects.cc) and the output (io/frame_writer.cc) find contact
// through it.
#pragma once

#include <memory>
#include <string>
#include <utility>

#include "contact/contact_filter.h"
#include "contact/contact_state.h"
#include "energies/effect.h"

namespace ipstep {

class ContactEffect final : public Effect {
 public:
  // `filter` works with `state` and must outlive the effect (the simulation
  // owns both the effect and the potential, which owns the filter).
  ContactEffect(std::unique_ptr<ContactState> state, ContactFilter* filter)
      : state_(std::move(state)), filter_(filter), summary_(state_->Summary()) {}

  // The line of the "active effects" report, as built.
  std::string Summary() const override { return summary_; }
  ContactState& state() const { return *state_; }
  ContactFilter& filter() const { return *filter_; }
  const ObstacleList& obstacles() const { return state_->obstacles(); }

 private:
  std::unique_ptr<ContactState> state_;
  ContactFilter* filter_;
  std::string summary_;
};

}  // namespace ipstep
