// The crack band's size condition (docs/cracking.md): every element that may
// crack must be narrower, across its diagonal, than the widest band its
// crack can soften over without snapping back, at every quadrature point's
// strength; and a cracking region must take in some concrete. BulkCracking
// checks its own elements when a run builds it; a sweep checks each case on
// the whole mesh before any case runs (check_cracking_mesh).
#pragma once

#include "../bulk/CrackBand.h"
#include "../mesh/MeshData.h"
#include "../scene/SceneParts.h"
#include <mpi.h>

namespace pushout::model
{
/// The softening envelope of [cracking] (laws/Envelope.h).
laws::Envelope envelope_of(const CrackingPart& part);

/// The worst of the elements it is shown, and the refusal it makes of it.
class BandSizeCheck
{
public:
  BandSizeCheck(const bulk::CrackBand& band, const CrackingPart& part);

  /// A quadrature point of strength `strength` (the field's factor of f_t)
  /// in an element `diagonal` [mm] across, centred at `centre` (x, y) [mm].
  void add(double diagonal, std::array<double, 2> centre, double strength);
  /// The worst over the processes of `comm` (each shown its own elements).
  /// Collective.
  void agree(MPI_Comm comm);
  /// Throws SceneError if the worst element is too wide, saying which,
  /// where (and how far from the tube `axis` (x, y) [mm], for
  /// cracking.radius), and what to change (the field's spread where only
  /// its strongest points fail).
  void refuse_if_too_wide(std::array<double, 2> axis) const;

private:
  const bulk::CrackBand& _band;
  const CrackingPart& _part;
  double _mean_band;      ///< the widest band at the mean strength [mm]
  double _worst = 0;      ///< the largest diagonal / band of a point
  double _worst_mean = 0; ///< the largest diagonal / band at the mean strength
  /// The worst element's diagonal, band [mm], centre x, y [mm], and the
  /// strength field's factor on f_t at its point.
  std::array<double, 5> _where{};
};

/// The checks of [cracking] that need the mesh, on the whole mesh `data`
/// (every process holds it, so all decide alike): a cracking.radius that
/// takes in no concrete cell (CrackingCells.h), and the size condition on
/// the elements that may crack, at their quadrature points (BulkCracking's)
/// mapped from the hexahedra's nodes. Throws SceneError in the words a run
/// refuses the scene in; nothing to check without cracks anywhere.
void check_cracking_mesh(const mesh::MeshData& data, const Material& concrete,
                         const CrackingPart& part, const Geometry& slice);
} // namespace pushout::model
