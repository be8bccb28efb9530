#include "symmetry.h"
#include <cmath>

namespace pushout::mesh
{
bool use_quarter_model(const Scene& scene, std::string& why)
{
  if (scene.string("model.type") != "pushout")
    return false;
  if (scene.string("model.symmetry") != "auto")
  {
    why = "model.symmetry = \"full\"";
    return false;
  }
  if (scene.boolean("output.xdmf"))
  {
    why = "output.xdmf asks for fields of the whole specimen";
    return false;
  }
  if (!scene.cracks().empty())
  {
    why = "crack planes (the quarter model has none)";
    return false;
  }
  if (scene.integer("mesh.elements_per_quarter") % 2 != 0)
  {
    why = "mesh.elements_per_quarter is odd (the symmetry planes are not mesh surfaces)";
    return false;
  }
  if (scene.string("geometry.outer_shape") == "square")
  {
    const double W = scene.number("geometry.width");
    const auto& c = scene.numbers("geometry.tube_center");
    if (std::abs(c[0] - W / 2) > 1e-12 * W || std::abs(c[1] - W / 2) > 1e-12 * W)
    {
      why = "the tube is not centred in the square";
      return false;
    }
  }
  return true;
}

void keep_quarter(MeshData& m, double xc, double yc)
{
  std::vector<std::int64_t> new_cell(m.num_cells(), -1), new_node(m.num_nodes(), -1);
  MeshData q;
  std::int64_t nodes = 0;
  for (std::size_t c = 0; c < m.num_cells(); ++c)
  {
    double x = 0, y = 0;
    for (int i = 0; i < 8; ++i)
    {
      x += m.x[3 * m.cells[8 * c + i]] / 8;
      y += m.x[3 * m.cells[8 * c + i] + 1] / 8;
    }
    if (x < xc || y < yc)
      continue;
    new_cell[c] = std::int64_t(q.num_cells());
    q.material.push_back(m.material[c]);
    for (int i = 0; i < 8; ++i)
    {
      std::int64_t& n = new_node[m.cells[8 * c + i]];
      if (n < 0)
        n = nodes++;
      q.cells.push_back(n);
    }
  }
  q.x.resize(3 * std::size_t(nodes));
  for (std::size_t n = 0; n < m.num_nodes(); ++n)
    if (new_node[n] >= 0)
      for (int d = 0; d < 3; ++d)
        q.x[3 * new_node[n] + d] = m.x[3 * n + d];
  for (const InterfacePair& p : m.pairs)
  {
    if (new_cell[p.minus_cell] < 0 || new_cell[p.plus_cell] < 0)
      continue;
    InterfacePair r = p;
    for (int i = 0; i < 4; ++i)
    {
      r.minus[i] = new_node[p.minus[i]];
      r.plus[i] = new_node[p.plus[i]];
    }
    r.minus_cell = new_cell[p.minus_cell];
    r.plus_cell = new_cell[p.plus_cell];
    q.pairs.push_back(r);
  }
  q.copies = 4;
  q.symmetry_center = {xc, yc};
  m = std::move(q);
}
} // namespace pushout::mesh
