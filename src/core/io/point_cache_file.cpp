#include "core/io/point_cache_file.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <stdexcept>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"

namespace neurocloth {
namespace {

constexpr std::size_t kPc2Header = 32;
constexpr std::size_t kMddHeader = 8;
constexpr std::size_t kVertexBytes = 12;  // float32 x y z

std::string shown_value(double v) {
  char s[32];
  std::snprintf(s, sizeof s, "%.6g", v);
  return s;
}

// The file's bytes, read in its byte order whatever the machine's.
class CacheBytes {
 public:
  CacheBytes(const std::string& bytes, bool big_endian)
      : data_(reinterpret_cast<const unsigned char*>(bytes.data())),
        size_(bytes.size()),
        big_(big_endian) {}

  std::size_t size() const { return size_; }
  std::uint32_t u32(std::size_t at) const {
    const unsigned char* p = data_ + at;
    return big_ ? std::uint32_t(p[0]) << 24 | std::uint32_t(p[1]) << 16 | std::uint32_t(p[2]) << 8 |
                      std::uint32_t(p[3])
                : std::uint32_t(p[3]) << 24 | std::uint32_t(p[2]) << 16 | std::uint32_t(p[1]) << 8 |
                      std::uint32_t(p[0]);
  }
  std::int32_t i32(std::size_t at) const { return static_cast<std::int32_t>(u32(at)); }
  float f32(std::size_t at) const {
    const std::uint32_t bits = u32(at);
    float f;
    std::memcpy(&f, &bits, sizeof f);
    return f;
  }

 private:
  const unsigned char* data_;
  std::size_t size_;
  bool big_;
};

// One cache's layout: `frames` frames (PC2's samples) of `vertices` vertices
// whose positions start at byte `positions`; `word` names a frame in messages.
struct Layout {
  std::size_t frames = 0, vertices = 0, positions = 0;
  const char* word = "frame";
  const char* count_field = "frame count";
  std::size_t count_at = 0;  // the frame count's byte
};

class CacheReader {
 public:
  CacheReader(const std::string& bytes, const std::string& path, bool big_endian,
              const PointCacheLimits& limits)
      : b_(bytes, big_endian), path_(path), limits_(limits) {}

  const CacheBytes& bytes() const { return b_; }

  [[noreturn]] void fail(const std::string& field, const std::string& message) const {
    throw InputError(path_, field, message);
  }

  void need_header(std::size_t header, const char* what) const {
    if (b_.size() < header)
      fail("header", "the file ends at byte " + std::to_string(b_.size()) + " inside the " +
                         std::to_string(header) + "-byte header: not " + what);
  }

  std::size_t count(std::size_t at, const char* field) const {
    const std::int32_t n = b_.i32(at);
    if (n <= 0) fail(field, std::to_string(n) + " at byte " + std::to_string(at) + ": must be > 0");
    return static_cast<std::size_t>(n);
  }

  // The counts against the limits and against the file's size, before
  // anything is allocated from them.
  void check_size(const Layout& l) const {
    if (l.frames > limits_.frames)
      fail(l.count_field, std::to_string(l.frames) + " at byte " + std::to_string(l.count_at) +
                              ": more than the " + std::to_string(limits_.frames) + " frames " +
                              limits_.holder + " may hold");
    if (l.vertices > limits_.positions / l.frames)
      fail("vertex count", std::to_string(l.frames) + " " + l.word + "s of " +
                               std::to_string(l.vertices) + " vertices: more than the " +
                               std::to_string(limits_.positions) + " positions " + limits_.holder +
                               " may hold");
    const std::uint64_t frame_bytes = std::uint64_t(l.vertices) * kVertexBytes;
    const std::uint64_t expected = l.positions + l.frames * frame_bytes;
    const std::size_t size = b_.size();
    if (size < l.positions)  // an MDD's times
      fail(l.count_field, "the file ends at byte " + std::to_string(size) + " in the time of " +
                              l.word + " " + std::to_string((size - kMddHeader) / 4) + " of " +
                              std::to_string(l.frames) +
                              " (the header's count is more than the file holds)");
    if (size < expected) {
      const std::uint64_t into = size - l.positions;
      fail(l.count_field, "the file ends at byte " + std::to_string(size) + " in " + l.word + " " +
                              std::to_string(into / frame_bytes) + " vertex " +
                              std::to_string(into % frame_bytes / kVertexBytes) + " of " +
                              std::to_string(l.frames) + " " + l.word +
                              "s (the header's count is more than the file holds)");
    }
    if (size > expected)
      fail(l.count_field, std::to_string(size - expected) +
                              (size - expected == 1 ? " byte" : " bytes") + " after the last " +
                              l.word + ", from byte " + std::to_string(expected) +
                              " (the header's count is less than the file holds)");
  }

  // Every vertex of every frame, each coordinate checked where it lies.
  void read_positions(const Layout& l, PointCacheFrames& out) const {
    out.positions.resize(l.frames);
    for (std::size_t k = 0; k < l.frames; ++k) {
      std::vector<Vec3>& frame = out.positions[k];
      frame.resize(l.vertices);
      for (std::size_t j = 0; j < l.vertices; ++j) {
        const std::size_t at = l.positions + (k * l.vertices + j) * kVertexBytes;
        double xyz[3];
        for (int axis = 0; axis < 3; ++axis) {
          xyz[axis] = b_.f32(at + 4 * axis);
          if (!(std::abs(xyz[axis]) <= limits_.coordinate))  // NaN fails too
            fail(std::string(l.word) + " " + std::to_string(k) + " vertex " + std::to_string(j),
                 std::string(1, "xyz"[axis]) + " at byte " + std::to_string(at + 4 * axis) + ": " +
                     (std::isfinite(xyz[axis])
                          ? shown_value(xyz[axis]) + " is beyond " + limits_.beyond
                          : std::string("NaN or infinite")));
        }
        frame[j] = Vec3(xyz[0], xyz[1], xyz[2]);
      }
    }
  }

 private:
  CacheBytes b_;
  const std::string& path_;
  const PointCacheLimits& limits_;
};

double rms(const std::vector<Vec3>& a, const std::vector<Vec3>& b, bool turn_a) {
  double sum = 0;
  for (std::size_t k = 0; k < a.size(); ++k)
    sum += ((turn_a ? z_up_to_y_up(a[k]) : a[k]) - b[k]).squaredNorm();
  return std::sqrt(sum / static_cast<double>(std::max<std::size_t>(1, a.size())));
}

}  // namespace

bool point_cache_format(const std::string& path, PointCacheFormat& format) {
  std::string ext = std::filesystem::path(path).extension().string();
  for (char& c : ext)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".pc2") format = PointCacheFormat::pc2;
  if (ext == ".mdd") format = PointCacheFormat::mdd;
  return ext == ".pc2" || ext == ".mdd";
}

PointCacheFrames decode_pc2(const std::string& bytes, const std::string& path,
                            const PointCacheClock& clock, const PointCacheLimits& limits) {
  const double fps = clock.fps, start = clock.start;
  if (!(fps > 0) || !std::isfinite(fps))
    throw std::invalid_argument("decode_pc2: " + shown_value(fps) + " frames per second");
  const CacheReader r(bytes, path, false, limits);
  r.need_header(kPc2Header, "a PC2 cache");
  if (bytes.compare(0, 12, "POINTCACHE2\0", 12) != 0)
    r.fail("magic", "not a PC2 cache: it starts with " + shown(bytes.substr(0, 12)) +
                        ", not 'POINTCACHE2' and a NUL byte");
  const CacheBytes& b = r.bytes();
  if (b.i32(12) != 1)
    r.fail("version", std::to_string(b.i32(12)) + " at byte 12: this reader reads PC2 version 1");
  Layout l;
  l.word = "sample";
  l.count_field = "sample count";
  l.count_at = 28;
  l.positions = kPc2Header;
  l.vertices = r.count(16, "vertex count");
  if (!std::isfinite(b.f32(20)))
    r.fail("start frame", "NaN or infinite at byte 20 (" + shown_value(b.f32(20)) + ")");
  const double sampling = b.f32(24);
  if (!(sampling > 0) || !std::isfinite(sampling))
    r.fail("sampling",
           shown_value(sampling) + " at byte 24: frames per sample must be a finite number > 0");
  l.frames = r.count(28, "sample count");
  r.check_size(l);

  PointCacheFrames out;
  out.times.resize(l.frames);
  for (std::size_t k = 0; k < l.frames; ++k) {
    out.times[k] = start + static_cast<double>(k) * sampling / fps;
    if (!std::isfinite(out.times[k]) || (k > 0 && !(out.times[k] > out.times[k - 1])))
      r.fail("sampling", shown_value(sampling) + " frames per sample at " + shown_value(fps) +
                             " frames per second: sample " + std::to_string(k) +
                             "'s time is not a finite time after the sample before it");
  }
  r.read_positions(l, out);
  return out;
}

PointCacheFrames decode_mdd(const std::string& bytes, const std::string& path,
                            const PointCacheClock& clock, const PointCacheLimits& limits) {
  const double start = clock.start;
  const CacheReader r(bytes, path, true, limits);
  r.need_header(kMddHeader, "an MDD cache");
  Layout l;
  l.count_at = 0;
  l.frames = r.count(0, "frame count");
  l.vertices = r.count(4, "vertex count");
  l.positions = kMddHeader + 4 * l.frames;  // one float32 time per frame
  r.check_size(l);

  PointCacheFrames out;
  out.times.resize(l.frames);
  const CacheBytes& b = r.bytes();
  for (std::size_t k = 0; k < l.frames; ++k) {
    const std::size_t at = kMddHeader + 4 * k;
    const float t = b.f32(at);
    const std::string field = "frame " + std::to_string(k) + " time";
    if (!std::isfinite(t)) r.fail(field, "NaN or infinite at byte " + std::to_string(at));
    // Frame 0's time is finite by now (checked at k = 0).
    out.times[k] =
        clock.mdd_from_first ? start + (double(t) - double(b.f32(kMddHeader))) : start + t;
    if (!(out.times[k] >= 0))
      r.fail(field, shown_value(t) + " s at byte " + std::to_string(at) +
                        " is before the scene's start (with " + clock.start_field + " " +
                        shown_value(start) + ")");
    if (k > 0 && !(out.times[k] > out.times[k - 1]))
      r.fail(field, shown_value(t) + " s at byte " + std::to_string(at) + " after frame " +
                        std::to_string(k - 1) + "'s " + shown_value(b.f32(at - 4)) +
                        " s: a frame going back or repeating (times must increase)");
  }
  r.read_positions(l, out);
  return out;
}

PointCacheFrames decode_point_cache(const std::string& bytes, const std::string& path,
                                    PointCacheFormat format, const PointCacheClock& clock,
                                    const PointCacheLimits& limits) {
  return format == PointCacheFormat::pc2 ? decode_pc2(bytes, path, clock, limits)
                                         : decode_mdd(bytes, path, clock, limits);
}

void check_cache_vertex_count(const std::string& cache_path, std::size_t cache_vertices,
                              const std::string& mesh_path, std::size_t mesh_vertices) {
  if (cache_vertices != mesh_vertices)
    throw InputError(cache_path, "vertex count",
                     "the cache has " + std::to_string(cache_vertices) + " vertices, its mesh '" +
                         mesh_path + "' " + std::to_string(mesh_vertices) +
                         ": not the mesh it deforms");
}

bool cache_is_z_up(const std::vector<Vec3>& first_frame, const std::vector<Vec3>& mesh,
                   double& as_written, double& turned) {
  if (first_frame.size() != mesh.size())
    throw std::invalid_argument("cache_is_z_up: a frame of " + std::to_string(first_frame.size()) +
                                " vertices for a mesh of " + std::to_string(mesh.size()));
  as_written = rms(first_frame, mesh, false);
  turned = rms(first_frame, mesh, true);
  return turned < as_written;  // a tie (a mesh symmetric about both) keeps the file's axes
}

}  // namespace neurocloth
