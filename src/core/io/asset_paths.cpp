#include "core/io/asset_paths.h"

#include <cstdlib>
#include <filesystem>

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

}  // namespace neurocloth
