// The corrosion stage of a push-out (scene section [corrosion];
// docs/corrosion.md): between the thermal step and the push, the steel
// turns to oxide to depth x [mm] in `steps` equal steps. The oxide occupies
// beta times the volume of the steel it replaces (Molina, Alonso & Andrade
// 1993), so the interface gets the free normal opening
//   g0 = max((beta - 1) x - porous_zone, 0)
// and the oxide layer (thickness beta x, bulk modulus B_ox, confined and
// shear-free) the normal compliance beta x / B_ox, in series with the
// joint's penalty: the inputs of the law oxide_friction (laws/Oxide.h).
// Each converged step (or part of a cut one) writes a row of corrosion.csv
// (rank 0), numbered as curve.csv's rows:
//   step, penetration_mm, p_MPa, crack_width_mm[, w_crack_I_mm...],
//   newton_iterations, cuts, wall_s
// p the mean interface pressure (as in curve.csv), crack_width_mm the
// widest crack at the outer faces: the largest crack-mouth opening of the
// planes, w_crack_I_mm that of crack plane I (Model::crack_mouth_openings),
// and with [cracking] the widest of the concrete's cracks as a gauge reads
// it (model/SurfaceCracks.h), then cracks_at_surface (those as wide as
// cracking.visible_width), cracked_points and concrete_dissipation_Nmm.
#pragma once

#include "../laws/Oxide.h"
#include "../mesh/cracks.h"
#include "../mesh/symmetry.h"
#include "../model/Model.h"
#include "../output/CurveWriter.h"
#include "../output/Summary.h"
#include "../record/RunReport.h"
#include "../scene/Scene.h"
#include "../solver/Equilibrium.h"
#include <array>
#include <filesystem>
#include <functional>
#include <optional>

namespace pushout::specimen
{
class Corrosion
{
public:
  /// Opens corrosion.csv in `out` if `corrosion` has a stage (penetration
  /// > 0); `cracks`: the crack planes' directions; `bulk_cracking`: the
  /// concrete may crack anywhere ([cracking]); `comm`: the run's processes;
  /// `symmetry`: the model's mirror planes; the specimen is copies() mirror
  /// images of the model, so the concrete's cracked points, dissipation and
  /// surface cracks are written as the specimen's (as the push force is);
  /// `slice`: where the crack planes run (crack_planes.csv).
  Corrosion(const CorrosionPart& corrosion, const CrackDirections& cracks, bool bulk_cracking,
            const std::filesystem::path& out, record::RunReport& report, MPI_Comm comm,
            mesh::Symmetry symmetry, const Geometry& slice);

  /// Whether the scene has a corrosion stage (penetration > 0).
  bool active() const { return _x_final > 0; }
  int steps() const { return _steps; }
  /// Corrosion depth x at stage parameter s in [0, steps] [mm].
  double penetration_at(double s) const { return _x_final * s / _steps; }

  /// Sets the interface's oxide inputs for depth x(s).
  void apply(double s, interface::Interface& itf) const;

  /// Records the converged `state` (whole model; with the condensed bulk,
  /// right on the joints) at s of corrosion step `step` (0: before
  /// corrosion): a corrosion.csv row and the progress line, which shows
  /// `step` of the nominal steps if `numbered` (not under dissipation
  /// control, whose steps are not those). `fields(row)` writes the row's
  /// fields first, so that a row the fields have no room for is not written
  /// either (as curve.csv's). The model's displacement is `state`'s after
  /// it. Collective.
  void record(double s, solver::Equilibrium& eq, Vec state, int iterations, int cuts, int step,
              bool numbered, const std::function<void(int row)>& fields);

  /// The force that works on the corrosion depth x [N]: the oxide's
  /// expansion does the work  int p dg0 dA = (beta - 1) N dx  on the
  /// interface, N = int p dA its normal force (0 while the porous zone
  /// takes the expansion), from the laws' last evaluation. Collective.
  double expansion_force(const interface::Interface& itf, double s) const;

  /// The cracks now into the summary: the crack planes' state (direction,
  /// mouth and largest opening, largest damage) and the concrete's cracks at
  /// the outer faces ([cracking]), whose pattern also goes to
  /// crack_pattern.csv (and .png). Collective.
  void describe_cracks(solver::Equilibrium& eq, Vec state, output::Summary& summary) const;

  /// At the end of the run, with the model's committed cracks at the edge
  /// of the cracking region (`edge`): if any cracked there, a note (the
  /// progress line and summary.json's notes) of how many and how wide, and
  /// since when (the first corrosion step that record() found them in):
  /// the concrete beyond cracking.radius stays linear, so the pattern
  /// there is the radius's, not the material's. Nothing if none did.
  void note_edge_cracks(model::EdgeCracks edge);

private:
  /// crack_pattern.csv: the cracking concrete's columns through the
  /// thickness, their centre, mean widest opening, size and four corners
  /// (rank 0's `columns`); with crack planes also crack_planes.csv, each
  /// plane's ends and mouth opening (`mouths` [mm]), which the figure draws
  /// over the columns; its plot asked for. Collective.
  void write_crack_pattern(const std::vector<model::CrackColumn>& columns,
                           const std::vector<double>& mouths) const;

  double _x_final = 0; ///< [mm]
  int _steps = 1;
  laws::OxideLayer _oxide;
  CrackDirections _directions;
  /// Each crack plane's ends in the x-y plane, at the interface and at the
  /// outer boundary [mm]: x0, y0, x1, y1.
  std::vector<std::array<double, 4>> _plane_ends;
  std::filesystem::path _out; ///< the output folder
  record::RunReport& _report;
  MPI_Comm _comm;
  mesh::Symmetry _symmetry;                ///< the model's mirror planes
  std::optional<output::CurveWriter> _csv; ///< rank 0
  int _row = 0; ///< corrosion.csv's next row number (its step column, as curve.csv's)
  /// The corrosion step whose record() first found cracks at the edge of
  /// the cracking region ("": none yet), said then on the progress line.
  std::string _edge_reached;
  void watch_edge(const model::EdgeCracks& edge, int step, double x);
};

/// The normal force N = -int t_n dA [N] and the area A [mm^2] of the whole
/// interface, from the last evaluation of the laws. Collective.
std::array<double, 2> pressure_force(const interface::Interface& itf, MPI_Comm comm);

/// The mean pressure p = -int t_n dA / A over the whole interface [MPa],
/// from the last evaluation of the laws. Collective.
double mean_pressure(const interface::Interface& itf, MPI_Comm comm);
} // namespace pushout::specimen
