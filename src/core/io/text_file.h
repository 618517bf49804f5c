#pragma once
// Reading a whole input file, and writing an output file so that a reader never
// sees half of it. Every reader of ours goes through here, so every one of them
// refuses a directory, a device that never ends (/dev/zero) and a file too
// large for what it claims to be, with the file named, before any parsing.
#include <cstddef>
#include <functional>
#include <iosfwd>
#include <string>

namespace neurocloth {

// Size limits, per kind of input: far above any real file of that kind, far
// below what would exhaust memory.
inline constexpr std::size_t kMaxSceneBytes = 16u << 20;    // JSON scenes, presets, scripts
inline constexpr std::size_t kMaxRuleBaseBytes = 4u << 20;  // FCL rule bases
inline constexpr std::size_t kMaxMeshBytes = 256u << 20;    // OBJ meshes
inline constexpr std::size_t kMaxTableBytes = 64u << 20;    // trade CSVs
inline constexpr std::size_t kMaxShaderBytes = 1u << 20;    // GLSL sources

// The file's bytes. Throws InputError naming `path` when it cannot be opened,
// is a directory, or holds more than `max_bytes` (read up to the limit only,
// so an endless device is refused too). `what` names the kind of file in
// messages ("scene file", "FCL file").
std::string read_text_file(const std::string& path, const char* what, std::size_t max_bytes);

// Writes `path` through a temporary file in the same folder, flushed to disk
// and renamed into place: a crash, a full disk or an encoder that fails leaves
// the old file or none, never a truncated one. `write` streams the content
// (text, or an encoder's bytes: PNG through libpng or cairo); an exception it
// throws, or a stream it leaves failed, removes the temporary file. Throws
// std::runtime_error naming `path`, or rethrows what `write` threw.
void write_file_atomically(const std::string& path,
                           const std::function<void(std::ostream&)>& write);
void write_file_atomically(const std::string& path, const std::string& text);

}  // namespace neurocloth
