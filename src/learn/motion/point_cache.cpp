#include "learn/motion/point_cache.h"

#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "core/scene/obj_mesh_builder.h"
#include "learn/motion/cache_vertex_match.h"

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
  CacheReader(const std::string& bytes, const std::string& path, bool big_endian)
      : b_(bytes, big_endian), path_(path) {}

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
    if (l.frames > kMaxReferenceFrames)
      fail(l.count_field, std::to_string(l.frames) + " at byte " + std::to_string(l.count_at) +
                              ": more than the " + std::to_string(kMaxReferenceFrames) +
                              " frames a reference may hold");
    if (l.vertices > kMaxReferenceObservations / l.frames)
      fail("vertex count", std::to_string(l.frames) + " " + l.word + "s of " +
                               std::to_string(l.vertices) + " vertices: more than the " +
                               std::to_string(kMaxReferenceObservations) +
                               " positions a reference may hold");
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
  void read_positions(const Layout& l, ReferenceMotion& m) const {
    for (std::size_t k = 0; k < l.frames; ++k) {
      ReferenceFrame& frame = m.frames[k];
      frame.nodes.resize(l.vertices);
      frame.positions.resize(l.vertices);
      for (std::size_t j = 0; j < l.vertices; ++j) {
        const std::size_t at = l.positions + (k * l.vertices + j) * kVertexBytes;
        double xyz[3];
        for (int axis = 0; axis < 3; ++axis) {
          xyz[axis] = b_.f32(at + 4 * axis);
          if (!(std::abs(xyz[axis]) <= kMaxReferenceCoordinate))  // NaN fails too
            fail(std::string(l.word) + " " + std::to_string(k) + " vertex " + std::to_string(j),
                 std::string(1, "xyz"[axis]) + " at byte " + std::to_string(at + 4 * axis) + ": " +
                     (std::isfinite(xyz[axis])
                          ? shown_value(xyz[axis]) +
                                " is beyond 1e6 m from the origin (a unit mistake?)"
                          : std::string("NaN or infinite")));
        }
        frame.nodes[j] = static_cast<std::int32_t>(j);
        frame.positions[j] = Vec3(xyz[0], xyz[1], xyz[2]);
      }
    }
  }

 private:
  CacheBytes b_;
  const std::string& path_;
};

ReferenceMotion cache_motion(const std::string& path, std::size_t frames) {
  ReferenceMotion m;
  m.path = path;
  m.source = ReferenceMotion::Source::cache;
  m.frames.resize(frames);
  return m;
}

// The OBJ's vertices in its file order (build_obj_mesh renumbers its nodes).
std::vector<Vec3> obj_vertices(const std::string& path) {
  ObjMeshSpec spec;
  spec.path = path;
  spec.bend = false;
  const ClothTopology mesh = build_obj_mesh(spec);
  std::vector<Vec3> vertices(mesh.rest_positions.size());
  for (std::size_t k = 0; k < vertices.size(); ++k)
    vertices[k] = mesh.rest_positions[mesh.numbering.node(static_cast<int>(k))];
  return vertices;
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

ReferenceMotion parse_pc2(const std::string& bytes, const std::string& path,
                          const ReferenceOptions& options) {
  const double fps = required_fps(options, path, "a PC2 cache holds no frame rate");
  const double start = checked_start(options, path);
  const CacheReader r(bytes, path, false);
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

  ReferenceMotion m = cache_motion(path, l.frames);
  for (std::size_t k = 0; k < l.frames; ++k) {
    m.frames[k].time = start + static_cast<double>(k) * sampling / fps;
    if (!std::isfinite(m.frames[k].time) || (k > 0 && !(m.frames[k].time > m.frames[k - 1].time)))
      r.fail("sampling", shown_value(sampling) + " frames per sample at " + shown_value(fps) +
                             " frames per second: sample " + std::to_string(k) +
                             "'s time is not a finite time after the sample before it");
  }
  r.read_positions(l, m);
  return m;
}

ReferenceMotion parse_mdd(const std::string& bytes, const std::string& path,
                          const ReferenceOptions& options) {
  const double start = checked_start(options, path);
  const CacheReader r(bytes, path, true);
  r.need_header(kMddHeader, "an MDD cache");
  Layout l;
  l.count_at = 0;
  l.frames = r.count(0, "frame count");
  l.vertices = r.count(4, "vertex count");
  l.positions = kMddHeader + 4 * l.frames;  // one float32 time per frame
  r.check_size(l);

  ReferenceMotion m = cache_motion(path, l.frames);
  const CacheBytes& b = r.bytes();
  for (std::size_t k = 0; k < l.frames; ++k) {
    const std::size_t at = kMddHeader + 4 * k;
    const float t = b.f32(at);
    const std::string field = "frame " + std::to_string(k) + " time";
    if (!std::isfinite(t)) r.fail(field, "NaN or infinite at byte " + std::to_string(at));
    m.frames[k].time = start + t;
    if (!(m.frames[k].time >= 0))
      r.fail(field, shown_value(t) + " s at byte " + std::to_string(at) +
                        " is before the scene's start (with --reference-start " +
                        shown_value(start) + ")");
    if (k > 0 && !(m.frames[k].time > m.frames[k - 1].time))
      r.fail(field, shown_value(t) + " s at byte " + std::to_string(at) + " after frame " +
                        std::to_string(k - 1) + "'s " + shown_value(b.f32(at - 4)) +
                        " s: a frame going back or repeating (times must increase)");
  }
  // The file's times are what was simulated; a frame rate given beside them
  // that disagrees is said, not followed.
  if (options.fps > 0 && std::isfinite(options.fps) && l.frames > 1) {
    const double t0 = m.frames.front().time, span = m.frames.back().time - t0;
    bool agree = true;
    for (std::size_t k = 0; k < l.frames && agree; ++k)
      agree = std::abs(m.frames[k].time - t0 - static_cast<double>(k) / options.fps) <=
              0.01 / options.fps + 1e-6 * std::abs(m.frames[k].time);
    if (!agree)
      m.note = "its own times kept, not --reference-fps " + shown_value(options.fps) + " (its " +
               std::to_string(l.frames) + " frames span " + shown_value(span) + " s, " +
               shown_value(static_cast<double>(l.frames - 1) / span) + " frames per second)";
  }
  r.read_positions(l, m);
  return m;
}

ReferenceMotion parse_point_cache(const std::string& bytes, const std::string& path,
                                  PointCacheFormat format, const std::vector<Vec3>& mesh,
                                  const std::string& mesh_path, std::size_t node_count,
                                  const ReferenceOptions& options) {
  ReferenceMotion m = format == PointCacheFormat::pc2 ? parse_pc2(bytes, path, options)
                                                      : parse_mdd(bytes, path, options);
  match_cache_to_scene(m, mesh, mesh_path, node_count, options.scene_positions);
  return m;
}

ReferenceMotion read_point_cache(const std::string& path, std::size_t node_count,
                                 const ReferenceOptions& options) {
  PointCacheFormat format = PointCacheFormat::pc2;
  if (!point_cache_format(path, format))
    throw InputError(path, "", "not a point cache: the name must end in .pc2 or .mdd");
  if (options.mesh.empty())
    throw InputError(path, "--reference-mesh",
                     "a point cache needs the mesh it deforms: give its OBJ (the cache's vertex k "
                     "is the mesh's vertex k)");
  const std::vector<Vec3> mesh = obj_vertices(options.mesh);
  return parse_point_cache(read_text_file(path, "point cache", kMaxReferenceBytes), path, format,
                           mesh, options.mesh, node_count, options);
}

}  // namespace neurocloth
