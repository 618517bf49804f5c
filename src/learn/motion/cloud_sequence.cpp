#include "learn/motion/cloud_sequence.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <system_error>

#include "core/io/input_error.h"
#include "core/io/text_file.h"
#include "learn/motion/ply_points.h"
#include "learn/motion/xyz_points.h"

namespace neurocloth {
namespace {
namespace fs = std::filesystem;

// At most 18 digits: far beyond any frame counter or millisecond clock, far
// below overflow.
constexpr std::size_t kMaxNumberDigits = 18;

bool digit(char c) {
  return c >= '0' && c <= '9';
}

std::uint64_t number_of(const std::string& digits) {
  std::uint64_t n = 0;
  for (const char c : digits)
    n = n * 10 + static_cast<std::uint64_t>(c - '0');
  return n;
}

// The place of the frame number in a pattern's file name: where "%0Nd" begins
// and ends, and N (0 for "%d").
struct NumberPlace {
  std::size_t begin = std::string::npos, end = 0;
  std::size_t width = 0;
};

NumberPlace number_place(const std::string& name) {
  NumberPlace place;
  for (std::size_t i = name.find('%'); i != std::string::npos; i = name.find('%', i + 1)) {
    std::size_t k = i + 1;
    if (k < name.size() && name[k] == '0' && k + 2 < name.size() && digit(name[k + 1]) &&
        name[k + 1] != '0' && name[k + 2] == 'd') {
      place.width = static_cast<std::size_t>(name[k + 1] - '0');
      k += 2;
    }
    if (k < name.size() && name[k] == 'd') {
      place.begin = i;
      place.end = k + 1;
      return place;
    }
  }
  return place;
}

// A file's frame number: the last run of digits in its name before the
// extension ("scan2_0041.ply" -> 41); false when it has none.
bool last_number(const std::string& name, std::string& digits) {
  const std::string stem = fs::path(name).stem().string();
  std::size_t end = stem.size();
  while (end > 0 && !digit(stem[end - 1]))
    --end;
  std::size_t begin = end;
  while (begin > 0 && digit(stem[begin - 1]))
    --begin;
  digits = stem.substr(begin, end - begin);
  return !digits.empty();
}

std::string lower(std::string s) {
  for (char& c : s)
    c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

const char* kind_name(CloudFileKind kind) {
  return kind == CloudFileKind::ply ? "PLY" : "XYZ";
}

// Gathers the files of a sequence, checking them as they come.
class FrameFiles {
 public:
  FrameFiles(const std::string& path, std::size_t most) : path_(path), most_(most) {}

  void add(const std::string& file, const std::string& digits, CloudFileKind kind) {
    if (digits.size() > kMaxNumberDigits)
      throw InputError(path_, "", "'" + file + "': a frame number of more than 18 digits");
    if (files_.empty()) {
      kind_ = kind;
      first_of_kind_ = file;
    } else if (kind != kind_) {
      throw InputError(path_, "",
                       "files of two kinds: '" + first_of_kind_ + "' is " + kind_name(kind_) +
                           ", '" + file + "' is " + kind_name(kind) +
                           " (a sequence is of one kind)");
    }
    if (files_.size() == most_)
      throw InputError(
          path_, "",
          "more than " + std::to_string(most_) + " files: more frames than a reference may hold");
    files_.push_back({file, number_of(digits)});
  }

  std::vector<FrameFile> sorted(const std::string& none) {
    if (files_.empty()) throw InputError(path_, "", none);
    std::sort(files_.begin(), files_.end(), [](const FrameFile& a, const FrameFile& b) {
      return a.number != b.number ? a.number < b.number : a.path < b.path;
    });
    for (std::size_t k = 1; k < files_.size(); ++k)
      if (files_[k].number == files_[k - 1].number)
        throw InputError(path_, "",
                         "'" + files_[k - 1].path + "' and '" + files_[k].path +
                             "' have the same frame number " + std::to_string(files_[k].number));
    return std::move(files_);
  }

 private:
  const std::string& path_;
  std::size_t most_;
  std::vector<FrameFile> files_;
  CloudFileKind kind_ = CloudFileKind::none;
  std::string first_of_kind_;
};

// The regular files of `folder` (links followed), by name.
std::vector<std::string> file_names(const fs::path& folder, const std::string& path) {
  std::vector<std::string> names;
  std::error_code ec;
  fs::directory_iterator it(folder.empty() ? fs::path(".") : folder, ec);
  for (; !ec && it != fs::directory_iterator(); it.increment(ec))
    if (it->is_regular_file(ec)) names.push_back(it->path().filename().string());
  if (ec) throw InputError(path, "", "cannot list the folder: " + ec.message());
  return names;
}

std::vector<FrameFile> folder_files(const std::string& path, const ReferenceLimits& limits) {
  FrameFiles files(path, limits.frames);
  std::vector<std::string> names = file_names(path, path);
  std::sort(names.begin(), names.end());  // the same messages whatever the folder's order
  for (const std::string& name : names) {
    const CloudFileKind kind = cloud_file_kind(name);
    if (kind == CloudFileKind::none) continue;  // a note, a mesh, a camera's metadata
    const std::string file = (fs::path(path) / name).string();
    std::string digits;
    if (!last_number(name, digits))
      throw InputError(path, "",
                       "'" + file + "' has no frame number in its name (frames are numbered: " +
                           "scan_0001.ply, scan_0002.ply, ...)");
    files.add(file, digits, kind);
  }
  return files.sorted("no PLY or XYZ file in the folder (.ply or .xyz, any case)");
}

std::vector<FrameFile> pattern_files(const std::string& path, const ReferenceLimits& limits) {
  const fs::path folder = fs::path(path).parent_path();
  const std::string pattern = fs::path(path).filename().string();
  const NumberPlace place = number_place(pattern);
  const std::string prefix = pattern.substr(0, place.begin), suffix = pattern.substr(place.end);
  if (number_place(suffix).begin != std::string::npos)
    throw InputError(path, "", "a pattern with two frame numbers (one %d or %04d only)");
  const CloudFileKind kind = cloud_file_kind(pattern);
  if (kind == CloudFileKind::none)
    throw InputError(path, "", "a frame pattern must end in .ply or .xyz");
  FrameFiles files(path, limits.frames);
  std::vector<std::string> names = file_names(folder, path);
  std::sort(names.begin(), names.end());
  for (const std::string& name : names) {
    if (name.size() <= prefix.size() + suffix.size() || name.compare(0, prefix.size(), prefix) ||
        name.compare(name.size() - suffix.size(), suffix.size(), suffix))
      continue;
    const std::string digits =
        name.substr(prefix.size(), name.size() - prefix.size() - suffix.size());
    if (digits.size() < std::max<std::size_t>(place.width, 1) ||
        !std::all_of(digits.begin(), digits.end(), digit))
      continue;
    files.add(folder.empty() ? name : (folder / name).string(), digits, kind);
  }
  return files.sorted("no file matches the pattern");
}

}  // namespace

CloudFileKind cloud_file_kind(const std::string& path) {
  const std::string ext = lower(fs::path(path).extension().string());
  if (ext == ".ply") return CloudFileKind::ply;
  if (ext == ".xyz") return CloudFileKind::xyz;
  return CloudFileKind::none;
}

std::vector<Vec3> parse_cloud_points(const std::string& bytes, const std::string& path,
                                     CloudFileKind kind, const ReferenceLimits& limits) {
  return kind == CloudFileKind::ply ? parse_ply_points(bytes, path)
                                    : parse_xyz_points(bytes, path, limits);
}

bool is_frame_pattern(const std::string& path) {
  return number_place(fs::path(path).filename().string()).begin != std::string::npos;
}

std::vector<FrameFile> list_frame_files(const std::string& path, const ReferenceLimits& limits) {
  return is_frame_pattern(path) ? pattern_files(path, limits) : folder_files(path, limits);
}

ReferenceMotion read_cloud_sequence(const std::string& path, const ReferenceOptions& options) {
  const double fps = required_fps(options, path, "a sequence of point cloud files holds no times");
  const double start = checked_start(options, path);
  const std::vector<FrameFile> files = list_frame_files(path, options.limits);
  ReferenceMotion motion;
  motion.path = path;
  motion.source = ReferenceMotion::Source::cloud;
  motion.frames.reserve(files.size());
  std::size_t points = 0;
  for (const FrameFile& file : files) {
    ReferenceFrame frame;
    frame.time = start + static_cast<double>(file.number - files.front().number) / fps;
    if (!std::isfinite(frame.time) ||
        (!motion.frames.empty() && !(frame.time > motion.frames.back().time)))
      throw InputError(file.path, "--reference-fps",
                       "frame number " + std::to_string(file.number) + " at " +
                           std::to_string(options.fps) +
                           " frames per second gives no later time than the frame before it");
    frame.positions =
        parse_cloud_points(read_text_file(file.path, "point cloud file", kMaxReferenceBytes),
                           file.path, cloud_file_kind(file.path), options.limits);
    points += frame.positions.size();
    if (points > options.limits.observations)
      throw InputError(file.path, "",
                       "the sequence passes " + std::to_string(options.limits.observations) +
                           " points in this file: more than a reference may hold");
    motion.frames.push_back(std::move(frame));
  }
  return motion;
}

ReferenceMotion read_cloud_file(const std::string& path, const ReferenceOptions& options) {
  ReferenceMotion motion;
  motion.path = path;
  motion.source = ReferenceMotion::Source::cloud;
  motion.frames.resize(1);
  motion.frames[0].time = checked_start(options, path);
  motion.frames[0].positions =
      parse_cloud_points(read_text_file(path, "point cloud file", kMaxReferenceBytes), path,
                         cloud_file_kind(path), options.limits);
  return motion;
}

}  // namespace neurocloth
