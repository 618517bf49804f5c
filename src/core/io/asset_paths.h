#pragma once
// Where shipped files are, and how a path written inside a file is resolved.
#include <string>
#include <vector>

namespace neurocloth {

// The NEUROCLOTH_ASSETS environment variable, else the source tree's assets/.
std::string assets_directory();
// `relative` as written in `from_file`: absolute as is; else beside from_file if
// it exists there, else under assets/; else beside from_file (for the error).
std::string resolve_path(const std::string& from_file, const std::string& relative);

// Shipped files chosen by name (the presets, the fabrics): the stems of the
// .json files in `folder`, sorted; and folder/NAME.json when `name` is one
// of them (a bare name, no path), else InputError naming that path and
// listing the names, e.g. "no material preset 'velvet' (presets: ...)".
std::vector<std::string> json_names_in(const std::string& folder);
std::string named_json_file(const std::string& folder, const std::string& name,
                            const std::string& what, const std::string& list_name);

}  // namespace neurocloth
