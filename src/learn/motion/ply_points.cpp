#include "learn/motion/ply_points.h"

#include <cmath>
#include <cstdint>
#include <cstring>
#include <string_view>

#include "core/io/csv_fields.h"
#include "core/io/input_error.h"
#include "learn/motion/ply_header.h"
#include "learn/motion/reference_motion.h"

namespace neurocloth {
namespace {

std::string bytes_of(std::uint64_t n) {
  return std::to_string(n) + (n == 1 ? " byte" : " bytes");
}

std::string values_of(std::size_t n) {
  return std::to_string(n) + (n == 1 ? " value" : " values");
}

// A coordinate as read, or the InputError saying why not; `where()` says which
// vertex and where it is ("vertex 12 at byte 345"), worded only for a message.
template <class Where>
double checked_coordinate(double v, int axis, const Where& where, const std::string& path,
                          int line) {
  if (std::isfinite(v) && std::abs(v) <= kMaxReferenceCoordinate) return v;
  const std::string field(1, "xyz"[axis]);
  if (!std::isfinite(v)) throw InputError(path, field, where() + ": NaN or infinite", line);
  throw InputError(
      path, field,
      where() + ": " + std::to_string(v) + " is beyond 1e6 m from the origin (a unit mistake?)",
      line);
}

// A binary body: raw numbers in the header's byte order, whatever the machine's.
class BinaryBody {
 public:
  BinaryBody(const std::string& bytes, const PlyHeader& h, const std::string& path)
      : data_(reinterpret_cast<const unsigned char*>(bytes.data())),
        size_(bytes.size()),
        at_(h.body),
        big_(h.format == PlyFormat::big_endian),
        header_(h),
        path_(path) {}

  std::vector<Vec3> read() {
    std::vector<Vec3> points;
    for (std::size_t k = 0; k < header_.elements.size(); ++k) {
      const PlyElement& e = header_.elements[k];
      if (e.properties.empty()) continue;
      if (k == header_.vertex) points.reserve(e.count);  // check_counts bounded it
      for (std::uint64_t i = 0; i < e.count; ++i)
        record(e, i, k == header_.vertex ? &points : nullptr);
    }
    if (at_ != size_) {
      const PlyElement& last = header_.elements.back();
      throw InputError(path_, "element " + last.name,
                       bytes_of(size_ - at_) + " after the last element, from byte " +
                           std::to_string(at_) + " (the header states fewer than the file holds)");
    }
    return points;
  }

 private:
  void record(const PlyElement& e, std::uint64_t i, std::vector<Vec3>* points) {
    double xyz[3] = {0, 0, 0};
    for (const PlyProperty& p : e.properties) {
      if (p.count) {
        need(p.count->bytes, e, i);
        const std::size_t count_at = at_;
        const double n = value(*p.count);
        if (n < 0)
          throw InputError(path_, p.name,
                           e.name + " " + std::to_string(i) + " at byte " +
                               std::to_string(count_at) + ": a list of " +
                               std::to_string(static_cast<long long>(n)) + " items");
        const auto items = static_cast<std::uint64_t>(n);
        if (items > (size_ - at_) / p.type->bytes) ends(e, i);
        at_ += items * p.type->bytes;
        continue;
      }
      need(p.type->bytes, e, i);
      const std::size_t value_at = at_;
      const double v = value(*p.type);
      if (p.axis >= 0 && points)
        xyz[p.axis] = checked_coordinate(
            v, p.axis,
            [&] { return "vertex " + std::to_string(i) + " at byte " + std::to_string(value_at); },
            path_, 0);
    }
    if (points) points->emplace_back(xyz[0], xyz[1], xyz[2]);
  }

  void need(std::size_t bytes, const PlyElement& e, std::uint64_t i) const {
    if (bytes > size_ - at_) ends(e, i);
  }

  [[noreturn]] void ends(const PlyElement& e, std::uint64_t i) const {
    throw InputError(path_, "element " + e.name,
                     "the file ends at byte " + std::to_string(size_) + " in " + e.name + " " +
                         std::to_string(i) + " of " + std::to_string(e.count) +
                         " (the header states more than the file holds)");
  }

  // The scalar at the cursor, which moves past it.
  double value(const PlyType& t) {
    std::uint64_t bits = 0;
    for (std::size_t b = 0; b < t.bytes; ++b) {
      const std::uint64_t byte = data_[at_ + b];
      bits |= big_ ? byte << (8 * (t.bytes - 1 - b)) : byte << (8 * b);
    }
    at_ += t.bytes;
    switch (t.scalar) {
      case PlyScalar::int8:
        return static_cast<std::int8_t>(bits);
      case PlyScalar::uint8:
        return static_cast<std::uint8_t>(bits);
      case PlyScalar::int16:
        return static_cast<std::int16_t>(bits);
      case PlyScalar::uint16:
        return static_cast<std::uint16_t>(bits);
      case PlyScalar::int32:
        return static_cast<std::int32_t>(bits);
      case PlyScalar::uint32:
        return static_cast<std::uint32_t>(bits);
      case PlyScalar::float32: {
        const auto b32 = static_cast<std::uint32_t>(bits);
        float f;
        std::memcpy(&f, &b32, sizeof f);
        return f;
      }
      case PlyScalar::float64: {
        double d;
        std::memcpy(&d, &bits, sizeof d);
        return d;
      }
    }
    return 0;
  }

  const unsigned char* data_;
  std::size_t size_, at_;
  bool big_;
  const PlyHeader& header_;
  const std::string& path_;
};

// A text body: one record a line, values separated by spaces or tabs; blank
// lines are let by.
class AsciiBody {
 public:
  AsciiBody(const std::string& bytes, const PlyHeader& h, const std::string& path)
      : rest_(std::string_view(bytes).substr(h.body)), line_(h.lines), header_(h), path_(path) {}

  std::vector<Vec3> read() {
    std::vector<Vec3> points;
    for (std::size_t k = 0; k < header_.elements.size(); ++k) {
      const PlyElement& e = header_.elements[k];
      if (e.properties.empty()) continue;
      for (std::uint64_t i = 0; i < e.count; ++i)
        record(e, i, k == header_.vertex ? &points : nullptr);
    }
    if (next_values())
      throw InputError(path_, "element " + header_.elements.back().name,
                       "data after the last element (the header states fewer than the file "
                       "holds): " +
                           shown(values_.front()),
                       line_);
    return points;
  }

 private:
  void record(const PlyElement& e, std::uint64_t i, std::vector<Vec3>* points) {
    const auto which = [&] { return e.name + " " + std::to_string(i); };
    if (!next_values())
      throw InputError(path_, "element " + e.name,
                       "the file ends at line " + std::to_string(line_) + " in " + which() +
                           " of " + std::to_string(e.count) +
                           " (the header states more than the file holds)",
                       line_);
    double xyz[3] = {0, 0, 0};
    std::size_t v = 0;  // the next value of the line
    for (const PlyProperty& p : e.properties) {
      if (v == values_.size())
        throw InputError(path_, p.name,
                         which() + " has " + values_of(values_.size()) +
                             ": the header declares more (" + p.name + " is missing)",
                         line_);
      if (p.count) {
        const FieldNumber n = finite_number(values_[v]);
        const std::size_t left = values_.size() - v - 1;
        if (!n.refusal.empty() || n.value < 0 || n.value != std::floor(n.value))
          throw InputError(
              path_, p.name,
              which() + ": a list's count must be a whole number >= 0, found " + shown(values_[v]),
              line_);
        if (n.value > static_cast<double>(left))
          throw InputError(path_, p.name,
                           which() + ": a list of " + shown(values_[v]) + " items, the line has " +
                               std::to_string(left) + " values after it",
                           line_);
        v += 1 + static_cast<std::size_t>(n.value);
        continue;
      }
      if (p.axis >= 0 && points) {
        const FieldNumber n = finite_number(values_[v]);
        if (!n.refusal.empty())
          throw InputError(path_, p.name, "vertex " + std::to_string(i) + ": " + n.refusal, line_);
        xyz[p.axis] = checked_coordinate(
            n.value, p.axis, [&] { return "vertex " + std::to_string(i); }, path_, line_);
      }
      ++v;
    }
    if (v != values_.size())
      throw InputError(path_, "element " + e.name,
                       which() + " has " + values_of(values_.size()) + ", the header " +
                           values_of(v) + " (its properties)",
                       line_);
    if (points) points->emplace_back(xyz[0], xyz[1], xyz[2]);
  }

  // The next line with something on it, split into values_; false at the end.
  bool next_values() {
    while (!rest_.empty()) {
      const std::size_t eol = rest_.find('\n');
      const std::string_view line = rest_.substr(0, eol);
      rest_.remove_prefix(eol == std::string_view::npos ? rest_.size() : eol + 1);
      ++line_;
      values_ = ply_words(line);
      if (!values_.empty()) return true;
    }
    return false;
  }

  std::string_view rest_;
  int line_;
  std::vector<std::string_view> values_;
  const PlyHeader& header_;
  const std::string& path_;
};

}  // namespace

std::vector<Vec3> parse_ply_points(const std::string& bytes, const std::string& path) {
  const PlyHeader header = read_ply_header(bytes, path);
  if (header.format == PlyFormat::ascii) return AsciiBody(bytes, header, path).read();
  return BinaryBody(bytes, header, path).read();
}

}  // namespace neurocloth
