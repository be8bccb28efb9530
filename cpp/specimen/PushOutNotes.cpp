// The push-out's notes on a scene before it runs (PushOut::scene_notes):
// what the scene asks for that the run will do otherwise, or that may not
// converge.
#include "../laws/LawRegistry.h"
#include "../mesh/size.h"
#include "../mesh/symmetry.h"
#include "PushOut.h"
#include <cmath>
#include <iomanip>
#include <sstream>

namespace pushout::specimen
{
namespace
{
/// The note on a random strength field the mesh does not resolve (its
/// correlation length below `h`, the elements' size at the tube [mm]), or
/// one nearly uniform over a slice `width` [mm] wide (StrengthField.h:
/// correlation exp(-(r/l)^2)); "" if none.
std::string field_note(const CrackingPart& cracking, double h, double width)
{
  if (!cracking.embedded || cracking.strength_cov == 0)
    return "";
  const double l = cracking.correlation_length; // [mm]
  std::ostringstream note;
  note << std::setprecision(3) << "cracking.correlation_length = " << l << " mm ";
  if (l < h)
    note << "is below the elements' size at the tube (" << h
         << " mm): the strength changes from one quadrature point to the next within an "
            "element, so the field the cracks see is not resolved and changes with the mesh "
            "(a length of a few elements resolves it)";
  else if (l > width)
    note << "is more than the slice's width (" << width
         << " mm): the strength is close to uniform over the slice, so a seed moves the "
            "whole slice's strength more than it picks where the concrete cracks";
  else
    return "";
  return note.str();
}
/// The note on a damage viscosity of the concrete's cracks that is not
/// small against a step's pseudo-time: the damage lags far behind, and the
/// concrete cracks late (docs/cracking.md, "Newton"); "" if none.
std::string viscosity_note(const Scene& scene)
{
  const double eta = scene.cracking().viscosity, step = scene.loading().first_push_step(); // [mm]
  if (!scene.cracking().embedded || eta == 0 || !(eta >= 0.1 * step))
    return "";
  std::ostringstream note;
  note << std::setprecision(3) << "cracking.viscosity = " << eta << " mm is " << eta / step
       << " times a step's pseudo-time (" << step
       << " mm: the push's first step, which each corrosion step lasts too): the cracks' "
          "damage lags far behind their openings, and the concrete cracks late (0.1 of a "
          "step's left the corroded demo's cover uncracked at x = 20 um on the paper's mesh: "
          "docs/cracking.md, \"Newton\"); a viscosity well below a step's pseudo-time, unless "
          "the delay is what it is for";
  return note.str();
}
} // namespace

std::vector<std::string> PushOut::scene_notes(const Scene& scene)
{
  const Geometry& g = scene.geometry();
  const double h =
      mesh::interface_element_size(g.tube_radius(), scene.mesh().elements_per_quarter); // [mm]
  const double E = scene.concrete().E;                                                  // [MPa]
  const bool nodal = scene.mesh().nodal_quadrature;
  std::vector<std::string> notes;
  // One note per layer, on its stiffest parameter (elastic's k_n and k_s
  // default to its k: the first of equals).
  auto check = [&](const std::string& prefix, const LayerSpec& layer)
  {
    const laws::LawInfo* law = laws::find_law(layer.law);
    if (!law)
      return;
    const laws::ParamDef* stiffest = nullptr;
    double k = 0; // [N/mm^3]
    for (const laws::ParamDef& def : law->params)
      if (const auto it = layer.params.find(def.name);
          def.unit == "N/mm^3" && it != layer.params.end() && it->second > k)
      {
        stiffest = &def;
        k = it->second;
      }
    if (!stiffest || !(k * h / E > stiff_joint_ratio))
      return;
    // A whole number where it says enough (not for an absurd E, 1e-300 MPa).
    const auto whole = [](double v)
    {
      std::ostringstream s;
      if (std::abs(v) >= 1 && std::abs(v) < 1e15)
        s << std::llround(v);
      else
        s << std::setprecision(3) << v;
      return s.str();
    };
    std::ostringstream note;
    note << std::setprecision(3) << prefix << stiffest->name << " = " << k << " N/mm^3 is "
         << whole(k * h / E) << " E / h (E " << whole(E) << " MPa the concrete's, h " << h
         << " mm an interface element's size): Newton may cycle between the joints' contact "
            "and sliding states and not converge (seen from about "
         << (nodal ? "3000 E / h"
                   : "130 E / h with 2x2 Gauss points, 3000 with "
                     "mesh.interface_quadrature = \"nodal\"")
         << "); stiffer than " << stiff_joint_ratio << " E / h (" << stiff_joint_ratio * E / h
         << " N/mm^3 here), a joint moves the curve by 0.1 % or less";
    notes.push_back(note.str());
  };
  for (std::size_t i = 0; i < scene.layers().size(); ++i)
    check("interface." + std::to_string(i) + ".", scene.layers()[i]);
  for (std::size_t i = 0; i < scene.cracks().size(); ++i)
    check("crack." + std::to_string(i) + ".", scene.cracks()[i].layer);
  std::string why;
  const bool symmetric = scene.model().symmetry == ModelPart::Symmetry::symmetric;
  const int copies = symmetric ? mesh::model_symmetry(mesh::MeshInput::of(scene), why).copies() : 0;
  // A cut the slice does not allow (the progress line says so too; --quiet hides it).
  if (copies == 1)
    notes.push_back("model.symmetry = \"symmetric\" finds no plane to cut at (" + why +
                    "): the whole slice is solved");
  // Cracks anywhere on a cut model are held symmetric (docs/cracking.md, "Reading the cracks").
  if (scene.cracking().embedded && copies > 1)
    notes.push_back("model.symmetry = \"symmetric\" holds the concrete's cracks symmetric: a "
                    "crack on a symmetry plane opens a band on each side of it, and its mirror "
                    "image opens too, where the whole slice may open one crack off the plane; "
                    "the bond after cracking differed by 15 % (tube off centre) and by 2.1 "
                    "times (tube centred: two cover cracks against one) on the coarse corroded "
                    "demo (docs/cracking.md; model.symmetry = \"auto\" keeps the whole slice)");
  // The residual bond of a cracked cover moves with the cells' shape
  // (docs/cracking.md, "How far to trust a corroded run";
  // bench/results/cracking_layouts.md): a corroded square slice on a
  // layout measured there that does not keep it is told which does. Those
  // layouts are refined near the tube at an outer_size_ratio above 1 (at
  // ratio 1 the two refinements mesh alike, and radial lines there are the
  // reference itself), with the projected band the numbers are of; radial
  // lines are refused with crack planes (PushOut::check_scene).
  const MeshPart& mesh = scene.mesh();
  if (scene.cracking().embedded && !scene.cracking().row_band && !g.circle &&
      scene.corrosion().penetration > 0 && scene.cracks().empty() && !mesh.refine_whole &&
      mesh.outer_size_ratio > 1)
    notes.push_back(
        std::string("cracks in the concrete on ") +
        (mesh.radial_lines ? "radial lines refined near the tube (mesh.graded_refinement = "
                             "\"near_tube\")"
                           : "the blocks (mesh.graded_lines = \"blocks\")") +
        ": the residual bond after the cover cracks moves with the cells' shape. On the "
        "corroded cover case (cover 15 mm, beta 2, x = 50 um, 16 / 8 elements, IMPL-EX, "
        "five seeds) it came " +
        (mesh.radial_lines ? "4.5 to 13.3 % below"
                           : "3.7 % below to 17.2 % above (7 % above on the seeds' mean)") +
        " a reference layout of 3.2 times the dofs, and within 1.7 % of it on radial lines "
        "refined whole: for residual bonds, mesh.graded_lines = \"radial\" with "
        "mesh.graded_refinement = \"whole\" (1.2 times the dofs; docs/cracking.md, \"How far "
        "to trust a corroded run\")");
  if (std::string note = field_note(scene.cracking(), h, g.width); !note.empty())
    notes.push_back(note);
  if (std::string note = viscosity_note(scene); !note.empty())
    notes.push_back(note);
  // A viscous crack's damage relaxes over pseudo-time, and an energy step
  // takes a whole nominal step's however little the load moves (not
  // settled: docs/cracking.md, "Newton", on a damage viscosity).
  const Loading::Control control = scene.loading().control;
  if (scene.cracking().embedded && scene.cracking().viscosity > 0 &&
      (control == Loading::Control::dissipation || control == Loading::Control::automatic))
    notes.push_back(std::string("cracking.viscosity under loading.control = \"") +
                    (control == Loading::Control::automatic ? "auto" : "dissipation") +
                    "\": an energy step takes a whole nominal step's pseudo-time however little "
                    "the load moves, so the viscous damage relaxes over time the load did not "
                    "take, and the concrete dissipates more than under displacement control at "
                    "fine steps; with a viscosity, loading.control = \"displacement\" with "
                    "enough steps (docs/cracking.md, \"Newton\", on a damage viscosity)");
  return notes;
}
} // namespace pushout::specimen
