// The scene keys of pushout: each declared once, with type, default, unit,
// range and doc. docs/scene-reference.md is printed from this table by
// `pushout keys`. Interface-layer keys are declared by each law (cpp/laws/).
#include "KeyDef.h"
#include <algorithm>
#include <cmath>
#include <sstream>

namespace pushout
{
namespace
{
constexpr double inf = std::numeric_limits<double>::infinity();

std::vector<KeyDef> make_keys()
{
  using K = KeyType;
  using A = Applies;
  std::vector<KeyDef> keys = {
      {"model.type",
       K::string,
       std::string("pushout"),
       "",
       "pushout: the slice test; single_joint: one 1x1 mm joint (law check)",
       -inf,
       inf,
       false,
       {"pushout", "single_joint"}},
      {"model.symmetry",
       K::string,
       std::string("auto"),
       "",
       "auto: a push-out symmetric about x = xc and y = yc (tube centred, crack planes "
       "symmetric, even elements_per_quarter, no output.xdmf) runs on a quarter of the mesh "
       "with symmetry conditions (about one of them: a half), the same curve at a fraction of "
       "the dofs; a crack plane on a symmetry plane keeps one face. It does not cut where two "
       "crack planes are mirror images of each other: the cut would make them open alike, and "
       "the whole slice may open one; nor with [cracking] (a crack may open on one side of a "
       "symmetry plane only). symmetric: cuts there too (the symmetric solution; with "
       "[cracking] a uniform strength only, and noted), with output.xdmf too (its fields are the "
       "part's); full: always the whole slice",
       -inf,
       inf,
       false,
       {"auto", "symmetric", "full"},
       A::pushout},

      // Geometry of the slice (paper §2.1, Fig. 1; the defaults the paper does
      // not state are documented assumptions).
      {"geometry.outer_shape",
       K::string,
       std::string("square"),
       "",
       "square slice, or circle (axisymmetric check against Lame)",
       -inf,
       inf,
       false,
       {"square", "circle"},
       A::pushout},
      {"geometry.width",
       K::number,
       100.0,
       "mm",
       "square side, or circle diameter (at most 10 m, as every length of [geometry])",
       0,
       1e4,
       true,
       {},
       A::pushout},
      {"geometry.thickness",
       K::number,
       20.0,
       "mm",
       "slice thickness L (paper eq. 1)",
       0,
       1e4,
       true,
       {},
       A::pushout},
      {"geometry.tube_outer_diameter",
       K::number,
       20.0,
       "mm",
       "tube outer diameter D (paper eq. 1)",
       0,
       1e4,
       true,
       {},
       A::pushout},
      {"geometry.tube_inner_diameter",
       K::number,
       16.0,
       "mm",
       "tube inner diameter",
       0,
       1e4,
       true,
       {},
       A::pushout},
      {"geometry.tube_center",
       K::number_array,
       std::vector<double>{50.0, 50.0},
       "mm",
       "tube axis position (x, y); the square spans [0, width]^2 (a circle slice is "
       "concentric with its tube: leave it out)",
       -inf,
       inf,
       false,
       {},
       A::pushout},
      {"geometry.support_inner_diameter",
       K::number,
       30.0,
       "mm",
       "the slice rests on z = 0 outside this circle (centred on the tube)",
       0,
       1e4,
       true,
       {},
       A::pushout},
      {"geometry.area",
       K::number,
       1.0,
       "mm^2",
       "joint area (square face; 1e-6 to 1e8)",
       1e-6,
       1e8,
       false,
       {},
       A::single_joint},

      // Mesh (paper §4.1: 16 per quarter, 8 through the thickness, 3 steel
      // layers, outer elements 10x the interface elements).
      {"mesh.elements_per_quarter",
       K::integer,
       std::int64_t(16),
       "",
       "elements along a quarter of the interface circumference",
       1,
       4096,
       false,
       {},
       A::pushout},
      {"mesh.elements_through_thickness",
       K::integer,
       std::int64_t(8),
       "",
       "element layers through the slice thickness",
       1,
       4096,
       false,
       {},
       A::pushout},
      {"mesh.steel_layers",
       K::integer,
       std::int64_t(3),
       "",
       "element layers across the tube wall",
       1,
       4096,
       false,
       {},
       A::pushout},
      {"mesh.outer_size_ratio",
       K::number,
       10.0,
       "",
       "outer concrete element size / interface element size on the shortest way from the "
       "support circle to the boundary (at most: the elements grow by 1.6 at most from one to "
       "the next, so a short way, e.g. a thin cover, keeps smaller ones). The longer ways out, "
       "to the corners or across an off-centre tube, have as many elements; where their first "
       "would exceed 1.6 times the interface size, all ways get enough elements to start the "
       "longest there (mesh.graded_refinement says how they grow then)",
       1,
       inf,
       false,
       {},
       A::pushout},
      {"mesh.graded_lines",
       K::string,
       std::string("blocks"),
       "",
       "the lines of the graded concrete from the support circle out to a square slice's "
       "boundary: blocks: from equal angles on the circle to equal steps along each quarter's "
       "side, ending at the square's corners (sheared where the tube is off-centre); radial: "
       "along rays from the tube axis at those angles (each corner on its nearest ray), so "
       "that a radial crack runs along a row of cells whose faces it is parallel to "
       "(docs/cracking.md, \"Radial graded lines\"). A circle slice's lines are radial either "
       "way; not with [[crack]] planes, whose sectors are meshed along their own rays",
       -inf,
       inf,
       false,
       {"blocks", "radial"},
       A::pushout},
      {"mesh.graded_refinement",
       K::string,
       std::string("near_tube"),
       "",
       "how the graded concrete's elements grow where the longest way out (to a far corner, or "
       "across an off-centre tube) needs more of them than its shortest way: near_tube: from "
       "1.6 times the interface size, growing by 1.6 at most, so the outer elements keep "
       "their size as elements_per_quarter refines the mesh round the tube; whole: from there "
       "to outer_size_ratio times it along every way, so every graded element shrinks with "
       "the interface's and keeps its shape (more elements; docs/cracking.md, \"Radial graded "
       "lines\")",
       -inf,
       inf,
       false,
       {"near_tube", "whole"},
       A::pushout},
      {"mesh.degree", K::integer, std::int64_t(1), "",
       "polynomial degree of the bulk displacement on the trilinear hexahedra: 1 (trilinear, "
       "8 nodes) or 2 (triquadratic, 27 nodes; push-out only), a check of the trilinear "
       "bulk's locking",
       1, 2, false},
      {"mesh.interface_quadrature",
       K::string,
       std::string("gauss"),
       "",
       "interface integration: gauss (2x2) or nodal (Newton-Cotes at the 4 "
       "node pairs)",
       -inf,
       inf,
       false,
       {"gauss", "nodal"}},

      // Bulk materials (paper Table 1).
      {"concrete.E", K::number, 30000.0, "MPa", "Young's modulus", 0, inf, true},
      {"concrete.nu", K::number, 0.2, "-", "Poisson's ratio", -1, 0.5, true},
      {"concrete.alpha", K::number, 1.0e-5, "1/degC",
       "thermal expansion (retraction as a temperature drop); at most 1e-4 either way (concrete's "
       "is about 1e-5: 10 for 10e-6 is refused)",
       -1e-4, 1e-4},
      {"steel.E", K::number, 200000.0, "MPa", "Young's modulus", 0, inf, true},
      {"steel.nu", K::number, 0.3, "-", "Poisson's ratio", -1, 0.5, true},
      {"steel.alpha", K::number, 0.0, "1/degC",
       "thermal expansion; at most 1e-4 either way (steel's is about 1.2e-5)", -1e-4, 1e-4},

      // Loading (paper §4.2).
      {"loading.temperature_change",
       K::number,
       -25.0,
       "degC",
       "applied to the bulk in one step before pushing (0: no thermal step); at most 1000 "
       "degC either way (the model is linear thermo-elastic: concrete does not survive more)",
       -1000,
       1000,
       false,
       {},
       A::pushout},
      {"loading.push_displacement",
       K::number,
       0.010,
       "mm",
       "final downward displacement delta of the tube's top nodes; at most 10 % of "
       "geometry.thickness either way: the model is small-displacement (it keeps the whole "
       "contact length L while tau = P / (pi D (L - |delta|)) divides by the shrinking one); "
       "positive under loading.control = auto, dissipation or arc_length; not read with "
       "push_path",
       -inf,
       inf,
       false,
       {},
       A::pushout},
      {"loading.step_growth",
       K::number,
       1.0,
       "",
       "ratio of each push step to the previous one (1: equal steps; > 1: fine steps "
       "first, for the peak, coarse ones later) under displacement control (and under "
       "dissipation control where nothing softens, which then runs so; refused where its "
       "own steps run, and under arc length); below 10, and the last step at most 1e6 "
       "times the first (step_growth^(steps - 1)): more leaves the first steps below round-off",
       0,
       10,
       true,
       {},
       A::pushout},
      {"loading.thermal_tube_top",
       K::string,
       std::string("held"),
       "",
       "during the thermal step the tube's top nodes are held at u_z = 0 (held: the "
       "paper's choice, §4.2) or free (free); the push then moves them from there",
       -inf,
       inf,
       false,
       {"held", "free"},
       A::pushout},
      {"loading.steps",
       K::integer,
       std::int64_t(9),
       "",
       "displacement steps from 0 to push_displacement (equal, or growing by step_growth); at "
       "most 100000 (a step takes milliseconds to seconds: more would run for days)",
       1,
       100000,
       false,
       {},
       A::pushout},
      {"loading.push_path",
       K::number_array,
       std::vector<double>{},
       "mm",
       "push delta along a piecewise-linear path through these values, starting at 0, "
       "loading.steps_per_segment steps each (unload and reload, e.g. [0, 0.05, 0.03, 0.2]); "
       "empty: the monotonic push to push_displacement in steps. Under loading.control = "
       "\"displacement\" only (each segment's steps are steps of delta)",
       -inf,
       inf,
       false,
       {},
       A::pushout},
      {"loading.unload_to",
       K::string,
       std::string("path"),
       "",
       "path: an unloading segment of push_path goes to its value (the tube pulled back if "
       "need be); zero_force: it ends where the push force P falls to zero, as a push-out "
       "device that cannot pull (summary.json permanent_displacements_mm; the path stays at "
       "0 or above), and the path goes on from there (past the unloading segments right after "
       "it, which would pull)",
       -inf,
       inf,
       false,
       {"path", "zero_force"},
       A::pushout},
      {"loading.control",
       K::string,
       std::string("displacement"),
       "",
       "displacement: steps of the push delta; arc_length: path following on the mean "
       "axial slip of the interface, steps of length push_displacement/steps in the "
       "(delta, slip) plane, through snap-back (delta may decrease) until delta reaches "
       "push_displacement; dissipation: steps of delta while the joints dissipate little, "
       "steps of the energy they release where a step of delta fails or jumps over a brittle "
       "event (snap-back), back to delta after it, and likewise steps of the corrosion depth x "
       "or of the energy released in the corrosion stage (docs/numerics.md); auto: the control "
       "we recommend for laws or cracks that may be brittle, today the same as dissipation",
       -inf,
       inf,
       false,
       {"displacement", "arc_length", "dissipation", "auto"},
       A::pushout},
      {"loading.dissipation_steps",
       K::integer,
       std::int64_t(20),
       "",
       "dissipation control: the energy released per step is the fracture energy of the "
       "softening joint layers and crack planes (InterfaceLaw G_F x area) over this many "
       "steps; a step of delta (or x) releasing more than that and more than the work of the "
       "push (or of the oxide's expansion) is redone under dissipation control; at most "
       "100000",
       1,
       100000,
       false,
       {},
       A::pushout},
      {"loading.max_cuts", K::integer, std::int64_t(10), "",
       "a step whose Newton solve fails is retried with half the increment, at most down to "
       "2^-max_cuts of a step (at most 40, and 44 - log2 of a stage's nominal steps: a "
       "smaller increment is lost in the round-off of the load's position)",
       0, 40, false},
      {"loading.normal_force_per_node",
       K::number,
       -0.1,
       "N",
       "normal (z) force on each upper node (negative: compression)",
       -inf,
       inf,
       false,
       {},
       A::single_joint},
      {"loading.shear_path",
       K::number_array,
       std::vector<double>{0.0, 0.02, 0.01, 0.025},
       "mm",
       "shear (x) displacement of the upper face: piecewise-linear path through these "
       "values, from 0 (the normal preload's state), at least one segment",
       -inf,
       inf,
       false,
       {},
       A::single_joint},
      {"loading.steps_per_segment",
       K::integer,
       std::int64_t(20),
       "",
       "load steps on each segment of shear_path (single joint) or push_path (push-out); at "
       "most 100000 on all segments together (a step takes milliseconds to seconds: more "
       "would run for days)",
       1,
       100000,
       false,
       {},
       A::all},

      // Corrosion (docs/corrosion.md): a load stage between the thermal step
      // and the push, in which the steel turns to oxide to depth x and the
      // oxide (beta times the volume) presses on the concrete through the
      // interface law oxide_friction.
      {"corrosion.penetration",
       K::number,
       0.0,
       "mm",
       "final corrosion depth x (steel radius turned to oxide; less than the tube wall (D - Di) / "
       "2), reached in corrosion.steps "
       "before the push; 0: no corrosion stage. From current and time: x [um] = 0.0317 i "
       "[uA/cm^2] t [days]",
       0,
       inf,
       false,
       {},
       A::pushout},
      {"corrosion.steps",
       K::integer,
       std::int64_t(20),
       "",
       "equal steps of x in the corrosion stage (cut in halves when Newton fails, as the "
       "push, or when IMPL-EX cracks miss cracking.implex_tolerance; corrosion.csv has a row "
       "per part); at most 100000 (a step takes milliseconds to seconds: more would run for days)",
       1,
       100000,
       false,
       {},
       A::pushout},
      {"corrosion.beta",
       K::number,
       2.0,
       "-",
       "oxide volume / volume of the steel it came from: the free opening of the interface is "
       "g0 = (beta - 1) x - porous_zone; iron's oxides and hydroxides are reported at 2 to 6.5 "
       "(docs/corrosion.md), so at most 7",
       1,
       7,
       false,
       {},
       A::pushout},
      {"corrosion.porous_zone",
       K::number,
       0.0,
       "mm",
       "expansion absorbed by the pores of the concrete before the oxide presses",
       0,
       inf,
       false,
       {},
       A::pushout},
      {"corrosion.oxide_bulk",
       K::number,
       2000.0,
       "MPa",
       "oxide bulk modulus B_ox: the oxide layer's normal compliance beta x / B_ox is in "
       "series with the joint's penalty",
       0,
       inf,
       true,
       {},
       A::pushout},

      // Solver (PETSc options from the command line refine it).
      {"solver.preconditioner",
       K::string,
       std::string("lagged"),
       "",
       "lagged: GMRES on the current Jacobian, preconditioned by the LU of an earlier one "
       "(the elastic tangent first), refactored only when GMRES slows down; jacobian: LU of "
       "the current Jacobian in every Newton iteration",
       -inf,
       inf,
       false,
       {"lagged", "jacobian"}},
      {"solver.condensation",
       K::string,
       std::string("auto"),
       "",
       "Newton on the interface jumps only, after condensing the linear bulk onto them once "
       "(Schur complement; exact, the curve is the whole model's). auto: when the run has one "
       "process, an LU preconditioner and at most 6000 interface dofs; on: the same, an error "
       "otherwise; off: Newton on the whole model",
       -inf,
       inf,
       false,
       {"auto", "on", "off"}},
      {"solver.refactor_iterations", K::integer, std::int64_t(10), "",
       "lagged: refactor from the current Jacobian when the last linear solve took more "
       "GMRES iterations than this",
       1, 1e9, false},
      {"solver.inexact_newton", K::boolean, true, "",
       "lagged: from a load step's second Newton iteration on, GMRES stops at half the "
       "residual that Newton's test still asks for (Kelley's safeguard on the forcing term), "
       "not at -ksp_rtol's relative reduction, which it never goes below; the first "
       "iteration solves to -ksp_rtol (where a step starts from a prediction that made the "
       "residual smaller, to what the step's unpredicted residual asks). Where GMRES measures "
       "the true residual (right preconditioning, the default -ksp_pc_side; flexible GMRES in "
       "single precision). The converged solution is the same to Newton's tolerance. false: "
       "every linear solve to -ksp_rtol"},
      {"solver.first_tangent",
       K::string,
       std::string("converged"),
       "",
       "the Jacobian of each load step's first Newton iteration. converged: the last "
       "converged step's (a predictor along the path; a sliding joint keeps its sliding "
       "tangent; a step that fails from it is tried again from the current one before it is "
       "cut); current: the tangent at the step's start, where the laws are at their "
       "committed state (always under dissipation control, whose steps must stay on the "
       "committed state's branch, in the thermal step, and with IMPL-EX cracks, whose step's "
       "tangent is known at its start). The converged solution is the same where it is "
       "unique; where softening leaves a step more than one equilibrium (implicit cracks in the "
       "concrete that compete, a brittle layer at its peak) Newton may find another from "
       "another start",
       -inf,
       inf,
       false,
       {"converged", "current"}},
      {"solver.precision",
       K::string,
       std::string("mixed"),
       "",
       "mixed: condensed bulk: flexible GMRES applies C and the lagged preconditioner's LU in "
       "single precision, to a relative tolerance of at least 1e-7; whole model (lagged "
       "MUMPS LU, or the LU of every Jacobian of implicit cracks): the LU factored and "
       "applied in single precision by MUMPS (on several processes too, each giving its "
       "rows), flexible GMRES to -ksp_rtol (or to what Newton needs: solver.inexact_newton) "
       "(half the memory traffic; the residual, and so "
       "the solution and the Newton tolerances, stay in double); double: everything in "
       "double, GMRES (right-preconditioned) to -ksp_rtol or what Newton needs",
       -inf,
       inf,
       false,
       {"mixed", "double"}},
      {"solver.time_linear_solve", K::boolean, false, "",
       "before the run, time one linear solve of the first load step of the whole model with "
       "the PETSc options' solver, MUMPS LU by default (where those are GMRES on MUMPS's LU, "
       "with solver.precision \"mixed\": flexible GMRES on the LU in single "
       "precision, as Newton's solves) (summary.json linear_solve_s: the floor a whole curve is "
       "compared with)"},

      // Output.
      {"output.xdmf", K::boolean, false, "",
       "write fields.xdmf (displacement, stress) and interface.xdmf"},
      {"output.plot", K::boolean, true, "",
       "write curve.png next to curve.csv (needs python3-matplotlib)"},
  };
  // The [cracking] section (keys_cracking.cpp), before the solver's.
  const std::vector<KeyDef> cracking = cracking_keys();
  const auto solver = std::find_if(
      keys.begin(), keys.end(), [](const KeyDef& k) { return k.path == "solver.preconditioner"; });
  keys.insert(solver, cracking.begin(), cracking.end());
  return keys;
}
} // namespace

const std::vector<KeyDef>& scene_keys()
{
  static const std::vector<KeyDef> keys = make_keys();
  return keys;
}

std::string range_text(double min, double max, bool open, bool integer)
{
  return range_text(min, max, open, open, integer);
}

std::string range_text(double min, double max, bool min_open, bool max_open, bool integer)
{
  auto bound = [&](double v)
  {
    std::ostringstream s;
    if (integer)
      s << std::int64_t(v);
    else
      s << v;
    return s.str();
  };
  std::string text;
  if (std::isfinite(min))
    text += (min_open ? "> " : ">= ") + bound(min);
  if (std::isfinite(min) && std::isfinite(max))
    text += " and ";
  if (std::isfinite(max))
    text += (max_open ? "< " : "<= ") + bound(max);
  return text.empty() ? "finite" : text;
}

const KeyDef* find_key(const std::string& path)
{
  for (const KeyDef& k : scene_keys())
    if (k.path == path)
      return &k;
  return nullptr;
}
} // namespace pushout
