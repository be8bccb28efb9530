// The scene: the user's TOML file, with `--set` overrides applied, checked
// against the declared keys (keys.cpp, cpp/laws/) and completed with defaults.
#pragma once

#include "../laws/LawRegistry.h"
#include "KeyDef.h"
#include "Value.h"
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pushout
{
/// One [[interface]] layer: its law and resolved parameters.
struct LayerSpec
{
  std::string law;
  laws::Params params;
};

/// One [[crack]] plane of a push-out (docs/corrosion.md): a plane through
/// the whole thickness of the concrete, from the interface to the slice's
/// outer boundary, with a cohesive law.
struct CrackSpec
{
  /// Direction from the tube axis in the x-y plane [deg, from +x towards
  /// +y]; unset: "nearest_face" (the cover side, resolved with the geometry).
  std::optional<double> angle_deg;
  LayerSpec layer; ///< the crack's law (one layer)
};

/// A `--set key=value` override, as typed by the user.
struct Override
{
  std::string path;
  std::string value;
};

/// Parses "key=value"; throws SceneError on a malformed override.
Override parse_override(const std::string& text);
/// Each of `texts` parsed.
std::vector<Override> parse_overrides(const std::vector<std::string>& texts);

class Scene
{
public:
  /// Reads `file`, applies `overrides` in order, validates and fills
  /// defaults. Throws SceneError naming the key on any problem.
  static Scene load(const std::filesystem::path& file, const std::vector<Override>& overrides = {});

  /// Same, from TOML text (`origin` names it in messages).
  static Scene parse(const std::string& toml_text, const std::vector<Override>& overrides = {},
                     const std::string& origin = "scene");

  double number(const std::string& path) const;
  std::int64_t integer(const std::string& path) const;
  bool boolean(const std::string& path) const;
  const std::string& string(const std::string& path) const;
  const std::vector<double>& numbers(const std::string& path) const;
  /// The value of a key, or nullptr if the scene has none (a key of another
  /// model type).
  const Value* find(const std::string& path) const
  {
    const auto it = _values.find(path);
    return it == _values.end() ? nullptr : &it->second;
  }

  const std::vector<LayerSpec>& layers() const { return _layers; }
  const std::vector<CrackSpec>& cracks() const { return _cracks; }

  /// The fully resolved scene as TOML (every key, defaults included).
  std::string to_toml() const;

private:
  const Value& get(const std::string& path, KeyType type) const;
  std::map<std::string, Value> _values;
  std::vector<LayerSpec> _layers;
  std::vector<CrackSpec> _cracks;
};
} // namespace pushout
