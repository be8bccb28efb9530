// Declaration of one scene key: type, default, range, unit and doc.
#pragma once

#include "Value.h"
#include <limits>
#include <string>
#include <vector>

namespace pushout
{
/// Which model types a key applies to.
enum class Applies
{
  all,
  pushout,
  single_joint
};

struct KeyDef
{
  std::string path; ///< dotted path, e.g. "geometry.width"
  KeyType type;
  Value default_value;
  std::string unit; ///< "mm", "N", "MPa", "N/mm^3", "degC", "-" or ""
  std::string doc;  ///< one line
  double min = -std::numeric_limits<double>::infinity();
  double max = std::numeric_limits<double>::infinity();
  bool open = false;                     ///< both bounds exclusive: min < value < max
  std::vector<std::string> choices = {}; ///< allowed strings (empty: any)
  Applies applies = Applies::all;
  /// Read by the outputs alone (how they read the run), not by the model:
  /// it changes no curve, so pushout fit refuses to free it.
  bool outputs_only = false;
};

/// Every scalar scene key outside [[interface]], declared once
/// (cpp/scene/keys.cpp).
const std::vector<KeyDef>& scene_keys();

/// The keys of the [cracking] section (cpp/scene/keys_cracking.cpp), part
/// of scene_keys().
std::vector<KeyDef> cracking_keys();

/// The values min .. max allow ("> 0", ">= 0 and <= 1"; open: both bounds
/// exclusive; integer: the bounds written as integers), "finite" if both
/// are infinite: what a scene's error and `pushout keys` say.
std::string range_text(double min, double max, bool open, bool integer = false);
/// The same with each bound open or closed on its own (a law's parameter:
/// min < x <= max).
std::string range_text(double min, double max, bool min_open, bool max_open, bool integer);

/// The declaration of the key at `path`, or nullptr.
const KeyDef* find_key(const std::string& path);
} // namespace pushout
