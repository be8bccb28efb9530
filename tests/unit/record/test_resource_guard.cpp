// The size guard (record/ResourceGuard.h): its count of what runs at once on
// this machine (a sweep's or a fit's other groups run other cases beside
// this one, and each is counted at this run's solving peak), and the solver
// path its estimate takes.
#include "../../../cpp/mesh/MeshInput.h"
#include "../../../cpp/record/ResourceGuard.h"
#include "../../../cpp/scene/Scene.h"
#include <gtest/gtest.h>

using pushout::Scene;
using pushout::mesh::MeshInput;
using pushout::record::check_fits;
using pushout::record::estimate_resources;
using pushout::record::ResourceEstimate;
using pushout::record::TooLarge;

TEST(ResourceGuard, OtherCasesOnThisMachineCountAtThisRunsSolvingPeak)
{
  const Scene scene = Scene::parse("[mesh]\nelements_per_quarter = 24\n");
  const MeshInput in = MeshInput::of(scene);
  const ResourceEstimate alone =
      estimate_resources(in, scene.solver(), scene.cracking(), MPI_COMM_SELF);
  const ResourceEstimate beside =
      estimate_resources(in, scene.solver(), scene.cracking(), MPI_COMM_SELF, 3);
  ASSERT_EQ(alone.processes_here, 1);
  EXPECT_EQ(alone.others_here, 0);
  // One process: its peak is the machine's.
  EXPECT_DOUBLE_EQ(alone.machine_mb, alone.peak_mb());
  // Three more cases as large: four solve peaks, or the meshing peak beside
  // three solve peaks.
  EXPECT_DOUBLE_EQ(beside.machine_mb,
                   std::max(4 * alone.solve_mb, alone.meshing_mb + 3 * alone.solve_mb));
  EXPECT_DOUBLE_EQ(beside.peak_mb(), alone.peak_mb()); // a process's own peak is unchanged
  EXPECT_NE(beside.memory().find("4 processes, 3 of them running other cases"), std::string::npos)
      << beside.memory();

  // A machine with room for this run alone refuses it beside the others,
  // and says what else to change.
  ResourceEstimate fits_alone = beside;
  fits_alone.available_mb = 1.5 * alone.machine_mb;
  fits_alone.address_space_mb = -1;
  ResourceEstimate only = alone;
  only.available_mb = fits_alone.available_mb;
  only.address_space_mb = -1;
  EXPECT_NO_THROW(check_fits(only, in, false));
  try
  {
    check_fits(fits_alone, in, false);
    FAIL() << "four cases at once fit in the memory of 1.5 cases";
  }
  catch (const TooLarge& e)
  {
    EXPECT_NE(std::string(e.what()).find("--ranks-per-case"), std::string::npos) << e.what();
  }
  EXPECT_NO_THROW(check_fits(fits_alone, in, true)); // --force
}

namespace
{
ResourceEstimate estimate_of(const std::string& scene_text)
{
  const Scene scene = Scene::parse(scene_text);
  return estimate_resources(MeshInput::of(scene), scene.solver(), scene.cracking(), MPI_COMM_SELF);
}
} // namespace

TEST(ResourceGuard, CrackingConcreteIsSolvedWholeWithItsPointsCounted)
{
  // The whole slice, so that both models have the same mesh.
  const std::string slice = "[model]\nsymmetry = \"full\"\n[mesh]\nelements_per_quarter = ";
  const std::string whole = "[solver]\ncondensation = \"off\"\n";
  const std::string cracks = "[cracking]\nmodel = \"embedded\"\n";
  const ResourceEstimate linear = estimate_of(slice + "16\n" + whole);
  const ResourceEstimate cracking = estimate_of(slice + "16\n" + cracks);
  const ResourceEstimate condensed = estimate_of(slice + "16\n");
  ASSERT_EQ(cracking.size.dofs, linear.size.dofs);
  EXPECT_TRUE(condensed.condensed);
  EXPECT_FALSE(cracking.condensed) << "concrete that may crack is not condensed";
  // What the cracks add is their points' share, in proportion to the
  // concrete's cells: a finer mesh, more of them (the same ratio but for the
  // round-off of sums of some 1e3 MB, 1e-13 MB).
  const ResourceEstimate linear_fine = estimate_of(slice + "24\n" + whole);
  const ResourceEstimate cracking_fine = estimate_of(slice + "24\n" + cracks);
  const double added = cracking.solve_mb - linear.solve_mb;
  const double added_fine = cracking_fine.solve_mb - linear_fine.solve_mb;
  EXPECT_GT(added, 0);
  EXPECT_NEAR(added_fine / added,
              double(cracking_fine.size.concrete_cells) / double(cracking.size.concrete_cells),
              1e-12);
  // The concrete is the model's cells but the tube's.
  EXPECT_GT(cracking.size.concrete_cells, 0);
  EXPECT_LT(cracking.size.concrete_cells, cracking.size.cells);
  // The LU in double (solver.precision) takes more than in single.
  const ResourceEstimate in_double =
      estimate_of(slice + "16\n" + whole + "precision = \"double\"\n");
  EXPECT_GT(in_double.solve_mb, linear.solve_mb);
}
