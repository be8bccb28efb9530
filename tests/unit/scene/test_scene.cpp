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
  EXPECT_EQ(s.string("model.type"), "pushout");
  EXPECT_DOUBLE_EQ(s.number("geometry.width"), 100.0);
  EXPECT_EQ(s.integer("mesh.elements_per_quarter"), 16);
  ASSERT_EQ(s.layers().size(), 1u);
  EXPECT_EQ(s.layers()[0].law, "friction");
  EXPECT_DOUBLE_EQ(s.layers()[0].params.at("k"), 1000.0);
}

TEST(Scene, OverridesReachTablesAndLayers)
{
  const Scene s = Scene::parse(
      "[[interface]]\nlaw = \"friction\"\nmu = 0.4\n"
      "[[interface]]\nlaw = \"elastic\"\nk = 5.0\n",
      {{"interface.0.mu", "0.2"}, {"loading.temperature_change", "-50"}, {"interface.1.k_s", "7"}});
  EXPECT_DOUBLE_EQ(s.layers()[0].params.at("mu"), 0.2);
  EXPECT_DOUBLE_EQ(s.number("loading.temperature_change"), -50.0);
  EXPECT_DOUBLE_EQ(s.layers()[1].params.at("k_n"), 5.0); // defaults to k
  EXPECT_DOUBLE_EQ(s.layers()[1].params.at("k_s"), 7.0);
}

TEST(Scene, ResolvedSceneReadsBackToTheSameScene)
{
  const Scene a =
      Scene::parse("[loading]\nsteps = 3\n[[interface]]\nmu = 0.3\n", {{"interface.0.mu", "0.25"}});
  const Scene b = Scene::parse(a.to_toml());
  EXPECT_EQ(a.to_toml(), b.to_toml());
  EXPECT_EQ(b.integer("loading.steps"), 3);
  EXPECT_DOUBLE_EQ(b.layers()[0].params.at("mu"), 0.25);
}

TEST(Scene, ErrorsNameTheKey)
{
  EXPECT_NE(error_of("[geometry]\nwidht = 1.0\n").find("geometry.widht"), std::string::npos);
  EXPECT_NE(error_of("[loading]\nsteps = 1.5\n").find("loading.steps"), std::string::npos);
  EXPECT_NE(error_of("[[interface]]\nk = -1.0\n").find("interface.0.k"), std::string::npos);
  EXPECT_NE(error_of("", {{"interface.2.k", "1"}}).find("interface.2.k"), std::string::npos);
  EXPECT_NE(error_of("[[interface]]\nlaw = 3\n").find("interface.0.law"), std::string::npos);
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
