#include "Scene.h"
#include "../laws/ParameterError.h"
#include "InputFile.h"
#include "SceneError.h"
#include "TomlNesting.h"
#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <toml++/toml.h>

namespace pushout
{
namespace
{
std::vector<std::string> split(const std::string& s, char sep)
{
  std::vector<std::string> parts;
  std::string part;
  std::istringstream in(s);
  while (std::getline(in, part, sep))
    parts.push_back(part);
  return parts;
}

/// The largest scene file [bytes]: 1 MiB (a scene is a few kB).
constexpr std::uintmax_t max_scene_bytes = std::uintmax_t(1) << 20;

/// The law of an [[interface]] layer that names none, and of the one layer
/// of a scene without [[interface]] tables.
constexpr const char* default_interface_law = "friction";

/// At most the first 60 characters of `s` (a path or value in a message).
std::string shortened(const std::string& s)
{
  return s.size() <= 60 ? s : s.substr(0, 60) + "...";
}

bool is_index(const std::string& s)
{
  return !s.empty() && s.find_first_not_of("0123456789") == std::string::npos;
}

std::string where(const toml::node& node)
{
  const auto& src = node.source();
  if (src.begin.line == 0)
    return "";
  return " (line " + std::to_string(src.begin.line) + ")";
}

/// Sets `from`'s keys in `to`, a table given as a value merged into the
/// table already there (nested tables alike).
void merge(toml::table& to, const toml::table& from)
{
  for (const auto& [key, value] : from)
  {
    auto* inner = to.get_as<toml::table>(key);
    if (const auto* given = value.as_table(); inner && given)
      merge(*inner, *given);
    else
      to.insert_or_assign(key, value);
  }
}

/// Applies one `--set` to the parsed document.
void apply_override(toml::table& root, const Override& o)
{
  const std::vector<std::string> parts = split(o.path, '.');
  const std::string what = "--set " + shortened(o.path);
  if (parts.size() > max_nesting)
    throw SceneError(what + ": too deeply nested (" + std::to_string(parts.size()) +
                     " levels; a scene key has at most " + std::to_string(max_nesting) + ")");
  if (too_deep_at(o.value))
    throw SceneError(what + ": the value is too deeply nested (arrays or tables more than " +
                     std::to_string(max_nesting) + " levels deep)");
  for (const std::string& p : parts)
    if (p.empty())
      throw SceneError(what + ": malformed key path");

  toml::node* node = &root;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i)
  {
    const std::string& seg = parts[i];
    if (auto* tbl = node->as_table())
    {
      if (!tbl->contains(seg))
      {
        // A scene without [[interface]] has the default layer, as its
        // resolved scene.toml shows: its keys are set as that layer's.
        if (seg == "interface" && i == 0)
          tbl->insert(seg, toml::array{toml::table{{"law", default_interface_law}}});
        else if (seg == "interface" || seg == "crack")
          throw SceneError(what + ": the scene has no [[" + seg + "]] tables");
        else
          tbl->insert(seg, toml::table{});
      }
      node = tbl->get(seg);
    }
    else if (auto* arr = node->as_array())
    {
      if (!is_index(seg) || std::stoul(seg) >= arr->size())
      {
        throw SceneError(what + ": index '" + seg + "' is not one of the " +
                         std::to_string(arr->size()) + " entries of '" + parts[i - 1] + "'");
      }
      node = arr->get(std::stoul(seg));
    }
    else
      throw SceneError(what + ": '" + seg + "' is inside a value, not a table");
  }

  toml::node_view<toml::node> parsed;
  toml::table holder;
  try
  {
    holder = toml::parse("v = " + o.value);
  }
  catch (const toml::parse_error&)
  {
    // Digits that TOML cannot hold (more than 18: beyond 64 bits) are not a
    // bare word.
    const std::size_t sign = !o.value.empty() && (o.value[0] == '+' || o.value[0] == '-');
    if (o.value.size() > sign + 18 &&
        std::all_of(o.value.begin() + long(sign), o.value.end(),
                    [](unsigned char c) { return std::isdigit(c) != 0; }))
      throw SceneError(what + " = " + shortened(o.value) + ": an integer beyond 64 bits");
    holder = toml::table{{"v", o.value}}; // a bare word: take it as a string
  }
  const std::string& key = parts.back();
  auto* tbl = node->as_table();
  auto* given = holder.get("v")->as_table();
  if (auto* to = tbl ? tbl->get_as<toml::table>(key) : nullptr; to && given)
    merge(*to, *given); // --set 'loading={steps=10}' sets those keys, not the section
  else if (tbl)
    tbl->insert_or_assign(key, *holder.get("v"));
  else if (auto* arr = node->as_array(); arr && is_index(key))
  {
    if (std::stoul(key) >= arr->size())
      throw SceneError(what + ": index " + key + " is out of range");
    if (auto* to = arr->get_as<toml::table>(std::stoul(key)); to && given)
      merge(*to, *given); // --set 'interface.0={mu=0.2}' keeps the layer's law
    else
      arr->replace(arr->begin() + std::stoul(key), *holder.get("v"));
  }
  else
    throw SceneError(what + ": cannot set a value here");
}

/// Converts a TOML node to the declared type, or throws naming the key.
Value convert(const toml::node& node, KeyType type, const std::string& path)
{
  const auto bad = [&]()
  { return SceneError("'" + path + "'" + where(node) + " must be " + type_name(type)); };
  switch (type)
  {
  case KeyType::number:
    if (auto v = node.value<double>(); v && (node.is_floating_point() || node.is_integer()))
      return *v;
    throw bad();
  case KeyType::integer:
    if (node.is_integer())
      return *node.value<std::int64_t>();
    throw bad();
  case KeyType::boolean:
    if (node.is_boolean())
      return *node.value<bool>();
    throw bad();
  case KeyType::string:
    if (node.is_string())
      return *node.value<std::string>();
    throw bad();
  case KeyType::number_array:
  {
    const auto* arr = node.as_array();
    if (!arr)
      throw bad();
    std::vector<double> out;
    for (const toml::node& e : *arr)
    {
      if (!(e.is_floating_point() || e.is_integer()))
        throw bad();
      out.push_back(*e.value<double>());
    }
    return out;
  }
  }
  throw bad();
}

/// Throws unless min <= x <= max (min_open: min < x; max_open: x < max)
/// and x is finite.
void check_range(double x, double min, double max, bool min_open, bool max_open,
                 const std::string& path, const std::string& unit)
{
  const std::string range = range_text(min, max, min_open, max_open, false);
  if (!std::isfinite(x))
    throw SceneError("'" + path + "' = " + std::to_string(x) +
                     " is not a finite number: it must be " + range);
  const bool inside = (min_open ? x > min : x >= min) && (max_open ? x < max : x <= max);
  if (!inside)
  {
    std::ostringstream s;
    s << "'" << path << "' = " << x << (unit.empty() || unit == "-" ? "" : " " + unit)
      << " is out of range: it must be " << range;
    throw SceneError(s.str());
  }
}

void check_value(const KeyDef& def, const Value& v)
{
  if (const auto* d = std::get_if<double>(&v))
    check_range(*d, def.min, def.max, def.open, def.open, def.path, def.unit);
  else if (const auto* i = std::get_if<std::int64_t>(&v))
  {
    // Exactly: a long double holds every 64-bit integer (and every double
    // bound), where a double would round a value above 2^53 onto its bound.
    static_assert(std::numeric_limits<long double>::digits >= 64);
    const long double x = *i;
    if (!(def.open ? (x > def.min && x < def.max) : (x >= def.min && x <= def.max)))
      throw SceneError("'" + def.path + "' = " + std::to_string(*i) +
                       (def.unit.empty() || def.unit == "-" ? "" : " " + def.unit) +
                       " is out of range: it must be " +
                       range_text(def.min, def.max, def.open, true));
  }
  else if (const auto* a = std::get_if<std::vector<double>>(&v))
  {
    // Every number of an array as a scalar of the key would be.
    for (std::size_t j = 0; j < a->size(); ++j)
      check_range((*a)[j], def.min, def.max, def.open, def.open,
                  def.path + "[" + std::to_string(j) + "]", def.unit);
  }
  else if (const auto* s = std::get_if<std::string>(&v); s && !def.choices.empty())
  {
    bool ok = false;
    std::string list;
    for (const std::string& c : def.choices)
    {
      ok = ok || c == *s;
      list += (list.empty() ? "" : ", ") + c;
    }
    if (!ok)
      throw SceneError("'" + def.path + "' = \"" + *s + "\" is not one of: " + list);
  }
}

std::string known_keys_in(const std::string& section)
{
  std::string list;
  for (const KeyDef& k : scene_keys())
    if (k.path.rfind(section + ".", 0) == 0)
      list += (list.empty() ? "" : ", ") + k.path.substr(section.size() + 1);
  return list;
}

/// Reads a law and its parameters from one table of an array of tables
/// (`section` "interface" or "crack"; `skip` names keys of the table that
/// are not the law's).
LayerSpec read_layer(const toml::node& node, std::size_t index, const std::string& section,
                     const std::string& default_law, const std::vector<std::string>& skip = {},
                     const laws::Params& defaults = {})
{
  const std::string prefix = section + "." + std::to_string(index) + ".";
  const auto* tbl = node.as_table();
  if (!tbl)
    throw SceneError("'" + section + "." + std::to_string(index) + "' must be a table ([[" +
                     section + "]])");
  LayerSpec layer;
  layer.law = default_law;
  if (const toml::node* law = tbl->get("law"))
  {
    if (!law->is_string())
      throw SceneError("'" + prefix + "law'" + where(*law) + " must be a string");
    layer.law = *law->value<std::string>();
  }
  const laws::LawInfo* info = laws::find_law(layer.law);
  if (!info)
  {
    std::string list;
    for (const auto& l : laws::registered_laws())
      list += (list.empty() ? "" : ", ") + l.name;
    throw SceneError("'" + prefix + "law' = \"" + layer.law +
                     "\" is not a known law; known laws: " + list);
  }

  for (const auto& [key, value] : *tbl)
  {
    const std::string name(key.str());
    if (name == "law" || std::find(skip.begin(), skip.end(), name) != skip.end())
      continue;
    const laws::ParamDef* def = nullptr;
    for (const auto& p : info->params)
      if (p.name == name)
        def = &p;
    if (!def)
    {
      std::string list;
      for (const auto& p : info->params)
        list += (list.empty() ? "" : ", ") + p.name;
      throw SceneError("unknown key '" + prefix + name + "'" + where(value) + " for law '" +
                       layer.law + "'; its parameters: " + list);
    }
    layer.params[name] = std::get<double>(convert(value, KeyType::number, prefix + name));
  }
  // A parameter that is only the default of others, all of which are given.
  for (const auto& p : info->params)
  {
    bool source = false, all_given = true;
    for (const auto& q : info->params)
      if (q.default_from == p.name)
      {
        source = true;
        all_given = all_given && layer.params.count(q.name);
      }
    if (source && all_given)
      layer.defaults_only.push_back(p.name);
  }
  // Defaults: the section's own, then the law's fixed ones, then those
  // copied from another parameter.
  for (const auto& p : info->params)
    if (!layer.params.count(p.name) && defaults.count(p.name))
      layer.params[p.name] = defaults.at(p.name);
  for (const auto& p : info->params)
    if (!layer.params.count(p.name) && p.default_value)
      layer.params[p.name] = *p.default_value;
  for (const auto& p : info->params)
  {
    if (layer.params.count(p.name))
      continue;
    if (!p.default_from.empty() && layer.params.count(p.default_from))
      layer.params[p.name] = layer.params.at(p.default_from);
    else if (!p.optional)
      throw SceneError("'" + prefix + p.name + "' (" + p.doc + ", " + p.unit +
                       ") is required for law '" + layer.law + "'");
  }
  for (const auto& p : info->params)
    if (layer.params.count(p.name))
    {
      // A lower bound open or closed, a closed upper one.
      check_range(layer.params.at(p.name), p.min, p.max, p.min_exclusive, false, prefix + p.name,
                  p.unit);
    }
  try
  {
    info->make(layer.params, prefix); // checks combinations of parameters
  }
  catch (const laws::ParameterError& e)
  {
    throw SceneError(e.what());
  }
  return layer;
}

/// Default penalty stiffness of a crack plane's law [N/mm^3].
constexpr double crack_penalty_default = 1e5;

/// One [[crack]] table: `angle` (degrees or "nearest_face") and a law.
CrackSpec read_crack(const toml::node& node, std::size_t index)
{
  const std::string path = "crack." + std::to_string(index) + ".angle";
  CrackSpec crack;
  // A crack plane's penalty must be stiff (an uncracked plane adds 1/k to the
  // ring's compliance: docs/corrosion.md), whatever the law's own default.
  crack.layer = read_layer(node, index, "crack", "exponential_softening", {"angle"},
                           {{"k", crack_penalty_default}});
  const toml::node* angle = node.as_table()->get("angle");
  if (!angle)
    throw SceneError("'" + path + "' is required: degrees from +x towards +y, or \"nearest_face\"");
  if (angle->is_string() && *angle->value<std::string>() == "nearest_face")
    return crack;
  if (!(angle->is_floating_point() || angle->is_integer()))
    throw SceneError("'" + path + "'" + where(*angle) +
                     " must be a number (degrees) or \"nearest_face\"");
  crack.angle_deg = *angle->value<double>();
  check_range(*crack.angle_deg, -360, 360, false, false, path, "deg");
  return crack;
}

bool applies(const KeyDef& def, const std::string& model)
{
  return def.applies == Applies::all || (def.applies == Applies::pushout && model == "pushout") ||
         (def.applies == Applies::single_joint && model == "single_joint");
}
} // namespace

Override parse_override(const std::string& text)
{
  const auto eq = text.find('=');
  if (eq == std::string::npos || eq == 0)
    throw SceneError("--set '" + text + "': expected key=value");
  return {text.substr(0, eq), text.substr(eq + 1)};
}

std::vector<Override> parse_overrides(const std::vector<std::string>& texts)
{
  std::vector<Override> o;
  for (const std::string& t : texts)
    o.push_back(parse_override(t));
  return o;
}

std::string integer_in_decimal(const std::string& value)
{
  if (too_deep_at(value)) // apply_override refuses it, before the parser sees it
    return value;
  try
  {
    const toml::table holder = toml::parse("v = " + value);
    if (const auto v = holder["v"].value_exact<std::int64_t>())
      return std::to_string(*v);
  }
  catch (const toml::parse_error&)
  {
  }
  return value;
}

std::string Scene::read(const std::filesystem::path& file)
{
  return read_input_file(file, "scene file '" + file.string() + "'", max_scene_bytes, "a scene");
}

Scene Scene::load(const std::filesystem::path& file, const std::vector<Override>& overrides)
{
  return parse(read(file), overrides, file.string());
}

Scene Scene::parse(const std::string& toml_text, const std::vector<Override>& overrides,
                   const std::string& origin)
{
  toml::table root;
  if (const std::size_t line = too_deep_at(toml_text))
    throw SceneError(origin + ": too deeply nested at line " + std::to_string(line) +
                     ": more than " + std::to_string(max_nesting) +
                     " levels of tables, arrays or dotted keys");
  try
  {
    root = toml::parse(toml_text, origin);
  }
  catch (const toml::parse_error& e)
  {
    throw SceneError(origin + ": TOML syntax error at line " +
                     std::to_string(e.source().begin.line) + ": " + std::string(e.description()));
  }
  for (const Override& o : overrides)
    apply_override(root, o);

  Scene scene;
  std::string model = "pushout";
  if (const toml::node* m = root.at_path("model.type").node())
  {
    scene._values["model.type"] = convert(*m, KeyType::string, "model.type");
    check_value(*find_key("model.type"), scene._values["model.type"]);
    model = std::get<std::string>(scene._values["model.type"]);
  }

  for (const auto& [section_key, section] : root)
  {
    const std::string sname(section_key.str());
    if (sname == "interface")
    {
      const auto* arr = section.as_array();
      if (!arr)
        throw SceneError("'interface' must be written as [[interface]] tables");
      for (std::size_t i = 0; i < arr->size(); ++i)
        scene._layers.push_back(read_layer(*arr->get(i), i, "interface", default_interface_law));
      continue;
    }
    if (sname == "crack")
    {
      const auto* arr = section.as_array();
      if (!arr)
        throw SceneError("'crack' must be written as [[crack]] tables");
      if (model != "pushout")
        throw SceneError("[[crack]] does not apply to model.type = \"" + model + "\"");
      for (std::size_t i = 0; i < arr->size(); ++i)
        scene._cracks.push_back(read_crack(*arr->get(i), i));
      continue;
    }
    const auto* tbl = section.as_table();
    if (!tbl)
    {
      const std::string known = known_keys_in(sname);
      if (!known.empty()) // a section's name given a value ([[cracking]], --set cracking=...)
        throw SceneError("'" + sname + "'" + where(section) + " must be the table [" + sname +
                         "] of its keys: " + known);
      throw SceneError("unknown key '" + sname + "'" + where(section) +
                       ": top-level keys must be sections such as [geometry]");
    }
    for (const auto& [key, value] : *tbl)
    {
      const std::string path = sname + "." + std::string(key.str());
      const KeyDef* def = find_key(path);
      if (!def)
      {
        const std::string known = known_keys_in(sname);
        throw SceneError("unknown key '" + path + "'" + where(value) +
                         (known.empty() ? ": unknown section [" + sname + "]"
                                        : "; keys in [" + sname + "]: " + known));
      }
      if (!applies(*def, model))
        throw SceneError("'" + path + "'" + where(value) + " does not apply to model.type = \"" +
                         model + "\"");
      Value v = convert(value, def->type, path);
      check_value(*def, v);
      scene._values[path] = v;
    }
  }
  for (const KeyDef& def : scene_keys())
    if (applies(def, model) && !scene._values.count(def.path))
      scene._values[def.path] = def.default_value;

  if (scene._layers.empty())
  {
    toml::table t{{"law", default_interface_law}};
    scene._layers.push_back(read_layer(t, 0, "interface", default_interface_law));
  }

  scene.fill_parts();
  // Relations between keys of one model type are its specimen's
  // (specimen/Scenario.h: check_scene), checked before the run.
  return scene;
}

const Value& Scene::get(const std::string& path, KeyType type) const
{
  const KeyDef* def = find_key(path);
  if (!def || def->type != type)
    throw std::logic_error("scene key '" + path + "' read as " + type_name(type) +
                           " but not declared so");
  // A key of another model type is not in the scene: its part holds the
  // declared default.
  const auto it = _values.find(path);
  return it == _values.end() ? def->default_value : it->second;
}

double Scene::number(const std::string& path) const
{
  return std::get<double>(get(path, KeyType::number));
}
std::int64_t Scene::integer(const std::string& path) const
{
  return std::get<std::int64_t>(get(path, KeyType::integer));
}
bool Scene::boolean(const std::string& path) const
{
  return std::get<bool>(get(path, KeyType::boolean));
}
const std::string& Scene::string(const std::string& path) const
{
  return std::get<std::string>(get(path, KeyType::string));
}
const std::vector<double>& Scene::numbers(const std::string& path) const
{
  return std::get<std::vector<double>>(get(path, KeyType::number_array));
}
} // namespace pushout
