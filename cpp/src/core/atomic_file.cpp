// Atomic output files: temporary file in the target's folder, renamed over the target on success.
#include "netshape/core/atomic_file.hpp"

#include <filesystem>
#include <fstream>
#include <random>
#include <system_error>

#include "netshape/core/error.hpp"

namespace netshape {

void write_file_atomically(const std::string& path, const std::function<void(std::ostream&)>& fill, bool binary) {
  namespace fs = std::filesystem;
  NETSHAPE_CHECK(!path.empty(), "path", path, "must not be empty");
  const fs::path target(path);
  fs::path dir = target.parent_path();
  if (dir.empty()) dir = ".";
  NETSHAPE_CHECK(fs::is_directory(dir), "path", path, "its folder does not exist");
  std::random_device rd;
  const fs::path tmp = dir / ("." + target.filename().string() + "." + std::to_string(rd()) + ".tmp");
  try {
    {
      std::ofstream out(tmp, binary ? std::ios::binary | std::ios::trunc : std::ios::out | std::ios::trunc);
      if (!out) throw Error("cannot open '" + tmp.string() + "' for writing");
      fill(out);
      out.flush();
      if (!out) throw Error("writing '" + path + "' failed");
    }
    std::error_code ec;
    fs::rename(tmp, target, ec);
    if (ec) throw Error("cannot rename '" + tmp.string() + "' to '" + path + "': " + ec.message());
  } catch (...) {
    std::error_code ec;
    fs::remove(tmp, ec);
    throw;
  }
}

}  // namespace netshape
