#include "Corrosion.h"
#include "../common/mpi_errors.h"
#include <iomanip>
#include <iostream>
#include <numeric>
#include <sstream>

namespace pushout::driver
{
Corrosion::Corrosion(const Scene& scene, const std::filesystem::path& out, RunReport& report)
    : _report(report)
{
  if (scene.string("model.type") != "pushout")
    return;
  _x_final = scene.number("corrosion.penetration");
  _steps = int(scene.integer("corrosion.steps"));
  _oxide = {scene.number("corrosion.beta"), scene.number("corrosion.porous_zone"),
            scene.number("corrosion.oxide_bulk")};
  if (!active())
    return;
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  mpi::collectively(MPI_COMM_WORLD,
                    [&]
                    {
                      if (rank == 0)
                        _csv.emplace(out / "corrosion.csv",
                                     std::vector<std::string>{"penetration_mm", "p_MPa",
                                                              "crack_width_mm", "newton_iterations",
                                                              "cuts", "wall_s"});
                    });
}

void Corrosion::apply(double s, interface::Interface& itf) const
{
  const laws::OxideInputs in = laws::oxide_inputs(_oxide, penetration_at(s));
  itf.set_oxide(in.gap, in.compliance);
}

void Corrosion::record(double s, const model::Model& model, int iterations, int cuts, int step)
{
  const double x = penetration_at(s);
  const double p = mean_pressure(model.interface());
  const double crack_width = 0; // no crack planes yet
  const std::vector<double> values = {
      x, p, crack_width, double(iterations), double(cuts), _report.seconds()};
  mpi::collectively(MPI_COMM_WORLD,
                    [&]
                    {
                      if (_csv)
                        _csv->row(step, values);
                    });
  if (!_report.talk())
    return;
  std::ostringstream line;
  line.precision(4);
  line << "corrosion " << step << "/" << _steps << "  x = " << x * 1e3 << " um  p = " << p
       << " MPa  (newton " << iterations << (cuts ? ", cuts " + std::to_string(cuts) : "") << ", "
       << std::fixed << std::setprecision(2) << _report.seconds() << " s)";
  std::cout << line.str() << std::endl;
}

double mean_pressure(const interface::Interface& itf)
{
  const std::vector<double> normal = itf.normal_force();
  double local[2] = {std::accumulate(normal.begin(), normal.end(), 0.0), itf.area()};
  MPI_Allreduce(MPI_IN_PLACE, local, 2, MPI_DOUBLE, MPI_SUM, MPI_COMM_WORLD);
  const double p = local[1] > 0 ? -local[0] / local[1] : 0.0;
  return p == 0 ? 0.0 : p; // never -0 in the progress line
}
} // namespace pushout::driver
