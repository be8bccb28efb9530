// Concrete that cracks, in the model (docs/cracking.md): the crack band of
// bulk/CrackBand.h at every quadrature point of the concrete that may crack
// (the cells within cracking.radius of the tube axis), each point with its
// own tensile strength from the random field of bulk/StrengthField.h.
//
// The linear stiffness K (forms/elasticity.py) stays as assembled; what
// cracking changes enters through forms/cracking.py on the cracking cells
// only: the forces of sigma - C : eps_e and the tangent C_t - C, both zero
// at a point that has not cracked. Per evaluation: the strain at the points
// (an FFCx expression of the displacement), the crack band's update from
// the committed state (one 3 x 3 equilibrium per cracked point), then the
// two differences into the forms' Quadrature coefficients.
//
// State: a committed and a trial copy at every point, as the joints'
// (interface/InterfaceState.h); evaluate() writes the trial one, commit()
// after a converged step, revert() before a retry.
#pragma once

#include "../bulk/CrackBand.h"
#include "../scene/SceneParts.h"
#include "SurfaceCracks.h"
#include <array>
#include <cstdint>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <memory>
#include <petscmat.h>
#include <span>
#include <vector>

namespace pushout::model
{
/// What the concrete's cracks add up to over all processes (collective).
struct CrackingTotals
{
  std::int64_t points = 0;         ///< quadrature points that may crack
  std::int64_t cracked_points = 0; ///< of those, cracked
  double max_opening = 0;          ///< the widest normal opening w . n at a point [mm]
  double dissipated = 0;           ///< energy the cracks dissipated [N mm]
  /// The cracks at the slice's outer faces as a gauge reads them, widest
  /// first (model/SurfaceCracks.h); the same on every process.
  std::vector<SurfaceCrack> surface;
  /// The cracking concrete's columns through the thickness (the crack
  /// pattern seen along the tube axis); on process 0 only.
  std::vector<CrackColumn> columns;
};

class BulkCracking
{
public:
  /// `material` the input cells' materials (MeshData); `slice` the
  /// slice's geometry (the tube axis, the outer faces). Throws SceneError, on every process, if a
  /// cracking cell is too large for its crack band to soften without snapping back.
  BulkCracking(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
               std::shared_ptr<const dolfinx::fem::FunctionSpace> V,
               std::shared_ptr<const dolfinx::fem::Function<double>> u,
               std::shared_ptr<const dolfinx::fem::Function<double>> alpha,
               const std::vector<std::int32_t>& material, const Material& concrete,
               const CrackingPart& part, const Geometry& slice);

  /// cracking.visible_width: a surface crack counts from this width [mm].
  double visible_width() const { return _visible_width; }

  /// The temperature change whose free strain the stress does not see [degC].
  void set_temperature_change(double dT);

  /// The crack band at every point, from the committed state to the strain
  /// of the model's displacement (ghosts up to date): the trial state, and
  /// the forms' coefficients. False if a point failed (its equilibrium did
  /// not converge): the step is to be cut.
  bool evaluate();
  /// Adds the forces of the last evaluate() to f (local with ghosts; the
  /// caller sums the ghosts into their owners) [N].
  void add_forces(std::span<double> f) const;
  /// Adds the tangent of the last evaluate() to A (before its final
  /// assembly) [N/mm].
  void add_tangent(Mat A) const;

  /// The trial state becomes the committed one (a converged step).
  void commit();
  /// The trial state back to the committed one (a step to retry).
  void revert();
  /// Every point back to uncracked (a model reused for another scene).
  void reset();

  /// Totals of the state at the model's displacement, evaluated from the
  /// committed one: a converged step's, recorded before its commit
  /// (stepping/StepRecorder.h). Collective.
  CrackingTotals totals();

  /// Per cell, the widest crack of its points (of the last evaluate()):
  /// its normal opening w . n [mm] (0: none), unit normal and damage, into
  /// DG0 functions of the model's mesh (zero where the concrete may not
  /// crack).
  void cell_fields(dolfinx::fem::Function<double>& opening, dolfinx::fem::Function<double>& normal,
                   dolfinx::fem::Function<double>& damage) const;

private:
  /// Where a cracking cell stands: its column and, on an outer face, what a
  /// gauge along the face reads across it (model/SurfaceCracks.h).
  struct CellPlace
  {
    double x = 0, y = 0;             ///< centre [mm]
    double weight = 0;               ///< its share of the slice's thickness
    double size = 0;                 ///< horizontal extent [mm]
    std::array<double, 8> outline{}; ///< corners (x, y) seen along the axis [mm]
    /// Outer faces it lies on: the face's index and horizontal tangent t,
    /// with the cell's extent along t and its centre's depth below the face
    /// [mm], and the half of its points nearest the face (where the gauge
    /// reads) with the cell's chord along t through each [mm].
    struct Face
    {
      int index = 0;
      double tx = 0, ty = 0, depth = 0;
      std::vector<int> points;
      std::vector<double> chords;
    };
    std::vector<Face> faces;
  };
  /// The places of the cracking cells on the slice `slice`; `positions`
  /// their points' (x, y, z) [mm].
  void place_cells(const Geometry& slice, const std::vector<double>& positions);
  /// The point's crack opening along the face tangent t, the crack strain
  /// t . eps_cr . t of point i [-].
  double crack_strain_along(std::size_t i, double tx, double ty) const;
  /// Gathers the columns on process 0 and reads the surface cracks there;
  /// into `t`. Collective.
  void read_surface(CrackingTotals& t) const;

  /// Band width of a cracking cell along a unit normal n: the extent of its
  /// vertices along n [mm] (bulk/CrackBand.h).
  double band_width(std::size_t cell, const bulk::Vec3& n) const;

  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  bulk::CrackBand _band;
  std::vector<std::int32_t> _cells;       ///< cracking cells (local, owned), sorted
  std::vector<double> _strength;          ///< [cell][point] f_t factor of the field
  std::vector<double> _committed, _trial; ///< [cell][point][CrackBand::state_size]
  std::vector<double> _dissipated;        ///< [cell][point] committed energy density [N mm/mm^3]
  std::vector<double> _dissipated_trial;
  /// [cell][point][3] crack opening in the crack's frame [n, s1, s2] [mm]
  std::vector<double> _opening, _opening_trial;
  std::vector<CellPlace> _places; ///< [cell]
  std::array<double, 2> _axis{};  ///< the tube axis (x, y) [mm]
  double _tube_radius = 0;        ///< [mm]
  double _visible_width = 0;      ///< cracking.visible_width [mm]
  std::shared_ptr<dolfinx::fem::Constant<double>> _dT;
  std::shared_ptr<dolfinx::fem::Function<double>> _d_sigma, _d_C, _d_dissipated;
  std::unique_ptr<dolfinx::fem::Expression<double>> _strain;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _region;
  std::shared_ptr<dolfinx::fem::Form<double>> _L, _a, _M;
  std::vector<double> _strain_values; ///< [cell][point][6], of the last evaluate()
};
} // namespace pushout::model
