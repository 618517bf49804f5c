#include "ui/drape_readout.h"

namespace neurocloth {

const std::string& DrapeReadout::line(const FrameSnapshot& snapshot, double now) {
  if (!meter_) return line_;
  const std::size_t nodes = meter_->node_count();
  if (snapshot.position.size() != 3 * nodes) {
    line_.clear();
    return line_;
  }
  const bool newer = snapshot.serial != serial_;
  const bool due = readings_ == 0 || now - measured_at_ >= kInterval;
  if (!newer || !due) return line_;
  x_.assign(snapshot.position.begin(), snapshot.position.end());
  line_ = describe(meter_->measure(x_.data()), meter_->support());
  serial_ = snapshot.serial;
  measured_at_ = now;
  ++readings_;
  return line_;
}

}  // namespace neurocloth
