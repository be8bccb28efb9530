// The outputs of each converged load step: a curve.csv row (rank 0 writes
// it), the fields of output.xdmf, and the progress line.
//
// A step is recorded before it is committed: evaluating the laws again (the
// reactions) from the committed state would advance a viscous law a second
// time.
#pragma once

#include "../output/CurveWriter.h"
#include "../output/FieldWriter.h"
#include "../record/RunReport.h"
#include "../solver/Equilibrium.h"
#include "../solver/Vector.h"
#include "../specimen/Scenario.h"
#include <filesystem>
#include <memory>
#include <optional>

namespace pushout::stepping
{
class StepRecorder
{
public:
  /// Opens curve.csv (and fields.xdmf, interface.xdmf) in `out`; an error
  /// writing them on rank 0 is the same error on every process.
  /// `corrosion`: the run has a corrosion stage, whose fields go to
  /// corrosion_fields.xdmf (and corrosion_interface.xdmf, ...) with
  /// output.xdmf.
  StepRecorder(const OutputPart& output, const std::filesystem::path& out,
               const specimen::Scenario& scenario, solver::Equilibrium& equilibrium,
               record::RunReport& report, bool corrosion = false);

  /// Whether a row or a field reads the bulk (a condensed solver then
  /// recovers it after each step).
  bool bulk_needed() const { return _scenario.uses_bulk() || _fields != nullptr; }

  /// With output.xdmf: the fields of a converged corrosion step (or step 0
  /// before corrosion) at the time of its corrosion.csv `row`, from the
  /// model's displacement (which specimen::Corrosion::record set).
  void record_corrosion(int row);

  /// Closes the corrosion stage's field files (at the push's start); an
  /// error as close()'s. Collective.
  void end_corrosion();

  /// Records the converged state x of step `step` of `steps` (0: path
  /// following, which does not know its number of steps).
  void record(Vec x, int iterations, int cuts, int step, int steps);

  /// Closes the field files; an error (a full disk) on any process is the
  /// same error on every process.
  void close();

private:
  const specimen::Scenario& _scenario;
  solver::Equilibrium& _equilibrium;
  record::RunReport& _report;
  std::optional<output::CurveWriter> _curve; ///< rank 0 only
  std::unique_ptr<output::FieldWriter> _fields;
  std::unique_ptr<output::FieldWriter> _corrosion_fields; ///< the corrosion stage's
  solver::Vector _reactions;
  int _row = 0;
};
} // namespace pushout::stepping
