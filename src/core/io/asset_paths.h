#pragma once
// Where shipped files are, and how a path written inside a file is resolved.
#include <string>

namespace neurocloth {

// The NEUROCLOTH_ASSETS environment variable, else the source tree's assets/.
std::string assets_directory();
// `relative` as written in `from_file`: absolute as is; else beside from_file if
// it exists there, else under assets/; else beside from_file (for the error).
std::string resolve_path(const std::string& from_file, const std::string& relative);

}  // namespace neurocloth
