#include "learn/motion/motion_recording.h"

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "core/io/input_error.h"

namespace neurocloth {
namespace {

std::string magic_line() {
  return std::string(kMotionRecordingMagic) + " " + std::to_string(kMotionRecordingVersion) + "\n";
}

std::size_t frame_stride(std::size_t node_count) {
  return sizeof(double) * (1 + 3 * node_count);
}

void put_double(unsigned char*& out, double v) {
  std::uint64_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  put_le64(out, bits);
  out += 8;
}

double get_double(const unsigned char* in) {
  const std::uint64_t bits = get_le64(in);
  double v;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// A header count: a whole number >= 0 that fits, else an InputError on line 2.
std::size_t header_count(const nlohmann::json& h, const char* key, const std::string& path) {
  const auto it = h.find(key);
  if (it == h.end()) throw InputError(path, key, "missing from the header", 2);
  if (!it->is_number_unsigned())
    throw InputError(path, key, "must be a whole number >= 0, not " + it->dump(), 2);
  const auto v = it->get<std::uint64_t>();
  if (v > std::numeric_limits<std::size_t>::max() / 2)
    throw InputError(path, key, "too large: " + std::to_string(v), 2);
  return static_cast<std::size_t>(v);
}

nlohmann::json parse_header(const std::string& bytes, std::size_t begin, std::size_t end,
                            const std::string& path) {
  nlohmann::json h;
  try {
    h = nlohmann::json::parse(bytes.begin() + static_cast<std::ptrdiff_t>(begin),
                              bytes.begin() + static_cast<std::ptrdiff_t>(end));
  } catch (const nlohmann::json::exception& e) {
    throw InputError(path, "header", std::string("not valid JSON: ") + e.what(), 2);
  }
  if (!h.is_object()) throw InputError(path, "header", "must be a JSON object", 2);
  return h;
}

}  // namespace

RecordingWriter::RecordingWriter(const std::string& path, RecordingInfo info)
    : file_(path), info_(std::move(info)) {
  if (info_.node_count == 0) throw std::invalid_argument(path + ": a recording of no nodes");
  const std::string magic = magic_line();
  // Room for any frame count: 20 digits more than "0" needs.
  const std::string header = header_line(0) + std::string(20, ' ') + "\n";
  header_line_bytes_ = header.size();
  header_bytes_ = magic.size() + header.size();
  file_.append(magic.data(), magic.size());
  file_.append(header.data(), header.size());
  frame_bytes_.resize(frame_stride(info_.node_count));
}

std::string RecordingWriter::header_line(std::size_t frame_count) const {
  const nlohmann::json h = {{"format", "neurocloth-motion"},
                            {"version", kMotionRecordingVersion},
                            {"scene", info_.scene},
                            {"node_count", info_.node_count},
                            {"fps", info_.fps},
                            {"frame_count", frame_count},
                            {"units", "m"},
                            {"node_order", "file"},
                            {"layout", "float64 little-endian: time, then x y z per node"}};
  // ensure_ascii: the header is plain text whatever the scene's name holds;
  // a name with invalid UTF-8 is written with replacement characters.
  return h.dump(-1, ' ', true, nlohmann::json::error_handler_t::replace);
}

void RecordingWriter::add_frame(double time, const std::vector<Vec3>& positions) {
  if (positions.size() != info_.node_count)
    throw std::logic_error(path() + ": a frame of " + std::to_string(positions.size()) +
                           " positions for " + std::to_string(info_.node_count) + " nodes");
  if (!std::isfinite(time) || time < 0 || (!times_.empty() && !(time > times_.back())))
    throw std::logic_error(path() + ": frame times must be finite, >= 0 and increasing");
  if (frame_count() + 1 > kMaxReferenceObservations / info_.node_count ||
      frame_count() + 1 > kMaxReferenceFrames)
    throw std::runtime_error(path() + ": a recording holds at most " +
                             std::to_string(kMaxReferenceObservations) +
                             " node positions (frames x nodes) and " +
                             std::to_string(kMaxReferenceFrames) + " frames; record fewer frames");
  unsigned char* out = frame_bytes_.data();
  put_double(out, time);
  for (std::size_t k = 0; k < positions.size(); ++k) {
    const Vec3& p = positions[k];
    if (!reference_position_ok(p))
      throw std::runtime_error(path() + ": refused the frame at t = " + std::to_string(time) +
                               " s: node " + std::to_string(k) +
                               " is NaN, infinite or beyond 1e6 m (never written to a file)");
    put_double(out, p.x());
    put_double(out, p.y());
    put_double(out, p.z());
  }
  file_.append(frame_bytes_.data(), frame_bytes_.size());
  times_.push_back(time);
}

void RecordingWriter::drop_frames_after(double time) {
  std::size_t keep = times_.size();
  while (keep > 0 && times_[keep - 1] > time)
    --keep;
  if (keep == times_.size()) return;
  times_.resize(keep);
  file_.truncate(header_bytes_ + keep * frame_bytes_.size());
}

void RecordingWriter::finish() {
  std::string header = header_line(frame_count());
  header.append(header_line_bytes_ - 1 - header.size(), ' ');
  header += '\n';
  file_.overwrite(magic_line().size(), header.data(), header.size());
  file_.finish();
}

bool is_motion_recording(const std::string& bytes) {
  const std::size_t n = std::strlen(kMotionRecordingMagic);
  return bytes.compare(0, n, kMotionRecordingMagic) == 0;
}

ReferenceMotion parse_motion_recording(const std::string& bytes, const std::string& path,
                                       std::size_t node_count) {
  // Line 1: the magic word and the version.
  const std::size_t magic_end = bytes.find('\n');
  const std::string expected = magic_line();
  if (magic_end == std::string::npos || bytes.compare(0, magic_end + 1, expected) != 0) {
    const std::string first =
        bytes.substr(0, std::min<std::size_t>(magic_end == std::string::npos ? 40 : magic_end, 40));
    throw InputError(path, "version",
                     "expected the line '" + expected.substr(0, expected.size() - 1) +
                         "' (this program reads recording version " +
                         std::to_string(kMotionRecordingVersion) + "), found '" + first + "'",
                     1);
  }
  // Line 2: the JSON header.
  const std::size_t header_begin = magic_end + 1;
  const std::size_t header_end = bytes.find('\n', header_begin);
  if (header_end == std::string::npos || header_end - header_begin > kMaxMotionHeaderBytes)
    throw InputError(path, "header",
                     header_end == std::string::npos
                         ? "the header line has no end (the file is truncated)"
                         : "the header line is longer than 64 KiB",
                     2);
  const nlohmann::json h = parse_header(bytes, header_begin, header_end, path);
  const auto units = h.find("units");
  if (units == h.end() || *units != "m")
    throw InputError(path, "units",
                     "must be \"m\" (found " + (units == h.end() ? "nothing" : units->dump()) + ")",
                     2);
  const auto fps = h.find("fps");
  if (fps == h.end() || !fps->is_number() || !(fps->get<double>() > 0) ||
      !std::isfinite(fps->get<double>()))
    throw InputError(path, "fps", "must be a finite number > 0", 2);
  const std::size_t nodes = header_count(h, "node_count", path);
  if (nodes == 0) throw InputError(path, "node_count", "must be > 0", 2);
  if (nodes != node_count)
    throw InputError(path, "node_count",
                     "the recording has " + std::to_string(nodes) + " nodes, the scene " +
                         std::to_string(node_count) + ": recorded from another scene?",
                     2);
  const std::size_t frames = header_count(h, "frame_count", path);
  if (frames == 0) throw InputError(path, "frame_count", "the recording has no frames", 2);
  if (frames > kMaxReferenceObservations / nodes)
    throw InputError(path, "frame_count",
                     std::to_string(frames) + " frames of " + std::to_string(nodes) +
                         " nodes: more than the " + std::to_string(kMaxReferenceObservations) +
                         " node positions a reference may hold",
                     2);
  if (frames > kMaxReferenceFrames)
    throw InputError(path, "frame_count",
                     std::to_string(frames) + " frames: more than the " +
                         std::to_string(kMaxReferenceFrames) + " a reference may hold",
                     2);
  // The frames: exactly as many bytes as the header says, checked before
  // anything is allocated for them.
  const std::size_t stride = frame_stride(nodes);
  const std::size_t body = bytes.size() - (header_end + 1);
  if (body != frames * stride)
    throw InputError(path, "frame_count",
                     body < frames * stride
                         ? "truncated: the header says " + std::to_string(frames) +
                               " frames, the file holds " + std::to_string(body / stride) +
                               " whole frames (" + std::to_string(body) + " bytes of " +
                               std::to_string(frames * stride) + ")"
                         : std::to_string(body - frames * stride) + " bytes after the last of " +
                               std::to_string(frames) + " frames",
                     2);

  ReferenceMotion motion;
  motion.path = path;
  motion.source = ReferenceMotion::Source::recording;
  motion.frames.resize(frames);
  const auto* in = reinterpret_cast<const unsigned char*>(bytes.data()) + header_end + 1;
  for (std::size_t f = 0; f < frames; ++f, in += stride) {
    ReferenceFrame& frame = motion.frames[f];
    const std::string where = "frame " + std::to_string(f);
    frame.time = get_double(in);
    if (!std::isfinite(frame.time) || frame.time < 0)
      throw InputError(path, where + " time", "must be a finite number >= 0 (s)");
    if (f > 0 && !(frame.time > motion.frames[f - 1].time))
      throw InputError(path, where + " time",
                       "time goes back or repeats: " + std::to_string(frame.time) + " s after " +
                           std::to_string(motion.frames[f - 1].time) + " s");
    frame.nodes.resize(nodes);
    frame.positions.resize(nodes);
    for (std::size_t k = 0; k < nodes; ++k) {
      const unsigned char* p = in + 8 * (1 + 3 * k);
      const Vec3 v(get_double(p), get_double(p + 8), get_double(p + 16));
      if (!reference_position_ok(v))
        throw InputError(path, where + " node " + std::to_string(k),
                         "NaN, infinite or beyond 1e6 m from the origin (a unit mistake?)");
      frame.nodes[k] = static_cast<std::int32_t>(k);
      frame.positions[k] = v;
    }
  }
  return motion;
}

}  // namespace neurocloth
