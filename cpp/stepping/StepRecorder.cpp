#include "StepRecorder.h"
#include "../common/Interrupt.h"
#include "../common/mpi_errors.h"
#include "../record/NonFinite.h"
#include <iomanip>
#include <iostream>

namespace pushout::stepping
{
StepRecorder::StepRecorder(const OutputPart& output, const std::filesystem::path& out,
                           const specimen::Scenario& scenario, solver::Equilibrium& equilibrium,
                           record::RunReport& report, bool corrosion)
    : _scenario(scenario), _equilibrium(equilibrium), _report(report),
      _reactions(equilibrium.model().create_vector())
{
  int rank = 0;
  const MPI_Comm comm = equilibrium.model().comm();
  MPI_Comm_rank(comm, &rank);
  mpi::collectively(comm,
                    [&]
                    {
                      if (rank != 0)
                        return;
                      auto columns = scenario.columns();
                      columns.insert(columns.end(), {"newton_iterations", "cuts", "wall_s"});
                      _curve.emplace(out / "curve.csv", columns);
                    });
  if (output.xdmf)
    _fields = std::make_unique<output::FieldWriter>(equilibrium.model(), out);
  if (output.xdmf && corrosion)
    _corrosion_fields =
        std::make_unique<output::FieldWriter>(equilibrium.model(), out, "corrosion_");
}

void StepRecorder::close()
{
  for (std::unique_ptr<output::FieldWriter>* f : {&_corrosion_fields, &_fields})
    if (*f)
    {
      mpi::collectively(_equilibrium.model().comm(), [&] { (*f)->close(); });
      f->reset();
    }
}

void StepRecorder::end_corrosion()
{
  if (!_corrosion_fields)
    return;
  mpi::collectively(_equilibrium.model().comm(), [&] { _corrosion_fields->close(); });
  _corrosion_fields.reset();
}

void StepRecorder::record_corrosion(int row)
{
  if (!_corrosion_fields)
    return;
  const interrupt::Phase writing("writing step outputs", -1);
  const double t_out = _report.seconds();
  mpi::collectively(_equilibrium.model().comm(),
                    [&]
                    {
                      if (model::BulkCracking* cracking = _equilibrium.model().bulk_cracking())
                        cracking->settle(); // as record()
                      _corrosion_fields->write(double(row));
                    });
  _report.summary().output_s += _report.seconds() - t_out;
}

void StepRecorder::record(Vec x, int iterations, int cuts, int step, int steps)
{
  const interrupt::Phase writing("writing step outputs", -1);
  const double t_out = _report.seconds();
  if (bulk_needed())
    _equilibrium.internal_forces(x, _reactions);
  else
    _equilibrium.update_displacement(x); // the interface reads the model's displacement
  std::vector<double> values;
  {
    const solver::ReadView r(_reactions), xa(x);
    values = _scenario.row(r.span(), xa.span(), _equilibrium.model());
  }
  record::refuse_non_finite(values, _scenario.columns(), "step " + std::to_string(step),
                            _equilibrium.model().comm());
  const std::string line = _scenario.progress(values);
  values.insert(values.end(), {double(iterations), double(cuts), _report.seconds()});
  // The fields first: a step they have no room for (FieldWriter's check of
  // the disk) writes no row either, so that curve.csv's rows are the steps
  // summary.json counts.
  if (_fields)
    mpi::collectively(_equilibrium.model().comm(),
                      [&]
                      {
                        // The cracks as the step commits them (the reactions'
                        // evaluation above holds IMPL-EX's prediction).
                        if (model::BulkCracking* cracking = _equilibrium.model().bulk_cracking())
                          cracking->settle();
                        _fields->write(double(_row));
                      });
  mpi::collectively(_equilibrium.model().comm(),
                    [&]
                    {
                      if (_curve)
                        _curve->row(_row, values);
                    });
  ++_row;
  _report.summary().output_s += _report.seconds() - t_out;
  if (!_report.talk())
    return;
  std::cout << "step " << step;
  if (steps > 0)
    std::cout << "/" << steps;
  std::cout << "  " << line << "  (newton " << iterations
            << (cuts ? ", cuts " + std::to_string(cuts) : "") << ", " << std::fixed
            << std::setprecision(2) << _report.seconds() << " s)" << std::defaultfloat << std::endl;
}
} // namespace pushout::stepping
