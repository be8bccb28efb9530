#include "Corrosion.h"
#include "../common/mpi_errors.h"
#include "../output/OutputFiles.h"
#include "../record/NonFinite.h"
#include "../scene/CrackPlanes.h"
#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <numbers>
#include <numeric>
#include <sstream>

namespace pushout::specimen
{
namespace
{
/// The widest crack at the slice's outer faces [mm]: the planes' mouth
/// openings and the concrete's widest surface crack (its gauge reading,
/// from the gauge's resolution up: model/SurfaceCracks.h); 0: none.
double widest_surface_crack(const std::vector<double>& mouths, const model::CrackingTotals& bulk)
{
  double widest = mouths.empty() ? 0.0 : *std::max_element(mouths.begin(), mouths.end());
  if (!bulk.surface.empty()) // widest first
    widest = std::max(widest, bulk.surface.front().width_mm);
  return widest;
}

/// The specimen's visible surface cracks of the concrete: those of `bulk`
/// at least `visible_width` wide [mm], each with its mirror images in a model
/// cut by `symmetry` (a crack along a symmetry plane once, one all round
/// once), as the crack
/// planes are counted.
std::vector<model::SurfaceCrack> visible_surface_cracks(const model::CrackingTotals& bulk,
                                                        double visible_width,
                                                        mesh::Symmetry symmetry)
{
  std::vector<model::SurfaceCrack> cracks;
  for (const model::SurfaceCrack& s : bulk.surface)
    if (s.width_mm >= visible_width)
    {
      const std::vector<double> images =
          s.all_round ? std::vector<double>{s.angle_deg * std::numbers::pi / 180}
                      : mesh::images_of(symmetry, s.angle_deg * std::numbers::pi / 180);
      for (std::size_t i = 0; i < images.size(); ++i)
      {
        model::SurfaceCrack c = s;
        if (i > 0) // the crack itself keeps its angle as it was read
          c.angle_deg = std::fmod(images[i] * 180 / std::numbers::pi + 720, 360);
        cracks.push_back(c);
      }
    }
  return cracks;
}
} // namespace

Corrosion::Corrosion(const CorrosionPart& corrosion, const CrackDirections& cracks,
                     bool bulk_cracking, const std::filesystem::path& out,
                     record::RunReport& report, MPI_Comm comm, mesh::Symmetry symmetry,
                     const Geometry& slice)
    : _out(out), _report(report), _comm(comm), _symmetry(symmetry)
{
  for (double a : cracks.angles)
  {
    const auto [cx, cy] = slice.tube_center;
    const std::array<double, 2> outer = boundary_point(slice, a);
    _plane_ends.push_back({cx + slice.tube_radius() * std::cos(a),
                           cy + slice.tube_radius() * std::sin(a), outer[0], outer[1]});
  }
  _x_final = corrosion.penetration;
  _steps = int(corrosion.steps);
  _oxide = {corrosion.beta, corrosion.porous_zone, corrosion.oxide_bulk};
  _directions = cracks;
  for (std::size_t i = 0; i < _directions.angles.size(); ++i)
    if (_directions.snapped[i] && _report.talk())
      std::cout << "pushout: crack." << i << ".angle "
                << _directions.asked[i] * 180 / std::numbers::pi
                << " deg is within half an element of a block corner of the mesh: the plane is at "
                << _directions.angles[i] * 180 / std::numbers::pi << " deg" << std::endl;
  if (!active())
    return;
  std::vector<std::string> columns = {"penetration_mm", "p_MPa", "crack_width_mm"};
  for (std::size_t i = 0; i < cracks.angles.size(); ++i)
    columns.push_back("w_crack_" + std::to_string(i) + "_mm");
  if (bulk_cracking) // the concrete's own cracks (docs/cracking.md)
    columns.insert(columns.end(),
                   {"cracks_at_surface", "cracked_points", "concrete_dissipation_Nmm"});
  columns.insert(columns.end(), {"newton_iterations", "cuts", "wall_s"});
  int rank = 0;
  MPI_Comm_rank(_comm, &rank);
  mpi::collectively(_comm,
                    [&]
                    {
                      if (rank == 0)
                        _csv.emplace(out / "corrosion.csv", columns);
                    });
}

void Corrosion::apply(double s, interface::Interface& itf) const
{
  const laws::OxideInputs in = laws::oxide_inputs(_oxide, penetration_at(s));
  itf.set_oxide(in.gap, in.compliance);
}

void Corrosion::record(double s, solver::Equilibrium& eq, Vec state, int iterations, int cuts,
                       int step, bool numbered, const std::function<void(int row)>& fields)
{
  eq.update_displacement(state); // the crack mouths read the model's displacement
  const model::Model& model = eq.model();
  const double x = penetration_at(s);
  const double p = mean_pressure(model.interface(), _comm);
  const std::vector<double> widths = model.crack_mouth_openings();
  model::CrackingTotals bulk;
  int at_surface = 0; // cracks as wide as cracking.visible_width at the outer faces
  if (model::BulkCracking* cracking = eq.model().bulk_cracking())
  {
    bulk = cracking->totals();
    watch_edge(bulk.edge, step, x);
    // The specimen's, as the push force is (a symmetric model's points and
    // energy are a 1/copies part of them; its surface cracks and the crack
    // planes' mouths, `widths`, are counted with their mirror images).
    const int copies = _symmetry.copies();
    bulk.points *= copies;
    bulk.cracked_points *= copies;
    bulk.dissipated *= copies;
    for (double w : widths)
      at_surface += w >= cracking->visible_width();
    at_surface += int(visible_surface_cracks(bulk, cracking->visible_width(), _symmetry).size());
  }
  const double crack_width = widest_surface_crack(widths, bulk);
  std::vector<double> values = {x, p, crack_width};
  values.insert(values.end(), widths.begin(), widths.end());
  if (model.bulk_cracking())
    values.insert(values.end(), {double(at_surface), double(bulk.cracked_points), bulk.dissipated});
  record::refuse_non_finite(values, {"penetration_mm", "p_MPa", "crack_width_mm"},
                            "corrosion step " + std::to_string(step), _comm);
  fields(_row);
  values.insert(values.end(), {double(iterations), double(cuts), _report.seconds()});
  mpi::collectively(_comm,
                    [&]
                    {
                      if (_csv)
                        _csv->row(_row, values);
                    });
  ++_row;
  if (!_report.talk())
    return;
  std::ostringstream line;
  line.precision(4);
  line << "corrosion " << step;
  if (numbered)
    line << "/" << _steps;
  line << "  x = " << x * 1e3 << " um  p = " << p << " MPa";
  if (const model::BulkCracking* cracking = model.bulk_cracking())
    // The gauge's reading of the widest surface crack, and how many count
    // as visible (corrosion.csv's crack_width_mm and cracks_at_surface);
    // then the largest normal opening at any one point, the faces' too
    // (a point's own, not a gauge's reading across a crack).
    line << "  widest surface crack " << crack_width * 1e3 << " um (" << at_surface
         << (at_surface == 1 ? " crack" : " cracks") << " >= " << cracking->visible_width() * 1e3
         << " um)  cracked points " << bulk.cracked_points << "/" << bulk.points
         << " (widest at a point " << bulk.max_opening * 1e3 << " um)";
  else if (!widths.empty())
    line << "  crack width = " << crack_width * 1e3 << " um";
  line << "  (newton " << iterations << (cuts ? ", cuts " + std::to_string(cuts) : "") << ", "
       << std::fixed << std::setprecision(2) << _report.seconds() << " s)";
  std::cout << line.str() << std::endl;
}

namespace
{
/// The head of what the run says of cracks at the edge of `radius` [mm].
std::string edge_reached(double radius)
{
  std::ostringstream s;
  s << "cracks reached the edge of the cracking region (cracking.radius = " << radius << " mm)";
  return s.str();
}
} // namespace

void Corrosion::watch_edge(const model::EdgeCracks& edge, int step, double x)
{
  if (!_edge_reached.empty() || edge.cracked_points == 0)
    return;
  std::ostringstream when;
  when.precision(4);
  // The progress lines' step (of corrosion.steps, or of dissipation
  // control's) and the row that corrosion.csv numbers.
  when << "corrosion step " << step << " (x = " << x * 1e3 << " um; corrosion.csv step " << _row
       << ")";
  _edge_reached = when.str();
  if (_report.talk())
    std::cout << "pushout: note: " << edge_reached(edge.radius) << " in " << _edge_reached
              << "; the concrete beyond stays linear" << std::endl;
}

void Corrosion::note_edge_cracks(model::EdgeCracks edge)
{
  if (edge.radius <= 0)
    return; // all the concrete may crack: no edge (EdgeCracks::radius)
  const int copies = _symmetry.copies();
  if (_edge_reached.empty() && edge.cracked_points > 0) // no corrosion step saw them
    _edge_reached = active() ? "the push" : "step 0 or the push (no corrosion stage)";
  _report.summary().cracking_edge =
      output::Summary::CrackingEdge{edge.radius, edge.points * copies, edge.cracked_points * copies,
                                    edge.max_opening, _edge_reached};
  if (edge.cracked_points == 0 && _edge_reached.empty())
    return;
  std::ostringstream note;
  note.precision(4);
  note << edge_reached(edge.radius) << (_edge_reached.empty() ? "" : " in " + _edge_reached)
       << "; at the end " << edge.cracked_points * copies << " of the " << edge.points * copies
       << " points of its outermost elements are cracked, the widest opening "
       << edge.max_opening * 1e3
       << " um. The concrete beyond stays linear, so cracks cannot run on there, and the "
          "pattern near the edge is the radius's, not the material's: a larger cracking.radius "
          "(0: all the concrete) lets them";
  _report.summary().notes.push_back(note.str());
  if (_report.talk())
    std::cout << "pushout: note: " << note.str() << std::endl;
}

void Corrosion::describe_cracks(solver::Equilibrium& eq, Vec state, output::Summary& summary) const
{
  eq.update_displacement(state);
  const model::Model& model = eq.model();
  const std::vector<double> mouth = model.crack_mouth_openings();
  summary.cracks.clear();
  for (std::size_t i = 0; i < model.num_cracks(); ++i)
  {
    const interface::Interface& crack = model.crack(i);
    double largest[2] = {-std::numeric_limits<double>::infinity(), 0.0}; // opening, damage
    for (std::size_t p = 0; p < crack.num_pairs(); ++p)
      for (std::size_t q = 0; q < crack.points_per_pair(); ++q)
      {
        const interface::PointOutput o =
            crack.point_output(model.displacement().x()->array(), p, q);
        largest[0] = std::max(largest[0], o.w[0]);
        largest[1] = std::max(largest[1], o.damage[0]);
      }
    MPI_Allreduce(MPI_IN_PLACE, largest, 2, MPI_DOUBLE, MPI_MAX, _comm);
    output::Summary::Crack c;
    c.angle_deg = _directions.angles[i] * 180 / std::numbers::pi;
    c.snapped = _directions.snapped[i];
    c.width_mm = c.mouth_opening_mm = mouth[i];
    c.max_opening_mm = largest[0];
    c.max_damage = largest[1];
    summary.cracks.push_back(c);
  }
  for (std::size_t i = 0; i < model.num_cracks(); ++i)
    if (const int image = model.crack_image(i); image >= 0) // cut away by symmetry
    {
      summary.cracks[i].max_opening_mm = summary.cracks[std::size_t(image)].max_opening_mm;
      summary.cracks[i].max_damage = summary.cracks[std::size_t(image)].max_damage;
    }
  model::BulkCracking* cracking = eq.model().bulk_cracking();
  const model::CrackingTotals bulk = cracking ? cracking->totals() : model::CrackingTotals{};
  summary.surface_crack_width_mm = widest_surface_crack(mouth, bulk);
  if (cracking)
  {
    for (const model::SurfaceCrack& s :
         visible_surface_cracks(bulk, cracking->visible_width(), _symmetry))
    {
      output::Summary::Crack c;
      c.plane = false;
      c.angle_deg = s.angle_deg;
      c.width_mm = s.width_mm;
      c.length_mm = s.length_mm;
      summary.cracks.push_back(c);
    }
    write_crack_pattern(bulk.columns, mouth);
  }
}

void Corrosion::write_crack_pattern(const std::vector<model::CrackColumn>& columns,
                                    const std::vector<double>& mouths) const
{
  int rank = 0;
  MPI_Comm_rank(_comm, &rank);
  mpi::collectively(_comm,
                    [&]
                    {
                      if (rank != 0)
                        return;
                      std::ostringstream csv;
                      csv.precision(10);
                      csv << "x_mm,y_mm,opening_mm,size_mm";
                      for (int k = 0; k < 4; ++k)
                        csv << ",corner_" << k << "_x_mm,corner_" << k << "_y_mm";
                      csv << "\n";
                      for (const model::CrackColumn& c : columns)
                      {
                        csv << c.x << "," << c.y << "," << c.opening << "," << c.size;
                        for (double v : c.outline)
                          csv << "," << v;
                        csv << "\n";
                      }
                      output::write_file(_out / "crack_pattern.csv", csv.str());
                      // The planes (a model cut by symmetry keeps each
                      // plane's mouth, its image's too: Model::crack_image).
                      std::filesystem::remove(_out / "crack_planes.csv");
                      if (_plane_ends.empty())
                        return;
                      std::ostringstream planes;
                      planes.precision(10);
                      planes << "plane,angle_deg,x_inner_mm,y_inner_mm,x_outer_mm,y_outer_mm,"
                                "mouth_mm\n";
                      for (std::size_t i = 0; i < _plane_ends.size(); ++i)
                      {
                        planes << i << "," << _directions.angles[i] * 180 / std::numbers::pi;
                        for (double v : _plane_ends[i])
                          planes << "," << v;
                        planes << "," << mouths.at(i) << "\n";
                      }
                      output::write_file(_out / "crack_planes.csv", planes.str());
                    });
  _report.plot_also("crack_pattern", "crack_pattern");
}

double Corrosion::expansion_force(const interface::Interface& itf, double s) const
{
  const double N = pressure_force(itf, _comm)[0]; // [N]
  return laws::oxide_inputs(_oxide, penetration_at(s)).gap > 0 ? (_oxide.beta - 1) * N : 0.0;
}

std::array<double, 2> pressure_force(const interface::Interface& itf, MPI_Comm comm)
{
  const std::vector<double> normal = itf.normal_force();
  std::array<double, 2> total = {-std::accumulate(normal.begin(), normal.end(), 0.0), itf.area()};
  MPI_Allreduce(MPI_IN_PLACE, total.data(), 2, MPI_DOUBLE, MPI_SUM, comm);
  return total;
}

double mean_pressure(const interface::Interface& itf, MPI_Comm comm)
{
  const auto [N, area] = pressure_force(itf, comm);
  const double p = area > 0 ? N / area : 0.0;
  return p == 0 ? 0.0 : p; // never -0 in the progress line
}
} // namespace pushout::specimen
