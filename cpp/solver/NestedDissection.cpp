#include "NestedDissection.h"
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <limits>
#include <scotch.h>

namespace pushout::solver
{
std::vector<std::int64_t> nested_dissection(std::int64_t n, int block_size,
                                            const std::vector<int>& rows,
                                            const std::vector<int>& cols)
{
  if (block_size < 1 || n < 1 || n % block_size != 0 || rows.size() != cols.size() ||
      n / block_size > std::numeric_limits<SCOTCH_Num>::max())
    return {};
  const auto nodes = static_cast<std::size_t>(n / block_size);
  // The node graph in compressed rows, without self-loops and repeats, as
  // SCOTCH_graphBuild takes it (each edge both ways: the pattern of a
  // stiffness matrix is symmetric; a one-way entry is made two-way here).
  std::vector<std::vector<SCOTCH_Num>> neighbours(nodes);
  for (std::size_t k = 0; k < rows.size(); ++k)
  {
    if (rows[k] < 1 || rows[k] > n || cols[k] < 1 || cols[k] > n)
      return {};
    const auto a = static_cast<SCOTCH_Num>((rows[k] - 1) / block_size);
    const auto b = static_cast<SCOTCH_Num>((cols[k] - 1) / block_size);
    if (a != b)
    {
      neighbours[std::size_t(a)].push_back(b);
      neighbours[std::size_t(b)].push_back(a);
    }
  }
  std::vector<SCOTCH_Num> offsets{0}, edges;
  for (auto& list : neighbours)
  {
    std::sort(list.begin(), list.end());
    list.erase(std::unique(list.begin(), list.end()), list.end());
    edges.insert(edges.end(), list.begin(), list.end());
    list = {};
    if (edges.size() > std::size_t(std::numeric_limits<SCOTCH_Num>::max()))
      return {};
    offsets.push_back(SCOTCH_Num(edges.size()));
  }

  SCOTCH_Graph graph;
  SCOTCH_Strat strategy;
  if (SCOTCH_graphInit(&graph) != 0)
    return {};
  if (SCOTCH_stratInit(&strategy) != 0)
  {
    SCOTCH_graphExit(&graph);
    return {};
  }
  // permutation[v]: the place of node v in the order (SCOTCH's permtab).
  std::vector<SCOTCH_Num> permutation(nodes), inverse(nodes);
  SCOTCH_Num blocks = 0;
  const bool ordered =
      SCOTCH_graphBuild(&graph, 0, SCOTCH_Num(nodes), offsets.data(), nullptr, nullptr, nullptr,
                        SCOTCH_Num(edges.size()), edges.data(), nullptr) == 0 &&
      SCOTCH_graphOrder(&graph, &strategy, permutation.data(), inverse.data(), &blocks, nullptr,
                        nullptr) == 0;
  SCOTCH_stratExit(&strategy);
  SCOTCH_graphExit(&graph);
  if (!ordered)
    return {};
  std::vector<std::int64_t> step(static_cast<std::size_t>(n));
  for (std::size_t r = 0; r < step.size(); ++r)
    step[r] = std::int64_t(permutation[r / std::size_t(block_size)]) * block_size +
              std::int64_t(r % std::size_t(block_size));
  return step;
}
} // namespace pushout::solver
