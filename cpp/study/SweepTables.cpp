// sweep.csv and sweep_seeds.csv (SweepTables.h).
#include "SweepTables.h"
#include "../output/OutputFiles.h"
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <utility>

namespace pushout::study
{
namespace
{
const double nan = std::numeric_limits<double>::quiet_NaN();

/// The curve's abscissa and ordinate of a model type: name, unit.
struct Axes
{
  std::string x, x_unit, y, y_unit;
};
Axes axes_of(const std::string& model_type)
{
  if (model_type == "single_joint")
    return {"u_s", "mm", "F_s", "N"};
  return {"delta", "mm", "tau", "MPa"};
}

/// The index in number_names of the last point's abscissa (delta_last_mm,
/// u_s_last_mm): the run's end, the same for every seed.
constexpr std::size_t last_abscissa = 3;

/// The names of a case's numbers (CaseNumbers) for `model_type`.
std::vector<std::string> number_names(const std::string& model_type)
{
  const Axes ax = axes_of(model_type);
  std::vector<std::string> names = {"peak_" + ax.y + "_" + ax.y_unit,
                                    ax.x + "_at_peak_" + ax.x_unit, ax.y + "_last_" + ax.y_unit,
                                    ax.x + "_last_" + ax.x_unit};
  if (model_type != "single_joint")
  {
    names.push_back("p_before_push_MPa"); // the mean pressure on the tube at delta = 0
    names.push_back("crack_width_mm");    // the widest surface crack then
  }
  return names;
}

/// A CSV cell's number; NaN if it is none (a damaged file costs its case's
/// numbers, not the sweep's tables).
double number(const std::string& cell)
{
  char* end = nullptr;
  const double v = std::strtod(cell.c_str(), &end);
  return end != cell.c_str() ? v : nan;
}

/// Columns of a CSV file of numbers (curve.csv): name -> values.
std::map<std::string, std::vector<double>> read_csv(const std::filesystem::path& file)
{
  std::vector<std::pair<std::string, std::vector<double>>> columns;
  std::ifstream in(file);
  std::string line;
  if (std::getline(in, line))
  {
    std::stringstream header(line);
    for (std::string name; std::getline(header, name, ',');)
      columns.push_back({name, {}});
    while (std::getline(in, line))
    {
      // Every column gets a value per row (NaN where the row is short), so
      // the columns stay aligned.
      std::stringstream row(line);
      std::string cell;
      for (auto& column : columns)
        column.second.push_back(std::getline(row, cell, ',') ? number(cell) : nan);
    }
  }
  return {columns.begin(), columns.end()};
}

/// The widest crack on the slice's outer faces at the push's start [mm]:
/// summary.json's surface_crack_width_mm, as corrosion.csv's last
/// crack_width_mm reads it (a plane's mouth, or the concrete's gauge
/// reading from its resolution up; 0: none); NaN if the case has no summary.
double widest_crack(const std::filesystem::path& folder)
{
  std::ifstream in(folder / "summary.json");
  if (!in)
    return nan;
  const nlohmann::json s = nlohmann::json::parse(in, nullptr, false);
  if (s.is_discarded() || !s.contains("surface_crack_width_mm") ||
      !s["surface_crack_width_mm"].is_number())
    return nan;
  return s["surface_crack_width_mm"].get<double>();
}

/// A case's numbers (number_names order) from its folder, and the number of
/// steps of its curve; NaN (0 steps) where it has no curve.
CaseNumbers case_numbers(const std::filesystem::path& folder, const std::string& model_type,
                         std::size_t& steps)
{
  const Axes ax = axes_of(model_type);
  CaseNumbers n(number_names(model_type).size(), nan);
  steps = 0;
  const auto curve = read_csv(folder / "curve.csv");
  const auto x = curve.find(ax.x + "_" + ax.x_unit), y = curve.find(ax.y + "_" + ax.y_unit);
  if (x == curve.end() || y == curve.end() || y->second.empty())
    return n;
  const std::vector<double>& ys = y->second;
  // The peak of the load steps: the first row is step 0's (the thermal
  // step, before any push), no peak of a case stopped before the push.
  if (ys.size() > 1)
  {
    const auto peak = std::max_element(ys.begin() + 1, ys.end());
    n[0] = *peak;
    n[1] = x->second[std::size_t(peak - ys.begin())];
  }
  n[2] = ys.back();
  n[3] = x->second.back();
  steps = ys.size() - 1;
  if (model_type != "single_joint")
  {
    const auto p = curve.find("p_MPa");
    n[4] = p != curve.end() && !p->second.empty() ? p->second.front() : nan;
    n[5] = widest_crack(folder);
  }
  return n;
}

std::string csv_cell(const std::string& s)
{
  if (s.find_first_of(",\"\n") == std::string::npos)
    return s;
  std::string q = "\"";
  for (char c : s)
    q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

/// The value of a "key=value" override.
std::string value_of(const std::string& set)
{
  return set.substr(set.find('=') + 1);
}

/// sweep_seeds.csv's text.
std::string seed_table(const std::vector<Variation>& vary, const std::vector<std::string>& names,
                       const std::vector<SeedGroup>& groups)
{
  std::ostringstream out;
  for (const Variation& v : vary)
    if (v.key != seed_key)
      out << csv_cell(v.key) << ",";
  out << "seeds,converged";
  for (std::size_t k = 0; k < names.size(); ++k)
    if (k != last_abscissa)
      out << "," << names[k] << "_mean," << names[k] << "_min," << names[k] << "_max";
  out << "\n" << std::setprecision(12);
  for (const SeedGroup& g : groups)
  {
    for (const std::string& v : g.values)
      out << csv_cell(v) << ",";
    out << g.seeds << "," << g.converged;
    for (std::size_t k = 0; k < names.size(); ++k)
      if (k != last_abscissa)
        out << "," << g.mean[k] << "," << g.min[k] << "," << g.max[k];
    out << "\n";
  }
  return out.str();
}

/// One number over a group's converged cases where it is a number.
struct Tally
{
  int count = 0;
  double sum = 0, min = std::numeric_limits<double>::infinity(),
         max = -std::numeric_limits<double>::infinity();

  void add(double v)
  {
    ++count;
    sum += v;
    min = std::min(min, v);
    max = std::max(max, v);
  }
};
} // namespace

std::string case_name(std::size_t i)
{
  std::ostringstream s;
  s << "case_" << std::setw(3) << std::setfill('0') << i;
  return s.str();
}

bool varies_seed(const std::vector<Variation>& vary)
{
  return std::any_of(vary.begin(), vary.end(),
                     [](const Variation& v) { return v.key == seed_key && v.values.size() >= 2; });
}

std::vector<SeedGroup> group_seeds(const std::vector<Variation>& vary,
                                   const std::vector<std::vector<std::string>>& cases,
                                   const std::vector<CaseNumbers>& numbers,
                                   const std::vector<CaseState>& states)
{
  std::vector<SeedGroup> groups;
  std::vector<std::vector<Tally>> tallies;                  // per group, per number
  std::map<std::vector<std::string>, std::size_t> group_of; // the other values -> group
  for (std::size_t i = 0; i < cases.size(); ++i)
  {
    std::vector<std::string> others;
    for (std::size_t k = 0; k < vary.size(); ++k)
      if (vary[k].key != seed_key)
        others.push_back(value_of(cases[i][k]));
    const auto [at, added] = group_of.emplace(others, groups.size());
    if (added)
    {
      groups.push_back({others, 0, 0, {}, {}, {}});
      tallies.emplace_back(numbers[i].size());
    }
    SeedGroup& g = groups[at->second];
    g.seeds += states[i] != CaseState::not_run;
    if (states[i] != CaseState::converged)
      continue;
    ++g.converged;
    std::vector<Tally>& t = tallies[at->second];
    for (std::size_t k = 0; k < t.size(); ++k)
      if (std::isfinite(numbers[i][k]))
        t[k].add(numbers[i][k]);
  }
  for (std::size_t j = 0; j < groups.size(); ++j)
    for (const Tally& t : tallies[j])
    {
      groups[j].mean.push_back(t.count == 0 ? nan : t.sum / t.count);
      groups[j].min.push_back(t.count == 0 ? nan : t.min);
      groups[j].max.push_back(t.count == 0 ? nan : t.max);
    }
  return groups;
}

void write_tables(const std::filesystem::path& out, const std::string& model_type,
                  const std::vector<Variation>& vary,
                  const std::vector<std::vector<std::string>>& cases,
                  const std::vector<CaseResult>& results)
{
  const std::vector<std::string> names = number_names(model_type);
  std::vector<CaseNumbers> numbers(cases.size(), CaseNumbers(names.size(), nan));
  std::vector<CaseState> states(cases.size(), CaseState::not_run);
  std::ostringstream table;
  table << "case";
  for (const Variation& v : vary)
    table << "," << csv_cell(v.key);
  for (const std::string& name : names)
    table << "," << name;
  table << ",steps,converged,exit_code,wall_s,message\n" << std::setprecision(12);
  for (const CaseResult& r : results)
  {
    const auto i = std::size_t(r.index);
    const std::string name = case_name(i);
    std::size_t steps = 0;
    numbers[i] = case_numbers(out / name, model_type, steps);
    states[i] = r.exit_code == 0 ? CaseState::converged : CaseState::failed;
    table << name;
    for (const std::string& set : cases[i])
      table << "," << csv_cell(value_of(set));
    for (double v : numbers[i])
      table << "," << v;
    table << "," << steps << "," << (r.exit_code == 0 ? 1 : 0) << "," << r.exit_code << ","
          << r.wall_s << "," << csv_cell(r.message) << "\n";
  }
  output::write_file(out / "sweep.csv", table.str());
  if (varies_seed(vary))
    output::write_file(out / "sweep_seeds.csv",
                       seed_table(vary, names, group_seeds(vary, cases, numbers, states)));
}
} // namespace pushout::study
