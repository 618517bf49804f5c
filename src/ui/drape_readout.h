#pragma once
// The drape test's figures in the window (ISO 9073-9: the drape coefficient
// and its nodes, tradeoff/drape_shape.h), of the published snapshot. Measuring
// rasterises the cloth's shadow, a few milliseconds on a large cloth: too much
// for every frame of the UI thread, so a reading is kept and taken again only
// for a newer snapshot and at most every kInterval seconds.
#include <memory>
#include <string>
#include <vector>

#include "core/scene/frame_snapshot.h"
#include "tradeoff/drape_shape.h"

namespace neurocloth {

class DrapeReadout {
 public:
  static constexpr double kInterval = 0.25;  // wall s between two readings

  DrapeReadout() = default;
  // Null: the scene has no support, and the readout stays empty.
  explicit DrapeReadout(std::shared_ptr<const DrapeMeter> meter) : meter_(std::move(meter)) {}

  bool active() const { return meter_ != nullptr; }
  // The line for `snapshot` at wall time `now` (s, any clock that only grows):
  // the last one, or a new reading when the snapshot is newer and kInterval
  // has passed since the last. Empty before the first reading and for a
  // snapshot of another cloth (a scene being replaced).
  const std::string& line(const FrameSnapshot& snapshot, double now);
  long readings() const { return readings_; }  // how many times it measured

 private:
  std::shared_ptr<const DrapeMeter> meter_;
  std::vector<double> x_;  // the snapshot's positions in double, as the meter reads them
  std::string line_;
  long serial_ = -1;  // the snapshot last measured
  double measured_at_ = 0;
  long readings_ = 0;
};

}  // namespace neurocloth
