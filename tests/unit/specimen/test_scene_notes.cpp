// The notes a valid push-out scene gets before its run (specimen::scene_notes):
// a joint's penalty stiffness far above the concrete's over an interface
// element, where Newton may cycle between contact and sliding states.
#include "scene/Scene.h"
#include "specimen/PushOut.h"
#include "specimen/Scenario.h"
#include <gtest/gtest.h>

using pushout::Scene;
using pushout::specimen::PushOut;
using pushout::specimen::scene_notes;

TEST(SceneNotes, StiffJointNotedAboveTheRatio)
{
  // The default scene: R 10 mm, 16 elements per quarter (h = 0.982 mm), the
  // concrete's E 30000 MPa: E / h = 30 558 N/mm^3, so the note starts at
  // k = 3.06e6 N/mm^3.
  const double E_over_h = 30000.0 / (3.14159265358979 / 2 * 10.0 / 16);
  const double k_limit = PushOut::stiff_joint_ratio * E_over_h;
  EXPECT_TRUE(scene_notes(Scene::parse("")).empty());
  EXPECT_TRUE(
      scene_notes(Scene::parse("", {{"interface.0.k", std::to_string(0.99 * k_limit)}})).empty());
  const auto notes =
      scene_notes(Scene::parse("", {{"interface.0.k", std::to_string(1.01 * k_limit)}}));
  ASSERT_EQ(notes.size(), 1u);
  EXPECT_NE(notes[0].find("interface.0.k"), std::string::npos) << notes[0];
  EXPECT_NE(notes[0].find("101 E / h"), std::string::npos) << notes[0];
  // A finer mesh (smaller h) takes a stiffer joint; every stiffness
  // parameter of a law (elastic's k_n and k_s) and the crack planes' laws
  // are read.
  EXPECT_TRUE(scene_notes(Scene::parse("", {{"interface.0.k", std::to_string(1.01 * k_limit)},
                                            {"mesh.elements_per_quarter", "32"}}))
                  .empty());
  // One note per layer: elastic's k_n and k_s take its k.
  EXPECT_EQ(scene_notes(Scene::parse("[[interface]]\nlaw = \"elastic\"\nk = 1e7\n")).size(), 1u);
  const auto elastic =
      scene_notes(Scene::parse("[[interface]]\nlaw = \"elastic\"\nk_s = 1e7\n"
                               "[[crack]]\nangle = 90.0\nlaw = \"linear_softening\"\nk = 1e7\n"
                               "f_t = 3.0\nw_c2 = 0.1\n"));
  ASSERT_EQ(elastic.size(), 2u);
  EXPECT_EQ(elastic[0].rfind("interface.0.k_s = ", 0), 0u) << elastic[0];
  EXPECT_EQ(elastic[1].rfind("crack.0.k = ", 0), 0u) << elastic[1];
  // An absurd E: the numbers as numbers (the ratio was rounded to an
  // integer it does not fit, -9223372036854775808, and E to 0).
  const auto soft = scene_notes(Scene::parse("", {{"concrete.E", "1e-300"}}));
  ASSERT_EQ(soft.size(), 1u);
  EXPECT_NE(soft[0].find("is 9.82e+302 E / h (E 1e-300 MPa"), std::string::npos) << soft[0];
}

TEST(SceneNotes, SingleJointHasNone)
{
  EXPECT_TRUE(
      scene_notes(Scene::parse("[model]\ntype = \"single_joint\"\n", {{"interface.0.k", "1e9"}}))
          .empty());
}

TEST(SceneNotes, CracksOnACutModelHeldSymmetric)
{
  // Cracks anywhere with a uniform strength: auto keeps the whole slice;
  // model.symmetry = "symmetric" cuts it and is noted. Where the slice has
  // no symmetry plane to cut on (the tube off centre both ways), that is
  // noted instead, cracks or not.
  const std::string cracks = "[cracking]\nmodel = \"embedded\"\n";
  EXPECT_TRUE(scene_notes(Scene::parse(cracks)).empty());
  const auto cut = scene_notes(Scene::parse(cracks, {{"model.symmetry", "symmetric"}}));
  ASSERT_EQ(cut.size(), 1u);
  EXPECT_EQ(cut[0].rfind("model.symmetry = \"symmetric\" holds the concrete's cracks", 0), 0u)
      << cut[0];
  EXPECT_TRUE(scene_notes(Scene::parse("", {{"model.symmetry", "symmetric"}})).empty());
  for (const std::string& scene : {cracks, std::string()})
  {
    const auto uncut = scene_notes(Scene::parse(
        scene, {{"model.symmetry", "symmetric"}, {"geometry.tube_center", "[45.0, 40.0]"}}));
    ASSERT_EQ(uncut.size(), 1u);
    EXPECT_EQ(uncut[0].rfind("model.symmetry = \"symmetric\" finds no plane to cut at", 0), 0u)
        << uncut[0];
  }
  const auto odd = scene_notes(
      Scene::parse("", {{"model.symmetry", "symmetric"}, {"mesh.elements_per_quarter", "3"}}));
  ASSERT_EQ(odd.size(), 1u);
  EXPECT_NE(odd[0].find("mesh.elements_per_quarter is odd"), std::string::npos) << odd[0];
}

TEST(SceneNotes, ViscousCracksUnderDissipationControl)
{
  // Energy steps take a nominal step's pseudo-time (docs/cracking.md,
  // "Newton", on a damage viscosity): noted under dissipation control and
  // "auto", not under displacement control or without a viscosity.
  // (1e-5 mm: 0.01 of a step, no note of its own; ViscousCracksNotSmall)
  const std::string viscous = "[cracking]\nmodel = \"embedded\"\nviscosity = 0.00001\n";
  for (const std::string control : {"dissipation", "auto"})
  {
    const auto notes = scene_notes(Scene::parse(viscous, {{"loading.control", control}}));
    ASSERT_EQ(notes.size(), 1u) << control;
    EXPECT_EQ(notes[0].rfind("cracking.viscosity under loading.control = \"" + control + "\"", 0),
              0u)
        << notes[0];
  }
  EXPECT_TRUE(scene_notes(Scene::parse(viscous, {{"loading.control", "displacement"}})).empty());
  EXPECT_TRUE(
      scene_notes(Scene::parse("[cracking]\nmodel = \"embedded\"\n", {{"loading.control", "auto"}}))
          .empty());
}

TEST(SceneNotes, CorrodedCracksOnALayoutThatMovesTheResidualBond)
{
  // The residual bond of a cracked cover moves with the cells' shape
  // (docs/cracking.md, "How far to trust a corroded run"): a corroded
  // square slice with cracks in the concrete is told the layout that keeps
  // it, unless it is on that layout or the reference; not without
  // corrosion, on a circle, or with crack planes (where radial lines are
  // refused).
  const std::string cracks = "[cracking]\nmodel = \"embedded\"\n[corrosion]\npenetration = 0.05\n";
  const std::string prefix = "cracks in the concrete on ";
  const auto blocks = scene_notes(Scene::parse(cracks));
  ASSERT_EQ(blocks.size(), 1u);
  EXPECT_EQ(blocks[0].rfind(prefix + "the blocks", 0), 0u) << blocks[0];
  EXPECT_NE(blocks[0].find("mesh.graded_refinement = \"whole\""), std::string::npos);
  const auto near_tube = scene_notes(Scene::parse(cracks, {{"mesh.graded_lines", "radial"}}));
  ASSERT_EQ(near_tube.size(), 1u);
  EXPECT_EQ(near_tube[0].rfind(prefix + "radial lines refined near the tube", 0), 0u)
      << near_tube[0];
  EXPECT_TRUE(scene_notes(Scene::parse(cracks, {{"mesh.graded_lines", "radial"},
                                                {"mesh.graded_refinement", "whole"}}))
                  .empty());
  // The reference layout (radial lines at outer_size_ratio 1), and the
  // row band, whose layouts the numbers are not of.
  EXPECT_TRUE(scene_notes(Scene::parse(cracks, {{"mesh.graded_lines", "radial"},
                                                {"mesh.outer_size_ratio", "1"}}))
                  .empty());
  EXPECT_TRUE(scene_notes(Scene::parse(cracks, {{"cracking.band_width", "row"}})).empty());
  EXPECT_TRUE(scene_notes(Scene::parse("[cracking]\nmodel = \"embedded\"\n")).empty());
  EXPECT_TRUE(scene_notes(Scene::parse(cracks, {{"geometry.outer_shape", "circle"}})).empty());
  for (const std::string& note : scene_notes(Scene::parse(
           cracks + "[[crack]]\nangle = \"nearest_face\"\nlaw = \"exponential_softening\"\n"
                    "k = 1000.0\nf_t = 3.0\nc = 30.0\n")))
    EXPECT_NE(note.rfind(prefix, 0), 0u) << note;
  EXPECT_TRUE(scene_notes(Scene::parse("[corrosion]\npenetration = 0.05\n")).empty());
}

TEST(SceneNotes, StrengthFieldTheMeshDoesNotResolveOrNearlyUniform)
{
  // A correlation length below the elements at the tube (the default mesh:
  // pi/2 10 mm / 16 = 0.98 mm) or beyond the slice's width (100 mm); none
  // between them, nor without a random field.
  const std::string field = "[cracking]\nmodel = \"embedded\"\nstrength_cov = 0.15\n";
  const std::string prefix = "cracking.correlation_length = ";
  const auto fine = scene_notes(Scene::parse(field, {{"cracking.correlation_length", "0.5"}}));
  ASSERT_EQ(fine.size(), 1u);
  EXPECT_EQ(fine[0].rfind(prefix + "0.5 mm is below the elements' size at the tube (0.982 mm)", 0),
            0u)
      << fine[0];
  const auto wide = scene_notes(Scene::parse(field, {{"cracking.correlation_length", "150"}}));
  ASSERT_EQ(wide.size(), 1u);
  EXPECT_EQ(wide[0].rfind(prefix + "150 mm is more than the slice's width (100 mm)", 0), 0u)
      << wide[0];
  EXPECT_TRUE(scene_notes(Scene::parse(field, {{"cracking.correlation_length", "5"}})).empty());
  EXPECT_TRUE(scene_notes(Scene::parse("[cracking]\nmodel = \"embedded\"\n",
                                       {{"cracking.correlation_length", "0.5"}}))
                  .empty());
}

TEST(SceneNotes, ViscousCracksNotSmallAgainstAStep)
{
  // A damage viscosity from 0.1 of the push's first step's pseudo-time (a
  // push of 0.01 mm in 10 steps: 0.001 mm) delays the cracking
  // (docs/cracking.md, "Newton"); with step_growth the first, smaller step.
  const std::string cracks = "[cracking]\nmodel = \"embedded\"\n[loading]\n"
                             "push_displacement = 0.01\nsteps = 10\n";
  const std::string prefix = "cracking.viscosity = ";
  const auto noted = scene_notes(Scene::parse(cracks, {{"cracking.viscosity", "0.0001"}}));
  ASSERT_EQ(noted.size(), 1u);
  EXPECT_EQ(noted[0].rfind(prefix + "0.0001 mm is 0.1 times a step's pseudo-time (0.001 mm", 0), 0u)
      << noted[0];
  EXPECT_TRUE(scene_notes(Scene::parse(cracks, {{"cracking.viscosity", "0.00009"}})).empty());
  const auto grown = scene_notes(
      Scene::parse(cracks, {{"cracking.viscosity", "0.00009"}, {"loading.step_growth", "1.2"}}));
  ASSERT_EQ(grown.size(), 1u); // first step 0.01 * 0.2 / (1.2^10 - 1) = 3.85e-4 mm
  EXPECT_NE(grown[0].find("(0.000385 mm"), std::string::npos) << grown[0];
}
