// The registry of interface laws: name -> parameters + factory.
// A new law is one file (the value type and its parameter list), one test
// file and one line in LawRegistry.cpp.
#pragma once

#include "InterfaceLaw.h"
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace pushout::laws
{
/// One declared law parameter.
struct ParamDef
{
  std::string name;
  std::optional<double> default_value; ///< none: required
  std::string unit;
  std::string doc;
  double min = -std::numeric_limits<double>::infinity();
  bool min_exclusive = false;
  /// Defaults to this other parameter's value, which the law reads only as
  /// such a default (a layer that gives every parameter defaulting to it
  /// gets a note that it is not read).
  std::string default_from = {};
  bool optional = false; ///< may be absent (then not in Params)
  double max = std::numeric_limits<double>::infinity();
};

/// The stiffest penalty a joint law takes [N/mm^3]: 1e9 is 5000 times the
/// steel's E over a 1 mm element, stiffer than any interface needs; beyond,
/// the joints' tangent swamps the bulk's in the linear solves.
constexpr double max_penalty = 1e9;

/// A penalty stiffness parameter [N/mm^3], > 0 and at most max_penalty.
inline ParamDef penalty_param(std::string name, std::optional<double> default_value,
                              std::string doc, std::string default_from = {})
{
  ParamDef p{std::move(name),        default_value, "N/mm^3", std::move(doc), 0, true,
             std::move(default_from)};
  p.max = max_penalty;
  return p;
}

/// Resolved parameters of one layer, by name. `at(name)` is valid for every
/// declared parameter except absent optional ones.
using Params = std::map<std::string, double>;

struct LawInfo
{
  std::string name;
  std::string doc;
  std::vector<ParamDef> params;
  /// Builds the law; throws ParameterError (naming `prefix` + key) on parameter
  /// combinations the per-parameter ranges cannot express.
  std::function<std::unique_ptr<InterfaceLaw>(const Params&, const std::string& prefix)> make;
};

/// All registered laws, in registration order.
const std::vector<LawInfo>& registered_laws();

/// The law called `name`, or nullptr.
const LawInfo* find_law(const std::string& name);

/// Registers value type `L`: it provides `name`, `doc`, `params()` and a
/// constructor `L(const Params&, const std::string& prefix)`.
template <typename L> LawInfo describe()
{
  return {L::name, L::doc, L::params(),
          [](const Params& p, const std::string& prefix) -> std::unique_ptr<InterfaceLaw>
          { return std::make_unique<LawAdapter<L>>(L(p, prefix)); }};
}
} // namespace pushout::laws
