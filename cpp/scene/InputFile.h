// An input file read whole (a scene, a fit's measured curve), refused with
// a SceneError that names it where it is no such file: missing, not a
// regular file (a directory reads as nothing, a device or a pipe forever)
// or larger than the inputs of its kind ever are.
#pragma once

#include <cstdint>
#include <filesystem>
#include <string>

namespace pushout
{
/// The content of `file`. `name` names it in the messages ("scene file
/// 'a.toml'"); a file over `max_bytes` is refused as "not `kind`" ("not a
/// scene"). Throws SceneError.
std::string read_input_file(const std::filesystem::path& file, const std::string& name,
                            std::uintmax_t max_bytes, const std::string& kind);
} // namespace pushout
