// The push-out's checks of a scene before it runs (PushOut::check_scene,
// PushOut::check_cracking): what the model cannot take is refused, with the
// keys and values that make it so (SceneError, exit 2).
#include "../laws/LawRegistry.h"
#include "../scene/SceneError.h"
#include "PushOut.h"
#include <algorithm>
#include <cmath>
#include <sstream>

namespace pushout::specimen
{
namespace
{
/// The thinnest tube wall, the narrowest bore, gap between the tube and
/// the support, and ring of concrete outside the tube and the support, as
/// a fraction of the tube's outer diameter D.
constexpr double min_width_ratio = 0.01;
/// The widest slice in tube diameters (the paper's: 5; a tube typed in um,
/// 0.02 for 20 mm, makes 5000).
constexpr double max_width_ratio = 1000;
/// The largest push as a fraction of the slice thickness L: the model's
/// small-displacement range.
constexpr double max_push_ratio = 0.1;
/// The largest ratio of the last push step to the first (step_growth).
constexpr double max_step_ratio = 1e6;

/// Whether a joint law of the scene ([[interface]] layers, [[crack]] planes)
/// or the concrete ([cracking]) softens: then dissipation control takes steps
/// of its own (StepLoop::by_dissipation; else it runs as displacement
/// control).
bool softens(const Scene& scene)
{
  const auto law_softens = [](const LayerSpec& spec, const std::string& prefix)
  { return laws::find_law(spec.law)->make(spec.params, prefix)->softens(); };
  bool any = scene.cracking().embedded;
  for (std::size_t i = 0; i < scene.layers().size(); ++i)
    any = any || law_softens(scene.layers()[i], "interface." + std::to_string(i) + ".");
  for (std::size_t i = 0; i < scene.cracks().size(); ++i)
    any = any || law_softens(scene.cracks()[i].layer, "crack." + std::to_string(i) + ".");
  return any;
}

/// loading.step_growth grows the push's steps under displacement control; a
/// control that takes equal steps of its own would ignore it: refused.
void refuse_ignored_step_growth(const Scene& scene)
{
  const Loading& loading = scene.loading();
  if (loading.step_growth == 1.0)
    return;
  std::ostringstream s;
  s << "'loading.step_growth' = " << loading.step_growth
    << " grows the push's steps under displacement control; ";
  if (loading.control == Loading::Control::arc_length)
    s << "arc length ('loading.control' = \"arc_length\") takes steps of equal length, "
         "push_displacement / steps in the (delta, slip) plane: leave it at 1";
  else if (loading.control != Loading::Control::displacement && softens(scene))
    s << "dissipation control ('loading.control' = \"auto\" or \"dissipation\"), which runs "
         "here as the joints or the concrete's cracks soften, takes steps of delta of "
         "push_displacement / steps and steps of energy: leave 'loading.step_growth' at 1 (more "
         "'loading.steps' for finer steps), or set 'loading.control' = \"displacement\"";
  else
    return;
  throw SceneError(s.str());
}
/// A corrosion step lasts the push's first step's pseudo-time
/// (StepLoop::corrosion_stage): none where that step has no length, and a
/// viscous damage would then never grow in the stage (the uncracked
/// answer): refused.
void refuse_timeless_corrosion(const Scene& scene)
{
  const Loading& loading = scene.loading();
  const auto& path = loading.push_path;
  if (loading.first_push_step() != 0 || scene.corrosion().penetration == 0)
    return;
  std::string keys;
  const auto add = [&](const std::string& prefix, const LayerSpec& layer)
  {
    if (const auto eta = layer.params.find("eta"); eta != layer.params.end() && eta->second > 0)
      keys += (keys.empty() ? "'" : ", '") + prefix + "eta'";
  };
  for (std::size_t i = 0; i < scene.layers().size(); ++i)
    add("interface." + std::to_string(i) + ".", scene.layers()[i]);
  for (std::size_t i = 0; i < scene.cracks().size(); ++i)
    add("crack." + std::to_string(i) + ".", scene.cracks()[i].layer);
  if (scene.cracking().embedded && scene.cracking().viscosity > 0)
    keys += std::string(keys.empty() ? "" : ", ") + "'cracking.viscosity'";
  if (keys.empty())
    return;
  throw SceneError(std::string("a corrosion step lasts the pseudo-time of the push's first step, "
                               "and ") +
                   (path.empty() ? "'loading.push_displacement' = 0 gives"
                                 : "'loading.push_path''s first segment, of no length, gives") +
                   " it none: the viscous damage of " + keys +
                   " would not grow in the corrosion stage. Give a push (0.001 mm in "
                   "'loading.steps' = 1 makes a corrosion step last 0.001 mm), or no viscosity");
}

/// The [loading] keys of a push-out with the rest of the scene.
void check_loading(const Scene& scene)
{
  const Loading& loading = scene.loading();
  const double L = scene.geometry().thickness;
  // The model is small-displacement: beyond a push of max_push_ratio L the
  // contact length it keeps (L) and the one tau divides by (L - |delta|)
  // differ by more than 10 %.
  const auto beyond_small_displacement = [&](const std::string& key, double push)
  {
    std::ostringstream s;
    s << "'" << key << "' pushes " << push << " mm, more than " << max_push_ratio * L
      << " mm (10 % of 'geometry.thickness'): the model is small-displacement (it keeps the whole "
         "contact length L while "
         "tau = P / (pi D (L - |delta|)))";
    return SceneError(s.str());
  };
  const auto& path = loading.push_path;
  if (path.empty())
  {
    if (const double push = loading.push_displacement; !(std::abs(push) <= max_push_ratio * L))
      throw beyond_small_displacement("loading.push_displacement", push);
    // Path following and dissipation control run the push to its end: a
    // load factor from 0 up to push_displacement.
    if (loading.control != Loading::Control::displacement && !(loading.push_displacement > 0))
    {
      std::ostringstream s;
      s << "'loading.control' other than \"displacement\" (auto, dissipation, arc_length) "
           "follows a push to a positive 'loading.push_displacement' (it is "
        << loading.push_displacement
        << " mm): give one (a short one, e.g. 0.001 mm, after a corrosion stage alone), or set "
           "'loading.control' = \"displacement\"";
      throw SceneError(s.str());
    }
  }
  else
  {
    check_load_path("loading.push_path", path, loading.steps_per_segment);
    for (const double d : path)
      if (!(std::abs(d) <= max_push_ratio * L))
        throw beyond_small_displacement("loading.push_path", d);
    if (loading.step_growth != 1.0)
      throw SceneError("'loading.step_growth' applies to the monotonic push "
                       "(push_displacement, steps), not to 'loading.push_path': leave it at 1");
    if (loading.control != Loading::Control::displacement)
      throw SceneError("'loading.push_path' is followed under 'loading.control' = "
                       "\"displacement\" (path following and dissipation control run a "
                       "monotonic push)");
    if (const double lowest = *std::min_element(path.begin(), path.end());
        loading.unload_to_zero_force && lowest < 0)
    {
      std::ostringstream s;
      s << "'loading.unload_to' = \"zero_force\" is a push-out device that cannot pull, and "
           "'loading.push_path' pulls the tube back to "
        << lowest << " mm: keep the path at 0 or above, or set 'loading.unload_to' = \"path\"";
      throw SceneError(s.str());
    }
  }
  refuse_ignored_step_growth(scene);
  refuse_timeless_corrosion(scene);
  // Steps growing (or shrinking) geometrically: the last at most
  // max_step_ratio times the first, or the other way round.
  const double growth = loading.step_growth;
  if (const auto steps = loading.steps;
      std::abs(double(steps - 1) * std::log(growth)) > std::log(max_step_ratio))
  {
    std::ostringstream s;
    s << "'loading.step_growth' = " << growth << " over 'loading.steps' = " << steps
      << " makes the last step " << growth << "^" << steps - 1
      << " times the first: at most 1e6 either way";
    throw SceneError(s.str());
  }
}
} // namespace

void PushOut::check_scene(const Scene& scene)
{
  const Geometry& g = scene.geometry();
  const double D = g.tube_outer_diameter, Di = g.tube_inner_diameter;
  const double Ds = g.support_inner_diameter;
  // The tube wall and the support's gap around the tube are meshed with
  // elements across them: thinner than min_width_ratio D they are no
  // geometry the mesher (or the model) can resolve.
  std::ostringstream min_width;
  min_width << min_width_ratio * D << " mm (1 % of 'geometry.tube_outer_diameter')";
  if (!(Di < D))
    throw SceneError("'geometry.tube_inner_diameter' must be smaller than "
                     "'geometry.tube_outer_diameter'");
  if (!((D - Di) / 2 >= min_width_ratio * D))
    throw SceneError("'geometry.tube_inner_diameter' leaves a tube wall (D - Di) / 2 thinner "
                     "than " +
                     min_width.str());
  if (!(Di >= min_width_ratio * D)) // (1e-7 mm: "Zero radius in circle" from the mesher)
    throw SceneError("'geometry.tube_inner_diameter' must be at least " + min_width.str() +
                     ": the tube's bore is meshed");
  // A slice of many tube diameters: the cells grade from the tube's to
  // outer_size_ratio times that, and no further (mesh/size.h), so their
  // number grows with the square of the ratio.
  if (g.width > max_width_ratio * D)
  {
    std::ostringstream s;
    s << "'geometry.width' = " << g.width << " mm is " << g.width / D
      << " times 'geometry.tube_outer_diameter' = " << D << " mm: at most " << max_width_ratio
      << " (every length of [geometry] is in mm)";
    throw SceneError(s.str());
  }
  if (!(Ds > D))
    throw SceneError("'geometry.support_inner_diameter' must be larger than "
                     "'geometry.tube_outer_diameter' (the support holds the "
                     "concrete, not the tube)");
  if (!((Ds - D) / 2 >= min_width_ratio * D))
    throw SceneError("'geometry.support_inner_diameter' leaves a gap (Ds - D) / 2 between the "
                     "tube and the support narrower than " +
                     min_width.str());
  // The tube, then the support hole, must leave a ring of concrete inside
  // the slice, as wide as the tube wall may be thin (a ring of 1e-5 mm
  // broke the mesher: memory corrupted, a hang).
  const auto mm = [](double v) // a length as given, to 10 digits [mm]
  {
    std::ostringstream s;
    s.precision(10);
    s << v;
    return s.str();
  };
  const std::string centre =
      "'geometry.tube_center' = [" + mm(g.tube_center[0]) + ", " + mm(g.tube_center[1]) + "] mm";
  const std::string where = "'geometry.width' = " + mm(g.width) + " mm" +
                            (g.circle ? "" : " and " + centre) + " put the nearest outer face " +
                            mm(g.nearest_face_distance()) + " mm from the tube axis";
  if (!g.circle && !(g.nearest_face_distance() > 0))
    throw SceneError(centre + " lies outside the slice ('geometry.width' = " + mm(g.width) +
                     " mm: it spans [0, " + mm(g.width) +
                     "] in x and in y; every length of [geometry] is in mm)");
  if (!(g.nearest_face_distance() - D / 2 >= min_width_ratio * D))
    throw SceneError("the tube ('geometry.tube_outer_diameter' = " + mm(D) +
                     " mm) does not fit in the slice with concrete round it at least " +
                     min_width.str() + " wide: " + where +
                     " (every length of [geometry] is in mm)");
  if (!(g.nearest_face_distance() - Ds / 2 >= min_width_ratio * D))
    throw SceneError("'geometry.support_inner_diameter' = " + mm(Ds) +
                     " mm leaves no support outside the hole at least " + min_width.str() +
                     " wide: " + where);
  if (scene.mesh().radial_lines && !scene.crack_directions().angles.empty())
    throw SceneError("'mesh.graded_lines' = \"radial\" does not apply with [[crack]] planes: "
                     "their sectors are meshed along their own rays; leave it out");
  check_loading(scene);
  // The oxide presses on the concrete only through a law that models it.
  const auto& layers = scene.layers();
  if (scene.corrosion().penetration > 0 &&
      std::none_of(layers.begin(), layers.end(),
                   [](const LayerSpec& l) { return l.law == "oxide_friction"; }))
    throw SceneError("'corrosion.penetration' > 0 needs an interface layer with law "
                     "\"oxide_friction\": the oxide presses on the concrete through it "
                     "(it replaces \"friction\"; docs/corrosion.md)");
  // Corrosion turns the tube's wall to oxide from outside: no deeper than
  // the wall (a depth typed in um, 50 for 0.05 mm, lands here).
  if (const double x = scene.corrosion().penetration; !(x < (D - Di) / 2))
  {
    std::ostringstream s;
    s << "'corrosion.penetration' = " << x
      << " mm is the tube's wall (D - Di) / 2 = " << (D - Di) / 2
      << " mm or deeper: it is in mm (50 um is 0.05)";
    throw SceneError(s.str());
  }
  check_cracking(scene);
}

/// [cracking] with the rest of the scene: what cracks anywhere in the
/// concrete works with so far (docs/cracking.md).
void PushOut::check_cracking(const Scene& scene)
{
  const CrackingPart& cracking = scene.cracking();
  if (!cracking.embedded)
    return;
  if (scene.mesh().degree != 1)
    throw SceneError("'cracking.model' = \"embedded\" needs 'mesh.degree' = 1 (the crack band's "
                     "forms are on the trilinear bulk)");
  if (cracking.radius > 0 && cracking.radius <= scene.geometry().tube_radius())
  {
    std::ostringstream s;
    s << "'cracking.radius' = " << cracking.radius << " mm lies within the tube (its radius is "
      << scene.geometry().tube_radius() << " mm): no concrete could crack; raise it, or 0 for "
      << "all the concrete";
    throw SceneError(s.str());
  }
  if (scene.solver().condensation == SolverPart::Condensation::on)
    throw SceneError("'solver.condensation' = \"on\" condenses a linear bulk, and "
                     "'cracking.model' = \"embedded\" makes the concrete nonlinear: leave it at "
                     "\"auto\" (the whole model is solved)");
  if (cracking.implex && cracking.viscosity > 0)
    throw SceneError("'cracking.integration' = \"implex\" extrapolates the cracks' damage, and "
                     "'cracking.viscosity' > 0 delays it: use one or the other");
  // The implicit cracks' step error is measured against IMPL-EX's
  // prediction, whose damage follows the history at once: with a viscosity
  // it misses the lagging damage by the same amount at any step (on the
  // coarse corroded demo every step cut to 2^-6 of a nominal one,
  // docs/cracking.md "The implicit cracks' step error").
  if (!cracking.implex && cracking.implicit_tolerance > 0 && cracking.viscosity > 0)
    throw SceneError("'cracking.implicit_tolerance' measures a step against IMPL-EX's "
                     "prediction, which takes no viscosity, and 'cracking.viscosity' > 0 delays "
                     "the cracks' damage: the error would not fall with the step. Leave the "
                     "tolerance at 0 and refine 'corrosion.steps' and 'loading.steps' together "
                     "(a corrosion step lasts a push step's pseudo-time)");
  if (scene.model().symmetry == ModelPart::Symmetry::symmetric && cracking.strength_cov > 0)
    throw SceneError("'model.symmetry' = \"symmetric\" cuts the slice, and a random strength "
                     "field ('cracking.strength_cov' > 0) is not symmetric: leave it at \"auto\"");
}
} // namespace pushout::specimen
