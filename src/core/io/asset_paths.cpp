#include "core/io/asset_paths.h"

#include <algorithm>
#include <cstdlib>
#include <filesystem>

#include "core/io/input_error.h"

namespace neurocloth {
namespace fs = std::filesystem;

std::string assets_directory() {
  if (const char* env = std::getenv("NEUROCLOTH_ASSETS")) return env;
  return NEUROCLOTH_ASSETS_DIR;
}

std::string resolve_path(const std::string& from_file, const std::string& relative) {
  const fs::path p(relative);
  if (p.is_absolute()) return relative;
  const fs::path beside = fs::path(from_file).parent_path() / p;
  if (fs::exists(beside)) return beside.string();
  const fs::path in_assets = fs::path(assets_directory()) / p;
  if (fs::exists(in_assets)) return in_assets.string();
  return beside.string();
}

std::vector<std::string> json_names_in(const std::string& folder) {
  std::vector<std::string> names;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(folder, ec))
    if (e.path().extension() == ".json") names.push_back(e.path().stem().string());
  std::sort(names.begin(), names.end());
  return names;
}

std::string named_json_file(const std::string& folder, const std::string& name,
                            const std::string& what, const std::string& list_name) {
  const std::string path = folder + "/" + name + ".json";
  std::error_code ec;
  if (name.empty() || name.find('/') != std::string::npos ||
      !std::filesystem::is_regular_file(path, ec)) {
    std::string known;
    for (const auto& n : json_names_in(folder))
      known += (known.empty() ? "" : ", ") + n;
    throw InputError(path, "", "no " + what + " '" + name + "' (" + list_name + ": " + known + ")");
  }
  return path;
}

}  // namespace neurocloth
