// The contact effect once built (energies/effect.h): the one object that
// stands for a scene's IPC contact. It gives the effects built after it
// (friction, contact/contact_effects.cc) and the output (io/frame_writer.cc)
// the contact filter, which the incremental potential owns as its step filter
// (contact/contact_filter.h), and with it the obstacles and the pairs.
#pragma once

#include <string>
#include <utility>

#include "contact/contact_filter.h"
#include "energies/effect.h"

namespace ipstep {

class ContactEffect final : public Effect {
 public:
  // `filter` must outlive the effect (the simulation owns both); `summary` is
  // the line of the "active effects" report, as built.
  ContactEffect(ContactFilter* filter, std::string summary)
      : filter_(filter), summary_(std::move(summary)) {}

  std::string Summary() const override { return summary_; }
  ContactFilter& filter() const { return *filter_; }
  const ObstacleList& obstacles() const { return filter_->obstacles(); }

 private:
  ContactFilter* filter_;
  std::string summary_;
};

}  // namespace ipstep
