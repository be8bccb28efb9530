// The scene: the user's TOML file, with `--set` overrides applied, checked
// against the declared keys (keys.cpp, cpp/laws/), completed with defaults
// and parsed once into typed parts (SceneParts.h) that the modules take.
#pragma once

#include "../laws/LawRegistry.h"
#include "KeyDef.h"
#include "SceneParts.h"
#include "Value.h"
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace pushout
{
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
/// An override's `value` as typed, but a TOML integer in decimal digits
/// ("0x10", "0o20", "0b10000" and "1_6" all give "16"): the value the scene
/// reads, in one spelling.
std::string integer_in_decimal(const std::string& value);

class Scene
{
public:
  /// Reads `file`, applies `overrides` in order, validates and fills
  /// defaults. Throws SceneError naming the key on any problem.
  static Scene load(const std::filesystem::path& file, const std::vector<Override>& overrides = {});

  /// The text of a scene file, as load() reads it (parse() makes it a
  /// scene, with the file's name as its origin). Throws SceneError.
  static std::string read(const std::filesystem::path& file);

  /// Same, from TOML text (`origin` names it in messages).
  static Scene parse(const std::string& toml_text, const std::vector<Override>& overrides = {},
                     const std::string& origin = "scene");

  const ModelPart& model() const { return _model; }
  const Geometry& geometry() const { return _geometry; }
  const MeshPart& mesh() const { return _mesh; }
  const Material& concrete() const { return _concrete; }
  const Material& steel() const { return _steel; }
  const Loading& loading() const { return _loading; }
  const CorrosionPart& corrosion() const { return _corrosion; }
  const CrackingPart& cracking() const { return _cracking; }
  const SolverPart& solver() const { return _solver; }
  const OutputPart& output() const { return _output; }
  const std::vector<LayerSpec>& layers() const { return _layers; }
  const std::vector<CrackSpec>& cracks() const { return _cracks; }
  /// The crack planes' directions, resolved from the geometry (CrackPlanes.h).
  const CrackDirections& crack_directions() const { return _crack_directions; }

  /// The value of a key named at run time (pushout fit --free, sweep
  /// --vary, the set-up's fingerprint), or nullptr if the scene has none (a
  /// key of another model type). Modules take the typed parts instead.
  const Value* find(const std::string& path) const
  {
    const auto it = _values.find(path);
    return it == _values.end() ? nullptr : &it->second;
  }

  /// The fully resolved scene as TOML (every key, defaults included).
  std::string to_toml() const;

  /// Keys set to other than their default that nothing reads, one line
  /// each for the run's progress output (SceneParts.cpp): the [cracking]
  /// keys while cracking.model = "none", the other law's parameter of
  /// cracking.law, the monotonic push's keys beside loading.push_path (and
  /// the path's without one), loading.dissipation_steps under displacement
  /// control or arc length, the random field's seed and correlation length
  /// with a uniform strength, the corrosion stage's keys without corrosion. Not errors: a scene
  /// turned off by --set keeps its keys.
  std::vector<std::string> unread_keys() const;

  /// Why `path` is not read, as unread_keys says it, whatever its value
  /// ("" where it is read). pushout sweep refuses to vary a key that no
  /// case reads.
  std::string unread_note(const std::string& path) const;

private:
  /// unread_keys' notes: the keys, and why they are not read; `set`
  /// counts as set to other than its default.
  struct Unread
  {
    std::vector<std::string> keys;
    std::string why;
  };
  std::vector<Unread> unread(const std::string& set = "") const;

  /// The typed parts from the validated values (SceneParts.cpp).
  void fill_parts();
  /// Refuses a loading.max_cuts whose smallest increment the load's
  /// position cannot hold after a stage's nominal steps.
  void check_max_cuts() const;
  double number(const std::string& path) const;
  std::int64_t integer(const std::string& path) const;
  bool boolean(const std::string& path) const;
  const std::string& string(const std::string& path) const;
  const std::vector<double>& numbers(const std::string& path) const;
  const Value& get(const std::string& path, KeyType type) const;

  std::map<std::string, Value> _values; ///< every key of the model type, by path
  ModelPart _model;
  Geometry _geometry;
  MeshPart _mesh;
  Material _concrete, _steel;
  Loading _loading;
  CorrosionPart _corrosion;
  CrackingPart _cracking;
  SolverPart _solver;
  OutputPart _output;
  std::vector<LayerSpec> _layers;
  std::vector<CrackSpec> _cracks;
  CrackDirections _crack_directions;
};
} // namespace pushout
