// Scene reading: defaults, overrides, errors that name the key.
#include "scene/Scene.h"
#include "scene/SceneError.h"
#include <gtest/gtest.h>

using pushout::Override;
using pushout::Scene;
using pushout::SceneError;

namespace
{
/// The message of the SceneError that parsing `text` throws ("" if none).
std::string error_of(const std::string& text, const std::vector<Override>& sets = {})
{
  try
  {
    Scene::parse(text, sets);
  }
  catch (const SceneError& e)
  {
    return e.what();
  }
  return "";
}
} // namespace

TEST(Scene, DefaultsFillEveryKey)
{
  const Scene s = Scene::parse("");
  EXPECT_TRUE(s.model().pushout());
  EXPECT_DOUBLE_EQ(s.geometry().width, 100.0);
  EXPECT_EQ(s.mesh().elements_per_quarter, 16);
  ASSERT_EQ(s.layers().size(), 1u);
  EXPECT_EQ(s.layers()[0].law, "friction");
  EXPECT_DOUBLE_EQ(s.layers()[0].params.at("k"), 1000.0);
  EXPECT_FALSE(s.cracking().row_band); // the projected band (docs/cracking.md)
}

// Every key reaches its typed part (SceneParts.h): a scene with no key at
// its default (but tube_center, which a circle refuses: a second scene)
// reads back each value from the part that holds it.
TEST(Scene, EveryKeyReachesItsTypedPart)
{
  const Scene s = Scene::parse(R"(
[model]
symmetry = "full"
[geometry]
outer_shape = "circle"
width = 90.0
thickness = 15.0
tube_outer_diameter = 18.0
tube_inner_diameter = 14.0
support_inner_diameter = 28.0
[mesh]
elements_per_quarter = 6
elements_through_thickness = 3
steel_layers = 2
outer_size_ratio = 4.0
degree = 2
interface_quadrature = "nodal"
[concrete]
E = 31000.0
nu = 0.21
alpha = 1.1e-5
[steel]
E = 210000.0
nu = 0.29
alpha = 1.2e-5
[loading]
temperature_change = -20.0
push_displacement = 0.02
step_growth = 1.5
thermal_tube_top = "free"
steps = 7
unload_to = "zero_force"
control = "arc_length"
dissipation_steps = 11
max_cuts = 4
steps_per_segment = 5
[corrosion]
penetration = 0.01
steps = 6
beta = 2.5
porous_zone = 0.002
oxide_bulk = 1500.0
[cracking]
model = "embedded"
law = "linear_softening"
f_t = 2.5
c = 20.0
w_c2 = 0.12
band_width = "row"
radius = 40.0
strength_cov = 0.15
correlation_length = 4.0
seed = 7
visible_width = 0.02
viscosity = 0.3
[solver]
preconditioner = "jacobian"
condensation = "off"
refactor_iterations = 3
first_tangent = "current"
precision = "double"
time_linear_solve = true
[output]
xdmf = true
plot = false
)");
  EXPECT_EQ(s.model().symmetry, pushout::ModelPart::Symmetry::full);
  const pushout::Geometry& g = s.geometry();
  EXPECT_TRUE(g.circle);
  EXPECT_EQ(g.width, 90.0);
  EXPECT_EQ(g.thickness, 15.0);
  EXPECT_EQ(g.tube_outer_diameter, 18.0);
  EXPECT_EQ(g.tube_inner_diameter, 14.0);
  EXPECT_EQ(g.support_inner_diameter, 28.0);
  // tube_center places the tube in a square (a circle is concentric with it).
  const pushout::Geometry square =
      Scene::parse("[geometry]\ntube_center = [45.0, 44.0]\n").geometry();
  EXPECT_EQ(square.tube_center[0], 45.0);
  EXPECT_EQ(square.tube_center[1], 44.0);
  const pushout::MeshPart& m = s.mesh();
  EXPECT_EQ(m.elements_per_quarter, 6);
  EXPECT_EQ(m.elements_through_thickness, 3);
  EXPECT_EQ(m.steel_layers, 2);
  EXPECT_EQ(m.outer_size_ratio, 4.0);
  EXPECT_EQ(m.degree, 2);
  EXPECT_TRUE(m.nodal_quadrature);
  EXPECT_EQ(s.concrete().E, 31000.0);
  EXPECT_EQ(s.concrete().nu, 0.21);
  EXPECT_EQ(s.concrete().alpha, 1.1e-5);
  EXPECT_EQ(s.steel().E, 210000.0);
  EXPECT_EQ(s.steel().nu, 0.29);
  EXPECT_EQ(s.steel().alpha, 1.2e-5);
  const pushout::Loading& l = s.loading();
  EXPECT_EQ(l.temperature_change, -20.0);
  EXPECT_EQ(l.push_displacement, 0.02);
  EXPECT_EQ(l.step_growth, 1.5);
  EXPECT_TRUE(l.tube_top_free);
  EXPECT_EQ(l.steps, 7);
  EXPECT_TRUE(l.unload_to_zero_force);
  EXPECT_EQ(l.control, pushout::Loading::Control::arc_length);
  EXPECT_EQ(l.dissipation_steps, 11);
  EXPECT_EQ(l.max_cuts, 4);
  EXPECT_EQ(l.steps_per_segment, 5);
  const pushout::CorrosionPart& c = s.corrosion();
  EXPECT_EQ(c.penetration, 0.01);
  EXPECT_EQ(c.steps, 6);
  EXPECT_EQ(c.beta, 2.5);
  EXPECT_EQ(c.porous_zone, 0.002);
  EXPECT_EQ(c.oxide_bulk, 1500.0);
  const pushout::CrackingPart& k = s.cracking();
  EXPECT_TRUE(k.embedded);
  EXPECT_TRUE(k.linear_softening);
  EXPECT_EQ(k.f_t, 2.5);
  EXPECT_EQ(k.c, 20.0);
  EXPECT_EQ(k.w_c2, 0.12);
  EXPECT_TRUE(k.row_band);
  EXPECT_EQ(k.radius, 40.0);
  EXPECT_EQ(k.strength_cov, 0.15);
  EXPECT_EQ(k.correlation_length, 4.0);
  EXPECT_EQ(k.seed, 7);
  EXPECT_EQ(k.visible_width, 0.02);
  EXPECT_EQ(k.viscosity, 0.3);
  const pushout::SolverPart& v = s.solver();
  EXPECT_FALSE(v.lagged_preconditioner);
  EXPECT_EQ(v.condensation, pushout::SolverPart::Condensation::off);
  EXPECT_EQ(v.refactor_iterations, 3);
  EXPECT_FALSE(v.first_tangent_converged);
  EXPECT_FALSE(v.mixed_precision);
  EXPECT_TRUE(v.time_linear_solve);
  EXPECT_TRUE(s.output().xdmf);
  EXPECT_FALSE(s.output().plot);

  // The single joint's keys, and a push path.
  const Scene j =
      Scene::parse("[model]\ntype = \"single_joint\"\n[geometry]\narea = 4.0\n"
                   "[loading]\nnormal_force_per_node = -0.3\nshear_path = [0.0, 0.1]\n");
  EXPECT_FALSE(j.model().pushout());
  EXPECT_EQ(j.geometry().area, 4.0);
  EXPECT_EQ(j.loading().normal_force_per_node, -0.3);
  EXPECT_EQ(j.loading().shear_path, (std::vector<double>{0.0, 0.1}));
  EXPECT_EQ(Scene::parse("[loading]\npush_path = [0.0, 0.01]\n").loading().push_path,
            (std::vector<double>{0.0, 0.01}));
  // A key of another model type holds its declared default, and is not
  // written to the resolved scene.
  EXPECT_EQ(j.geometry().width, 100.0);
  EXPECT_EQ(j.to_toml().find("width"), std::string::npos);
}

// cracking.integration = "auto" (the default) is IMPL-EX under displacement
// and dissipation control without a damage viscosity, the implicit cracks
// otherwise (arc length, a viscosity).
TEST(Scene, AutoIntegrationIsImplexWhereItApplies)
{
  const std::string cracks = "[cracking]\nmodel = \"embedded\"\n";
  EXPECT_TRUE(Scene::parse(cracks).cracking().implex);
  EXPECT_TRUE(Scene::parse(cracks, {{"loading.control", "auto"}}).cracking().implex);
  EXPECT_TRUE(Scene::parse(cracks, {{"loading.control", "dissipation"}}).cracking().implex);
  EXPECT_TRUE(Scene::parse(cracks, {{"loading.control", "arc_length"}}).cracking().implex);
  EXPECT_FALSE(Scene::parse(cracks, {{"cracking.viscosity", "0.01"}}).cracking().implex);
  EXPECT_FALSE(Scene::parse(cracks, {{"cracking.integration", "implicit"}}).cracking().implex);
  EXPECT_TRUE(Scene::parse(cracks, {{"cracking.integration", "implex"}}).cracking().implex);
}

// Keys that nothing reads are named (a note, not an error): [cracking]
// keys while cracking.model = "none", the other softening law's parameter.
TEST(Scene, UnreadCrackingKeysAreNamed)
{
  EXPECT_TRUE(Scene::parse("").unread_keys().empty());
  const std::vector<std::string> off =
      Scene::parse("[cracking]\nstrength_cov = 0.15\nf_t = 3.0\n").unread_keys();
  ASSERT_EQ(off.size(), 1u);
  EXPECT_NE(off[0].find("cracking.strength_cov"), std::string::npos);
  EXPECT_EQ(off[0].find("cracking.f_t"), std::string::npos); // its default: nothing lost
  const std::string cracks = "[cracking]\nmodel = \"embedded\"\n";
  EXPECT_TRUE(Scene::parse(cracks, {{"cracking.c", "50"}}).unread_keys().empty());
  const std::vector<std::string> linear =
      Scene::parse(cracks, {{"cracking.law", "linear_softening"}, {"cracking.c", "50"}})
          .unread_keys();
  ASSERT_EQ(linear.size(), 1u);
  EXPECT_NE(linear[0].find("cracking.c "), std::string::npos);
  EXPECT_EQ(Scene::parse(cracks, {{"cracking.w_c2", "0.25"}}).unread_keys().size(), 1u);
  // The resolved scene of a run without cracks reads back without a note.
  EXPECT_TRUE(Scene::parse(Scene::parse("").to_toml()).unread_keys().empty());
  // The random field's keys with a uniform strength; the corrosion stage's
  // without corrosion.
  const Scene uniform = Scene::parse(cracks, {{"cracking.seed", "2"}});
  ASSERT_EQ(uniform.unread_keys().size(), 1u);
  EXPECT_NE(uniform.unread_keys()[0].find("cracking.strength_cov = 0"), std::string::npos);
  EXPECT_TRUE(Scene::parse(cracks, {{"cracking.seed", "2"}, {"cracking.strength_cov", "0.1"}})
                  .unread_keys()
                  .empty());
  EXPECT_EQ(Scene::parse("", {{"corrosion.beta", "3"}}).unread_keys().size(), 1u);
  EXPECT_TRUE(Scene::parse("", {{"corrosion.beta", "3"}, {"corrosion.penetration", "0.01"}})
                  .unread_keys()
                  .empty());
  // IMPL-EX's keys where the cracks are integrated implicitly without an
  // IMPL-EX rescue: asked for with the rescue off, or chosen by auto for a
  // viscosity (which IMPL-EX does not take). With the rescue, its steps
  // read them.
  const std::vector<Override> implex_keys = {{"cracking.implex_tolerance", "0.01"},
                                             {"cracking.implex_predictor", "history"}};
  EXPECT_TRUE(Scene::parse(cracks, implex_keys).unread_keys().empty());
  std::vector<Override> rescued = implex_keys;
  rescued.push_back({"cracking.integration", "implicit"});
  EXPECT_TRUE(Scene::parse(cracks, rescued).unread_keys().empty());
  for (const Override& implicit_by :
       std::vector<Override>{{"cracking.integration", "implicit"}, {"cracking.viscosity", "0.001"}})
  {
    std::vector<Override> set = implex_keys;
    set.push_back(implicit_by);
    if (implicit_by.path == "cracking.integration")
      set.push_back({"cracking.implex_rescue", "false"});
    const std::vector<std::string> implicit = Scene::parse(cracks, set).unread_keys();
    ASSERT_EQ(implicit.size(), 1u) << implicit_by.path;
    EXPECT_EQ(implicit[0].rfind("cracking.implex_tolerance, cracking.implex_predictor not read", 0),
              0u)
        << implicit[0];
    EXPECT_NE(implicit[0].find(implicit_by.path == "cracking.viscosity"
                                   ? "\"auto\" with a cracking.viscosity"
                                   : "cracking.integration = \"implicit\""),
              std::string::npos)
        << implicit[0];
  }
}

// unread_note says why a key is not read whatever its value (its default
// too: pushout sweep and fit ask it of the key they vary), "" where it is.
TEST(Scene, UnreadNoteWhateverTheValue)
{
  const Scene plain = Scene::parse("");
  EXPECT_NE(plain.unread_note("cracking.seed").find("cracking.model = \"none\""),
            std::string::npos);
  EXPECT_EQ(plain.unread_note("cracking.seed").rfind("cracking.seed not read", 0), 0u);
  EXPECT_NE(plain.unread_note("corrosion.beta").find("corrosion.penetration = 0"),
            std::string::npos);
  EXPECT_EQ(plain.unread_note("interface.0.mu"), "");
  const Scene field = Scene::parse("[cracking]\nmodel = \"embedded\"\nstrength_cov = 0.15\n");
  EXPECT_EQ(field.unread_note("cracking.seed"), "");
  EXPECT_NE(field.unread_note("cracking.w_c2").find("exponential_softening"), std::string::npos);
  EXPECT_EQ(field.unread_note("cracking.implex_tolerance"), "");
  const Scene implicit =
      Scene::parse("[cracking]\nmodel = \"embedded\"\nintegration = \"implicit\"\n");
  EXPECT_EQ(implicit.unread_note("cracking.implex_tolerance"), ""); // its IMPL-EX rescue's
  const Scene unrescued = Scene::parse("[cracking]\nmodel = \"embedded\"\nintegration = "
                                       "\"implicit\"\nimplex_rescue = false\n");
  EXPECT_EQ(unrescued.unread_note("cracking.implex_tolerance")
                .rfind("cracking.implex_tolerance not read", 0),
            0u);
}

TEST(Scene, OverridesReachTablesAndLayers)
{
  const Scene s = Scene::parse(
      "[[interface]]\nlaw = \"friction\"\nmu = 0.4\n"
      "[[interface]]\nlaw = \"elastic\"\nk = 5.0\n",
      {{"interface.0.mu", "0.2"}, {"loading.temperature_change", "-50"}, {"interface.1.k_s", "7"}});
  EXPECT_DOUBLE_EQ(s.layers()[0].params.at("mu"), 0.2);
  EXPECT_DOUBLE_EQ(s.loading().temperature_change, -50.0);
  EXPECT_DOUBLE_EQ(s.layers()[1].params.at("k_n"), 5.0); // defaults to k
  EXPECT_DOUBLE_EQ(s.layers()[1].params.at("k_s"), 7.0);
}

TEST(Scene, ATableOverrideSetsItsKeysAndKeepsTheSections)
{
  // --set 'loading={steps=10}' sets loading.steps and keeps the file's
  // other [loading] keys (it replaced the section: push_displacement went
  // back to its default); nested tables alike, and a section the file has
  // not is made.
  const Scene s = Scene::parse("[loading]\npush_displacement = 0.2\nsteps = 40\n"
                               "[geometry]\nthickness = 30.0\n",
                               {{"loading", "{steps = 10}"},
                                {"geometry", "{width = 120.0}"},
                                {"corrosion", "{penetration = 0.01, steps = 3}"}});
  EXPECT_EQ(s.loading().steps, 10);
  EXPECT_DOUBLE_EQ(s.loading().push_displacement, 0.2);
  EXPECT_DOUBLE_EQ(s.geometry().width, 120.0);
  EXPECT_DOUBLE_EQ(s.geometry().thickness, 30.0);
  EXPECT_DOUBLE_EQ(s.corrosion().penetration, 0.01);
  EXPECT_EQ(s.corrosion().steps, 3);
  // A layer alike: its law and other parameters stay.
  const Scene layer = Scene::parse("[[interface]]\nlaw = \"elastic\"\nk_n = 500.0\n",
                                   {{"interface.0", "{k_s = 7.0}"}});
  EXPECT_EQ(layer.layers()[0].law, "elastic");
  EXPECT_DOUBLE_EQ(layer.layers()[0].params.at("k_n"), 500.0);
  EXPECT_DOUBLE_EQ(layer.layers()[0].params.at("k_s"), 7.0);
}

TEST(Scene, AParameterOnlyDefaultingOthersGivenWithThemIsNoted)
{
  // elastic's k is only the default of k_n and k_s: given with both, other
  // than its default, nothing reads it (single joint and push-out alike).
  const std::string elastic = "[[interface]]\nlaw = \"elastic\"\nk = 2000.0\n";
  const auto noted = [](const Scene& s) { return s.unread_keys(); };
  for (const std::string model : {"single_joint", "pushout"})
  {
    const auto notes = noted(Scene::parse("[model]\ntype = \"" + model + "\"\n" + elastic,
                                          {{"interface.0.k_n", "500"}, {"interface.0.k_s", "7"}}));
    ASSERT_EQ(notes.size(), 1u) << model;
    EXPECT_EQ(notes[0], "interface.0.k not read: it is only the default of interface.0.k_n and "
                        "interface.0.k_s, which are given");
  }
  EXPECT_TRUE(noted(Scene::parse(elastic, {{"interface.0.k_n", "500"}})).empty());
  const Scene at_default = Scene::parse("[[interface]]\nlaw = \"elastic\"\nk = 1000.0\n",
                                        {{"interface.0.k_n", "500"}, {"interface.0.k_s", "7"}});
  EXPECT_TRUE(noted(at_default).empty()); // its default
  // Whatever its value, for a key a sweep would vary or a fit free.
  EXPECT_EQ(at_default.unread_note("interface.0.k").rfind("interface.0.k not read", 0), 0u);
  EXPECT_EQ(Scene::parse(elastic, {{"interface.0.k_n", "500"}}).unread_note("interface.0.k"), "");
}

TEST(Scene, OverridesReachTheDefaultLayer)
{
  // A scene without [[interface]] has one friction layer (scene.toml shows
  // it as interface.0); --set reaches it, as a fit's or sweep's key does.
  const Scene s = Scene::parse("", {{"interface.0.mu", "0.2"}});
  ASSERT_EQ(s.layers().size(), 1u);
  EXPECT_EQ(s.layers()[0].law, "friction");
  EXPECT_DOUBLE_EQ(s.layers()[0].params.at("mu"), 0.2);
  EXPECT_EQ(Scene::parse("").to_toml(),
            Scene::parse("", {{"interface.0.mu", "0.4"}}).to_toml()); // 0.4: the default
  EXPECT_NE(error_of("", {{"crack.0.f_t", "1"}}).find("no [[crack]]"), std::string::npos);
}

TEST(Scene, ResolvedSceneReadsBackToTheSameScene)
{
  const Scene a =
      Scene::parse("[loading]\nsteps = 3\n[[interface]]\nmu = 0.3\n", {{"interface.0.mu", "0.25"}});
  const Scene b = Scene::parse(a.to_toml());
  EXPECT_EQ(a.to_toml(), b.to_toml());
  EXPECT_EQ(b.loading().steps, 3);
  EXPECT_DOUBLE_EQ(b.layers()[0].params.at("mu"), 0.25);
}

TEST(Scene, ErrorsNameTheKey)
{
  EXPECT_NE(error_of("[geometry]\nwidht = 1.0\n").find("geometry.widht"), std::string::npos);
  EXPECT_NE(error_of("[loading]\nsteps = 1.5\n").find("loading.steps"), std::string::npos);
  EXPECT_NE(error_of("[[interface]]\nk = -1.0\n").find("interface.0.k"), std::string::npos);
  EXPECT_NE(error_of("", {{"interface.2.k", "1"}}).find("interface.2.k"), std::string::npos);
  EXPECT_NE(error_of("[[interface]]\nlaw = 3\n").find("interface.0.law"), std::string::npos);
  // An integer against its bound exactly, above 2^53 too (a double rounds
  // 2^53 + 1 onto 2^53, cracking.seed's largest).
  EXPECT_EQ(error_of("", {{"cracking.seed", "9007199254740992"}}), "");
  EXPECT_NE(error_of("", {{"cracking.seed", "9007199254740993"}}).find("= 9007199254740993 is out"),
            std::string::npos);
}

TEST(Scene, CrackTablesTakeAnAngleAndALaw)
{
  const Scene s = Scene::parse("[[crack]]\nangle = \"nearest_face\"\n"
                               "[[crack]]\nangle = 90\nlaw = \"linear_softening\"\nw_c2 = 0.1\n",
                               {{"crack.1.f_t", "2.5"}});
  ASSERT_EQ(s.cracks().size(), 2u);
  EXPECT_FALSE(s.cracks()[0].angle_deg.has_value());
  EXPECT_EQ(s.cracks()[0].layer.law, "exponential_softening");
  EXPECT_DOUBLE_EQ(s.cracks()[0].layer.params.at("k"), 1e5); // a crack's stiff default
  EXPECT_DOUBLE_EQ(*s.cracks()[1].angle_deg, 90.0);
  EXPECT_DOUBLE_EQ(s.cracks()[1].layer.params.at("f_t"), 2.5);
  // The resolved scene reads back to the same cracks.
  const Scene again = Scene::parse(s.to_toml());
  ASSERT_EQ(again.cracks().size(), 2u);
  EXPECT_FALSE(again.cracks()[0].angle_deg.has_value());
  EXPECT_DOUBLE_EQ(*again.cracks()[1].angle_deg, 90.0);
  EXPECT_EQ(again.cracks()[1].layer.params, s.cracks()[1].layer.params);
  EXPECT_NE(error_of("[[crack]]\nangle = 400.0\n").find("crack.0.angle"), std::string::npos);
}

TEST(Scene, AnIntegerOverrideHasOneSpelling)
{
  using pushout::integer_in_decimal;
  for (const char* v : {"0x10", "0o20", "0b10000", "1_6", "16", "+16"})
    EXPECT_EQ(integer_in_decimal(v), "16") << v;
  EXPECT_EQ(integer_in_decimal("-9223372036854775808"), "-9223372036854775808");
  for (const char* v :
       {"1.5", "1e2", "007", "0x", "[1, 2]", "true", "name", "99999999999999999999"})
    EXPECT_EQ(integer_in_decimal(v), v) << v;
  // Nesting that exhausts the TOML parser's stack (200 000 levels crashed
  // this test without the guard) is not parsed: the override refuses it.
  std::string deep = "{";
  for (int i = 0; i < 200000; ++i)
    deep += "a.";
  deep += "a = 1}";
  EXPECT_EQ(integer_in_decimal(deep), deep);
}
