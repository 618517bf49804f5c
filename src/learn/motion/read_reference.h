#pragma once
// The one entry to every reference-motion reader: which reader a path names
// (a folder, a frame pattern, a cache, a cloud file, else by its first bytes).
// It sits above the readers, which all make the ReferenceMotion of
// reference_motion.h, so no reader depends on another through it.
#include <cstddef>
#include <string>

#include "learn/motion/reference_motion.h"

namespace neurocloth {

// Reads a recording or a CSV (markers or a cloud, told apart by the header),
// told apart by their first bytes (the recording's magic line, else the CSV);
// a folder or a numbered pattern ("scan_%04d.ply") of PLY / XYZ files; a .pc2
// or .mdd cache. `node_count` is the scene's: every node must be below it,
// and a recording or cache must hold exactly that many. Throws InputError
// naming the file, the line or byte offset and the field on any bad input.
ReferenceMotion read_reference(const std::string& path, std::size_t node_count,
                               const ReferenceOptions& options = {});
// The same on bytes already in memory; `path` names them in messages.
ReferenceMotion parse_reference(const std::string& bytes, const std::string& path,
                                std::size_t node_count);

}  // namespace neurocloth
