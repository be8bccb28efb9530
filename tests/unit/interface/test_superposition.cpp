// Superposition (paper §4.3): an interface with two layers gives the sum of
// the forces of the layers run separately, each layer keeping its own state.
#include "interface/Interface.h"
#include "laws/LawRegistry.h"
#include <algorithm>
#include <gtest/gtest.h>
#include <random>

using namespace pushout;

namespace
{
std::unique_ptr<laws::InterfaceLaw> make(const std::string& name, const laws::Params& p)
{
  return laws::find_law(name)->make(p, "");
}

interface::Interface one_pair(std::vector<std::unique_ptr<laws::InterfaceLaw>> layers)
{
  // Steel nodes 0-3 and concrete nodes 4-7 on the unit square z = 0 (normal
  // +z): tensor order (0,0), (1,0), (0,1), (1,1).
  std::vector<double> x = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  return interface::Interface({0, 1, 2, 3, 4, 5, 6, 7}, x, interface::make_quadrature("gauss"),
                              std::move(layers));
}
} // namespace

TEST(Superposition, TwoLayersAreTheSumOfEachAlone)
{
  const laws::Params fr = {{"k", 100}, {"mu", 0.4}};
  const laws::Params ls = {{"k", 100}, {"f_t", 1}, {"w_c2", 0.3}, {"eta", 0}};
  std::vector<std::unique_ptr<laws::InterfaceLaw>> both, a, b;
  both.push_back(make("friction", fr));
  both.push_back(make("linear_softening", ls));
  a.push_back(make("friction", fr));
  b.push_back(make("linear_softening", ls));
  interface::Interface I = one_pair(std::move(both)), Ia = one_pair(std::move(a)),
                       Ib = one_pair(std::move(b));

  std::mt19937 gen(1);
  std::uniform_real_distribution<double> U(-1, 1);
  for (int step = 0; step < 20; ++step)
  {
    std::vector<double> u(24, 0.0);
    for (int i = 12; i < 24; ++i) // concrete nodes move; normal stays compressive
      u[i] = (i % 3 == 2 ? -0.004 : 0.002 * step) + 1e-3 * U(gen);
    std::vector<double> f(24, 0.0), fa(24, 0.0), fb(24, 0.0);
    ASSERT_TRUE(I.assemble(u, f, nullptr));
    ASSERT_TRUE(Ia.assemble(u, fa, nullptr));
    ASSERT_TRUE(Ib.assemble(u, fb, nullptr));
    for (int i = 0; i < 24; ++i)
      EXPECT_NEAR(f[i], fa[i] + fb[i], 1e-13);
    for (std::size_t p = 0; p < I.num_points(); ++p)
    {
      EXPECT_TRUE(std::ranges::equal(I.state().trial(p, 0), Ia.state().trial(p, 0)));
      EXPECT_TRUE(std::ranges::equal(I.state().trial(p, 1), Ib.state().trial(p, 0)));
    }
    I.state().commit();
    Ia.state().commit();
    Ib.state().commit();
  }
}
