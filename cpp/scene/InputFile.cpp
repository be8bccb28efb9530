#include "InputFile.h"
#include "SceneError.h"
#include <fstream>

namespace pushout
{
std::string read_input_file(const std::filesystem::path& file, const std::string& name,
                            std::uintmax_t max_bytes, const std::string& kind)
{
  namespace fs = std::filesystem;
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (ec || !fs::exists(status))
    throw SceneError("cannot read " + name);
  if (!fs::is_regular_file(status))
    throw SceneError(name + " is not a regular file");
  const auto too_large = [&]
  {
    return SceneError(name + " is larger than " + std::to_string(max_bytes >> 20) + " MiB: not " +
                      kind);
  };
  if (fs::file_size(file, ec) > max_bytes && !ec)
    throw too_large();
  std::ifstream in(file, std::ios::binary);
  if (!in)
    throw SceneError("cannot read " + name);
  // In blocks, never beyond the limit, should the file grow meanwhile.
  std::string text;
  char block[1 << 16];
  while (in.read(block, sizeof block) || in.gcount() > 0)
  {
    text.append(block, std::size_t(in.gcount()));
    if (text.size() > max_bytes)
      throw too_large();
  }
  if (in.bad())
    throw SceneError("cannot read " + name);
  return text;
}
} // namespace pushout
